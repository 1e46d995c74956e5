/* SPDX-License-Identifier: Apache-2.0 */
/* The UCMM and the explicit server instances 10-14 (the Altivar 312 DeviceNet manual's Connection
 * object: "Instances 10-14 = Explicit server instances", Initial Comm Characteristics 33, transport
 * class 3 server), frame for frame on the bench's node at MAC ID 25: Open Explicit Messaging
 * Connection on group 3 message 6 (781h from MAC ID 1), its answer on group 3 message 5 (759h),
 * requests on the connection's group 3 IDs (641h the client's message ID 1, 619h the server's
 * message ID 0) with fragmentation, the duplicate Open, the sixth Open, Close, the watchdog's auto
 * delete, and the ends told to the application (docs/decisions.md, D-DEVICENET-UCMM). */
#include "check_main.h"
#include "dn_bench.h"

static dn_bench_t b;

static void setup(void)
{
    memset(&b, 0, sizeof b);
    bench_online(&b, 25);
}

/* Open by MAC ID 1, group 3, its source message ID 1: instance 10, server message ID 0. */
static void open_instance_10(void)
{
    bench_exchange(&b, "781#194B0031", "759#01CB00100A00");
}

START_TEST(open_then_get_and_set_on_the_connection)
{
    open_instance_10();
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_GREEN);
    ck_assert_uint_eq(dn_node_connection_state(&b.node, 10), DN_CONN_ESTABLISHED);
    /* Get the vendor ID; the header carries the client's MAC ID and the request's XID. */
    bench_exchange(&b, "641#190E010101", "619#018EF300");
    bench_exchange(&b, "641#590E010101", "619#418EF300");
    /* Instance 10's attributes as the manual's table of instances 1, 10-14 has them. */
    static const char *const attributes[][2] = {
        {"641#190E050A01", "619#018E03"},   {"641#190E050A02", "619#018E00"},
        {"641#190E050A03", "619#018E83"},   {"641#190E050A04", "619#018E1906"},
        {"641#190E050A05", "619#018E4106"}, {"641#190E050A06", "619#018E33"},
        {"641#190E050A07", "619#018E4000"}, {"641#190E050A08", "619#018E4000"},
        {"641#190E050A09", "619#018EC809"}, {"641#190E050A0C", "619#018E01"},
        {"641#190E050A0D", "619#018E0000"}, {"641#190E050A0E", "619#018E"},
        {"641#190E050A0F", "619#018E0000"}, {"641#190E050A10", "619#018E"},
        {"641#190E050A11", "619#018E0000"}, {"641#190E050A12", "619#018E00"},
    };
    for (size_t i = 0; i < sizeof attributes / sizeof attributes[0]; i++)
        bench_exchange(&b, attributes[i][0], attributes[i][1]);
    /* Set: the expected packet rate (rounded to 8 ms), Run1 of the application's class; the
     * watchdog timeout action is instance 1's only ("Only settable for instance 1"). */
    bench_exchange(&b, "641#1910050A09E903", "619#0190F003");
    bench_exchange(&b, "641#191029010301", "619#0190");
    ck_assert_uint_eq(b.run1, 1);
    bench_exchange(&b, "641#1910050A0C03", "619#01940EFF");
    /* The product name, 8 bytes of response: two fragments, acknowledged on the connection. */
    bench_rx(&b, "641#190E010107");
    bench_expect(&b, "619#81008E0641545633");
    bench_expect_none(&b);
    bench_exchange(&b, "641#99C000", "619#81813132");
    bench_rx(&b, "641#99C100");
    bench_expect_none(&b);
    ck_assert(!b.node.messages[1].tx.active);
    /* A fragmented request (a Set of the assembly's 8 bytes of body), acknowledged. */
    bench_exchange(&b, "641#9900100415036100", "619#81C000");
    bench_rx(&b, "641#9981B004");
    bench_expect(&b, "619#81C100");
    bench_expect(&b, "619#0190");
    bench_expect_none(&b);
    /* The predefined set is there as before, beside it. */
    bench_exchange(&b, "4CE#014B03010101", "4CB#01CB00");
    bench_exchange(&b, "4CC#010E050A01", "4CB#018E03");
    bench_exchange(&b, "4CC#010E050B01", "4CB#019416FF"); /* not open */
}
END_TEST

/* The Open asked again (its response lost) is answered with the connection it opened: the same
 * response, no second connection; another message ID of the client is another connection; a
 * sixth is 0x02 resource unavailable; one closed is free again. */
START_TEST(duplicate_and_sixth_open)
{
    open_instance_10();
    open_instance_10();
    ck_assert_uint_eq(dn_node_connection_state(&b.node, 11), DN_CONN_NON_EXISTENT);
    bench_exchange(&b, "781#194B0032", "759#01CB00210B00");
    bench_exchange(&b, "781#594B0033", "759#41CB00320C00");
    bench_exchange(&b, "781#194B0034", "759#01CB00430D00");
    bench_exchange(&b, "782#194B0030", "759#02CB00040E00"); /* MAC ID 2's message ID 0 */
    bench_exchange(&b, "782#194B0031", "759#029402FF");
    /* Each client's requests on its own connection: MAC ID 2's message ID 0 is instance 14,
     * answered with the server's message ID 4. */
    bench_exchange(&b, "602#190E010101", "719#028EF300");
    bench_exchange(&b, "641#190E010101", "619#018EF300");
    bench_exchange(&b, "781#194C0C00", "759#01CC");
    bench_exchange(&b, "782#194B0031", "759#02CB00120C00");
    bench_expect_ends(&b, {12, DN_END_RELEASED});
}
END_TEST

/* Refusals of the UCMM: another group than 3 (19 4B 00 03 asks for group 1, message ID 3), a
 * message ID of the UCMM's own (5, 6) or the invalid 7, a short or long request, another service;
 * a request naming another node is not this node's. */
START_TEST(open_refusals)
{
    bench_exchange(&b, "781#194B0003", "759#019420FF");
    bench_exchange(&b, "781#194B0013", "759#019420FF");
    bench_exchange(&b, "781#194B0035", "759#019420FF");
    bench_exchange(&b, "781#194B0037", "759#019420FF");
    bench_exchange(&b, "781#194B00", "759#019413FF");
    bench_exchange(&b, "781#194B003100", "759#019415FF");
    bench_exchange(&b, "781#190E010101", "759#019408FF");
    bench_rx(&b, "781#184B0031");
    bench_rx(&b, "781#994B0031"); /* a fragment: the UCMM has none */
    bench_rx(&b, "759#01CB00100A00");
    bench_expect_none(&b);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
    bench_expect_stats(&b, .explicit_requests = 7, .error_responses = 7);
}
END_TEST

/* Close: by the client that opened it, the application told as of a release; the connection's
 * requests are then nobody's; closing it again, closing another's, instance 1 or one out of
 * 10-14 is refused. */
START_TEST(close)
{
    open_instance_10();
    bench_exchange(&b, "782#194C0A00", "759#02940CFF");
    bench_exchange(&b, "781#194C0100", "759#019416FF");
    bench_exchange(&b, "781#194C0F00", "759#019416FF");
    bench_exchange(&b, "781#194C0A", "759#019413FF");
    bench_exchange(&b, "781#194C0A00", "759#01CC");
    bench_expect_ends(&b, {10, DN_END_RELEASED});
    bench_rx(&b, "641#190E010101");
    bench_expect_none(&b);
    bench_exchange(&b, "781#194C0A00", "759#019416FF");
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
}
END_TEST

/* The watchdog: the expected packet rate 2504 ms x 4; a request starts it again; then auto delete
 * (the timeout action of 10-14), counted and told. */
START_TEST(watchdog_deletes)
{
    open_instance_10();
    bench_advance(&b, 10016000 - 1);
    bench_exchange(&b, "641#190E010101", "619#018EF300");
    bench_advance(&b, 10016000 - 1);
    ck_assert_uint_eq(dn_node_connection_state(&b.node, 10), DN_CONN_ESTABLISHED);
    bench_expect_no_end(&b);
    bench_advance(&b, 1);
    ck_assert_uint_eq(dn_node_connection_state(&b.node, 10), DN_CONN_NON_EXISTENT);
    bench_expect_ends(&b, {10, DN_END_TIMEOUT});
    bench_rx(&b, "641#190E010101");
    bench_expect_none(&b);
    bench_expect_stats(&b, .explicit_requests = 2, .timeouts = 1);
    open_instance_10(); /* open again */
}
END_TEST

/* A restart ends the UCMM's connections as the predefined set's (DN_END_OFFLINE); the node
 * routes group 3 messages 0-4 and 6 of every source MAC ID. */
START_TEST(restart_ends_them_and_consumed_ids)
{
    open_instance_10();
    bench_exchange(&b, "781#194B0032", "759#01CB00210B00");
    dn_node_start(&b.node, b.now);
    bench_expect_ends(&b, {10, DN_END_OFFLINE}, {11, DN_END_OFFLINE});
    uint16_t ids[DN_NODE_CONSUMED_IDS];
    ck_assert_uint_eq(dn_node_consumed_ids(&b.node, ids), 5 + 6 * 64);
    ck_assert_uint_eq(ids[5], 0x600);
    ck_assert_uint_eq(ids[5 + 5 * 64 - 1], 0x73F);
    ck_assert_uint_eq(ids[5 + 5 * 64], 0x780);
    ck_assert_uint_eq(ids[5 + 6 * 64 - 1], 0x7BF);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet_ucmm");
    TCase *tc = tcase_create("ucmm");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, open_then_get_and_set_on_the_connection);
    tcase_add_test(tc, duplicate_and_sixth_open);
    tcase_add_test(tc, open_refusals);
    tcase_add_test(tc, close);
    tcase_add_test(tc, watchdog_deletes);
    tcase_add_test(tc, restart_ends_them_and_consumed_ids);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
