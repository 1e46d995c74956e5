/* SPDX-License-Identifier: Apache-2.0 */
/* Heartbeat producer (exact period, restart on write; on the time grid with
 * CO_NODE_HEARTBEAT_GRID) and consumers (start on the first frame, one loss report per loss,
 * re-arm, duplicate entries, unused entries). */
#include "check_main.h"
#include "memory_storage.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdlib.h>

static test_node_t t;

#define HOOK_LOG 16
static struct {
    uint8_t producer;
    bool lost;
    co_time_t at;
} events[HOOK_LOG];
static size_t event_count;

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    ck_assert_uint_lt(event_count, HOOK_LOG);
    events[event_count].producer = producer;
    events[event_count].lost = lost;
    events[event_count].at = node->now;
    event_count++;
}

static const co_app_hooks_t hooks = {.heartbeat = on_heartbeat};

static void setup(void)
{
    event_count = 0;
    test_node_start(&t, 4, &hooks, NULL);
}

START_TEST(producer_period_is_exact)
{
    test_advance(&t, 5000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    for (int i = 1; i <= 20; i++) {
        test_advance(&t, 100000);
        ck_assert_uint_eq(test_expect(&t, "704#7F"), 5000 + (co_time_t)i * 100000);
    }
    test_advance(&t, 99999);
    test_expect_none(&t);
}
END_TEST

START_TEST(writing_1017_restarts_the_period)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&t, 60000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 50, 2), 0);
    test_advance(&t, 49999);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "704#7F"), 110000);
    test_advance(&t, 50000);
    ck_assert_uint_eq(test_expect(&t, "704#7F"), 160000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 0, 2), 0);
    test_advance(&t, 10000000);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

START_TEST(producer_restarts_after_reset_communication)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&t, 30000);
    test_rx(&t, "000#8204"); /* 1017h back to its default 0 */
    test_expect(&t, "704#00");
    test_advance(&t, 500000);
    test_expect_none(&t);
}
END_TEST

START_TEST(consumer_starts_at_first_heartbeat_and_reports_once)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 150, 4), 0);
    test_advance(&t, 1000000); /* not monitored before the first heartbeat */
    ck_assert_uint_eq(event_count, 0);
    test_rx(&t, "705#05");
    test_advance(&t, 100000);
    test_rx(&t, "705#05");
    test_advance(&t, 149999);
    ck_assert_uint_eq(event_count, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(events[0].producer, 5);
    ck_assert(events[0].lost);
    ck_assert_uint_eq(events[0].at, 1250000);
    test_advance(&t, 5000000);
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(t.node.heartbeat.consumer[0].state, 0x05);
    test_expect_none(&t);
}
END_TEST

START_TEST(consumer_rearmed_by_next_heartbeat)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    test_rx(&t, "705#7F");
    test_advance(&t, 100000);
    ck_assert_uint_eq(event_count, 1);
    test_advance(&t, 20000);
    test_rx(&t, "705#04");
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(events[1].producer, 5);
    ck_assert(!events[1].lost);
    test_rx(&t, "705#04"); /* no second "came back" */
    ck_assert_uint_eq(event_count, 2);
    test_advance(&t, 100000);
    ck_assert_uint_eq(event_count, 3);
    ck_assert(events[2].lost);
    ck_assert_uint_eq(events[2].at, 220000);
}
END_TEST

START_TEST(boot_up_is_a_sign_of_life)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    test_rx(&t, "705#05");
    test_advance(&t, 90000);
    test_rx(&t, "705#00");
    test_advance(&t, 99999);
    ck_assert_uint_eq(event_count, 0);
    ck_assert_uint_eq(t.node.heartbeat.consumer[0].state, 0x00);
    test_advance(&t, 1);
    ck_assert_uint_eq(event_count, 1);
    ck_assert(events[0].lost);
}
END_TEST

START_TEST(malformed_and_foreign_heartbeats_ignored)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    test_rx(&t, "705#R1");
    test_rx(&t, "705#0505");
    test_rx(&t, "705#");
    test_rx(&t, "706#05");
    test_advance(&t, 1000000);
    ck_assert_uint_eq(event_count, 0);
    ck_assert(!t.node.heartbeat.consumer[0].monitor.monitoring);
}
END_TEST

START_TEST(two_consumers)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00070000 | 300, 4), 0);
    test_rx(&t, "705#05");
    test_rx(&t, "707#05");
    test_advance(&t, 100000);
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(events[0].producer, 5);
    test_advance(&t, 200000);
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(events[1].producer, 7);
    ck_assert_uint_eq(events[1].at, 300000);
}
END_TEST

START_TEST(duplicate_entries_abort)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00050000 | 200, 4),
                      CO_SDO_ABORT_PARAM_INCOMPATIBLE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1016, 2), 0);
    /* Same node with time 0, or node-id 0, is an unused entry: accepted. */
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00050000, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 200, 4), 0);
    /* Rewriting the same entry is not a duplicate of itself. */
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 300, 4), 0);
    /* Disable the first, then the second may take the node. */
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00050000 | 200, 4), 0);
    /* Reserved bits 24..31 must be 0. */
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x01060000 | 100, 4), CO_SDO_ABORT_VALUE_RANGE);
}
END_TEST

START_TEST(unused_entries_do_not_monitor)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00000000 | 100, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00800000 | 100, 4), 0); /* node 128 */
    test_rx(&t, "700#05");
    test_rx(&t, "780#05");
    test_advance(&t, 1000000);
    ck_assert_uint_eq(event_count, 0);
}
END_TEST

START_TEST(rewriting_an_entry_restarts_monitoring)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    test_rx(&t, "705#05");
    test_advance(&t, 50000);
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 200, 4), 0);
    test_advance(&t, 1000000);
    ck_assert_uint_eq(event_count, 0);
    test_rx(&t, "705#05");
    test_advance(&t, 200000);
    ck_assert_uint_eq(event_count, 1);
}
END_TEST

START_TEST(consumers_reloaded_by_reset_communication)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 100, 4), 0);
    test_rx(&t, "705#05");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    test_advance(&t, 1000000);
    ck_assert_uint_eq(event_count, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1016, 1), 0);
}
END_TEST

/* CO_NODE_HEARTBEAT_GRID: the beats fall on the multiples of the period from time 0. */
static test_node_t other;
static memory_storage_t mem;
static co_storage_t storage;

static void start_on_grid(test_node_t *node, const co_storage_t *store)
{
    co_node_config_t config = {.node_id = 4,
                               .od = &test_od,
                               .storage = store,
                               .options = CO_NODE_HEARTBEAT_GRID,
                               .options_code = &co_node_options};
    test_node_start_config(node, &config);
}

static void setup_grid(void)
{
    memory_storage_init(&mem, &storage);
    start_on_grid(&t, &storage);
}

/* Each of `count` beats of `node`, `period` apart from `first`, and nothing in between. */
static void expect_beats(test_node_t *node, co_time_t first, co_time_t period, int count)
{
    test_advance(node, first - node->bus.now - 1);
    test_expect_none(node);
    for (int i = 0; i < count; i++) {
        test_advance(node, first + (co_time_t)i * period - node->bus.now);
        ck_assert_uint_eq(test_expect(node, "704#7F"), first + (co_time_t)i * period);
        test_advance(node, period - 1);
        test_expect_none(node);
    }
}

/* CiA 301: the protocol begins with the write; the first beat comes at the next multiple of the
 * period, sooner than one period after an off-grid write, never later. */
START_TEST(grid_first_beat_after_an_off_grid_write)
{
    test_advance(&t, 30000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    ck_assert_uint_eq(t.bus.deadline, 100000);
    expect_beats(&t, 100000, 100000, 5);
}
END_TEST

/* A write on a grid instant starts the period there: its first beat is one period later, not
 * at the write. Writing the running period again does not move the beats. */
START_TEST(grid_write_on_the_grid_and_same_value_again)
{
    test_advance(&t, 200000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_expect_none(&t);
    expect_beats(&t, 300000, 100000, 1);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "704#7F"), 400000);
    test_advance(&t, 50000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    expect_beats(&t, 500000, 100000, 3);
}
END_TEST

/* CiA 301: with 1017h stored, the boot-up is the first heartbeat and the next one is due within
 * one period: at the next grid instant after a boot-up at an off-grid time. */
START_TEST(grid_first_beat_after_boot_up)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x1010, 2, CO_STORE_SIGNATURE_SAVE, 4), 0);
    test_advance(&t, 1234567);
    test_drain(&t);
    test_rx(&t, "000#8104");
    ck_assert_uint_eq(test_expect(&t, "704#00"), 1234567);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 100);
    expect_beats(&t, 1300000, 100000, 3);
}
END_TEST

/* A new period starts on its own grid: 40 ms written at 250 ms beats at 280, 320, 360 ms; 30 ms
 * written at 370 ms beats at 390, 420 ms. */
START_TEST(grid_period_change)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    expect_beats(&t, 100000, 100000, 2);
    test_advance(&t, 250000 - t.bus.now);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 40, 2), 0);
    expect_beats(&t, 280000, 40000, 3);
    test_advance(&t, 370000 - t.bus.now);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 30, 2), 0);
    expect_beats(&t, 390000, 30000, 2);
}
END_TEST

/* A late process call sends the beat it missed and goes back to the grid. */
START_TEST(grid_late_call_returns_to_the_grid)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    t.bus.now = 350000;
    ck_assert_uint_eq(co_node_process(&t.node, 350000), 400000);
    ck_assert_uint_eq(test_expect(&t, "704#7F"), 350000);
    test_expect_none(&t);
}
END_TEST

/* Two nodes whose 1017h were written 40 ms apart beat at the same instants: one wake-up of a
 * runtime serves both. The other starts without the option for contrast. */
START_TEST(grid_two_nodes_written_at_different_times_beat_together)
{
    start_on_grid(&other, NULL);
    test_advance(&t, 30000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&other, 70000);
    ck_assert_uint_eq(test_write(&other, 0x1017, 0, 100, 2), 0);
    for (co_time_t at = 100000; at <= 1000000; at += 100000) {
        test_advance(&t, at - t.bus.now);
        test_advance(&other, at - other.bus.now);
        ck_assert_uint_eq(test_expect(&t, "704#7F"), at);
        ck_assert_uint_eq(test_expect(&other, "704#7F"), at);
        ck_assert_uint_eq(t.bus.deadline, other.bus.deadline);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("heartbeat");
    TCase *tc = tcase_create("heartbeat");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, producer_period_is_exact);
    tcase_add_test(tc, writing_1017_restarts_the_period);
    tcase_add_test(tc, producer_restarts_after_reset_communication);
    tcase_add_test(tc, consumer_starts_at_first_heartbeat_and_reports_once);
    tcase_add_test(tc, consumer_rearmed_by_next_heartbeat);
    tcase_add_test(tc, boot_up_is_a_sign_of_life);
    tcase_add_test(tc, malformed_and_foreign_heartbeats_ignored);
    tcase_add_test(tc, two_consumers);
    tcase_add_test(tc, duplicate_entries_abort);
    tcase_add_test(tc, unused_entries_do_not_monitor);
    tcase_add_test(tc, rewriting_an_entry_restarts_monitoring);
    tcase_add_test(tc, consumers_reloaded_by_reset_communication);
    suite_add_tcase(s, tc);
    TCase *grid = tcase_create("grid");
    tcase_add_checked_fixture(grid, setup_grid, NULL);
    tcase_add_test(grid, grid_first_beat_after_an_off_grid_write);
    tcase_add_test(grid, grid_write_on_the_grid_and_same_value_again);
    tcase_add_test(grid, grid_first_beat_after_boot_up);
    tcase_add_test(grid, grid_period_change);
    tcase_add_test(grid, grid_late_call_returns_to_the_grid);
    tcase_add_test(grid, grid_two_nodes_written_at_different_times_beat_together);
    suite_add_tcase(s, grid);
    return check_run_suite(s);
}
