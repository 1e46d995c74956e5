/* SPDX-License-Identifier: Apache-2.0 */
/* Explicit messaging on connection instance 1 and the group 2 only unconnected port: Allocate
 * and Release (also by another master), every standard object's attributes and refusals, the
 * application's classes through the registry, Identity Reset, the explicit watchdog. Frames in
 * candump text of a slave with MAC ID 63 and a master with MAC ID 1. */
#include "check_main.h"
#include "dn_bench.h"

#include <string.h>

static dn_bench_t b;

static void setup(void)
{
    bench_online(&b, 63);
    bench_exchange(&b, "5FE#014B03010101", "5FB#01CB00"); /* allocate explicit */
}

START_TEST(allocate_explicit)
{
    ck_assert_uint_eq(b.node.allocation, DN_ALLOC_EXPLICIT);
    ck_assert_uint_eq(b.node.master_mac, 1);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_ESTABLISHED);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_GREEN);
    bench_exchange(&b, "5FC#010E030105", "5FB#018E0101"); /* allocation information */
    /* The XID of the request comes back in the response. */
    bench_exchange(&b, "5FC#410E010101", "5FB#418EF300");
}
END_TEST

START_TEST(allocate_refusals)
{
    /* Another master: allocation conflict. */
    bench_exchange(&b, "5FE#024B03010202", "5FB#02940C01");
    /* Already allocated, not supported (bit-strobe, multicast poll, reserved), COS with cyclic,
     * acknowledge suppression alone, nothing: invalid allocation choice. */
    bench_exchange(&b, "5FE#014B03010101", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03010401", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03010801", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03018001", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03013001", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03014001", "5FB#01942002");
    bench_exchange(&b, "5FE#014B03010001", "5FB#01942002");
    /* The allocator's MAC ID out of range, too little and too much data. */
    bench_exchange(&b, "5FE#014B03010240", "5FB#019420FF");
    bench_exchange(&b, "5FE#014B030102", "5FB#019413FF");
    bench_exchange(&b, "5FE#014B0301020100", "5FB#019415FF");
    /* The class level, another class, another instance. */
    bench_exchange(&b, "5FE#014B03000201", "5FB#019408FF");
    bench_exchange(&b, "5FE#014B01010201", "5FB#019408FF");
    bench_exchange(&b, "5FE#014B03020201", "5FB#019416FF");
    /* Not Allocate or Release on the group 2 only port. */
    bench_exchange(&b, "5FE#010E010101", "5FB#01940803");
    ck_assert_uint_eq(b.node.allocation, DN_ALLOC_EXPLICIT);
    /* The Allocate of the setup and these 15, each refused with an error response. */
    bench_expect_stats(&b, .explicit_requests = 16, .error_responses = 15);
}
END_TEST

START_TEST(release)
{
    bench_exchange(&b, "5FE#014B03010201", "5FB#01CB00"); /* polled too */
    ck_assert_uint_eq(b.node.allocation, 0x03);
    bench_exchange(&b, "5FE#024C030103", "5FB#02940C01"); /* by another master */
    bench_exchange(&b, "5FE#014C030104", "5FB#01942002"); /* bit-strobe: not supported */
    bench_exchange(&b, "5FE#014C0301", "5FB#019413FF");
    bench_exchange(&b, "5FE#014C03010200", "5FB#019415FF");
    bench_exchange(&b, "5FE#014C030110", "5FB#01CC"); /* COS, not allocated: nothing to do */
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    ck_assert_uint_eq(b.node.allocation, DN_ALLOC_EXPLICIT);
    /* The polled connection was configuring: no data of the master stopped, nothing closed. */
    ck_assert_uint_eq(b.event_count, 1);
    ck_assert_uint_eq(b.events[0], DN_IO_RELEASED);
    /* Released through the explicit connection itself: answered, then gone. */
    bench_exchange(&b, "5FC#014C030101", "5FB#01CC");
    ck_assert_uint_eq(b.node.allocation, 0);
    ck_assert_uint_eq(b.node.master_mac, DN_MAC_ID_NONE);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_NON_EXISTENT);
    bench_rx(&b, "5FC#010E010101");
    bench_expect_none(&b);
    ck_assert_int_eq(dn_node_ns_led(&b.node), DN_LED_FLASHING_GREEN);
    /* Free again: another master may allocate. */
    bench_exchange(&b, "5FE#024B03010102", "5FB#02CB00");
}
END_TEST

/* The manual's Class Instance Editor example: Get_Attribute_Single class 1, instance 1,
 * attribute 1, the vendor ID 0x00F3. */
START_TEST(identity_attributes)
{
    bench_exchange(&b, "5FC#010E010101", "5FB#018EF300");
    bench_exchange(&b, "5FC#010E010102", "5FB#018E0200");
    bench_exchange(&b, "5FC#010E010103", "5FB#018E0918"); /* 6153 */
    bench_exchange(&b, "5FC#010E010104", "5FB#018E0102");
    bench_exchange(&b, "5FC#010E010105", "5FB#018E3100"); /* owned, no I/O connection */
    bench_exchange(&b, "5FC#010E010106", "5FB#018E78563412");
    bench_exchange(&b, "5FC#010E010164", "5FB#018E"); /* fatal log: empty */
    bench_exchange(&b, "5FC#010E010001", "5FB#018E0100");
    /* Product name "ATV312", a SHORT_STRING: 8 bytes, in two fragments. */
    bench_rx(&b, "5FC#010E010107");
    bench_expect(&b, "5FB#81008E0641545633");
    bench_expect_none(&b);
    bench_exchange(&b, "5FC#81C000", "5FB#81813132");
    bench_rx(&b, "5FC#81C100");
    bench_expect_none(&b);
    ck_assert(!b.node.messages[0].tx.active);
}
END_TEST

START_TEST(identity_refusals)
{
    bench_exchange(&b, "5FC#010E010108", "5FB#019414FF");     /* no attribute 8 */
    bench_exchange(&b, "5FC#010E010002", "5FB#019414FF");     /* class: only the revision */
    bench_exchange(&b, "5FC#0110010101F300", "5FB#01940EFF"); /* not settable */
    bench_exchange(&b, "5FC#010E01010100", "5FB#019415FF");   /* a Get with data */
    bench_exchange(&b, "5FC#010E010201", "5FB#019416FF");     /* no instance 2 */
    bench_exchange(&b, "5FC#010E600101", "5FB#019416FF");     /* no class 0x60 */
    bench_exchange(&b, "5FC#01330101", "5FB#019408FF");       /* no such service */
    bench_exchange(&b, "5FC#010E0101", "5FB#019413FF");       /* no attribute byte */
    bench_exchange(&b, "5FC#010E01", "5FB#019413FF");         /* no instance */
    bench_exchange(&b, "5FC#010E020101", "5FB#019408FF");     /* message router: nothing */
    bench_exchange(&b, "5FC#01010201", "5FB#019408FF");
}
END_TEST

START_TEST(identity_reset)
{
    bench_exchange(&b, "5FC#01050101", "5FB#0185");
    ck_assert_int_eq(b.reset_type, 0);
    bench_exchange(&b, "5FC#0105010101", "5FB#0185");
    ck_assert_int_eq(b.reset_type, 1);
    b.reset_type = -1;
    bench_exchange(&b, "5FC#0105010102", "5FB#019420FF");
    bench_exchange(&b, "5FC#010501010000", "5FB#019415FF");
    bench_exchange(&b, "5FC#01050100", "5FB#019408FF");
    ck_assert_int_eq(b.reset_type, -1);
}
END_TEST

START_TEST(devicenet_object)
{
    bench_exchange(&b, "5FC#010E030001", "5FB#018E0200");
    bench_exchange(&b, "5FC#010E030101", "5FB#018E3F");
    bench_exchange(&b, "5FC#010E030102", "5FB#018E01");
    bench_exchange(&b, "5FC#010E030103", "5FB#018E00");
    bench_exchange(&b, "5FC#010E030104", "5FB#018E00");
    bench_exchange(&b, "5FC#010E030106", "5FB#018E00");
    bench_exchange(&b, "5FC#010E030107", "5FB#018E00");
    bench_exchange(&b, "5FC#010E030108", "5FB#018E3F");
    bench_exchange(&b, "5FC#010E030109", "5FB#018E01");
    bench_exchange(&b, "5FC#010E03010A", "5FB#018E00");
    bench_exchange(&b, "5FC#010E03010B", "5FB#019414FF");
    /* BOI: 0 or 1. */
    bench_exchange(&b, "5FC#011003010301", "5FB#0190");
    bench_exchange(&b, "5FC#010E030103", "5FB#018E01");
    bench_exchange(&b, "5FC#011003010302", "5FB#019409FF");
    bench_exchange(&b, "5FC#0110030103", "5FB#019413FF");
    bench_exchange(&b, "5FC#01100301030100", "5FB#019415FF");
    /* The bus-off counter: any value written clears it. */
    dn_node_bus_off(&b.node, b.now); /* BOI set: back online after a new check */
    b.deadline = dn_node_process(&b.node, b.now);
    bench_advance(&b, 2000000);
    b.next = b.count;
    bench_exchange(&b, "5FE#014B03010101", "5FB#01CB00");
    bench_exchange(&b, "5FC#010E030104", "5FB#018E01");
    bench_exchange(&b, "5FC#011003010405", "5FB#0190");
    bench_exchange(&b, "5FC#010E030104", "5FB#018E00");
    /* Read-only attributes. */
    bench_exchange(&b, "5FC#01100301013F", "5FB#01940EFF");
    bench_exchange(&b, "5FC#011003010200", "5FB#01940EFF");
    bench_exchange(&b, "5FC#01100301050101", "5FB#01940EFF");
}
END_TEST

START_TEST(quick_connect_stored)
{
    bench_exchange(&b, "5FC#01100301 0A01", "5FB#0190");
    ck_assert_int_eq(b.stores, 1);
    ck_assert(b.stored.quick_connect);
    ck_assert_uint_eq(b.stored.consumed_assembly, 21);
    ck_assert_uint_eq(b.stored.produced_assembly, 71);
    bench_exchange(&b, "5FC#010E03010A", "5FB#018E01");
    bench_exchange(&b, "5FC#010E010105", "5FB#018E3500"); /* configured: not out-of-box */
    bench_exchange(&b, "5FC#01100301 0A02", "5FB#019409FF");
    b.store_fails = true;
    bench_exchange(&b, "5FC#01100301 0A00", "5FB#019419FF");
    bench_exchange(&b, "5FC#010E03010A", "5FB#018E01");
}
END_TEST

/* A Set of 4 bytes of assembly data is 9 bytes of message body: two fragments, each
 * acknowledged, then the response. */
static void set_in_fragments(const char *first, const char *last, const char *response)
{
    bench_rx(&b, first);
    bench_expect(&b, "5FB#81C000");
    bench_rx(&b, last);
    bench_expect(&b, "5FB#81C100");
    bench_expect(&b, response);
    bench_expect_none(&b);
}

START_TEST(assembly_object)
{
    bench_exchange(&b, "5FC#010E040001", "5FB#018E0200");
    bench_exchange(&b, "5FC#010E040002", "5FB#018E6500"); /* max instance 101 */
    uint8_t status[4] = {0x27, 0x06, 0xDC, 0x05};
    memcpy(bench_assembly(&b, 101), status, 4);
    bench_exchange(&b, "5FC#010E046503", "5FB#018E2706DC05");
    set_in_fragments("5FC#8100 100415038100", "5FC#8181 0C00", "5FB#0190");
    ck_assert_mem_eq(bench_assembly(&b, 21), "\x81\x00\x0C\x00", 4);
    bench_exchange(&b, "5FC#010E041503", "5FB#018E81000C00");
    set_in_fragments("5FC#8100 100447030000", "5FC#8181 0000", "5FB#01940EFF"); /* produced */
    bench_exchange(&b, "5FC#0110041503010000", "5FB#019413FF");
    set_in_fragments("5FC#8100 100415030100", "5FC#8181 000000", "5FB#019415FF");
    bench_exchange(&b, "5FC#010E041603", "5FB#019416FF");
    bench_exchange(&b, "5FC#010E041501", "5FB#019414FF");
    /* An I/O connection against instance 21: its data are the connection's. */
    bench_exchange(&b, "5FE#014B03010201", "5FB#01CB00");
    set_in_fragments("5FC#8100 100415030000", "5FC#8181 0000", "5FB#01940CFF");
    set_in_fragments("5FC#8100 100414030000", "5FC#8181 0000", "5FB#0190"); /* 20: not in use */
}
END_TEST

START_TEST(connection_class)
{
    bench_exchange(&b, "5FC#010E050001", "5FB#018E0100");
    bench_exchange(&b, "5FC#010E050064", "5FB#018E1500");
    bench_exchange(&b, "5FC#010E050065", "5FB#018E4700");
    /* The manual's selection path 5/0/64 and 5/0/65: stored, used after a restart. */
    bench_exchange(&b, "5FC#01100500641400", "5FB#0190");
    bench_exchange(&b, "5FC#01100500656500", "5FB#0190");
    ck_assert_int_eq(b.stores, 2);
    ck_assert_uint_eq(b.stored.consumed_assembly, 20);
    ck_assert_uint_eq(b.stored.produced_assembly, 101);
    bench_exchange(&b, "5FC#010E050064", "5FB#018E1400");
    ck_assert_uint_eq(b.node.consumed_assembly, 21);          /* until the restart */
    bench_exchange(&b, "5FC#01100500644700", "5FB#019409FF"); /* produced, as consumed */
    bench_exchange(&b, "5FC#01100500651500", "5FB#019409FF");
    bench_exchange(&b, "5FC#01100500646300", "5FB#019409FF");
    bench_exchange(&b, "5FC#011005006414", "5FB#019413FF");
    bench_exchange(&b, "5FC#0110050001 0200", "5FB#01940EFF");
    bench_exchange(&b, "5FC#010E050002", "5FB#019414FF");
}
END_TEST

START_TEST(restart_uses_stored_assemblies)
{
    dn_stored_t stored = {100, 101, false};
    bench_init(&b, 63, stored);
    ck_assert_uint_eq(b.node.consumed_assembly, 100);
    ck_assert_uint_eq(b.node.produced_assembly, 101);
    dn_stored_t wrong = {71, 22, false}; /* not consumed, not in the table: the defaults */
    bench_init(&b, 63, wrong);
    ck_assert_uint_eq(b.node.consumed_assembly, 21);
    ck_assert_uint_eq(b.node.produced_assembly, 71);
}
END_TEST

START_TEST(explicit_connection_attributes)
{
    bench_exchange(&b, "5FC#010E050101", "5FB#018E03");
    bench_exchange(&b, "5FC#010E050102", "5FB#018E00");
    bench_exchange(&b, "5FC#010E050103", "5FB#018E83");
    bench_exchange(&b, "5FC#010E050104", "5FB#018EFB05");
    bench_exchange(&b, "5FC#010E050105", "5FB#018EFC05");
    bench_exchange(&b, "5FC#010E050106", "5FB#018E21");
    bench_exchange(&b, "5FC#010E050107", "5FB#018E4000");
    bench_exchange(&b, "5FC#010E050108", "5FB#018E4000");
    bench_exchange(&b, "5FC#010E050109", "5FB#018EC809"); /* 2504 ms */
    bench_exchange(&b, "5FC#010E05010C", "5FB#018E01");
    bench_exchange(&b, "5FC#010E05010D", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E05010E", "5FB#018E");
    bench_exchange(&b, "5FC#010E05010F", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E050110", "5FB#018E");
    bench_exchange(&b, "5FC#010E050111", "5FB#018E0000");
    bench_exchange(&b, "5FC#010E050112", "5FB#018E00");
    bench_exchange(&b, "5FC#010E05010A", "5FB#019414FF");
    /* Settable: the expected packet rate (rounded up to 8 ms, the value in use answered), the
     * watchdog action (auto or deferred delete), the multiplier (0..7). */
    bench_exchange(&b, "5FC#0110050109E803", "5FB#0190E803");
    bench_exchange(&b, "5FC#0110050109E903", "5FB#0190F003");
    bench_exchange(&b, "5FC#0110050109FFFF", "5FB#0190F8FF");
    bench_exchange(&b, "5FC#011005010C00", "5FB#019409FF");
    bench_exchange(&b, "5FC#011005010C02", "5FB#019409FF");
    bench_exchange(&b, "5FC#011005010C03", "5FB#0190");
    bench_exchange(&b, "5FC#011005011207", "5FB#0190");
    bench_exchange(&b, "5FC#011005011208", "5FB#019409FF");
    bench_exchange(&b, "5FC#0110050111 0000", "5FB#01940EFF"); /* inhibit: instance 4 only */
    bench_exchange(&b, "5FC#01100501010300", "5FB#01940EFF");
    /* Instances that do not exist: 2 and 4 before allocation, 3 never, 10 beyond. */
    bench_exchange(&b, "5FC#010E050201", "5FB#019416FF");
    bench_exchange(&b, "5FC#010E050301", "5FB#019416FF");
    bench_exchange(&b, "5FC#010E050401", "5FB#019416FF");
    bench_exchange(&b, "5FC#010E050A01", "5FB#019416FF");
    bench_exchange(&b, "5FC#01050501", "5FB#019408FF");
}
END_TEST

START_TEST(ack_handler_object)
{
    bench_exchange(&b, "5FC#010E2B0001", "5FB#018E0100");
    bench_exchange(&b, "5FC#010E2B0101", "5FB#018E1000"); /* 16 ms */
    bench_exchange(&b, "5FC#010E2B0102", "5FB#018E01");
    bench_exchange(&b, "5FC#010E2B0103", "5FB#018E0400");
    bench_exchange(&b, "5FC#01102B01012000", "5FB#0190");
    bench_exchange(&b, "5FC#010E2B0101", "5FB#018E2000");
    bench_exchange(&b, "5FC#01102B01010000", "5FB#019409FF");
    bench_exchange(&b, "5FC#01102B010203", "5FB#0190");
    bench_exchange(&b, "5FC#010E2B0102", "5FB#018E03");
    bench_exchange(&b, "5FC#01102B01030500", "5FB#01940EFF");
    bench_exchange(&b, "5FC#010E2B0201", "5FB#019416FF");
}
END_TEST

/* The drive adapter's classes through the registry: a table-driven class and a range of
 * classes answered by one handler. */
START_TEST(application_objects)
{
    bench_exchange(&b, "5FC#010E290001", "5FB#018E0100");
    bench_exchange(&b, "5FC#010E290103", "5FB#018E00");
    bench_exchange(&b, "5FC#011029010301", "5FB#0190");
    bench_exchange(&b, "5FC#010E290103", "5FB#018E01");
    bench_exchange(&b, "5FC#011029010302", "5FB#019409FF"); /* the handler's refusal */
    bench_exchange(&b, "5FC#011029010603", "5FB#01940EFF"); /* the table's */
    bench_exchange(&b, "5FC#010E290107", "5FB#019414FF");
    bench_exchange(&b, "5FC#01102901030100", "5FB#019415FF");
    bench_exchange(&b, "5FC#01052901", "5FB#0185");
    bench_exchange(&b, "5FC#010E290103", "5FB#018E00");
    bench_exchange(&b, "5FC#010E290203", "5FB#019416FF");
    /* The manual's parameter paths: ADL 3000 = 16#70/01/01, 3100 = 16#70/01/65. */
    bench_exchange(&b, "5FC#011070010134 12", "5FB#0190");
    bench_exchange(&b, "5FC#010E700101", "5FB#018E3412");
    bench_exchange(&b, "5FC#0110700165 0A00", "5FB#0190");
    ck_assert_uint_eq(b.param[101], 10);
    bench_exchange(&b, "5FC#010E710102", "5FB#019414FF"); /* 3201: not kept by this bench */
    bench_exchange(&b, "5FC#010EA80101", "5FB#019414FF");
    bench_exchange(&b, "5FC#010EA90101", "5FB#019416FF");
    bench_exchange(&b, "5FC#010E700201", "5FB#019416FF");
    bench_exchange(&b, "5FC#0110700101 34", "5FB#019413FF");
}
END_TEST

/* Inactivity: 2504 ms x 4; any message of the connection restarts it; auto delete. */
START_TEST(explicit_watchdog_auto_delete)
{
    bench_advance(&b, 5000000);
    bench_exchange(&b, "5FC#010E010101", "5FB#018EF300");
    bench_advance(&b, 10015999);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_ESTABLISHED);
    bench_advance(&b, 1);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_NON_EXISTENT);
    ck_assert_uint_eq(b.node.allocation, 0);
    ck_assert_uint_eq(b.node.master_mac, DN_MAC_ID_NONE);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
    bench_rx(&b, "5FC#010E010101");
    bench_expect_none(&b);
    bench_expect_stats(&b, .explicit_requests = 2, .timeouts = 1);
}
END_TEST

START_TEST(explicit_watchdog_multiplier)
{
    bench_exchange(&b, "5FC#0110050109 6400", "5FB#01906800"); /* 100 -> 104 ms */
    bench_exchange(&b, "5FC#011005011201", "5FB#0190");        /* x8 */
    bench_advance(&b, 831999);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_ESTABLISHED);
    bench_advance(&b, 1);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_NON_EXISTENT);
}
END_TEST

START_TEST(explicit_watchdog_deferred_delete)
{
    bench_exchange(&b, "5FC#011005010C03", "5FB#0190");
    bench_exchange(&b, "5FE#014B03010201", "5FB#01CB00");
    bench_advance(&b, 10016000);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_DEFERRED_DELETE);
    ck_assert_uint_eq(b.node.allocation, 0x03);
    bench_rx(&b, "5FC#010E010101");
    bench_expect_none(&b);
    /* The I/O connection released: the explicit connection goes with it. */
    bench_exchange(&b, "5FE#014C030102", "5FB#01CC");
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_NON_EXISTENT);
    ck_assert_uint_eq(b.node.allocation, 0);
    ck_assert_uint_eq(b.node.master_mac, DN_MAC_ID_NONE);
}
END_TEST

START_TEST(deferred_delete_without_io_deletes)
{
    bench_exchange(&b, "5FC#011005010C03", "5FB#0190");
    bench_advance(&b, 10016000);
    ck_assert_int_eq(b.node.conn[0].state, DN_CONN_NON_EXISTENT);
}
END_TEST

START_TEST(frames_not_for_the_slave)
{
    bench_rx(&b, "5F4#010E010101"); /* MAC ID 62's explicit request */
    bench_rx(&b, "5FC#01");         /* too short */
    bench_rx(&b, "5FC#018E0101");   /* a response */
    bench_rx(&b, "7FC#010E010101"); /* group 3 */
    co_frame_t remote = {0x5FC, 0, CO_FRAME_RTR, {0}};
    dn_node_receive(&b.node, &remote, b.now);
    co_frame_t extended = {0x5FC, 5, CO_FRAME_EFF, {1, 0x0E, 1, 1, 1}};
    dn_node_receive(&b.node, &extended, b.now);
    bench_expect_none(&b);
    /* A length over 8 from a faulty driver: not read past the frame's 8 bytes. */
    co_frame_t too_long = {0x5FC, 9, 0, {1, 0x0E, 1, 1, 1, 0, 0, 0}};
    dn_node_receive(&b.node, &too_long, b.now);
    bench_expect_none(&b);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet explicit messaging");
    TCase *tc = tcase_create("explicit");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, allocate_explicit);
    tcase_add_test(tc, allocate_refusals);
    tcase_add_test(tc, release);
    tcase_add_test(tc, identity_attributes);
    tcase_add_test(tc, identity_refusals);
    tcase_add_test(tc, identity_reset);
    tcase_add_test(tc, devicenet_object);
    tcase_add_test(tc, quick_connect_stored);
    tcase_add_test(tc, assembly_object);
    tcase_add_test(tc, connection_class);
    tcase_add_test(tc, restart_uses_stored_assemblies);
    tcase_add_test(tc, explicit_connection_attributes);
    tcase_add_test(tc, ack_handler_object);
    tcase_add_test(tc, application_objects);
    tcase_add_test(tc, explicit_watchdog_auto_delete);
    tcase_add_test(tc, explicit_watchdog_multiplier);
    tcase_add_test(tc, explicit_watchdog_deferred_delete);
    tcase_add_test(tc, deferred_delete_without_io_deletes);
    tcase_add_test(tc, frames_not_for_the_slave);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
