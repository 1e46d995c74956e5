/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 401 I/O node on its dictionary (eds/IO401.eds): its default PDOs following its
 * terminals, its serial number, CiA 301's error behaviour without 1029h (Pre-operational from
 * Operational only) and the same by 1029h:01, which may say Stopped, for a heartbeat loss and a
 * bus off recovery, 1F80h without self start, its LEDs as CiA 303-3 has them (both show), TIME
 * consumed on 100h, its second SDO server 1201h. */
#include "check_main.h"
#include "nodes/io/io401.h"
#include "plain_bench.h"

#define NODE 10

static plain_bench_t b;

static void start_operational(void)
{
    plain_bench_start(&b, &io401_model, NODE, 0x4010000Au);
    plain_bench_expect(&b, "70A#00");
    plain_bench_rx(&b, "000#010A");
    plain_bench_drain(&b);
}

START_TEST(the_tpdos_send_the_inputs_when_they_change)
{
    start_operational();
    ck_assert(io401_set_input(&b.plain, 3, true));
    plain_bench_advance(&b, 1000);
    plain_bench_expect(&b, "18A#04");
    plain_bench_expect_none(&b);
    ck_assert(io401_set_analog(&b.plain, 2, -300));
    plain_bench_advance(&b, 1000);
    plain_bench_expect(&b, "28A#0000D4FE");
    plain_bench_expect_none(&b);
    ck_assert(!io401_set_input(&b.plain, 9, true));
    ck_assert(!io401_set_analog(&b.plain, 3, 1));
    ck_assert_uint_eq(io401_inputs(&b.plain), 0x04);
    ck_assert_int_eq(io401_analog(&b.plain, 2), -300);
}
END_TEST

START_TEST(rpdo1_sets_the_outputs)
{
    start_operational();
    plain_bench_rx(&b, "20A#A5");
    ck_assert_uint_eq(io401_outputs(&b.plain), 0xA5);
}
END_TEST

START_TEST(it_consumes_time_on_100h)
{
    start_operational();
    ck_assert(!b.plain.time_received);
    plain_bench_rx(&b, "60A#4012100000000000");
    plain_bench_expect(&b, "58A#4312100000010080");
    plain_bench_rx(&b, "100#952CB302393D"); /* 2026-11-29 12:34:56.789 */
    ck_assert(b.plain.time_received);
    ck_assert_uint_eq(b.plain.time.ms, 45296789u);
    ck_assert_uint_eq(b.plain.time.days, 15673u);
    plain_bench_expect_none(&b);
}
END_TEST

START_TEST(the_serial_number_is_the_nodes)
{
    start_operational();
    plain_bench_rx(&b, "60A#4018100400000000");
    plain_bench_expect(&b, "58A#431810040A001040");
}
END_TEST

START_TEST(a_heartbeat_loss_leaves_stopped_alone)
{
    start_operational();
    plain_bench_rx(&b, "60A#2316100164000500");
    plain_bench_rx(&b, "000#020A");
    plain_bench_rx(&b, "705#05");
    plain_bench_advance(&b, 200000);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_STOPPED);
    ck_assert_uint_eq(b.plain.loss, PLAIN_LOSS_HEARTBEAT);
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_DOUBLE_FLASH);
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_SINGLE_FLASH);
    /* From Operational it enters Pre-operational (CiA 301, 1029h:01 = 0). */
    plain_bench_rx(&b, "705#05");
    plain_bench_rx(&b, "000#010A");
    plain_bench_advance(&b, 200000);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
}
END_TEST

/* 1029h:01 = 2 (CiA 301 7.5.2.32): a heartbeat loss and a bus off recovery stop the node. */
START_TEST(error_behaviour_1029_stops_it)
{
    start_operational();
    plain_bench_rx(&b, "60A#4029100100000000");
    plain_bench_expect(&b, "58A#4F29100100000000");
    plain_bench_rx(&b, "60A#2F29100103000000");
    plain_bench_expect(&b, "58A#8029100130000906");
    plain_bench_rx(&b, "60A#2F29100102000000");
    plain_bench_expect(&b, "58A#6029100100000000");
    plain_bench_rx(&b, "60A#2316100164000500");
    plain_bench_expect(&b, "58A#6016100100000000");
    plain_bench_rx(&b, "705#05");
    plain_bench_advance(&b, 200000);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_STOPPED);
    ck_assert_uint_eq(b.plain.loss, PLAIN_LOSS_HEARTBEAT);
    plain_bench_rx(&b, "000#010A");
    plain_bench_expect(&b, "18A#00"); /* the TPDOs on entering Operational again */
    plain_bench_expect(&b, "28A#00000000");
    plain_node_bus_event(&b.plain, CO_EMCY_BUS_OFF, true);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_OPERATIONAL);
    plain_node_bus_event(&b.plain, CO_EMCY_BUS_OFF, false);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_STOPPED);
    plain_bench_expect_none(&b);
}
END_TEST

START_TEST(nmt_startup_1f80_waits_for_the_master)
{
    plain_bench_start(&b, &io401_model, NODE, 0x4010000Au);
    plain_bench_expect(&b, "70A#00");
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    plain_bench_rx(&b, "60A#40801F0000000000");
    plain_bench_expect(&b, "58A#43801F0004000000");
    plain_bench_rx(&b, "60A#23801F0001000000"); /* NMT master: not a slave's */
    plain_bench_expect(&b, "58A#80801F0030000906");
    plain_bench_expect_none(&b);
}
END_TEST

/* 1201h, the second SDO server: not valid until a master gives it COB-IDs, then a client on 68Ah
 * and 6CAh talks to the node as one on 60Ah does; reset communication makes it not valid again. */
START_TEST(a_second_sdo_server_on_1201h)
{
    start_operational();
    plain_bench_rx(&b, "60A#4001120100000000");
    plain_bench_expect(&b, "58A#4301120180060080");
    plain_bench_rx(&b, "680#4018100400000000");
    plain_bench_expect_none(&b);
    plain_bench_rx(&b, "60A#230112018A060000");
    plain_bench_expect(&b, "58A#6001120100000000");
    plain_bench_rx(&b, "60A#23011202CA060000");
    plain_bench_expect(&b, "58A#6001120200000000");
    plain_bench_rx(&b, "68A#4018100400000000");
    plain_bench_expect(&b, "6CA#431810040A001040");
    plain_bench_rx(&b, "60A#230112018B060000"); /* a new CAN-ID while valid */
    plain_bench_expect(&b, "58A#8001120130000906");
    plain_bench_rx(&b, "000#820A");
    plain_bench_expect(&b, "70A#00");
    plain_bench_rx(&b, "68A#4018100400000000");
    plain_bench_expect_none(&b);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("io401");
    TCase *tc = tcase_create("io401");
    tcase_add_test(tc, the_tpdos_send_the_inputs_when_they_change);
    tcase_add_test(tc, rpdo1_sets_the_outputs);
    tcase_add_test(tc, it_consumes_time_on_100h);
    tcase_add_test(tc, the_serial_number_is_the_nodes);
    tcase_add_test(tc, a_heartbeat_loss_leaves_stopped_alone);
    tcase_add_test(tc, error_behaviour_1029_stops_it);
    tcase_add_test(tc, nmt_startup_1f80_waits_for_the_master);
    tcase_add_test(tc, a_second_sdo_server_on_1201h);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
