/* SPDX-License-Identifier: Apache-2.0 */
/* The duplicate MAC ID check at start-up: two requests a second apart, online after two quiet
 * seconds; another node's request or response with this MAC ID keeps the node offline with the
 * Identity's minor recoverable fault and the NS LED solid red; online, other nodes' checks are
 * answered; bus off with and without BOI. */
#include "check_main.h"
#include "dn_bench.h"

static dn_bench_t b;
static const dn_stored_t defaults = {0, 0, false};

START_TEST(no_answer_goes_online)
{
    bench_init(&b, 63, defaults);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_OFF);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_OFF);
    dn_node_power_up(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    ck_assert_uint_eq(bench_expect(&b, "5FF#00F30078563412"), 0);
    ck_assert_uint_eq(b.deadline, 250000); /* the LED test's next step; the check at 1 s */
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_OFF);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
    bench_advance(&b, 999999);
    bench_expect_none(&b);
    bench_advance(&b, 1);
    ck_assert_uint_eq(bench_expect(&b, "5FF#00F30078563412"), 1000000);
    ck_assert_int_eq(b.node.link, DN_LINK_DUP_CHECK_2);
    bench_advance(&b, 999999);
    ck_assert_int_eq(b.node.link, DN_LINK_DUP_CHECK_2);
    bench_advance(&b, 1);
    ck_assert_int_eq(b.node.link, DN_LINK_ONLINE);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
    bench_expect_none(&b);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0030); /* no I/O connection */
}
END_TEST

/* The manual's start-up LED test ("performed during start-up, after module init is complete"),
 * 0.25 s steps: MS green, MS red, NS green, NS red, NS off (MS green from the third step on);
 * then the standard indication: NS off while the check runs, flashing green once online. Each
 * step is a deadline, so that an application samples every change. */
START_TEST(led_test_at_start_up)
{
    bench_init(&b, 63, defaults);
    dn_node_power_up(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    static const dn_led_t ms[] = {DN_LED_GREEN, DN_LED_RED, DN_LED_GREEN, DN_LED_GREEN,
                                  DN_LED_GREEN};
    static const dn_led_t ns[] = {DN_LED_OFF, DN_LED_OFF, DN_LED_GREEN, DN_LED_RED, DN_LED_OFF};
    for (size_t step = 0; step < 5; step++) {
        ck_assert_uint_eq(b.deadline, (step + 1) * 250000);
        ck_assert_int_eq(dn_node_ms_led(&b.node), ms[step]);
        ck_assert_int_eq(dn_node_ns_led(&b.node), ns[step]);
        bench_advance(&b, 250000);
    }
    /* 1.25 s: the standard indication, the check still running. */
    ck_assert_uint_eq(b.deadline, 2000000);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_OFF);
    bench_advance(&b, 750000);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
}
END_TEST

START_TEST(mac_25_check_frames)
{
    bench_init(&b, 25, defaults);
    dn_node_start(&b.node, b.now);
    bench_expect(&b, "4CF#00F30078563412");
}
END_TEST

/* What a runtime may route to the node: group 2 messages 2, 4, 5, 6, 7 of its MAC ID (then group
 * 3's of every MAC ID, test_ucmm.c), and an online node ignores the other group 2 messages of its
 * MAC ID (0, 1 and its own 3) and every group 2 frame of another MAC ID: they change nothing and
 * send nothing. */
START_TEST(consumed_ids_are_all_it_acts_on)
{
    uint16_t ids[DN_NODE_CONSUMED_IDS];
    bench_online(&b, 25);
    ck_assert_uint_eq(dn_node_consumed_ids(&b.node, ids), DN_NODE_CONSUMED_IDS);
    static const uint16_t mac_25[5] = {0x4CA, 0x4CC, 0x4CD, 0x4CE, 0x4CF};
    ck_assert_mem_eq(ids, mac_25, sizeof mac_25);
    bench_rx(&b, "4C8#004B03010100");
    bench_rx(&b, "4C9#004B03010100");
    bench_rx(&b, "4CB#004B03010100");
    bench_rx(&b, "4D6#004B03010100"); /* MAC ID 26's unconnected port */
    bench_rx(&b, "4D7#00F30078563412");
    bench_expect_none(&b);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
    bench_online(&b, 63);
    dn_node_consumed_ids(&b.node, ids);
    static const uint16_t mac_63[5] = {0x5FA, 0x5FC, 0x5FD, 0x5FE, 0x5FF};
    ck_assert_mem_eq(ids, mac_63, sizeof mac_63);
}
END_TEST

/* A node online with MAC ID 63 answers the check: the node stays offline. */
START_TEST(response_means_duplicate)
{
    bench_init(&b, 63, defaults);
    dn_node_power_up(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    bench_expect(&b, "5FF#00F30078563412");
    bench_advance(&b, 500000);
    bench_rx(&b, "5FF#80F300EFBEADDE");
    ck_assert_int_eq(b.node.link, DN_LINK_FAULTED);
    ck_assert_uint_eq(b.deadline, 750000); /* only the LED test's steps are left */
    bench_advance(&b, 5000000);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
    bench_expect_none(&b); /* no second request, never online */
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_RED);
    ck_assert_uint_eq(dn_node_identity_status(&b.node) & DN_STATUS_MINOR_RECOVERABLE,
                      DN_STATUS_MINOR_RECOVERABLE);
    /* Offline: an allocation is not answered. */
    bench_rx(&b, "5FE#014B03010101");
    bench_expect_none(&b);
}
END_TEST

/* Another node checking the same MAC ID at the same time (its request, during the second
 * wait): both are duplicates. */
START_TEST(request_during_check_means_duplicate)
{
    bench_init(&b, 63, defaults);
    dn_node_start(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    bench_advance(&b, 1500000);
    bench_expect(&b, "5FF#00F30078563412");
    bench_expect(&b, "5FF#00F30078563412");
    bench_rx(&b, "5FF#00F300EFBEADDE");
    bench_expect_none(&b);
    ck_assert_int_eq(b.node.link, DN_LINK_FAULTED);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_RED);
}
END_TEST

/* Checks of other MAC IDs, and frames of other lengths, change nothing. */
START_TEST(other_mac_ids_ignored)
{
    bench_init(&b, 63, defaults);
    dn_node_start(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    bench_rx(&b, "5F7#80F300EFBEADDE");
    bench_rx(&b, "5FF#80F300EFBEAD");
    bench_advance(&b, 2000000);
    ck_assert_int_eq(b.node.link, DN_LINK_ONLINE);
}
END_TEST

START_TEST(online_answers_checks)
{
    bench_online(&b, 63);
    bench_exchange(&b, "5FF#00F300EFBEADDE", "5FF#80F30078563412");
    bench_rx(&b, "5FF#80F300EFBEADDE"); /* a response: not answered, still online */
    bench_expect_none(&b);
    ck_assert_int_eq(b.node.link, DN_LINK_ONLINE);
}
END_TEST

START_TEST(bus_off_without_boi_stays_offline)
{
    bench_online(&b, 63);
    bench_rx(&b, "5FE#014B03010101");
    bench_expect(&b, "5FB#01CB00");
    dn_node_bus_off(&b.node, b.now);
    ck_assert_int_eq(b.node.link, DN_LINK_FAULTED);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_RED);
    ck_assert_uint_eq(b.node.bus_off_counter, 1);
    ck_assert_uint_eq(b.node.allocation, 0);
    bench_rx(&b, "5FF#00F300EFBEADDE"); /* faulted: another node's check is not answered */
    bench_expect_none(&b);
}
END_TEST

START_TEST(bus_off_with_boi_checks_again)
{
    bench_online(&b, 63);
    bench_rx(&b, "5FE#014B03010101");
    bench_expect(&b, "5FB#01CB00");
    bench_exchange(&b,
                   "5FC#0110030103"
                   "01",
                   "5FB#0190"); /* BOI = 1 */
    dn_node_bus_off(&b.node, b.now);
    b.deadline = dn_node_process(&b.node, b.now);
    bench_expect(&b, "5FF#00F30078563412");
    ck_assert_int_eq(b.node.link, DN_LINK_DUP_CHECK_1);
    /* On the bus again, not powered up: no LED test, the check's next request is the deadline. */
    ck_assert_uint_eq(b.deadline, b.now + 1000000);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_OFF);
    bench_advance(&b, 2000000);
    bench_expect(&b, "5FF#00F30078563412");
    ck_assert_int_eq(b.node.link, DN_LINK_ONLINE);
    ck_assert_uint_eq(b.node.bus_off_counter, 1);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet duplicate MAC ID check");
    TCase *tc = tcase_create("dup_mac");
    tcase_add_test(tc, no_answer_goes_online);
    tcase_add_test(tc, mac_25_check_frames);
    tcase_add_test(tc, consumed_ids_are_all_it_acts_on);
    tcase_add_test(tc, led_test_at_start_up);
    tcase_add_test(tc, response_means_duplicate);
    tcase_add_test(tc, request_during_check_means_duplicate);
    tcase_add_test(tc, other_mac_ids_ignored);
    tcase_add_test(tc, online_answers_checks);
    tcase_add_test(tc, bus_off_without_boi_stays_offline);
    tcase_add_test(tc, bus_off_with_boi_checks_again);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
