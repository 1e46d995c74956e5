/* SPDX-License-Identifier: Apache-2.0 */
/* Node guarding (toggle sequence, state bytes, DLC 0 or 1), life guarding (one event per loss,
 * resume, restart on 100Ch/100Dh writes) and the exclusion by the heartbeat producer. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdlib.h>

static test_node_t t;

#define HOOK_LOG 16
static struct {
    bool lost;
    co_time_t at;
} events[HOOK_LOG];
static size_t event_count;

static void on_guarding(co_node_t *node, bool lost)
{
    ck_assert_uint_lt(event_count, HOOK_LOG);
    events[event_count].lost = lost;
    events[event_count].at = node->now;
    event_count++;
}

static const co_app_hooks_t hooks = {.guarding = on_guarding};

static void setup(void)
{
    event_count = 0;
    test_node_start(&t, 4, &hooks, NULL);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
}

/* Life time 2 s: guard time 500 ms x factor 4, as in the ATV312 manual's example. */
static void configure_life_time(void)
{
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 500, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x100D, 0, 4, 1), 0);
}

START_TEST(toggle_sequence_and_state_bytes)
{
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_rx(&t, "704#R1");
    test_expect(&t, "704#FF");
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_rx(&t, "000#0104");
    test_rx(&t, "704#R");
    test_expect(&t, "704#85");
    test_rx(&t, "000#0204");
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_rx(&t, "704#R");
    test_expect(&t, "704#84");
    test_expect_none(&t);
}
END_TEST

START_TEST(toggle_reset_by_reset_communication_only)
{
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_rx(&t, "000#0104"); /* state changes keep the toggle */
    test_rx(&t, "000#8004");
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
}
END_TEST

START_TEST(malformed_requests_ignored)
{
    test_rx(&t, "704#R2");
    test_rx(&t, "704#R8");
    test_rx(&t, "705#R");
    test_rx(&t, "704#00"); /* a data frame is not a request */
    test_expect_none(&t);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F"); /* toggle untouched by the ignored frames */
}
END_TEST

START_TEST(life_guarding_event_once_and_resume)
{
    configure_life_time();
    test_advance(&t, 10000000); /* not started before the first request */
    ck_assert_uint_eq(event_count, 0);
    co_time_t start = t.bus.now;
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_advance(&t, 1500000);
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    test_advance(&t, 1999999);
    ck_assert_uint_eq(event_count, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(event_count, 1);
    ck_assert(events[0].lost);
    ck_assert_uint_eq(events[0].at, start + 3500000);
    test_advance(&t, 10000000);
    ck_assert_uint_eq(event_count, 1);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    ck_assert_uint_eq(event_count, 2);
    ck_assert(!events[1].lost);
    test_advance(&t, 2000000);
    ck_assert_uint_eq(event_count, 3);
    ck_assert(events[2].lost);
}
END_TEST

START_TEST(no_life_guarding_with_zero_life_time)
{
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 500, 2), 0);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_advance(&t, 10000000);
    ck_assert_uint_eq(event_count, 0);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

START_TEST(parameter_writes_restart_life_timer)
{
    configure_life_time();
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_advance(&t, 1900000);
    ck_assert_uint_eq(test_write(&t, 0x100D, 0, 2, 1), 0); /* life time 1 s from now */
    test_advance(&t, 999999);
    ck_assert_uint_eq(event_count, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(events[0].at, 2900000);
    /* While lost, a write does not arm a new event. */
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 100, 2), 0);
    test_advance(&t, 10000000);
    ck_assert_uint_eq(event_count, 1);
    /* A write of 0 stops life guarding. */
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 0, 2), 0);
    test_advance(&t, 10000000);
    ck_assert_uint_eq(event_count, 2);
    ck_assert(!events[1].lost);
}
END_TEST

START_TEST(heartbeat_excludes_guarding)
{
    configure_life_time();
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_advance(&t, 1000000);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 1000, 2), 0);
    test_rx(&t, "704#R"); /* ignored: no reply */
    test_expect_none(&t);
    test_advance(&t, 1000000);
    test_expect(&t, "704#7F"); /* the heartbeat */
    test_advance(&t, 5000000);
    ck_assert_uint_eq(event_count, 0); /* life guarding stopped with heartbeat on */
    test_drain(&t);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 0, 2), 0);
    test_advance(&t, 5000000);
    ck_assert_uint_eq(event_count, 0); /* waits for the next request */
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF"); /* the toggle continues */
    test_advance(&t, 2000000);
    ck_assert_uint_eq(event_count, 1);
}
END_TEST

START_TEST(atv312_guard_time_frames)
{
    /* T31-12..15: guard time 500 ms and life time factor 4 written by expedited SDO. */
    test_rx(&t, "604#2B0C1000F4010000");
    test_expect(&t, "584#600C100000000000");
    test_rx(&t, "604#2F0D100004000000");
    test_expect(&t, "584#600D100000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x100D, 0), 4);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_advance(&t, 2000000);
    ck_assert_uint_eq(event_count, 1);
}
END_TEST

/* 100Eh moves node guarding, request and reply, to its CAN-ID; boot-up and heartbeat stay on
 * 700h + node-id; reset communication brings back the default. */
START_TEST(cob_id_100e_moves_guarding)
{
    configure_life_time();
    test_rx(&t, "604#230E100023010000"); /* 100Eh = 123h */
    test_expect(&t, "584#600E100000000000");
    test_rx(&t, "704#R");
    test_expect_none(&t);
    test_rx(&t, "123#R");
    test_expect(&t, "123#7F");
    test_rx(&t, "123#R1");
    test_expect(&t, "123#FF");
    test_advance(&t, 2000000); /* life guarding runs on the new CAN-ID */
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&t, 100000);
    test_expect(&t, "704#7F");
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 0, 2), 0);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x100E, 0), 0x704);
    test_rx(&t, "123#R");
    test_expect_none(&t);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
}
END_TEST

/* 100Eh holds an 11-bit CAN-ID: any of bits 11-31 set is refused with 0x06090030. */
START_TEST(cob_id_100e_write_rules)
{
    test_rx(&t, "604#230E100000080000"); /* 100Eh = 800h */
    test_expect(&t, "584#800E100030000906");
    static const uint32_t refused[] = {0x00000800, 0x00010704, 0x20000704, 0x40000704, 0x80000704};
    for (size_t i = 0; i < sizeof(refused) / sizeof(refused[0]); i++)
        ck_assert_uint_eq(test_write(&t, 0x100E, 0, refused[i], 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x100E, 0), 0x704);
    ck_assert_uint_eq(test_write(&t, 0x100E, 0, 0x7FF, 4), 0);
    test_rx(&t, "7FF#R");
    test_expect(&t, "7FF#7F");
}
END_TEST

/* A dictionary without 100Eh guards on 700h + node-id. */
START_TEST(without_100e_guarding_on_700h_plus_node_id)
{
    test_node_start_od(&t, test_od_without(0x100E), 5, &hooks, NULL);
    test_rx(&t, "705#R");
    test_expect(&t, "705#7F");
    ck_assert_uint_eq(test_write(&t, 0x100E, 0, 0x123, 4), CO_SDO_ABORT_NO_OBJECT);
    test_rx(&t, "123#R");
    test_rx(&t, "704#R");
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("guarding");
    TCase *tc = tcase_create("guarding");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, toggle_sequence_and_state_bytes);
    tcase_add_test(tc, toggle_reset_by_reset_communication_only);
    tcase_add_test(tc, malformed_requests_ignored);
    tcase_add_test(tc, life_guarding_event_once_and_resume);
    tcase_add_test(tc, no_life_guarding_with_zero_life_time);
    tcase_add_test(tc, parameter_writes_restart_life_timer);
    tcase_add_test(tc, heartbeat_excludes_guarding);
    tcase_add_test(tc, atv312_guard_time_frames);
    tcase_add_test(tc, cob_id_100e_moves_guarding);
    tcase_add_test(tc, cob_id_100e_write_rules);
    tcase_add_test(tc, without_100e_guarding_on_700h_plus_node_id);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
