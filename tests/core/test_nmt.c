/* SPDX-License-Identifier: Apache-2.0 */
/* NMT slave: every command to this node, to another node and broadcast, with the state seen in
 * the heartbeat and guarding replies; the boot-up frame; the scope of reset node and reset
 * communication; malformed commands; the application hooks. */
#include "check_main.h"
#include "test_bus.h"

#include <stdlib.h>

static test_node_t t;

#define HOOK_LOG 16
static co_nmt_state_t states[HOOK_LOG];
static size_t state_count;
static co_nmt_reset_t resets[HOOK_LOG];
static size_t reset_count;

static void on_state(co_node_t *node, co_nmt_state_t state)
{
    (void)node;
    ck_assert_uint_lt(state_count, HOOK_LOG);
    states[state_count++] = state;
}

static void on_reset(co_node_t *node, co_nmt_reset_t scope)
{
    (void)node;
    ck_assert_uint_lt(reset_count, HOOK_LOG);
    resets[reset_count++] = scope;
}

static const co_app_hooks_t hooks = {.nmt_state = on_state, .reset = on_reset};

static void setup(void)
{
    state_count = 0;
    reset_count = 0;
    test_node_start(&t, 4, &hooks, NULL);
    /* TPDO1 would send on entering Operational: keep the bus to NMT and error control. */
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0);
}

/* The heartbeat producer at 100 ms shows the state one period after it is switched on. */
static void expect_heartbeat_state(const char *frame)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&t, 100000);
    test_expect(&t, frame);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 0, 2), 0);
    test_expect_none(&t);
}

START_TEST(boot_up_frame_and_initial_state)
{
    /* T31-16: boot-up 0x700 + node-id, one byte 00 (checked by test_node_start). */
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(reset_count, 1);
    ck_assert_int_eq(resets[0], CO_NMT_RESET_NODE);
    ck_assert_uint_eq(state_count, 1);
    ck_assert_int_eq(states[0], CO_NMT_PRE_OPERATIONAL);
    test_expect_none(&t);
}
END_TEST

START_TEST(commands_to_own_id)
{
    test_rx(&t, "000#0104");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    expect_heartbeat_state("704#05");
    test_rx(&t, "000#0204");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_STOPPED);
    expect_heartbeat_state("704#04");
    test_rx(&t, "000#8004"); /* T31-01 */
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    expect_heartbeat_state("704#7F");
    test_rx(&t, "000#0204");
    test_rx(&t, "000#0104"); /* Stopped -> Operational */
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_expect_none(&t);
    co_nmt_state_t want[] = {CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL, CO_NMT_STOPPED,
                             CO_NMT_PRE_OPERATIONAL, CO_NMT_STOPPED,     CO_NMT_OPERATIONAL};
    ck_assert_uint_eq(state_count, sizeof(want) / sizeof(want[0]));
    for (size_t i = 0; i < state_count; i++)
        ck_assert_int_eq(states[i], want[i]);
}
END_TEST

START_TEST(commands_to_other_id_ignored)
{
    test_rx(&t, "000#0105");
    test_rx(&t, "000#0203");
    test_rx(&t, "000#817F");
    test_rx(&t, "000#8205");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(state_count, 1);
    ck_assert_uint_eq(reset_count, 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(broadcast_commands)
{
    test_rx(&t, "000#0100");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_rx(&t, "000#0200");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_STOPPED);
    /* Guarding shows the state too: toggle 0 then 1. */
    test_rx(&t, "704#R");
    test_expect(&t, "704#04");
    test_rx(&t, "000#8000");
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    test_rx(&t, "704#R");
    test_expect(&t, "704#FF");
    test_rx(&t, "000#8100");
    test_expect(&t, "704#00");
    test_rx(&t, "000#8200");
    test_expect(&t, "704#00");
    ck_assert_uint_eq(reset_count, 3);
    ck_assert_int_eq(resets[1], CO_NMT_RESET_NODE);
    ck_assert_int_eq(resets[2], CO_NMT_RESET_COMMUNICATION);
    test_expect_none(&t);
}
END_TEST

START_TEST(same_state_command_is_silent)
{
    test_rx(&t, "000#8004");
    ck_assert_uint_eq(state_count, 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(malformed_commands_ignored)
{
    test_rx(&t, "000#01");
    test_rx(&t, "000#010400");
    test_rx(&t, "000#R2");
    test_rx(&t, "000#0304"); /* no such command specifier */
    test_rx(&t, "000#");
    co_frame_t eff = test_frame("000#0104");
    eff.flags = CO_FRAME_EFF;
    test_rx_frame(&t, &eff);
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(state_count, 1);
    ck_assert_uint_eq(reset_count, 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(reset_communication_scope)
{
    ck_assert_uint_eq(test_write(&t, 0x2000, 0x07, 0xCAFEF00D, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 250, 2), 0);
    test_rx(&t, "000#0104");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0xCAFEF00D);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    test_advance(&t, 1000000);
    test_expect_none(&t);
}
END_TEST

START_TEST(reset_node_scope)
{
    ck_assert_uint_eq(test_write(&t, 0x2000, 0x07, 0xCAFEF00D, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 250, 2), 0);
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_int_eq(resets[1], CO_NMT_RESET_NODE);
    test_advance(&t, 1000000);
    test_expect_none(&t);
}
END_TEST

START_TEST(heartbeat_in_every_state)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 10, 2), 0);
    test_advance(&t, 10000);
    test_expect(&t, "704#7F");
    test_rx(&t, "000#0204");
    test_advance(&t, 10000);
    test_expect(&t, "704#04");
    test_rx(&t, "000#0104");
    test_advance(&t, 10000);
    test_expect(&t, "704#05");
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("nmt");
    TCase *tc = tcase_create("nmt");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, boot_up_frame_and_initial_state);
    tcase_add_test(tc, commands_to_own_id);
    tcase_add_test(tc, commands_to_other_id_ignored);
    tcase_add_test(tc, broadcast_commands);
    tcase_add_test(tc, same_state_command_is_silent);
    tcase_add_test(tc, malformed_commands_ignored);
    tcase_add_test(tc, reset_communication_scope);
    tcase_add_test(tc, reset_node_scope);
    tcase_add_test(tc, heartbeat_in_every_state);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
