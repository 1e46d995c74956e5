/* SPDX-License-Identifier: Apache-2.0 */
/* SYNC: producer period and counter wrap, production only in Pre-operational and Operational,
 * 1005h/1019h parameter rules, the consumer's counter and its wrong-length emergency, and the
 * SYNC driving synchronous TPDOs. Frame-exact with injected time. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdlib.h>

#define MS 1000u

static test_node_t t;
static unsigned sync_calls;
static uint8_t sync_counter;

static void on_sync(co_node_t *node, uint8_t counter)
{
    (void)node;
    sync_calls++;
    sync_counter = counter;
}

static const co_app_hooks_t hooks = {.sync = on_sync};

static uint32_t write_param(uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    uint8_t data[4];
    co_put_u32(data, value);
    t.node.now = t.bus.now;
    uint32_t abort = co_od_write(&t.node, index, sub, data, len, CO_OD_ORIGIN_SDO);
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    return abort;
}

static void start(void)
{
    sync_calls = 0;
    sync_counter = 0xFF;
    test_node_start(&t, 4, &hooks, NULL);
}

/* Producer of a SYNC every `period_us`, with counter overflow `overflow` (0 = no counter). */
static void start_producer(uint32_t period_us, uint8_t overflow)
{
    start();
    ck_assert_uint_eq(write_param(0x1019, 0, overflow, 1), 0);
    ck_assert_uint_eq(write_param(0x1006, 0, period_us, 4), 0);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x40000080, 4), 0);
}

START_TEST(producer_period_and_counter_wrap)
{
    start_producer(10 * MS, 3);
    ck_assert_uint_eq(t.bus.deadline, 10 * MS);
    test_advance(&t, 45 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#01"), 10 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#02"), 20 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#03"), 30 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#01"), 40 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(sync_calls, 4);
    ck_assert_uint_eq(sync_counter, 1);
}
END_TEST

START_TEST(producer_without_counter)
{
    start_producer(2500, 0);
    test_advance(&t, 7500);
    ck_assert_uint_eq(test_expect(&t, "080#"), 2500);
    ck_assert_uint_eq(test_expect(&t, "080#"), 5000);
    ck_assert_uint_eq(test_expect(&t, "080#"), 7500);
    test_expect_none(&t);
    ck_assert_uint_eq(sync_counter, 0);
}
END_TEST

START_TEST(producer_stops_outside_pre_operational_and_operational)
{
    start_producer(10 * MS, 240);
    test_advance(&t, 20 * MS);
    test_expect(&t, "080#01");
    test_expect(&t, "080#02");
    test_advance(&t, 5 * MS);
    test_rx(&t, "000#0204");
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    test_advance(&t, 100 * MS);
    test_expect_none(&t);
    /* Back in Pre-operational: a new period, and the counter restarts at 1. */
    test_rx(&t, "000#8004");
    test_advance(&t, 10 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#01"), 135 * MS);
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000");
    test_advance(&t, 10 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#02"), 145 * MS);
}
END_TEST

START_TEST(late_runtime_gets_one_sync_not_a_burst)
{
    start_producer(10 * MS, 0);
    ck_assert_uint_eq(co_node_process(&t.node, 55 * MS), 65 * MS);
    test_expect(&t, "080#");
    test_expect_none(&t);
}
END_TEST

START_TEST(period_change_restarts_production)
{
    start_producer(10 * MS, 0);
    test_advance(&t, 15 * MS);
    test_expect(&t, "080#");
    ck_assert_uint_eq(write_param(0x1006, 0, 3 * MS, 4), 0);
    test_advance(&t, 3 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#"), 18 * MS);
    ck_assert_uint_eq(write_param(0x1006, 0, 0, 4), 0);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    test_advance(&t, 100 * MS);
    test_expect_none(&t);
}
END_TEST

START_TEST(overflow_value_rules)
{
    start();
    ck_assert_uint_eq(write_param(0x1019, 0, 1, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1019, 0, 241, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1019, 0, 255, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1019, 0, 2, 1), 0);
    ck_assert_uint_eq(write_param(0x1019, 0, 240, 1), 0);
    ck_assert_uint_eq(write_param(0x1019, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1006, 0, 1000, 4), 0);
    ck_assert_uint_eq(write_param(0x1019, 0, 10, 1), CO_SDO_ABORT_DATA_STATE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1019, 0), 0);
}
END_TEST

START_TEST(cob_id_rules)
{
    start();
    ck_assert_uint_eq(write_param(0x1005, 0, 0x20000080, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x00000880, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x81, 4), 0);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x40000081, 4), 0);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x40000082, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1005, 0), 0x40000081);
    /* Stopping production and changing the CAN-ID in one write is allowed. */
    ck_assert_uint_eq(write_param(0x1005, 0, 0x82, 4), 0);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x80000082, 4), 0);
    /* The consumer follows the CAN-ID. */
    test_rx(&t, "082#");
    ck_assert_uint_eq(sync_calls, 1);
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 1);
}
END_TEST

/* CiA 301 7.3.5: 1005h refuses a restricted CAN-ID at both edges of every range, whatever bits 30
 * and 31 say; the free CAN-IDs beside them are taken by a consumer and a producer. */
START_TEST(restricted_can_ids_at_every_edge)
{
    start();
    test_rx(&t, "604#23051000FF050000"); /* 1005h = 5FFh */
    test_expect(&t, "584#8005100030000906");
    for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++) {
        uint32_t id = test_restricted_can_id[i];
        ck_assert_uint_eq(write_param(0x1005, 0, id, 4), CO_SDO_ABORT_VALUE_RANGE);
        ck_assert_uint_eq(write_param(0x1005, 0, 0x40000000u | id, 4), CO_SDO_ABORT_VALUE_RANGE);
        ck_assert_uint_eq(write_param(0x1005, 0, 0x80000000u | id, 4), CO_SDO_ABORT_VALUE_RANGE);
    }
    ck_assert_int_eq(co_od_value(&t.node, 0x1005, 0), 0x80);
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 1);
    for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++) {
        uint32_t id = test_free_can_id[i];
        ck_assert_uint_eq(write_param(0x1005, 0, id, 4), 0);
        ck_assert_uint_eq(write_param(0x1005, 0, 0x40000000u | id, 4), 0);
        ck_assert_uint_eq(write_param(0x1005, 0, 0x80000000u | id, 4), 0);
    }
}
END_TEST

/* A dictionary with 1006h but without the producer's code (co_od_t.sync_producer NULL: a table
 * written by hand) refuses bit 30 as one without 1006h does, and never produces. */
START_TEST(producer_refused_without_its_code)
{
    static co_od_t od;
    od = test_od;
    od.sync_producer = NULL;
    test_node_start_od(&t, &od, 4, &hooks, NULL);
    ck_assert_uint_eq(write_param(0x1006, 0, 1000, 4), 0);
    test_rx(&t, "604#2305100080000040"); /* 1005h = 40000080h */
    test_expect(&t, "584#8005100030000906");
    ck_assert_int_eq(co_od_value(&t.node, 0x1005, 0), 0x80);
    test_advance(&t, 100 * MS);
    test_expect_none(&t);
}
END_TEST

/* CiA 301 7.5.2.5/7.5.2.6: without 1006h nothing could be produced, so bit 30 is refused; the
 * consumer works as before and no SYNC is ever sent. */
START_TEST(producer_refused_without_1006)
{
    sync_calls = 0;
    test_node_start_od(&t, test_od_without(0x1006), 4, &hooks, NULL);
    test_rx(&t, "604#2305100080000040"); /* 1005h = 40000080h */
    test_expect(&t, "584#8005100030000906");
    ck_assert_uint_eq(write_param(0x1005, 0, 0x40000081, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1005, 0, 0xC0000080, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1005, 0), 0x80);
    ck_assert_uint_eq(write_param(0x1006, 0, 1000, 4), CO_SDO_ABORT_NO_OBJECT);
    ck_assert_uint_eq(write_param(0x1005, 0, 0x81, 4), 0);
    test_rx(&t, "081#");
    ck_assert_uint_eq(sync_calls, 1);
    test_advance(&t, 10000 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

START_TEST(consumer_counter_and_hook)
{
    start();
    ck_assert_uint_eq(write_param(0x1019, 0, 5, 1), 0);
    test_rx(&t, "080#04");
    ck_assert_uint_eq(sync_calls, 1);
    ck_assert_uint_eq(sync_counter, 4);
    test_rx(&t, "080#R");
    ck_assert_uint_eq(sync_calls, 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(consumer_wrong_length_emcy_8240)
{
    start();
    test_rx(&t, "080#05");
    ck_assert_uint_eq(sync_calls, 0);
    test_expect(&t, "084#4082110100000000");
    test_rx(&t, "080#05");
    test_expect_none(&t);
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 1);
    test_expect(&t, "084#0000000000000000");
    ck_assert_uint_eq(write_param(0x1019, 0, 2, 1), 0);
    test_rx(&t, "080#");
    test_expect(&t, "084#4082110001000000");
    ck_assert_uint_eq(sync_calls, 1);
}
END_TEST

/* No SYNC within 1.5 x 1006h of the last one: EMCY 8100h once (D-SYNC-TIMEOUT), its reset at the
 * next SYNC; not watched before the first SYNC, nor in Stopped, nor by the producer. */
START_TEST(consumer_timeout_emcy_8100)
{
    start();
    ck_assert_uint_eq(write_param(0x1006, 0, 10 * MS, 4), 0);
    test_advance(&t, 50 * MS);
    test_expect_none(&t);
    test_rx(&t, "080#"); /* at 50 ms */
    test_advance(&t, 15 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 100 * MS + 1);
    ck_assert_uint_eq(test_expect(&t, "084#0081110000000000"), 65 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(co_od_value(&t.node, 0x1001, 0), 0x11);
    test_rx(&t, "080#"); /* at 165 ms */
    ck_assert_uint_eq(test_expect(&t, "084#0000000000000000"), 165 * MS);
    test_advance(&t, 14 * MS);
    test_rx(&t, "080#"); /* in time: the watch moves on */
    test_advance(&t, 15 * MS - 1);
    test_expect_none(&t);
    test_rx(&t, "000#0204"); /* Stopped */
    test_advance(&t, 100 * MS);
    test_rx(&t, "000#8004");
    test_advance(&t, 100 * MS);
    test_expect_none(&t);
    /* A producer watches no SYNC, neither its own nor one received. */
    ck_assert_uint_eq(write_param(0x1005, 0, 0x40000080, 4), 0);
    co_time_t from = t.bus.now;
    test_rx(&t, "080#");
    test_advance(&t, 100 * MS);
    for (co_time_t n = 1; n <= 10; n++)
        ck_assert_uint_eq(test_expect(&t, "080#"), from + n * 10 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(co_od_value(&t.node, 0x1001, 0), 0);
}
END_TEST

/* A SYNC in time moves the armed watch later: the services keep their deadline (the watch's
 * former one, looked at once early), so that a SYNC does not run every service; the time-out
 * still comes 15 ms after the last SYNC. */
START_TEST(sync_in_time_reschedules_no_service)
{
    start();
    ck_assert_uint_eq(write_param(0x1006, 0, 10 * MS, 4), 0);
    test_rx(&t, "080#");
    ck_assert_uint_eq(t.bus.deadline, t.bus.now + 15 * MS);
    test_advance(&t, 10 * MS);
    co_frame_t sync = test_frame("080#");
    co_node_receive(&t.node, &sync, t.bus.now);
    ck_assert(!t.node.schedule_changed);
    co_time_t last = t.bus.now;
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    test_advance(&t, 15 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "084#0081110000000000"), last + 15 * MS);
    test_expect_none(&t);
}
END_TEST

/* Issue 7, item 7, with its frames (node 5): reset communication ends the SYNC length error
 * together with its EMCY, so 1001h does not keep bits that no correct SYNC would ever clear, and
 * the next wrong SYNC raises the EMCY again. */
START_TEST(sync_length_error_ends_with_reset_communication)
{
    uint32_t reg;
    sync_calls = 0;
    test_node_start(&t, 5, &hooks, NULL);
    test_rx(&t, "080#01");
    test_expect(&t, "085#4082110100000000");
    test_rx(&t, "000#8205");
    test_expect(&t, "705#00");
    ck_assert_uint_eq(test_sdo_read(&t, 0x1001, 0, &reg), 0);
    ck_assert_uint_eq(reg, 0);
    test_rx(&t, "080#");
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 2);
    test_rx(&t, "080#01");
    test_expect(&t, "085#4082110100000000");
    test_rx(&t, "080#");
    test_expect(&t, "085#0000000000000000");
    test_expect_none(&t);
}
END_TEST

/* The service keeps 1005h and 1019h in its own state: a write of either and a reset, which
 * restores their defaults, take effect on the next SYNC. */
START_TEST(parameters_follow_writes_and_resets)
{
    start();
    test_rx(&t, "604#2305100081000000"); /* 1005h = 081h */
    test_expect(&t, "584#6005100000000000");
    test_rx(&t, "604#2F19100003000000"); /* 1019h = 3 */
    test_expect(&t, "584#6019100000000000");
    test_rx(&t, "080#02");
    ck_assert_uint_eq(sync_calls, 0);
    test_rx(&t, "081#02");
    ck_assert_uint_eq(sync_calls, 1);
    ck_assert_uint_eq(sync_counter, 2);
    test_expect_none(&t);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    test_rx(&t, "081#");
    ck_assert_uint_eq(sync_calls, 1);
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 2);
    ck_assert_uint_eq(sync_counter, 0);
    test_expect_none(&t);
}
END_TEST

START_TEST(consumer_ignored_when_stopped)
{
    start();
    test_rx(&t, "000#0204");
    test_rx(&t, "080#");
    ck_assert_uint_eq(sync_calls, 0);
}
END_TEST

START_TEST(produced_sync_drives_synchronous_tpdo)
{
    start_producer(10 * MS, 0);
    ck_assert_uint_eq(write_param(0x1800, 5, 0, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, 1, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000");
    test_advance(&t, 20 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#"), 10 * MS);
    ck_assert_uint_eq(test_expect(&t, "284#00000000"), 10 * MS);
    ck_assert_uint_eq(test_expect(&t, "080#"), 20 * MS);
    ck_assert_uint_eq(test_expect(&t, "284#00000000"), 20 * MS);
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sync");
    TCase *tc = tcase_create("sync");
    tcase_add_test(tc, producer_period_and_counter_wrap);
    tcase_add_test(tc, producer_without_counter);
    tcase_add_test(tc, producer_stops_outside_pre_operational_and_operational);
    tcase_add_test(tc, late_runtime_gets_one_sync_not_a_burst);
    tcase_add_test(tc, period_change_restarts_production);
    tcase_add_test(tc, overflow_value_rules);
    tcase_add_test(tc, cob_id_rules);
    tcase_add_test(tc, restricted_can_ids_at_every_edge);
    tcase_add_test(tc, producer_refused_without_1006);
    tcase_add_test(tc, producer_refused_without_its_code);
    tcase_add_test(tc, consumer_counter_and_hook);
    tcase_add_test(tc, consumer_wrong_length_emcy_8240);
    tcase_add_test(tc, sync_length_error_ends_with_reset_communication);
    tcase_add_test(tc, parameters_follow_writes_and_resets);
    tcase_add_test(tc, consumer_ignored_when_stopped);
    tcase_add_test(tc, consumer_timeout_emcy_8100);
    tcase_add_test(tc, sync_in_time_reschedules_no_service);
    tcase_add_test(tc, produced_sync_drives_synchronous_tpdo);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
