/* SPDX-License-Identifier: Apache-2.0 */
/* A test bench around one drive_t of any model: every frame the drive sends is recorded with its
 * time, frames are injected as text ("604#40..."), time advances deadline by deadline. No sleeps.
 */
#ifndef DRIVE_BENCH_H
#define DRIVE_BENCH_H

#include "drive/drive.h"

#include <check.h>

#define BENCH_FRAMES 4096
#define BENCH_NODE_ID 4
/* Room for the dictionary data block of any model under test. */
#define BENCH_OD_DATA_MAX 2048

typedef struct bench {
    drive_t drive;
    uint8_t od_data[BENCH_OD_DATA_MAX];
    co_frame_t frame[BENCH_FRAMES];
    co_time_t at[BENCH_FRAMES];
    size_t count; /* frames sent */
    size_t next;  /* first frame not yet consumed */
    co_time_t now;
    co_time_t deadline; /* returned by the last drive_process */
} bench_t;

/* Boots node 4 of the model at time 0, with a storage backend (1010h / 1011h) or NULL, and
 * consumes its boot-up frame (8 bytes for a model of CO_NODE_PAD_DLC8). */
void bench_start_model(bench_t *b, const drive_profile_t *profile, const co_storage_t *storage);
/* The same with every byte of the drive_t `fill` before drive_init (bench_start_model: 0), as the
 * memory of a caller that does not zero it. */
void bench_start_model_over(bench_t *b, const drive_profile_t *profile, const co_storage_t *storage,
                            uint8_t fill);
/* Starts the model at time 0 with CANopen off (node-id 0, the Altivars' AdCO = 0): nothing sent. */
void bench_start_can_off(bench_t *b, const drive_profile_t *profile);
/* Delivers a frame now, then runs drive_process. */
void bench_rx(bench_t *b, const char *text);
/* Advances time by `us`, processing at every deadline on the way and at the end. */
void bench_advance(bench_t *b, co_time_t us);

#define bench_expect(b, text) bench_expect_at(b, text, __FILE__, __LINE__)
co_time_t bench_expect_at(bench_t *b, const char *text, const char *file, int line);
#define bench_expect_none(b) bench_expect_none_at(b, __FILE__, __LINE__)
void bench_expect_none_at(bench_t *b, const char *file, int line);

/* One exchange of a manual's session: a frame the master sends (or NULL), time advanced by
 * `advance_us`, then the frames the drive must send, in order (NULL-terminated). */
typedef struct bench_exchange {
    const char *vector; /* the manual's vector, named in a failure */
    const char *rx;
    co_time_t advance_us;
    const char *expect[3];
} bench_exchange_t;

/* Plays a session: each exchange's frame, time, and exactly its expected frames. */
void bench_play(bench_t *b, const bench_exchange_t *session, size_t count);
#define BENCH_PLAY(b, session) bench_play(b, session, sizeof session / sizeof session[0])

/* Expedited SDO write / read; return the abort code (0 on success), consuming the answer. */
uint32_t bench_sdo_write(bench_t *b, uint16_t index, uint8_t sub, uint32_t value, uint8_t len);
uint32_t bench_sdo_read(bench_t *b, uint16_t index, uint8_t sub, uint32_t *value);
/* Reads by SDO a value the test needs (failing the test on an abort). */
uint32_t bench_read(bench_t *b, uint16_t index, uint8_t sub);
/* Writes the control word by SDO and returns the status word read back by SDO. */
uint16_t bench_command(bench_t *b, uint16_t control);
/* Speed 6044h read by SDO, signed. */
int16_t bench_speed(bench_t *b);

#endif
