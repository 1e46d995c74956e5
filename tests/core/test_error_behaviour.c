/* SPDX-License-Identifier: Apache-2.0 */
/* Error behaviour 1029h (CiA 301 7.5.2.32): a heartbeat producer or life guarding lost takes the
 * node where 1029h:01 says (0 Pre-operational from Operational only, 1 no change, 2 Stopped), a
 * device error class where its sub-index says, the reserved values refused; a node without the
 * service leaves its state alone. The state is read back with a node guarding request. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

static test_node_t t;
static unsigned losses;
static co_nmt_state_t state_at_loss;

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    (void)producer;
    if (lost)
        state_at_loss = node->nmt_state;
    losses += lost;
}

static const co_app_hooks_t hooks = {.heartbeat = on_heartbeat};

static void start(const co_error_behaviour_code_t *code)
{
    losses = 0;
    co_node_config_t config = {
        .node_id = 4, .od = &test_od, .hooks = &hooks, .error_behaviour = code};
    test_node_start_config(&t, &config);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0); /* no TPDO in Operational */
}

static void setup(void)
{
    start(&co_error_behaviour);
}

/* Producer 5 monitored for 150 ms, seen once at the current time: lost 150 ms later. */
static void lose_producer_5(void)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050000 | 150, 4), 0);
    test_rx(&t, "705#05");
    test_advance(&t, 149999);
    ck_assert_uint_eq(losses, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(losses, 1);
}

START_TEST(communication_error_0_operational_to_pre_operational)
{
    ck_assert_int_eq(co_od_value(&t.node, 0x1029, 1), 0);
    test_rx(&t, "000#0104");
    lose_producer_5();
    /* The application hears of the loss after the state changed. */
    ck_assert_uint_eq(state_at_loss, CO_NMT_PRE_OPERATIONAL);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
    test_expect_none(&t);
}
END_TEST

START_TEST(communication_error_0_leaves_stopped_alone)
{
    test_rx(&t, "000#0204");
    lose_producer_5();
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_expect_none(&t);
}
END_TEST

START_TEST(communication_error_1_no_change)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 1, 1), 0);
    test_rx(&t, "000#0104");
    lose_producer_5();
    test_rx(&t, "704#R");
    test_expect(&t, "704#05");
    test_expect_none(&t);
}
END_TEST

START_TEST(communication_error_2_to_stopped_from_any_state)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 2, 1), 0);
    lose_producer_5(); /* from Pre-operational */
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_rx(&t, "000#0104");
    test_rx(&t, "705#05"); /* back, and lost again, now from Operational */
    test_advance(&t, 150000);
    ck_assert_uint_eq(losses, 2);
    test_rx(&t, "704#R");
    test_expect(&t, "704#84");
    test_expect_none(&t);
}
END_TEST

/* Life time 1 s (100Ch 250 ms x 100Dh 4), started by the first guarding request. */
START_TEST(life_guarding_loss_is_a_communication_error)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 2, 1), 0);
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 250, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x100D, 0, 4, 1), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "704#R");
    test_expect(&t, "704#05");
    test_advance(&t, 999999);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_advance(&t, 1);
    test_rx(&t, "704#R");
    test_expect(&t, "704#84");
    test_expect_none(&t);
}
END_TEST

/* RPDO 6 monitored for 100 ms (1405h:05), silent after one frame: the EMCY 8250h, then Stopped. */
START_TEST(rpdo_timeout_is_a_communication_error)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 2, 1), 0);
    ck_assert_uint_eq(test_write(&t, 0x1405, 5, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x1405, 1, 0x305, 4), 0);
    test_rx(&t, "000#0104");
    test_drain(&t);
    test_rx(&t, "305#0F00B004");
    test_advance(&t, 99999);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_advance(&t, 1);
    test_expect(&t, "084#5082110600000400");
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_expect_none(&t);
}
END_TEST

/* A device error class of the dictionary (1029h:02), raised by the application. */
START_TEST(device_error_class_raised_by_the_application)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 2, 2, 1), 0);
    test_rx(&t, "000#0104");
    t.node.error_behaviour->raise(&t.node, 2);
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    /* A class the dictionary lacks behaves as 0, CiA 301's default. */
    test_rx(&t, "000#0104");
    t.node.error_behaviour->raise(&t.node, 3);
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    test_expect_none(&t);
}
END_TEST

START_TEST(reserved_values_refused)
{
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 3, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 127, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1029, 1), 0);
    /* 128..255 are the manufacturer's: taken, and no change of state. */
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 128, 1), 0);
    test_rx(&t, "000#0104");
    lose_producer_5();
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    ck_assert_uint_eq(test_write(&t, 0x1029, 0, 1, 1), CO_SDO_ABORT_READ_ONLY);
}
END_TEST

START_TEST(node_without_the_service_keeps_its_state)
{
    start(NULL);
    ck_assert_uint_eq(test_write(&t, 0x1029, 1, 2, 1), 0);
    test_rx(&t, "000#0104");
    lose_producer_5();
    test_rx(&t, "704#R");
    test_expect(&t, "704#05");
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("error_behaviour");
    TCase *tc = tcase_create("error_behaviour");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, communication_error_0_operational_to_pre_operational);
    tcase_add_test(tc, communication_error_0_leaves_stopped_alone);
    tcase_add_test(tc, communication_error_1_no_change);
    tcase_add_test(tc, communication_error_2_to_stopped_from_any_state);
    tcase_add_test(tc, life_guarding_loss_is_a_communication_error);
    tcase_add_test(tc, rpdo_timeout_is_a_communication_error);
    tcase_add_test(tc, device_error_class_raised_by_the_application);
    tcase_add_test(tc, reserved_values_refused);
    tcase_add_test(tc, node_without_the_service_keeps_its_state);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
