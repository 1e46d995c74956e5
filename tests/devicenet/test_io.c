/* SPDX-License-Identifier: Apache-2.0 */
/* The I/O connections: polled (instance 2) and COS/cyclic (instance 4, and instance 2 consuming
 * the master's COS/cyclic data) with their attributes, states and watchdogs, the zero-length
 * (idle) message, the acknowledge handler's retries and the events the application gets. */
#include "check_main.h"
#include "dn_bench.h"

#include <string.h>

static dn_bench_t b;

static void setup(void)
{
    bench_online(&b, 63);
    memcpy(bench_assembly(&b, 71), "\x64\x03\xDC\x05", 4);
}

static void process(void)
{
    b.deadline = dn_node_process(&b.node, b.now);
}

static void expect_events(const dn_io_event_t *want, size_t count)
{
    ck_assert_uint_eq(b.event_count, count);
    for (size_t i = 0; i < count; i++)
        ck_assert_int_eq(b.events[i], want[i]);
}

/* An 8-byte response body: two fragments. */
static void get_in_fragments(const char *request, const char *first, const char *last)
{
    bench_rx(&b, request);
    bench_expect(&b, first);
    bench_exchange(&b, "5FC#81C000", last);
    bench_rx(&b, "5FC#81C100");
    bench_expect_none(&b);
}

START_TEST(polled_connection_attributes)
{
    bench_exchange(&b, "5FE#014B03010301", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050201", "5FB#018E01"); /* configuring */
    bench_exchange(&b, "5FC#010E050202", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050203", "5FB#018E82");
    bench_exchange(&b, "5FC#010E050204", "5FB#018EFF03");
    bench_exchange(&b, "5FC#010E050205", "5FB#018EFD05");
    bench_exchange(&b, "5FC#010E050206", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050207", "5FB#018E0400");
    bench_exchange(&b, "5FC#010E050208", "5FB#018E0400");
    bench_exchange(&b, "5FC#010E050209", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E05020C", "5FB#018E00");
    bench_exchange(&b, "5FC#010E05020D", "5FB#018E0700");
    get_in_fragments("5FC#010E05020E", "5FB#81008E2004254700", "5FB#81813003");
    bench_exchange(&b, "5FC#010E05020F", "5FB#018E0700");
    get_in_fragments("5FC#010E050210", "5FB#81008E2004251500", "5FB#81813003");
    bench_exchange(&b, "5FC#010E050211", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E050212", "5FB#018E00");
    bench_exchange(&b, "5FC#011005020C01", "5FB#01940EFF");
    bench_exchange(&b, "5FC#0110050211 0000", "5FB#01940EFF");
    bench_exchange(&b, "5FC#010E050401", "5FB#019416FF");
}
END_TEST

START_TEST(poll_exchange_idle_and_timeout)
{
    bench_exchange(&b, "5FE#014B03010301", "5FB#01CB00");
    bench_rx(&b, "5FD#0100DC05"); /* configuring: not consumed */
    bench_expect_none(&b);
    ck_assert_uint_eq(b.event_count, 0);
    bench_exchange(&b, "5FC#01100502096000", "5FB#01906000"); /* 96 ms: established */
    bench_exchange(&b, "5FC#010E050201", "5FB#018E03");
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_GREEN);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0071); /* owned, idle */
    bench_exchange(&b, "5FD#0100DC05", "3FF#6403DC05");
    ck_assert_mem_eq(bench_assembly(&b, 21), "\x01\x00\xDC\x05", 4);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0061); /* run */
    /* Zero length: the master is idle; the drive still answers. */
    bench_exchange(&b, "5FD#", "3FF#6403DC05");
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0071);
    ck_assert_mem_eq(bench_assembly(&b, 21), "\x01\x00\xDC\x05", 4);
    bench_exchange(&b, "5FD#", "3FF#6403DC05"); /* still idle: no second event */
    bench_rx(&b, "5FD#0100");                   /* another length: dropped, unanswered */
    bench_expect_none(&b);
    /* 96 ms x 4 after the last poll. */
    bench_advance(&b, 383999);
    ck_assert_int_eq(b.node.conn[1].state, DN_CONN_ESTABLISHED);
    bench_advance(&b, 1);
    ck_assert_int_eq(b.node.conn[1].state, DN_CONN_TIMED_OUT);
    dn_io_event_t want[] = {DN_IO_ESTABLISHED, DN_IO_RUN, DN_IO_IDLE};
    expect_events(want, 3);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_TIMEOUT});
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_RED);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0021); /* faulted I/O connection */
    bench_rx(&b, "5FD#0100DC05");
    bench_expect_none(&b);
    bench_exchange(&b, "5FC#010E050201", "5FB#018E04");
    /* The expected packet rate written again establishes it again. */
    bench_exchange(&b, "5FC#01100502096000", "5FB#01906000");
    bench_exchange(&b, "5FD#0100DC05", "3FF#6403DC05");
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_GREEN);
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    dn_io_event_t released[] = {DN_IO_ESTABLISHED, DN_IO_RUN, DN_IO_IDLE,
                                DN_IO_ESTABLISHED, DN_IO_RUN, DN_IO_RELEASED};
    expect_events(released, 6);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_RELEASED});
    bench_rx(&b, "5FD#0100DC05");
    bench_expect_none(&b);
    /* Consumed: a poll, two idle ones and a poll after the timeout; not the one of the
     * configuring connection, the wrong length, the timed-out or the released connection's. */
    bench_expect_stats(&b, .explicit_requests = 6, .io_messages = 4, .timeouts = 1);
}
END_TEST

START_TEST(poll_without_watchdog)
{
    bench_exchange(&b, "5FE#014B03010201", "5FB#01CB00"); /* polled only, no explicit */
    bench_exchange(&b, "5FE#014B03010101", "5FB#01CB00");
    bench_exchange(&b, "5FC#01100502090000", "5FB#01900000"); /* 0: no watchdog */
    bench_exchange(&b, "5FD#0100DC05", "3FF#6403DC05");
    ck_assert_uint_eq(b.node.conn[1].watchdog, CO_TIME_NEVER);
}
END_TEST

START_TEST(poll_with_transparent_assemblies)
{
    dn_stored_t stored = {100, 101, false};
    bench_init(&b, 25, stored);
    dn_node_start(&b.node, b.now);
    process();
    bench_advance(&b, 2000000);
    b.next = b.count;
    memcpy(bench_assembly(&b, 101), "\x27\x06\xDC\x05", 4);
    bench_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    bench_rx(&b, "4CC#010E05020E");
    bench_expect(&b, "4CB#81008E2004256500"); /* produced path: assembly 101 */
    bench_exchange(&b, "4CC#81C000", "4CB#81813003");
    bench_rx(&b, "4CC#81C100");
    bench_exchange(&b, "4CC#01100502096000", "4CB#01906000");
    bench_exchange(&b, "4CD#0F00DC05", "3D9#2706DC05");
    ck_assert_mem_eq(bench_assembly(&b, 100), "\x0F\x00\xDC\x05", 4);
}
END_TEST

START_TEST(cos_connection_attributes)
{
    bench_exchange(&b, "5FE#014B03011101", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050401", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050402", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050403", "5FB#018E12");
    bench_exchange(&b, "5FC#010E050404", "5FB#018E7F03");
    bench_exchange(&b, "5FC#010E050405", "5FB#018EFA05");
    bench_exchange(&b, "5FC#010E050406", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050407", "5FB#018E0400");
    bench_exchange(&b, "5FC#010E050408", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E05040C", "5FB#018E00");
    bench_exchange(&b, "5FC#010E05040D", "5FB#018E0700");
    bench_exchange(&b, "5FC#010E05040F", "5FB#018E0500");
    bench_exchange(&b, "5FC#010E050410", "5FB#018E202B250100");
    /* Instance 2 consumes the master's COS data and acknowledges them. */
    bench_exchange(&b, "5FC#010E050203", "5FB#018E82");
    bench_exchange(&b, "5FC#010E050204", "5FB#018EFF03");
    bench_exchange(&b, "5FC#010E050206", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050207", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E05020D", "5FB#018E0000");
}
END_TEST

START_TEST(cos_production_acknowledged)
{
    bench_exchange(&b, "5FE#014B03011101", "5FB#01CB00");
    co_time_t start = b.now;
    bench_rx(&b, "5FC#0110050409E803"); /* 1000 ms: established, the first data at once */
    bench_expect(&b, "5FB#0190E803");
    bench_expect(&b, "37F#6403DC05");
    bench_expect_none(&b);
    bench_rx(&b, "5FA#");
    ck_assert(!b.node.awaiting_ack);
    /* No change: the data again after the expected packet rate. */
    bench_advance(&b, 999999);
    bench_expect_none(&b);
    bench_advance(&b, 1);
    ck_assert_uint_eq(bench_expect(&b, "37F#6403DC05"), start + 1000000);
    /* Not acknowledged: once more after the 16 ms acknowledge timer, then given up. */
    bench_advance(&b, 16000);
    ck_assert_uint_eq(bench_expect(&b, "37F#6403DC05"), start + 1016000);
    bench_advance(&b, 16000);
    bench_expect_none(&b);
    ck_assert_int_eq(b.events[b.event_count - 1], DN_IO_ACK_FAILED);
    /* A change goes out at once. */
    memcpy(bench_assembly(&b, 71), "\x65\x03\xDC\x05", 4);
    process();
    bench_expect(&b, "37F#6503DC05");
    bench_rx(&b, "5FA#");
    /* Production inhibit time 50 ms: a change 10 ms after a production waits. */
    bench_exchange(&b, "5FC#01100504113200", "5FB#0190");
    memcpy(bench_assembly(&b, 71), "\x64\x03\xDC\x05", 4);
    process();
    bench_expect(&b, "37F#6403DC05");
    bench_rx(&b, "5FA#");
    co_time_t produced = b.now;
    bench_advance(&b, 10000);
    memcpy(bench_assembly(&b, 71), "\x65\x03\xDC\x05", 4);
    process();
    bench_expect_none(&b);
    ck_assert_uint_eq(b.deadline, produced + 50000);
    bench_advance(&b, 40000);
    ck_assert_uint_eq(bench_expect(&b, "37F#6503DC05"), produced + 50000);
}
END_TEST

/* The producer's watchdog is fed by acknowledgements: none for 1000 ms x 4, timed out. */
START_TEST(cos_producer_timeout)
{
    bench_exchange(&b, "5FE#014B03011101", "5FB#01CB00");
    bench_rx(&b, "5FC#0110050409E803");
    co_time_t established = b.now;
    bench_advance(&b, 3999999);
    ck_assert_int_eq(b.node.conn[2].state, DN_CONN_ESTABLISHED);
    bench_advance(&b, 1);
    ck_assert_int_eq(b.node.conn[2].state, DN_CONN_TIMED_OUT);
    ck_assert_uint_eq(b.now, established + 4000000);
    bench_expect_ends(&b, {DN_CONN_COS_CYCLIC, DN_END_TIMEOUT});
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_RED);
    b.next = b.count;
    bench_advance(&b, 5000000);
    bench_expect_none(&b); /* timed out: no more production */
}
END_TEST

START_TEST(cyclic_production)
{
    bench_exchange(&b, "5FE#014B03012101", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050403", "5FB#018E02");
    bench_rx(&b, "5FC#01100504096400"); /* 100 -> 104 ms */
    bench_expect(&b, "5FB#01906800");
    co_time_t first = bench_expect(&b, "37F#6403DC05");
    bench_rx(&b, "5FA#");
    memcpy(bench_assembly(&b, 71), "\x65\x03\xDC\x05", 4);
    process();
    bench_expect_none(&b); /* cyclic: a change waits for the cycle */
    bench_advance(&b, 104000);
    ck_assert_uint_eq(bench_expect(&b, "37F#6503DC05"), first + 104000);
}
END_TEST

START_TEST(acknowledge_suppression)
{
    bench_exchange(&b, "5FE#014B03015101", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050403", "5FB#018E10");
    bench_exchange(&b, "5FC#010E050405", "5FB#018EFFFF");
    bench_exchange(&b, "5FC#010E050406", "5FB#018E0F");
    bench_exchange(&b, "5FC#010E05040F", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E050203", "5FB#018E80");
    bench_exchange(&b, "5FC#010E050204", "5FB#018EFFFF");
    bench_exchange(&b, "5FC#010E050206", "5FB#018EF1");
    bench_rx(&b, "5FC#0110050409E803");
    bench_expect(&b, "5FB#0190E803");
    bench_expect(&b, "37F#6403DC05");
    ck_assert(!b.node.awaiting_ack);
    bench_advance(&b, 10000000); /* no acknowledgement expected: never timed out */
    ck_assert_int_eq(b.node.conn[2].state, DN_CONN_ESTABLISHED);
    ck_assert_uint_eq(b.count - b.next, 10); /* one a second, none repeated */
    b.next = b.count;
    /* The master's COS data: consumed, not acknowledged. */
    bench_exchange(&b, "5FC#01100502090000", "5FB#01900000");
    bench_rx(&b, "5FD#0100DC05");
    bench_expect_none(&b);
    ck_assert_mem_eq(bench_assembly(&b, 21), "\x01\x00\xDC\x05", 4);
}
END_TEST

START_TEST(master_cos_data_acknowledged)
{
    bench_exchange(&b, "5FE#014B03011101", "5FB#01CB00");
    bench_exchange(&b, "5FC#01100502096000", "5FB#01906000");
    bench_exchange(&b, "5FD#0100DC05", "3FF#");
    bench_exchange(&b, "5FD#", "3FF#");
    bench_advance(&b, 384000);
    ck_assert_int_eq(b.node.conn[1].state, DN_CONN_TIMED_OUT);
}
END_TEST

START_TEST(poll_and_cos_together)
{
    bench_exchange(&b, "5FE#014B03011301", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050203", "5FB#018E82");
    bench_exchange(&b, "5FC#010E050207", "5FB#018E0400");
    bench_exchange(&b, "5FC#01100502090000", "5FB#01900000");
    bench_exchange(&b, "5FD#0100DC05", "3FF#6403DC05");
    /* The poll released: instance 2 goes on with the master's COS data, configuring again, so
     * the master's data stopped: instance 2 ended. */
    size_t before = b.event_count;
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    ck_assert_uint_eq(b.event_count, before);
    bench_expect_ends(&b, {DN_CONN_POLL, DN_END_RELEASED});
    bench_exchange(&b, "5FC#010E050201", "5FB#018E01");
    bench_exchange(&b, "5FC#010E050207", "5FB#018E0000");
    /* COS released too: no I/O left; instance 2 was configuring, nothing closed. */
    bench_exchange(&b, "5FE#014C030110", "5FB#01CC");
    bench_exchange(&b, "5FC#010E050201", "5FB#019416FF");
    bench_expect_no_end(&b);
    ck_assert_uint_eq(b.event_count, before + 1);
    ck_assert_int_eq(b.events[b.event_count - 1], DN_IO_RELEASED);
    ck_assert_uint_eq(b.node.allocation, DN_ALLOC_EXPLICIT);
}
END_TEST

START_TEST(cos_then_poll_allocated)
{
    bench_exchange(&b, "5FE#014B03011101", "5FB#01CB00");
    bench_exchange(&b, "5FE#014B03010201", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E050207", "5FB#018E0400");   /* instance 2 polls now */
    bench_exchange(&b, "5FE#014B03012001", "5FB#01942002"); /* cyclic with COS */
    bench_exchange(&b, "5FE#014B03014001", "5FB#01942002");
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet I/O connections");
    TCase *tc = tcase_create("io");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, polled_connection_attributes);
    tcase_add_test(tc, poll_exchange_idle_and_timeout);
    tcase_add_test(tc, poll_without_watchdog);
    tcase_add_test(tc, poll_with_transparent_assemblies);
    tcase_add_test(tc, cos_connection_attributes);
    tcase_add_test(tc, cos_production_acknowledged);
    tcase_add_test(tc, cos_producer_timeout);
    tcase_add_test(tc, cyclic_production);
    tcase_add_test(tc, acknowledge_suppression);
    tcase_add_test(tc, master_cos_data_acknowledged);
    tcase_add_test(tc, poll_and_cos_together);
    tcase_add_test(tc, cos_then_poll_allocated);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
