/* SPDX-License-Identifier: Apache-2.0 */
/* The per-node options of an older profile (CO_NODE_*, co_node.h), each on the test dictionary
 * with and without it: 8-byte frames out and the lengths accepted in, the expedited-only SDO
 * server, long expedited writes, the DS301 V3 abort layout, NMT Disconnect remote node, the
 * generic error register, an asynchronous TPDO's inhibit time written while it runs. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#define MS 1000u

static test_node_t t;

static void start(uint32_t options)
{
    co_node_config_t config = {
        .node_id = 4, .od = &test_od, .options = options, .options_code = &co_node_options};
    test_node_start_config(&t, &config);
}

/* Boot-up, guarding reply, TPDO and EMCY go out with DLC 8; SDO frames were 8 already. */
START_TEST(padded_frames_out)
{
    start(CO_NODE_PAD_DLC8); /* boot-up 704#00 + 7 zero bytes, checked by the start */
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F00000000000000");
    ck_assert_uint_eq(test_write(&t, 0x1800, 5, 0, 2), 0);
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000000000000000");
    test_rx(&t, "204#0F");
    test_expect(&t, "084#1082110100010200"); /* 0x8210: RPDO 1, 1 byte of 2 */
    test_expect_none(&t);
}
END_TEST

/* NMT commands of DLC 2..8 and guarding RTRs of any DLC count with the option only. */
START_TEST(longer_frames_in)
{
    start(0);
    test_rx(&t, "000#0104000000000000");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    test_rx(&t, "704#R8");
    test_expect_none(&t);

    start(CO_NODE_PAD_DLC8);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    test_rx(&t, "000#010400");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_rx(&t, "000#8004000000000000"); /* T58-01 */
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    test_rx(&t, "000#80");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    test_rx(&t, "000#0104000000000000");
    test_rx(&t, "704#R8");
    test_expect(&t, "704#0500000000000000");
    test_rx(&t, "704#R2");
    test_expect(&t, "704#8500000000000000");
    test_expect_none(&t);
}
END_TEST

/* An RPDO padded to DLC 8 is its mapping's frame on a node of 8-byte frames: applied, no EMCY;
 * without the option it is a frame longer than the mapping, 0x8220. */
START_TEST(padded_rpdo_in)
{
    start(CO_NODE_PAD_DLC8);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "204#0600000000000000");
    test_expect_none(&t);
    ck_assert_uint_eq(co_od_value(&t.node, 0x6040, 0), 6);

    start(0);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "204#0600000000000000");
    test_expect(&t, "084#2082110100080200");
    ck_assert_uint_eq(co_od_value(&t.node, 0x6040, 0), 6);
}
END_TEST

/* Segmented and block initiates are refused with 0x05040001, and a value longer than 4 bytes
 * (1008h "ATV312") cannot be uploaded: 0x06010000. Expedited transfers work as ever. */
START_TEST(expedited_only)
{
    start(CO_NODE_SDO_EXPEDITED_ONLY);
    test_rx(&t, "604#2100200804000000"); /* segmented download, 4 bytes */
    test_expect(&t, "584#8000200801000405");
    test_rx(&t, "604#C600200804000000"); /* block download */
    test_expect(&t, "584#8000200801000405");
    test_rx(&t, "604#A400200815000000"); /* block upload, blksize 21 */
    test_expect(&t, "584#8000200801000405");
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#8008100000000106");
    test_rx(&t, "604#2300200778563412");
    test_expect(&t, "584#6000200700000000");
    test_rx(&t, "604#4000200700000000");
    test_expect(&t, "584#4300200778563412");
    test_expect_none(&t);

    start(0);
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
}
END_TEST

/* T58-08: the 16-bit guard time written with 0x23: taken when bytes 6-7 are 0, else still too
 * long (0x06070012); without the option always too long. */
START_TEST(long_expedited_write)
{
    start(CO_NODE_SDO_LONG_EXPEDITED);
    test_rx(&t, "604#230C1000F4010000");
    test_expect(&t, "584#600C100000000000");
    ck_assert_uint_eq(co_od_value(&t.node, 0x100C, 0), 500);
    test_rx(&t, "604#230C1000F4010100");
    test_expect(&t, "584#800C100012000706");
    test_rx(&t, "604#2B0D100004000000"); /* 2 bytes to the 8-bit life time factor */
    test_expect(&t, "584#600D100000000000");
    ck_assert_uint_eq(co_od_value(&t.node, 0x100D, 0), 4);
    ck_assert_uint_eq(co_od_value(&t.node, 0x100C, 0), 500);

    start(0);
    test_rx(&t, "604#230C1000F4010000");
    test_expect(&t, "584#800C100012000706");
}
END_TEST

/* The DS301 V3 layout: byte 6 error code, byte 7 error class, bytes 4-5 zero, the ATV58 card's
 * four (ATV58 manual, "Invalid SDO transactions"). */
START_TEST(error_class_layout)
{
    start(CO_NODE_SDO_ERROR_CLASS | CO_NODE_SDO_EXPEDITED_ONLY);
    static const char *const exchanges[][2] = {
        {"604#4000300000000000", "584#8000300000000206"}, /* no object */
        {"604#4000207F00000000", "584#8000207F00000906"}, /* no sub-index (0x06090011) */
        {"604#2300100000000000", "584#8000100000000106"}, /* read only (0x06010002) */
        {"604#E000100000000000", "584#8000100000000305"}, /* unknown command specifier */
        {"604#2100200804000000", "584#8000200800000305"}, /* segmented: not supported */
        {"604#2F00200501000000", "584#8000200500000106"}, /* value too low (0x06090032) */
        {"604#2B00100000000000", "584#8000100000000106"}, /* length (0x06070010) */
    };
    for (size_t i = 0; i < sizeof exchanges / sizeof exchanges[0]; i++) {
        test_rx(&t, exchanges[i][0]);
        test_expect(&t, exchanges[i][1]);
    }
    test_expect_none(&t);

    start(0);
    test_rx(&t, "604#4000207F00000000");
    test_expect(&t, "584#8000207F11000906");
}
END_TEST

/* NMT command 3 takes the node to Stopped with the option (guarding then answers 04), and is an
 * unknown command without it. */
START_TEST(nmt_disconnect)
{
    start(CO_NODE_NMT_DISCONNECT);
    test_rx(&t, "000#0304");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_STOPPED);
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_rx(&t, "604#4000100000000000");
    test_expect_none(&t);
    test_rx(&t, "000#8000"); /* broadcast Enter pre-operational brings it back */
    test_rx(&t, "000#0300"); /* broadcast disconnect */
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_STOPPED);

    start(0);
    test_rx(&t, "000#0304");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
}
END_TEST

/* 1001h and every EMCY's byte 2 hold the generic bit alone, whoever raises the error: the RPDO
 * length and SYNC length errors of the core (0x11 without the option) and an application's error
 * of another class; 0 again once none is active. */
START_TEST(error_register_generic)
{
    start(CO_NODE_ERROR_REGISTER_GENERIC);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "204#06");
    test_expect(&t, "084#1082010100010200");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x01);
    test_rx(&t, "080#01");
    test_expect(&t, "084#4082010100000000");
    ck_assert(co_emcy_raise(&t.node, 0x5000, CO_ERR_REG_CURRENT | CO_ERR_REG_MANUFACTURER, NULL));
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    test_expect(&t, "084#0050010000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x01);
    co_emcy_clear(&t.node, 0x5000);
    test_rx(&t, "080#");
    test_rx(&t, "204#0600");
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    test_expect(&t, "084#0000000000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0);

    start(0);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "204#06");
    test_expect(&t, "084#1082110100010200");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x11);
}
END_TEST

/* The application changes mapped data and runs the node, as co_node.h asks. */
static void app_set(uint16_t index, uint8_t sub, int64_t value)
{
    ck_assert(co_od_set_value(&t.node, index, sub, value));
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

/* A valid asynchronous TPDO's inhibit time (TPDO1, type 255, 300 = 30 ms) is taken by SDO with
 * the option, the Altivar manuals' "In asynchronous mode "Inhibit time" and "Event timer" can be
 * modified": the window of the last transmission runs out as it was (30 ms), the new value (100 ms)
 * holds from the next transmission on. A valid synchronous TPDO (TPDO6, type 1) keeps CiA 301 table
 * 72's rule, 0x06090030, and so does TPDO1 without the option. */
START_TEST(async_tpdo_inhibit_writable)
{
    start(CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE);
    ck_assert_uint_eq(test_write(&t, 0x1800, 5, 0, 2), 0); /* no event timer: changes only */
    ck_assert_uint_eq(test_write(&t, 0x1805, 2, 1, 1), 0);
    ck_assert_uint_eq(test_write(&t, 0x1805, 1, 0x284, 4), 0);
    test_rx(&t, "604#2B05180364000000");
    test_expect(&t, "584#8005180330000906");
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 3), 300);
    test_rx(&t, "000#0104");
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 0);
    test_advance(&t, 5 * MS);
    test_rx(&t, "604#2B001803E8030000");
    ck_assert_uint_eq(test_expect(&t, "584#6000180300000000"), 5 * MS);
    ck_assert_int_eq(co_od_value(&t.node, 0x1800, 3), 1000);
    test_advance(&t, 5 * MS);
    app_set(0x6041, 0, 0x0021);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, 30 * MS);
    test_advance(&t, 20 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "184#2100"), 30 * MS);
    app_set(0x6041, 0, 0x0023);
    test_advance(&t, 100 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "184#2300"), 130 * MS);
    test_expect_none(&t);

    start(0);
    test_rx(&t, "604#2B001803E8030000");
    test_expect(&t, "584#8000180330000906");
    ck_assert_int_eq(co_od_value(&t.node, 0x1800, 3), 300);
}
END_TEST

static void ignore_frame(void *user, const co_frame_t *frame)
{
    (void)user;
    (void)frame;
}

/* Every option's code is reached through options_code: a node given options without it is
 * refused, each option alone, so that the firmware cannot link without the code it would call. */
START_TEST(options_without_their_code_are_refused)
{
    static uint8_t data[2048];
    co_node_t node;
    ck_assert_uint_le(test_od.data_size, sizeof(data));
    const uint32_t options[] = {CO_NODE_PAD_DLC8,
                                CO_NODE_SDO_EXPEDITED_ONLY,
                                CO_NODE_SDO_LONG_EXPEDITED,
                                CO_NODE_SDO_ERROR_CLASS,
                                CO_NODE_NMT_DISCONNECT,
                                CO_NODE_HEARTBEAT_GRID,
                                CO_NODE_ERROR_REGISTER_GENERIC,
                                CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE};
    for (size_t i = 0; i < sizeof(options) / sizeof(options[0]); i++) {
        co_node_config_t config = {.node_id = 4,
                                   .od = &test_od,
                                   .od_data = data,
                                   .send = ignore_frame,
                                   .options = options[i]};
        ck_assert_int_eq(co_node_init(&node, &config), CO_NODE_ERR_OPTIONS);
        config.options_code = &co_node_options;
        ck_assert_int_eq(co_node_init(&node, &config), 0);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("node_options");
    TCase *tc = tcase_create("options");
    tcase_add_test(tc, padded_frames_out);
    tcase_add_test(tc, longer_frames_in);
    tcase_add_test(tc, padded_rpdo_in);
    tcase_add_test(tc, expedited_only);
    tcase_add_test(tc, long_expedited_write);
    tcase_add_test(tc, error_class_layout);
    tcase_add_test(tc, nmt_disconnect);
    tcase_add_test(tc, error_register_generic);
    tcase_add_test(tc, async_tpdo_inhibit_writable);
    tcase_add_test(tc, options_without_their_code_are_refused);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
