/* SPDX-License-Identifier: Apache-2.0 */
/* The bounded transmit queue: order, capacity, drops counted, wrap-around, reading by position. */
#include "check_main.h"
#include "co_linux/txq.h"

#include <check.h>
#include <stdlib.h>

static co_txq_t q;

static co_frame_t frame_with_id(uint32_t id)
{
    co_frame_t f = {.id = id, .len = 1, .data = {(uint8_t)id}};
    return f;
}

START_TEST(keeps_fifo_order)
{
    co_txq_init(&q, 4);
    int origin;
    for (uint32_t id = 0x181; id <= 0x183; id++) {
        co_frame_t f = frame_with_id(id);
        ck_assert(co_txq_push(&q, &f, &origin));
    }
    ck_assert_uint_eq(co_txq_count(&q), 3);
    for (uint32_t id = 0x181; id <= 0x183; id++) {
        const co_txq_entry_t *e = co_txq_peek(&q);
        ck_assert_ptr_nonnull(e);
        ck_assert_uint_eq(e->frame.id, id);
        ck_assert_uint_eq(e->frame.data[0], (uint8_t)id);
        ck_assert_ptr_eq(e->origin, &origin);
        co_txq_pop(&q);
    }
    ck_assert_ptr_null(co_txq_peek(&q));
}
END_TEST

START_TEST(full_queue_drops_newest_and_counts)
{
    co_txq_init(&q, 3);
    q.dropped = 0;
    for (uint32_t id = 1; id <= 3; id++) {
        co_frame_t f = frame_with_id(id);
        ck_assert(co_txq_push(&q, &f, NULL));
    }
    ck_assert(co_txq_full(&q));
    for (uint32_t id = 4; id <= 5; id++) {
        co_frame_t f = frame_with_id(id);
        ck_assert(!co_txq_push(&q, &f, NULL));
    }
    ck_assert_uint_eq(q.dropped, 2);
    ck_assert_uint_eq(co_txq_count(&q), 3);
    /* The queued frames are untouched by the refused ones. */
    for (uint32_t id = 1; id <= 3; id++) {
        ck_assert_uint_eq(co_txq_peek(&q)->frame.id, id);
        co_txq_pop(&q);
    }
}
END_TEST

START_TEST(wraps_around_without_losing_order)
{
    co_txq_init(&q, 3);
    uint32_t next_in = 1, next_out = 1;
    for (int round = 0; round < 10; round++) {
        while (!co_txq_full(&q)) {
            co_frame_t f = frame_with_id(next_in++);
            ck_assert(co_txq_push(&q, &f, NULL));
        }
        co_txq_pop(&q);
        next_out++;
        ck_assert_uint_eq(co_txq_peek(&q)->frame.id, next_out);
    }
    ck_assert_uint_eq(co_txq_count(&q), 2);
}
END_TEST

/* The batch a sendmmsg takes is read by position, the oldest first, across the wrap. */
START_TEST(at_reads_by_position_across_the_wrap)
{
    co_txq_init(&q, 3);
    for (uint32_t id = 0x181; id <= 0x182; id++) {
        co_frame_t f = frame_with_id(id);
        ck_assert(co_txq_push(&q, &f, NULL));
    }
    co_txq_pop(&q);
    for (uint32_t id = 0x183; id <= 0x184; id++) {
        co_frame_t f = frame_with_id(id);
        ck_assert(co_txq_push(&q, &f, NULL));
    }
    for (size_t i = 0; i < 3; i++)
        ck_assert_uint_eq(co_txq_at(&q, i)->frame.id, 0x182 + i);
    ck_assert_ptr_null(co_txq_at(&q, 3));
    ck_assert_ptr_eq(co_txq_at(&q, 0), co_txq_peek(&q));
    co_txq_clear(&q);
    ck_assert_ptr_null(co_txq_at(&q, 0));
}
END_TEST

START_TEST(clear_reports_count_and_empties)
{
    co_txq_init(&q, 8);
    for (uint32_t id = 1; id <= 5; id++) {
        co_frame_t f = frame_with_id(id);
        co_txq_push(&q, &f, NULL);
    }
    ck_assert_uint_eq(co_txq_clear(&q), 5);
    ck_assert_uint_eq(co_txq_count(&q), 0);
    co_txq_pop(&q); /* popping an empty queue is harmless */
    ck_assert_uint_eq(co_txq_count(&q), 0);
}
END_TEST

START_TEST(capacity_is_clamped)
{
    co_txq_init(&q, 0);
    ck_assert_uint_eq(q.capacity, 1);
    co_txq_init(&q, CO_TXQ_MAX + 10);
    ck_assert_uint_eq(q.capacity, CO_TXQ_MAX);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("txq");
    TCase *tc = tcase_create("txq");
    tcase_add_test(tc, keeps_fifo_order);
    tcase_add_test(tc, full_queue_drops_newest_and_counts);
    tcase_add_test(tc, wraps_around_without_losing_order);
    tcase_add_test(tc, at_reads_by_position_across_the_wrap);
    tcase_add_test(tc, clear_reports_count_and_empties);
    tcase_add_test(tc, capacity_is_clamped);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
