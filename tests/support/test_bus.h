/* SPDX-License-Identifier: Apache-2.0 */
/* An in-process CAN bus for frame-exact tests with injected time: a node under test whose sent
 * frames are recorded with their timestamps, helpers to inject frames written as text
 * ("604#4000100000000000", "704#R") and to advance time deadline by deadline. No sleeps. */
#ifndef TEST_BUS_H
#define TEST_BUS_H

#include "co/co_node.h"

#include <check.h>

#define TEST_BUS_FRAMES 4096

typedef struct test_bus {
    co_frame_t frame[TEST_BUS_FRAMES];
    co_time_t at[TEST_BUS_FRAMES];
    size_t count; /* frames sent so far */
    size_t next;  /* first frame not yet consumed by test_expect */
    co_time_t now;
    co_time_t deadline; /* returned by the last co_node_process */
} test_bus_t;

typedef struct test_node {
    co_node_t node;
    test_bus_t bus;
    uint8_t data[4096];
} test_node_t;

/* Initialises a node on the test OD with the given hooks and storage (either may be NULL), starts
 * it at time 0 and checks its boot-up frame. */
void test_node_start(test_node_t *t, uint8_t node_id, const co_app_hooks_t *hooks,
                     const co_storage_t *storage);
/* The same on another dictionary (a variant of the test OD), which must outlive the node. */
void test_node_start_od(test_node_t *t, const co_od_t *od, uint8_t node_id,
                        const co_app_hooks_t *hooks, const co_storage_t *storage);
/* The same from a whole node configuration (its dictionary, hooks, storage, options, LSS); the
 * bus supplies the data block and the send callback. The boot-up is 8 bytes with
 * CO_NODE_PAD_DLC8; a node without a node-id (FFh, LSS) must send none. */
void test_node_start_config(test_node_t *t, const co_node_config_t *config);

/* Parses "123#0102", "123#R" (RTR, len 0) or "123#R2" (RTR, len 2) into a frame. */
co_frame_t test_frame(const char *text);
/* Formats a frame the same way (buffer of at least 32 bytes). */
const char *test_format(const co_frame_t *frame, char *buf);

/* Delivers a frame at the current time and runs co_node_process. */
void test_rx(test_node_t *t, const char *text);
void test_rx_frame(test_node_t *t, const co_frame_t *frame);

/* Advances time by `us`, running co_node_process at every deadline on the way. */
void test_advance(test_node_t *t, co_time_t us);

/* Next unconsumed frame must equal `text`; returns the time it was sent. */
#define test_expect(t, text) test_expect_at(t, text, __FILE__, __LINE__)
co_time_t test_expect_at(test_node_t *t, const char *text, const char *file, int line);
/* No unconsumed frame is left. */
#define test_expect_none(t) test_expect_none_at(t, __FILE__, __LINE__)
void test_expect_none_at(test_node_t *t, const char *file, int line);
/* Skips all unconsumed frames. */
void test_drain(test_node_t *t);

/* The CiA 301 7.3.5 restricted CAN-IDs at both edges of every range of the table, and the free
 * CAN-IDs just beside them (080h, the SYNC default, among them), for the COB-ID rules. */
#define TEST_RESTRICTED_CAN_IDS 15
extern const uint16_t test_restricted_can_id[TEST_RESTRICTED_CAN_IDS];
#define TEST_FREE_CAN_IDS 8
extern const uint16_t test_free_can_id[TEST_FREE_CAN_IDS];

/* Expedited SDO write/read helpers: return the abort code (0 on success). */
uint32_t test_sdo_write(test_node_t *t, uint16_t index, uint8_t sub, uint32_t value, uint8_t len);
uint32_t test_sdo_read(test_node_t *t, uint16_t index, uint8_t sub, uint32_t *value);

/* Writes a numeric value of `len` bytes through co_od_write (SDO origin, every check, no SDO
 * frames) at the current time, then runs co_node_process. Returns the abort code (0 on success). */
uint32_t test_write(test_node_t *t, uint16_t index, uint8_t sub, uint32_t value, uint8_t len);

#endif
