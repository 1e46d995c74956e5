/* A test bench around one atv312_t: every frame the drive sends is recorded with its time, frames
 * are injected as text ("604#40..."), time advances deadline by deadline. No sleeps. */
#ifndef ATV312_BENCH_H
#define ATV312_BENCH_H

#include "atv312/atv312.h"

#include <check.h>

#define BENCH_FRAMES 4096
#define BENCH_NODE_ID 4

typedef struct bench {
    atv312_t drive;
    co_frame_t frame[BENCH_FRAMES];
    co_time_t at[BENCH_FRAMES];
    size_t count; /* frames sent */
    size_t next;  /* first frame not yet consumed */
    co_time_t now;
    co_time_t deadline; /* returned by the last atv312_process */
} bench_t;

/* Boots node 4 at time 0 and consumes its boot-up frame. */
void bench_start(bench_t *b);
/* The same with a storage backend (1010h / 1011h). */
void bench_start_stored(bench_t *b, const co_storage_t *storage);
/* Delivers a frame now, then runs atv312_process. */
void bench_rx(bench_t *b, const char *text);
/* Advances time by `us`, processing at every deadline on the way and at the end. */
void bench_advance(bench_t *b, co_time_t us);

#define bench_expect(b, text) bench_expect_at(b, text, __FILE__, __LINE__)
co_time_t bench_expect_at(bench_t *b, const char *text, const char *file, int line);
#define bench_expect_none(b) bench_expect_none_at(b, __FILE__, __LINE__)
void bench_expect_none_at(bench_t *b, const char *file, int line);
void bench_drain(bench_t *b);

/* Expedited SDO write / read; return the abort code (0 on success), consuming the answer. */
uint32_t bench_sdo_write(bench_t *b, uint16_t index, uint8_t sub, uint32_t value, uint8_t len);
uint32_t bench_sdo_read(bench_t *b, uint16_t index, uint8_t sub, uint32_t *value);
/* Reads by SDO a value the test needs (failing the test on an abort). */
uint32_t bench_read(bench_t *b, uint16_t index, uint8_t sub);
/* Writes the control word by SDO and returns the status word read back by SDO. */
uint16_t bench_command(bench_t *b, uint16_t control);
/* Speed 6044h read by SDO, signed. */
int16_t bench_speed(bench_t *b);
/* NMT start, and PDO event timers off so that TPDOs follow changes only. */
void bench_operational(bench_t *b);

#endif
