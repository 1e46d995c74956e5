/* SPDX-License-Identifier: Apache-2.0 */
/* EMCY producer: frame bytes, 1001h bits, 1003h history (order, cap, clear, bad value), the
 * error reset frame, the inhibit time queue with exact times, 1014h validity and CAN-ID rules,
 * states in which EMCY is sent. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdio.h>
#include <stdlib.h>

static test_node_t t;

static void setup(void)
{
    test_node_start(&t, 4, NULL, NULL);
}

static void raise_error(uint16_t code, uint8_t reg)
{
    t.node.now = t.bus.now;
    ck_assert(co_emcy_raise(&t.node, code, reg, NULL));
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

static void clear_error(uint16_t code)
{
    t.node.now = t.bus.now;
    co_emcy_clear(&t.node, code);
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

START_TEST(frame_bytes_register_and_error_reset)
{
    const uint8_t msef[5] = {1, 2, 3, 4, 5};
    t.node.now = t.bus.now;
    ck_assert(co_emcy_raise(&t.node, 0x8130, CO_ERR_REG_COMMUNICATION, msef));
    test_expect(&t, "084#3081110102030405");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x11);
    ck_assert(co_emcy_is_active(&t.node, 0x8130));
    raise_error(0x4210, CO_ERR_REG_TEMPERATURE);
    test_expect(&t, "084#1042190000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x19);
    clear_error(0x8130); /* others remain: no frame */
    test_expect_none(&t);
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0x09);
    ck_assert(!co_emcy_is_active(&t.node, 0x8130));
    clear_error(0x8130); /* not active any more: nothing */
    test_expect_none(&t);
    clear_error(0x4210);
    test_expect(&t, "084#0000000000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0);
}
END_TEST

/* CiA 301 7.2.7.1: a dictionary without 1014h (the PLC300's) sends its EMCY on the predefined
 * CAN-ID, 80h + node-id, never on 000h, the NMT's. */
START_TEST(without_1014h_the_predefined_can_id)
{
    test_node_start_od(&t, test_od_without(0x1014), 5, NULL, NULL);
    raise_error(0x8130, CO_ERR_REG_COMMUNICATION);
    test_expect(&t, "085#3081110000000000");
}
END_TEST

START_TEST(raise_refusals)
{
    raise_error(0x1000, 0);
    test_expect(&t, "084#0010010000000000");
    t.node.now = t.bus.now;
    ck_assert(!co_emcy_raise(&t.node, 0x1000, 0, NULL)); /* already active */
    ck_assert(!co_emcy_raise(&t.node, 0x0000, 0, NULL)); /* not an error */
    for (uint16_t i = 1; i < CO_CONFIG_EMCY_HISTORY; i++)
        ck_assert(co_emcy_raise(&t.node, (uint16_t)(0xFF00 + i), 0, NULL));
    ck_assert(!co_emcy_raise(&t.node, 0xFFFF, 0, NULL)); /* table full */
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 0), 5);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 1), 0xFF00 + CO_CONFIG_EMCY_HISTORY - 1);
}
END_TEST

START_TEST(history_order_cap_and_clear)
{
    uint16_t codes[] = {0x2310, 0x3210, 0x4310, 0x5000, 0x6100, 0x7000};
    for (size_t i = 0; i < 6; i++)
        raise_error(codes[i], 0);
    test_drain(&t);
    uint32_t v;
    ck_assert_uint_eq(test_sdo_read(&t, 0x1003, 0, &v), 0);
    ck_assert_uint_eq(v, 5); /* capped at the five sub-indexes of the test OD */
    for (uint8_t sub = 1; sub <= 5; sub++) {
        ck_assert_uint_eq(test_sdo_read(&t, 0x1003, sub, &v), 0);
        ck_assert_uint_eq(v, codes[6 - sub]);
    }
    ck_assert_uint_eq(test_sdo_write(&t, 0x1003, 0, 1, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 0), 5);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1003, 1, 0, 4), CO_SDO_ABORT_READ_ONLY);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1003, 0, 0, 1), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 0), 0);
    for (uint8_t sub = 1; sub <= 5; sub++)
        ck_assert_int_eq(co_od_value(&t.node, 0x1003, sub), 0);
    /* Clearing the history does not clear the active errors. */
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 1);
    raise_error(0x8110, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 0), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 1), 0x8110);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 2), 0);
}
END_TEST

START_TEST(inhibit_time_queues_with_exact_times)
{
    ck_assert_uint_eq(test_write(&t, 0x1015, 0, 100, 2), 0); /* 10 ms */
    test_advance(&t, 1000);
    raise_error(0x1000, 0);
    raise_error(0x2000, CO_ERR_REG_CURRENT);
    raise_error(0x3000, CO_ERR_REG_VOLTAGE);
    ck_assert_uint_eq(test_expect(&t, "084#0010010000000000"), 1000);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, 11000);
    test_advance(&t, 9999);
    test_expect_none(&t);
    test_advance(&t, 1);
    /* The register byte is the one at the time of the raise. */
    ck_assert_uint_eq(test_expect(&t, "084#0020030000000000"), 11000);
    test_advance(&t, 10000);
    ck_assert_uint_eq(test_expect(&t, "084#0030070000000000"), 21000);
    test_advance(&t, 100000);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    /* After the inhibit time, the next one goes at once. */
    clear_error(0x1000);
    clear_error(0x2000);
    clear_error(0x3000);
    ck_assert_uint_eq(test_expect(&t, "084#0000000000000000"), 121000);
}
END_TEST

START_TEST(queue_overflow_drops_newest)
{
    ck_assert_uint_eq(test_write(&t, 0x1015, 0, 10, 2), 0); /* 1 ms */
    raise_error(0x1001, 0);
    for (uint16_t i = 0; i < CO_CONFIG_EMCY_QUEUE + 1; i++)
        raise_error((uint16_t)(0x1100 + i), 0);
    test_advance(&t, 100000);
    test_expect(&t, "084#0110010000000000");
    for (uint16_t i = 0; i < CO_CONFIG_EMCY_QUEUE; i++) {
        char want[32];
        snprintf(want, sizeof(want), "084#%02X11010000000000", i);
        ck_assert_uint_eq(test_expect(&t, want), 1000u * (i + 1));
    }
    test_expect_none(&t);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 1), 0x1100 + CO_CONFIG_EMCY_QUEUE);
}
END_TEST

START_TEST(invalid_cobid_silences_and_can_id_rules)
{
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x85, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x20000084, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000800, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x84, 4), 0); /* same value */
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000084, 4), 0);
    raise_error(0x1000, 0);
    test_expect_none(&t);
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 1), 0x1000);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000095, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x00000095, 4), 0);
    clear_error(0x1000);
    test_expect(&t, "095#0000000000000000");
}
END_TEST

/* CiA 301 7.3.5: 1014h refuses a restricted CAN-ID at both edges of every range, valid or not
 * (bit 31), so an invalid EMCY cannot be prepared on one either; 080h + node-id and the other free
 * CAN-IDs are taken. */
START_TEST(restricted_can_ids_refused_even_when_invalid)
{
    test_rx(&t, "604#23141000FF050080"); /* 1014h = 800005FFh */
    test_expect(&t, "584#8014100030000906");
    for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++) {
        uint32_t id = test_restricted_can_id[i];
        ck_assert_uint_eq(test_write(&t, 0x1014, 0, id, 4), CO_SDO_ABORT_VALUE_RANGE);
        ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000000u | id, 4), CO_SDO_ABORT_VALUE_RANGE);
    }
    ck_assert_int_eq(co_od_value(&t.node, 0x1014, 0), 0x84);
    for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++) {
        uint32_t id = test_free_can_id[i];
        ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000000u | id, 4), 0);
        ck_assert_uint_eq(test_write(&t, 0x1014, 0, id, 4), 0);
        ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x80000000u | id, 4), 0);
    }
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x800000FF, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1014, 0, 0x000000FF, 4), 0);
    raise_error(0x1000, 0);
    test_expect(&t, "0FF#0010010000000000");
}
END_TEST

START_TEST(not_sent_in_stopped)
{
    ck_assert_uint_eq(test_write(&t, 0x1015, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
    raise_error(0x1000, 0);
    raise_error(0x2000, 0); /* queued behind the inhibit time */
    test_expect(&t, "084#0010010000000000");
    test_rx(&t, "000#0204");
    test_advance(&t, 100000);
    test_expect_none(&t); /* the queued one was dropped */
    raise_error(0x3000, 0);
    test_expect_none(&t);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 1), 0x3000);
    test_rx(&t, "000#0104");
    clear_error(0x1000);
    clear_error(0x2000);
    clear_error(0x3000);
    test_expect(&t, "084#0000000000000000");
}
END_TEST

START_TEST(reset_scopes)
{
    raise_error(0x1000, CO_ERR_REG_VOLTAGE);
    test_drain(&t);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    /* Reset communication: the condition is still there, the history is not. */
    ck_assert(co_emcy_is_active(&t.node, 0x1000));
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 5);
    ck_assert_int_eq(co_od_value(&t.node, 0x1003, 0), 0);
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
    ck_assert(!co_emcy_is_active(&t.node, 0x1000));
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("emcy");
    TCase *tc = tcase_create("emcy");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, frame_bytes_register_and_error_reset);
    tcase_add_test(tc, without_1014h_the_predefined_can_id);
    tcase_add_test(tc, raise_refusals);
    tcase_add_test(tc, history_order_cap_and_clear);
    tcase_add_test(tc, inhibit_time_queues_with_exact_times);
    tcase_add_test(tc, queue_overflow_drops_newest);
    tcase_add_test(tc, invalid_cobid_silences_and_can_id_rules);
    tcase_add_test(tc, restricted_can_ids_refused_even_when_invalid);
    tcase_add_test(tc, not_sent_in_stopped);
    tcase_add_test(tc, reset_scopes);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
