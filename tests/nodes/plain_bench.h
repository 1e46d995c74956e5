/* SPDX-License-Identifier: Apache-2.0 */
/* One plain node (nodes/plain_node.h) of a model on a recorded bus with injected time: frames in
 * and out written as text ("601#4000300000000000"), as the core's test bus has them. */
#ifndef PLAIN_BENCH_H
#define PLAIN_BENCH_H

#include "nodes/plain_node.h"
#include "test_bus.h"

#include <check.h>
#include <stdio.h>
#include <string.h>

#define PLAIN_BENCH_FRAMES 64

typedef struct plain_bench {
    plain_node_t plain;
    uint8_t data[8192];
    co_frame_t sent[PLAIN_BENCH_FRAMES];
    size_t count, next;
    co_time_t now;
} plain_bench_t;

static inline void plain_bench_send(void *user, const co_frame_t *frame)
{
    plain_bench_t *b = user;
    ck_assert_uint_lt(b->count, PLAIN_BENCH_FRAMES);
    b->sent[b->count++] = *frame;
}

/* The node of `model` at `node_id`, serial number `serial`, started at time 0: its boot-up. */
static inline void plain_bench_start(plain_bench_t *b, const plain_model_t *model, uint8_t node_id,
                                     uint32_t serial)
{
    memset(b, 0, sizeof *b);
    ck_assert_uint_le(model->od->data_size, sizeof b->data);
    plain_node_config_t config = {.model = model,
                                  .od_data = b->data,
                                  .node_id = node_id,
                                  .serial_number = serial,
                                  .send = plain_bench_send,
                                  .send_user = b};
    ck_assert_int_eq(plain_node_init(&b->plain, &config), 0);
    plain_node_start(&b->plain, 0);
    plain_node_process(&b->plain, 0);
}

static inline void plain_bench_rx(plain_bench_t *b, const char *text)
{
    co_frame_t frame = test_frame(text);
    plain_node_receive(&b->plain, &frame, b->now);
    plain_node_process(&b->plain, b->now);
}

/* Time runs `us` on, the node processed at every deadline on the way. */
static inline void plain_bench_advance(plain_bench_t *b, co_time_t us)
{
    co_time_t end = b->now + us;
    for (;;) {
        co_time_t next = plain_node_process(&b->plain, b->now);
        if (next > end)
            break;
        b->now = next > b->now ? next : b->now + 1;
    }
    b->now = end;
    plain_node_process(&b->plain, b->now);
}

#define plain_bench_expect(b, text) plain_bench_expect_at(b, text, __LINE__)
static inline void plain_bench_expect_at(plain_bench_t *b, const char *text, int line)
{
    char got[32] = "nothing";
    if (b->next < b->count)
        test_format(&b->sent[b->next++], got);
    ck_assert_msg(strcmp(got, text) == 0, "line %d: expected %s, got %s", line, text, got);
}

static inline void plain_bench_expect_none(plain_bench_t *b)
{
    char got[32] = "";
    if (b->next < b->count)
        test_format(&b->sent[b->next], got);
    ck_assert_msg(b->next == b->count, "unexpected frame %s", got);
}

static inline void plain_bench_drain(plain_bench_t *b)
{
    b->next = b->count;
}

#endif
