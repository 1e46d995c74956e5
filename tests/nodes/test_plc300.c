/* SPDX-License-Identifier: Apache-2.0 */
/* The PLC300 slave on its dictionary (eds/PLC300.eds), after its CANopen User's Manual: the SDO
 * example of 6.2.2 frame for frame, the markers of one area as views of one memory (Table 5.4's
 * note) by SDO, RPDO and the PLC program, Pre-operational after a heartbeat or life guarding loss
 * from Operational and Stopped (6.5.2, 6.5.3), its LEDs with red over green (2.4), its identity
 * (6.1.4). */
#include "check_main.h"
#include "nodes/plc300/plc300.h"
#include "plain_bench.h"

#define NODE 1
#define SERIAL 0x30000001u

static plain_bench_t b;

static void start(void)
{
    plain_bench_start(&b, &plc300_model, NODE, SERIAL);
    plain_bench_expect(&b, "701#00");
}

START_TEST(the_manuals_sdo_example_reads_999_from_3000h)
{
    start();
    plain_bench_rx(&b, "601#4000300000000000");
    plain_bench_expect(&b, "581#4B003000E7030000");
    plain_bench_expect_none(&b);
}
END_TEST

START_TEST(identity_is_the_manuals_with_the_nodes_serial_number)
{
    start();
    plain_bench_rx(&b, "601#4018100100000000");
    plain_bench_expect(&b, "581#4318100123010000");
    plain_bench_rx(&b, "601#4018100200000000");
    plain_bench_expect(&b, "581#4318100220020000");
    /* The serial number survives the reset that restores 1018h's EDS default. */
    plain_bench_rx(&b, "000#8101");
    plain_bench_expect(&b, "701#00");
    plain_bench_rx(&b, "601#4018100400000000");
    plain_bench_expect(&b, "581#4318100401000030");
}
END_TEST

/* A double word written by SDO at %ID2004 is %IB2004..%IB2007 and %IW2004/%IW2006; a byte
 * written at %IB2001 is the high byte of 3000h (two bytes, D-PLC300-3000H), of %IW2000 and of
 * %ID2000. */
START_TEST(the_views_of_an_area_share_one_memory)
{
    start();
    plain_bench_rx(&b, "601#2304380078563412");
    plain_bench_expect(&b, "581#6004380000000000");
    plain_bench_rx(&b, "601#4005300000000000");
    plain_bench_expect(&b, "581#4F05300056000000");
    plain_bench_rx(&b, "601#4006340000000000");
    plain_bench_expect(&b, "581#4B06340034120000");
    plain_bench_rx(&b, "601#2F013000AA000000");
    plain_bench_expect(&b, "581#6001300000000000");
    plain_bench_rx(&b, "601#4000300000000000");
    plain_bench_expect(&b, "581#4B003000E7AA0000");
    plain_bench_rx(&b, "601#4000380000000000");
    plain_bench_expect(&b, "581#43003800E7AA0000");
    /* The outputs are another memory. */
    plain_bench_rx(&b, "601#4004480000000000");
    plain_bench_expect(&b, "581#4304480000000000");
}
END_TEST

START_TEST(the_plc_program_reads_and_writes_markers)
{
    start();
    plc300_marker_t m;
    ck_assert(plc300_marker_parse("%QW2510", &m));
    ck_assert(m.output && m.size == 2 && m.index == 0x45FE && m.offset == 510);
    ck_assert_uint_eq(plc300_marker_set(&b.plain, &m, 0xBEEF), 0);
    ck_assert(plc300_marker_parse("qb2511", &m));
    ck_assert_uint_eq(plc300_marker_get(&b.plain, &m), 0xBE);
    ck_assert(plc300_marker_parse("%QD2508", &m));
    ck_assert_uint_eq(plc300_marker_get(&b.plain, &m), 0xBEEF0000u);
    /* %IB2000 is the low byte of 3000h: setting it keeps the high byte. */
    ck_assert(plc300_marker_parse("%IB2000", &m));
    ck_assert_uint_eq(plc300_marker_get(&b.plain, &m), 0xE7);
    ck_assert_uint_eq(plc300_marker_set(&b.plain, &m, 0x01), 0);
    plain_bench_rx(&b, "601#4000300000000000");
    plain_bench_expect(&b, "581#4B00300001030000");
    char name[16];
    plc300_marker_name(&m, name, sizeof name);
    ck_assert_str_eq(name, "%IB2000");
}
END_TEST

START_TEST(what_is_no_marker)
{
    plc300_marker_t m;
    const char *bad[] = {"%IW2001", "%ID2002", "%IB1999", "%IB2512",  "%IW2511", "%ID2509",
                         "%XB2000", "%I2000",  "%IB",     "%IB2000x", "%QK2000"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        ck_assert_msg(!plc300_marker_parse(bad[i], &m), "%s parsed", bad[i]);
    ck_assert(plc300_marker_parse("%ID2508", &m) && m.index == 0x39FC);
}
END_TEST

/* The manual's RPDO mapping example (6.3.2) applied by an RPDO in Operational. */
START_TEST(an_rpdo_writes_the_input_markers)
{
    start();
    const char *const steps[][2] = {
        {"601#2300140101020080", "581#6000140100000000"}, /* RPDO1 invalid (CiA 301) */
        {"601#2F00160000000000", "581#6000160000000000"}, /* sub 0 = 0 */
        {"601#2300160110000034", "581#6000160100000000"}, /* 3400.0010h */
        {"601#2300160220000438", "581#6000160200000000"}, /* 3804.0020h */
        {"601#2F00160002000000", "581#6000160000000000"}, /* sub 0 = 2 */
        {"601#2300140101020000", "581#6000140100000000"}, /* valid again */
    };
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        plain_bench_rx(&b, steps[i][0]);
        plain_bench_expect(&b, steps[i][1]);
    }
    plain_bench_rx(&b, "000#0101");
    /* TPDO1-4 valid with nothing mapped (the manual's defaults) go out once, empty (docs/plc300.md,
     * "PDOs"). */
    plain_bench_expect(&b, "181#");
    plain_bench_expect(&b, "281#");
    plain_bench_expect(&b, "381#");
    plain_bench_expect(&b, "481#");
    /* Longer than the mapping: applied up to its 6 bytes, and the EMCY 8220h on the predefined
     * CAN-ID (80h + node-id: the PLC300 has no 1014h, Table 1.2). */
    plain_bench_rx(&b, "201#3412785634120000");
    plain_bench_expect(&b, "081#2082110100080600");
    plain_bench_rx(&b, "601#4000300000000000");
    plain_bench_expect(&b, "581#4B00300034120000");
    plain_bench_rx(&b, "601#4004300000000000");
    plain_bench_expect(&b, "581#4F04300078000000");
}
END_TEST

static void lose_heartbeat_in(const char *nmt_command, const char *state_byte)
{
    start();
    plain_bench_rx(&b, "601#2316100164000500");
    plain_bench_expect(&b, "581#6016100100000000");
    plain_bench_rx(&b, nmt_command);
    plain_bench_rx(&b, "705#05");
    plain_bench_advance(&b, 99000);
    ck_assert_uint_eq(b.plain.node.nmt_state, (co_nmt_state_t)state_byte[1] - '0');
    plain_bench_advance(&b, 2000);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(b.plain.loss, PLAIN_LOSS_HEARTBEAT);
    ck_assert_uint_eq(b.plain.lost_producer, 5);
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_DOUBLE_FLASH);
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_OFF);
    /* The producer is back: the event is over, the LEDs show the state again. */
    plain_bench_rx(&b, "705#05");
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_OFF);
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_BLINKING);
}

START_TEST(a_heartbeat_loss_in_operational_enters_pre_operational)
{
    lose_heartbeat_in("000#0101", "05");
}
END_TEST

START_TEST(a_heartbeat_loss_in_stopped_enters_pre_operational)
{
    lose_heartbeat_in("000#0201", "04");
}
END_TEST

START_TEST(a_life_guarding_loss_enters_pre_operational)
{
    start();
    plain_bench_rx(&b, "601#2B0C100032000000"); /* 50 ms */
    plain_bench_rx(&b, "601#2F0D100002000000"); /* x 2 */
    plain_bench_rx(&b, "000#0201");
    plain_bench_drain(&b);
    plain_bench_rx(&b, "701#R");
    plain_bench_expect(&b, "701#04");
    plain_bench_advance(&b, 100000);
    ck_assert_uint_eq(b.plain.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(b.plain.loss, PLAIN_LOSS_GUARDING);
    plain_bench_rx(&b, "701#R");
    plain_bench_expect(&b, "701#FF");
    ck_assert_uint_eq(b.plain.loss, PLAIN_LOSS_NONE);
}
END_TEST

/* 63 entries (Table 5.2), the first 8 monitored (docs/decisions.md,
 * D-PLC300-HEARTBEAT-CONSUMERS): a ninth refuses a producer, takes 0. */
START_TEST(heartbeat_consumers_63_entries_8_monitored)
{
    start();
    plain_bench_rx(&b, "601#4016100000000000");
    plain_bench_expect(&b, "581#4F1610003F000000");
    plain_bench_rx(&b, "601#2316100864000500");
    plain_bench_expect(&b, "581#6016100800000000");
    plain_bench_rx(&b, "601#2316100964000600");
    plain_bench_expect(&b, "581#8016100947000406");
    plain_bench_rx(&b, "601#2316103F00000000");
    plain_bench_expect(&b, "581#6016103F00000000");
}
END_TEST

START_TEST(the_red_led_wins_over_the_green)
{
    start();
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_BLINKING);
    plain_node_bus_warning(&b.plain, true);
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_SINGLE_FLASH);
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_OFF);
    plain_node_bus_event(&b.plain, CO_EMCY_BUS_OFF, true);
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_ON);
    plain_node_bus_event(&b.plain, CO_EMCY_BUS_OFF, false);
    plain_node_bus_warning(&b.plain, false);
    ck_assert_uint_eq(plain_node_err_led(&b.plain), CO_LED_OFF);
    plain_bench_rx(&b, "000#0101");
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_ON);
    plain_bench_rx(&b, "000#0201");
    ck_assert_uint_eq(plain_node_run_led(&b.plain), CO_LED_SINGLE_FLASH);
    ck_assert_str_eq(co_led_name(CO_LED_DOUBLE_FLASH), "double flash");
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("plc300");
    TCase *tc = tcase_create("plc300");
    tcase_add_test(tc, the_manuals_sdo_example_reads_999_from_3000h);
    tcase_add_test(tc, identity_is_the_manuals_with_the_nodes_serial_number);
    tcase_add_test(tc, the_views_of_an_area_share_one_memory);
    tcase_add_test(tc, the_plc_program_reads_and_writes_markers);
    tcase_add_test(tc, what_is_no_marker);
    tcase_add_test(tc, an_rpdo_writes_the_input_markers);
    tcase_add_test(tc, a_heartbeat_loss_in_operational_enters_pre_operational);
    tcase_add_test(tc, a_heartbeat_loss_in_stopped_enters_pre_operational);
    tcase_add_test(tc, a_life_guarding_loss_enters_pre_operational);
    tcase_add_test(tc, heartbeat_consumers_63_entries_8_monitored);
    tcase_add_test(tc, the_red_led_wins_over_the_green);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
