/* SPDX-License-Identifier: Apache-2.0 */
/* How a connection ends: every way an Established connection stops carrying the master's
 * messages (its watchdog, a Release, bus off with and without BOI, the node leaving the bus or
 * starting again) is told to the application once, with the instance and the cause, the I/O
 * connections before the explicit one; connections that never were Established, and one whose
 * end was told already (deferred delete, Timed out), are not told again. */
#include "check_main.h"
#include "dn_bench.h"

static dn_bench_t b;

/* MAC ID 63, the scanner at 1: explicit and polled allocated, the poll at 96 ms (a watchdog of
 * 384 ms) and one poll answered. */
static void setup(void)
{
    bench_online(&b, 63);
    bench_exchange(&b, "5FE#014B03010301", "5FB#01CB00");
    bench_exchange(&b, "5FC#01100502096000", "5FB#01906000");
    bench_exchange(&b, "5FD#0100DC05", "3FF#00000000");
}

START_TEST(explicit_watchdog_auto_delete)
{
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_RELEASED});
    /* 2504 ms x 4 after the last request. */
    bench_advance(&b, 10015999);
    bench_expect_no_end(&b);
    bench_advance(&b, 1);
    bench_expect_ends(&b, {DN_CONN_EXPLICIT, DN_END_TIMEOUT});
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_EXPLICIT), DN_CONN_NON_EXISTENT);
    bench_advance(&b, 20000000);
    bench_expect_no_end(&b);
}
END_TEST

/* Deferred delete: told when the watchdog expires, not again when the I/O release deletes it. */
START_TEST(explicit_deferred_delete_told_once)
{
    bench_exchange(&b, "5FC#011005010C03", "5FB#0190");       /* timeout action: deferred delete */
    bench_exchange(&b, "5FC#01100502090000", "5FB#01900000"); /* the poll: no watchdog */
    bench_advance(&b, 10016000);
    bench_expect_ends(&b, {DN_CONN_EXPLICIT, DN_END_TIMEOUT});
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_EXPLICIT), DN_CONN_DEFERRED_DELETE);
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_RELEASED});
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_EXPLICIT), DN_CONN_NON_EXISTENT);
}
END_TEST

START_TEST(release_of_both)
{
    bench_exchange(&b, "5FC#014C030103", "5FB#01CC");
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_RELEASED}, {DN_CONN_EXPLICIT, DN_END_RELEASED});
    ck_assert_uint_eq(b.event_count, 3); /* established, run, released */
    ck_assert_int_eq(b.events[2], DN_IO_RELEASED);
}
END_TEST

/* Timed out is its end: a release afterwards tells nothing more of instance 2. */
START_TEST(poll_timeout_then_release)
{
    bench_advance(&b, 384000);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_TIMEOUT});
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    bench_expect_no_end(&b);
}
END_TEST

START_TEST(cos_producer_released)
{
    bench_exchange(&b, "5FE#014B03011001", "5FB#01CB00");
    bench_rx(&b, "5FC#0110050409E803");
    bench_expect(&b, "5FB#0190E803");
    bench_expect(&b, "37F#00000000");
    bench_exchange(&b, "5FE#014C030110", "5FB#01CC");
    bench_expect_ends(&b, {DN_CONN_COS_CYCLIC, DN_END_RELEASED});
}
END_TEST

START_TEST(bus_off_without_boi)
{
    dn_node_bus_off(&b.node, b.now);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_BUS_OFF}, {DN_CONN_EXPLICIT, DN_END_BUS_OFF});
    ck_assert_int_eq(b.node.link, DN_LINK_FAULTED);
    bench_rx(&b, "5FD#0100DC05");
    bench_expect_none(&b);
    bench_advance(&b, 20000000);
    bench_expect_no_end(&b);
}
END_TEST

START_TEST(bus_off_with_boi)
{
    bench_exchange(&b, "5FC#011003010301", "5FB#0190"); /* BOI = 1 */
    dn_node_bus_off(&b.node, b.now);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_BUS_OFF}, {DN_CONN_EXPLICIT, DN_END_BUS_OFF});
    bench_expect(&b, "5FF#00F30078563412"); /* on the bus again, nothing allocated */
    ck_assert_uint_eq(b.node.allocation, 0);
}
END_TEST

/* Leaving the bus: the connections end, nothing is sent or served until the next start, which
 * has nothing left to end. */
START_TEST(stop_and_start_again)
{
    dn_node_stop(&b.node, b.now);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_OFFLINE}, {DN_CONN_EXPLICIT, DN_END_OFFLINE});
    ck_assert_int_eq(b.node.link, DN_LINK_OFF);
    ck_assert_uint_eq(dn_node_process(&b.node, b.now), CO_TIME_NEVER);
    bench_rx(&b, "5FE#014B03010301");
    bench_expect_none(&b);
    dn_node_start(&b.node, b.now);
    bench_expect_no_end(&b);
    bench_expect(&b, "5FF#00F30078563412");
}
END_TEST

START_TEST(start_of_a_started_node)
{
    dn_node_start(&b.node, b.now);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_OFFLINE}, {DN_CONN_EXPLICIT, DN_END_OFFLINE});
    bench_expect(&b, "5FF#00F30078563412");
}
END_TEST

/* A connection still configuring never carried anything: its going is not an end. */
START_TEST(configuring_is_not_told)
{
    bench_exchange(&b, "5FE#014B03011001", "5FB#01CB00"); /* COS: instance 4 configuring */
    dn_node_bus_off(&b.node, b.now);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_BUS_OFF}, {DN_CONN_EXPLICIT, DN_END_BUS_OFF});
}
END_TEST

START_TEST(connection_state_by_instance)
{
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_EXPLICIT), DN_CONN_ESTABLISHED);
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_POLL), DN_CONN_ESTABLISHED);
    ck_assert_int_eq(dn_node_connection_state(&b.node, DN_CONN_COS_CYCLIC), DN_CONN_NON_EXISTENT);
    ck_assert_int_eq(dn_node_connection_state(&b.node, 3), DN_CONN_NON_EXISTENT);
    ck_assert_int_eq(dn_node_connection_state(&b.node, 0), DN_CONN_NON_EXISTENT);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet connection ends");
    TCase *tc = tcase_create("ends");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, explicit_watchdog_auto_delete);
    tcase_add_test(tc, explicit_deferred_delete_told_once);
    tcase_add_test(tc, release_of_both);
    tcase_add_test(tc, poll_timeout_then_release);
    tcase_add_test(tc, cos_producer_released);
    tcase_add_test(tc, bus_off_without_boi);
    tcase_add_test(tc, bus_off_with_boi);
    tcase_add_test(tc, stop_and_start_again);
    tcase_add_test(tc, start_of_a_started_node);
    tcase_add_test(tc, configuring_is_not_told);
    tcase_add_test(tc, connection_state_by_instance);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
