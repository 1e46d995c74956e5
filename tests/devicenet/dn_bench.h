/* SPDX-License-Identifier: Apache-2.0 */
/* The bench of the DeviceNet slave tests: one node on a recorded bus with injected time, the
 * ATV312's assembly table (20, 21, 100 consumed; 70, 71, 101 produced; 4 bytes each) in memory,
 * a store, the I/O events, connection ends and resets the node reports, and two application classes
 * (a table driven one at 0x29, a range 0x70..0xA8 answered by its handler) that exercise the
 * registry. */
#ifndef DN_BENCH_H
#define DN_BENCH_H

#include <check.h>

#include "dn/dn_node.h"

#define BENCH_FRAMES 256
#define BENCH_EVENTS 16
#define BENCH_ASSEMBLIES 6
#define BENCH_MASTER 1u /* the scanner's MAC ID in the tests */
#define BENCH_SERIAL 0x12345678u

typedef struct bench_end {
    uint8_t instance;
    dn_end_cause_t cause;
} bench_end_t;

typedef struct dn_bench {
    dn_node_t node;
    dn_config_t config;
    dn_app_t app;
    co_time_t now;
    co_time_t deadline;
    co_frame_t frame[BENCH_FRAMES];
    co_time_t at[BENCH_FRAMES];
    size_t count;
    size_t next;
    uint8_t data[BENCH_ASSEMBLIES][DN_IO_MAX]; /* by position in the assembly table */
    dn_io_event_t events[BENCH_EVENTS];
    size_t event_count;
    bench_end_t ends[BENCH_EVENTS]; /* the connections' ends, as told */
    size_t end_count;
    dn_stats_t stats; /* what the node counted */
    dn_stored_t stored;
    bool store_fails;
    int stores;
    int reset_type; /* -1: none */
    /* The application class 0x29's attributes. */
    uint8_t run1;
    uint16_t param[201]; /* the 0x70.. classes' attributes 1..200 of class 0x70 */
    dn_object_t objects[2];
} dn_bench_t;

extern const dn_assembly_t bench_assemblies[BENCH_ASSEMBLIES];

/* Initialised, not started, with this MAC ID and the stored selection. */
void bench_init(dn_bench_t *b, uint8_t mac_id, dn_stored_t stored);
/* Initialised, started, two quiet seconds: online, the check's frames drained. */
void bench_online(dn_bench_t *b, uint8_t mac_id);
void bench_rx(dn_bench_t *b, const char *text);
void bench_advance(dn_bench_t *b, co_time_t us);
co_time_t bench_expect_at(dn_bench_t *b, const char *text, const char *file, int line);
void bench_expect_none_at(dn_bench_t *b, const char *file, int line);
#define bench_expect(b, text) bench_expect_at((b), (text), __FILE__, __LINE__)
#define bench_expect_none(b) bench_expect_none_at((b), __FILE__, __LINE__)
/* A request and its one-frame answer. */
#define bench_exchange(b, request, response)                                                       \
    do {                                                                                           \
        bench_rx((b), (request));                                                                  \
        bench_expect((b), (response));                                                             \
        bench_expect_none(b);                                                                      \
    } while (0)
uint8_t *bench_assembly(dn_bench_t *b, uint16_t instance);
/* The connections' ends told since the last call, exactly these, in this order. */
void bench_expect_ends_at(dn_bench_t *b, const bench_end_t *want, size_t count, const char *file,
                          int line);
#define bench_expect_ends(b, ...)                                                                  \
    do {                                                                                           \
        const bench_end_t want_[] = {__VA_ARGS__};                                                 \
        bench_expect_ends_at((b), want_, sizeof want_ / sizeof want_[0], __FILE__, __LINE__);      \
    } while (0)
#define bench_expect_no_end(b) bench_expect_ends_at((b), NULL, 0, __FILE__, __LINE__)
/* The node's counters, all five. */
void bench_expect_stats_at(const dn_bench_t *b, dn_stats_t want, const char *file, int line);
#define bench_expect_stats(b, ...)                                                                 \
    bench_expect_stats_at((b), (dn_stats_t){__VA_ARGS__}, __FILE__, __LINE__)

#endif
