/* SPDX-License-Identifier: Apache-2.0 */
/* The explicit fragmentation protocol both ways: requests reassembled with every fragment
 * acknowledged, a repeated fragment acknowledged again and dropped, a lost fragment dropping the
 * message, too much data refused; responses sent fragment by fragment on the master's
 * acknowledgements, a lost acknowledgement answered by one retransmission, then given up. */
#include "check_main.h"
#include "dn_bench.h"

#include <stdio.h>

static dn_bench_t b;

static void setup(void)
{
    bench_online(&b, 63);
    bench_exchange(&b, "5FE#014B03010101", "5FB#01CB00");
}

/* Set of class 0x70 attribute 1 with 10 bytes of data: 14 bytes, three fragments; the handler
 * refuses the length, which shows the whole body arrived. */
START_TEST(request_in_three_fragments)
{
    bench_exchange(&b, "5FC#8100 107001010102", "5FB#81C000");
    bench_exchange(&b, "5FC#8141 030405060708", "5FB#81C100");
    bench_rx(&b, "5FC#8182 090A");
    bench_expect(&b, "5FB#81C200");
    bench_expect(&b, "5FB#019415FF");
    bench_expect_none(&b);
    /* The Allocate of the setup, and one request of three fragments. */
    bench_expect_stats(&b, .explicit_requests = 2, .error_responses = 1, .fragments = 3);
}
END_TEST

START_TEST(repeated_fragment_acknowledged_again)
{
    bench_exchange(&b, "5FC#8100 100415038100", "5FB#81C000");
    bench_exchange(&b, "5FC#8100 100415038100", "5FB#81C000"); /* a new first: starts again */
    bench_rx(&b, "5FC#8181 0C00");
    bench_expect(&b, "5FB#81C100");
    bench_expect(&b, "5FB#0190");
    bench_expect_none(&b);
    ck_assert_mem_eq(bench_assembly(&b, 21), "\x81\x00\x0C\x00", 4);
    /* Three fragments with the middle one repeated (its acknowledgement was lost). */
    bench_exchange(&b, "5FC#8100 107001010102", "5FB#81C000");
    bench_exchange(&b, "5FC#8141 030405060708", "5FB#81C100");
    bench_exchange(&b, "5FC#8141 030405060708", "5FB#81C100");
    bench_rx(&b, "5FC#8182 090A");
    bench_expect(&b, "5FB#81C200");
    bench_expect(&b, "5FB#019415FF"); /* 10 bytes of data, not 16 */
    bench_expect_none(&b);
    bench_expect_stats(&b, .explicit_requests = 3, .error_responses = 1, .fragments = 7);
}
END_TEST

START_TEST(lost_fragment_drops_the_message)
{
    bench_exchange(&b, "5FC#8100 107001010102", "5FB#81C000");
    bench_rx(&b, "5FC#8182 090A"); /* count 2 after 0: count 1 was lost */
    bench_expect_none(&b);
    bench_rx(&b, "5FC#8141 030405060708"); /* too late: no message in progress */
    bench_expect_none(&b);
    bench_rx(&b, "5FC#8181 0C00"); /* a last fragment alone */
    bench_expect_none(&b);
    /* The next message goes through. */
    bench_exchange(&b, "5FC#010E010101", "5FB#018EF300");
}
END_TEST

/* 66 bytes in eleven fragments: the eleventh overflows the 64-byte connection size. */
START_TEST(too_much_data)
{
    bench_exchange(&b, "5FC#8100 107001010102", "5FB#81C000");
    char frame[32];
    for (unsigned count = 1; count < 10; count++) {
        char ack[16];
        snprintf(frame, sizeof(frame), "5FC#81%02X 000000000000", 0x40 | count);
        snprintf(ack, sizeof(ack), "5FB#81%02X00", 0xC0 | count);
        bench_exchange(&b, frame, ack);
    }
    bench_exchange(&b, "5FC#814A 000000000000", "5FB#81CA01");
    ck_assert(!b.node.messages[0].rx.active);
    bench_rx(&b, "5FC#818B 00");
    bench_expect_none(&b);
}
END_TEST

START_TEST(fragments_only_on_the_explicit_connection)
{
    bench_rx(&b, "5FE#8100 4B0301020100"); /* the unconnected port carries no fragments */
    bench_expect_none(&b);
}
END_TEST

/* A 22-byte response: first, two middle and the last fragment, each after its ack. */
START_TEST(response_in_four_fragments)
{
    b.config.product_name = "ALTIVAR 312 EMULATED";
    bench_rx(&b, "5FC#010E010107");
    bench_expect(&b, "5FB#8100 8E14414C5449");
    bench_expect_none(&b);
    bench_exchange(&b, "5FC#81C000", "5FB#8141 564152203331");
    bench_exchange(&b, "5FC#81C100", "5FB#8142 3220454D554C");
    bench_exchange(&b, "5FC#81C200", "5FB#8183 41544544");
    bench_rx(&b, "5FC#81C300");
    bench_expect_none(&b);
    ck_assert(!b.node.messages[0].tx.active);
}
END_TEST

START_TEST(lost_acknowledgement)
{
    co_time_t start = b.now;
    bench_rx(&b, "5FC#010E010107");
    ck_assert_uint_eq(bench_expect(&b, "5FB#81008E0641545633"), start);
    ck_assert_uint_eq(b.deadline, start + 1000000);
    bench_rx(&b, "5FC#81C100"); /* another fragment's count: ignored */
    bench_expect_none(&b);
    bench_advance(&b, 999999);
    bench_expect_none(&b);
    bench_advance(&b, 1);
    ck_assert_uint_eq(bench_expect(&b, "5FB#81008E0641545633"), start + 1000000);
    bench_advance(&b, 1000000); /* one retransmission only, then given up */
    bench_expect_none(&b);
    ck_assert(!b.node.messages[0].tx.active);
    ck_assert_uint_eq(b.deadline, b.node.conn[0].watchdog);
    bench_rx(&b, "5FC#81C000");
    bench_expect_none(&b);
    /* The first fragment sent twice; acknowledgements are not counted. */
    bench_expect_stats(&b, .explicit_requests = 2, .fragments = 2);
}
END_TEST

START_TEST(acknowledgement_with_error_ends_the_response)
{
    bench_rx(&b, "5FC#010E010107");
    bench_expect(&b, "5FB#81008E0641545633");
    bench_rx(&b, "5FC#81C001");
    bench_expect_none(&b);
    ck_assert(!b.node.messages[0].tx.active);
}
END_TEST

START_TEST(retransmission_then_ack_continues)
{
    bench_rx(&b, "5FC#010E010107");
    bench_expect(&b, "5FB#81008E0641545633");
    bench_advance(&b, 1000000);
    bench_expect(&b, "5FB#81008E0641545633");
    bench_exchange(&b, "5FC#81C000", "5FB#81813132");
    bench_rx(&b, "5FC#81C100");
    bench_expect_none(&b);
    ck_assert(!b.node.messages[0].tx.active);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet fragmentation");
    TCase *tc = tcase_create("fragment");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, request_in_three_fragments);
    tcase_add_test(tc, repeated_fragment_acknowledged_again);
    tcase_add_test(tc, lost_fragment_drops_the_message);
    tcase_add_test(tc, too_much_data);
    tcase_add_test(tc, fragments_only_on_the_explicit_connection);
    tcase_add_test(tc, response_in_four_fragments);
    tcase_add_test(tc, lost_acknowledgement);
    tcase_add_test(tc, acknowledgement_with_error_ends_the_response);
    tcase_add_test(tc, retransmission_then_ack_continues);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
