/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS slave, frame by frame with injected time: an unconfigured node (FFh) silent but for
 * LSS until it gets a node-id and boots, the pending node-id taken at NMT resets, every service in
 * the state that takes it and ignored in the other, switch state selective and identify remote
 * slave in and out of order, fastscan to the configuration state, bit timing with its delays,
 * store through the application with every error code, and malformed frames that change nothing.
 * The test dictionary's identity (1018h): vendor 5Fh, product 312h, revision 00010002h, serial
 * 12345678h. */
#include "check_main.h"
#include "co/co_consumers.h"
#include "test_bus.h"
#include "test_od.h"

#include <string.h>

static test_node_t t;
static co_lss_slave_t lss;

/* What the hooks were called with. */
static struct {
    unsigned supported_calls, switch_calls, store_calls;
    uint8_t supported_index, switched_index, stored_id, stored_timing;
    co_time_t switched_at;
    uint8_t store_result, store_specific;
} h;

static bool supported(co_node_t *node, uint8_t index)
{
    (void)node;
    h.supported_calls++;
    h.supported_index = index;
    return index != 8; /* anything but 10 kbit/s */
}

static void switch_timing(co_node_t *node, uint8_t index)
{
    h.switch_calls++;
    h.switched_index = index;
    h.switched_at = node->now;
}

static uint8_t store(co_node_t *node, uint8_t node_id, uint8_t bit_timing, uint8_t *specific)
{
    (void)node;
    h.store_calls++;
    h.stored_id = node_id;
    h.stored_timing = bit_timing;
    *specific = h.store_specific;
    return h.store_result;
}

static const co_lss_slave_hooks_t all_hooks = {supported, switch_timing, store};

static void start(uint8_t node_id, const co_lss_slave_hooks_t *hooks)
{
    memset(&h, 0, sizeof(h));
    co_lss_slave_init(&lss, hooks, 3); /* 250 kbit/s */
    co_node_config_t config = {.node_id = node_id, .od = &test_od, .lss = &lss};
    test_node_start_config(&t, &config);
}

static void to_configuration(void)
{
    test_rx(&t, "7E5#0401000000000000");
    test_expect_none(&t);
}

static void select_by_address(void)
{
    test_rx(&t, "7E5#405F000000000000");
    test_rx(&t, "7E5#4112030000000000");
    test_rx(&t, "7E5#4202000100000000");
    test_rx(&t, "7E5#4378563412000000");
}

START_TEST(unconfigured_node_is_silent_but_for_lss)
{
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_INITIALISING);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    test_rx(&t, "000#0100");             /* NMT start all */
    test_rx(&t, "000#8100");             /* NMT reset node all */
    test_rx(&t, "67F#4000100000000000"); /* an SDO request to 127 */
    test_rx(&t, "6FF#4000100000000000"); /* to 600h + FFh */
    test_advance(&t, 10000000);
    test_expect_none(&t);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_INITIALISING);
    to_configuration();
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5EFF000000000000");
    test_expect_none(&t);
}
END_TEST

START_TEST(configured_node_id_boots_on_switch_to_waiting)
{
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    to_configuration();
    test_rx(&t, "7E5#1105000000000000");
    test_expect(&t, "7E4#1100000000000000");
    /* Pending, not active, until the node leaves the configuration state. */
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5EFF000000000000");
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_INITIALISING);
    test_rx(&t, "7E5#0400000000000000");
    test_expect(&t, "705#00");
    test_expect_none(&t);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(t.node.node_id, 5);
    /* A working node now: SDO on 605h, NMT to 5. */
    uint32_t vendor = 0;
    ck_assert_uint_eq(test_sdo_read(&t, 0x1018, 1, &vendor), 0);
    ck_assert_uint_eq(vendor, 0x5F);
    test_rx(&t, "000#0105");
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    test_drain(&t); /* its TPDOs */
    /* A second switch to waiting boots nothing: the node has its node-id. */
    to_configuration();
    test_rx(&t, "7E5#0400000000000000");
    test_expect_none(&t);
}
END_TEST

START_TEST(switch_to_waiting_without_node_id_stays_silent)
{
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    to_configuration();
    test_rx(&t, "7E5#0400000000000000");
    test_expect_none(&t);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_INITIALISING);
}
END_TEST

START_TEST(new_node_id_waits_for_an_nmt_reset)
{
    start(5, NULL);
    to_configuration();
    /* An LSS frame moves no deadline of the services. */
    ck_assert(!t.node.schedule_changed);
    co_frame_t inquire = test_frame("7E5#5E00000000000000");
    co_node_receive(&t.node, &inquire, t.bus.now);
    ck_assert(!t.node.schedule_changed);
    test_expect(&t, "7E4#5E05000000000000");
    test_rx(&t, "7E5#1109000000000000");
    test_expect(&t, "7E4#1100000000000000");
    test_rx(&t, "7E5#0400000000000000");
    test_expect_none(&t);
    test_rx(&t, "7E5#0401000000000000");
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5E05000000000000");
    test_rx(&t, "000#8205"); /* reset communication */
    test_expect(&t, "709#00");
    ck_assert_uint_eq(t.node.node_id, 9);
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5E09000000000000");
    /* FFh takes the node-id away: after the next reset the node is silent but for LSS. */
    test_rx(&t, "7E5#11FF000000000000");
    test_expect(&t, "7E4#1100000000000000");
    uint32_t generation = co_node_consumer_generation(&t.node);
    test_rx(&t, "000#8100");
    test_expect_none(&t);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_INITIALISING);
    /* The runtime's filter must narrow to 7E5h. */
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5EFF000000000000");
}
END_TEST

START_TEST(node_id_out_of_range_is_refused)
{
    static const char *const refused[] = {"7E5#1100000000000000", "7E5#1180000000000000",
                                          "7E5#11FE000000000000"};
    start(5, NULL);
    to_configuration();
    for (size_t i = 0; i < sizeof(refused) / sizeof(refused[0]); i++) {
        test_rx(&t, refused[i]);
        test_expect(&t, "7E4#1101000000000000");
    }
    ck_assert_uint_eq(lss.pending_node_id, 5);
    test_rx(&t, "7E5#117F000000000000");
    test_expect(&t, "7E4#1100000000000000");
    ck_assert_uint_eq(lss.pending_node_id, 127);
}
END_TEST

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user;
    (void)frame;
}

START_TEST(node_id_ff_needs_lss)
{
    co_node_config_t config = {.node_id = 0xFF, .od = &test_od, .od_data = t.data, .send = no_send};
    ck_assert_int_eq(co_node_init(&t.node, &config), CO_NODE_ERR_NODE_ID);
}
END_TEST

START_TEST(switch_selective_in_order_only)
{
    start(5, NULL);
    select_by_address();
    test_expect(&t, "7E4#4400000000000000");
    test_expect_none(&t);
    ck_assert_uint_eq(lss.state, CO_LSS_CONFIGURATION);
    /* In the configuration state a selection is not taken. */
    select_by_address();
    test_expect_none(&t);
    test_rx(&t, "7E5#0400000000000000");
    /* Another serial, or a part out of order or left out, selects nothing. */
    test_rx(&t, "7E5#405F000000000000");
    test_rx(&t, "7E5#4112030000000000");
    test_rx(&t, "7E5#4202000100000000");
    test_rx(&t, "7E5#4379563412000000");
    test_rx(&t, "7E5#405F000000000000");
    test_rx(&t, "7E5#4202000100000000");
    test_rx(&t, "7E5#4112030000000000");
    test_rx(&t, "7E5#4378563412000000");
    test_rx(&t, "7E5#405F000000000000");
    test_rx(&t, "7E5#4112030000000000");
    test_rx(&t, "7E5#4378563412000000");
    test_rx(&t, "7E5#4112030000000000");
    test_rx(&t, "7E5#4202000100000000");
    test_rx(&t, "7E5#4378563412000000");
    test_expect_none(&t);
    ck_assert_uint_eq(lss.state, CO_LSS_WAITING);
    /* The vendor-ID starts over whatever came before. */
    test_rx(&t, "7E5#405F000000000000");
    select_by_address();
    test_expect(&t, "7E4#4400000000000000");
}
END_TEST

START_TEST(inquire_identity_and_node_id)
{
    start(5, NULL);
    /* Not in the waiting state. */
    test_rx(&t, "7E5#5A00000000000000");
    test_rx(&t, "7E5#5E00000000000000");
    test_expect_none(&t);
    to_configuration();
    test_rx(&t, "7E5#5A00000000000000");
    test_expect(&t, "7E4#5A5F000000000000");
    test_rx(&t, "7E5#5B00000000000000");
    test_expect(&t, "7E4#5B12030000000000");
    test_rx(&t, "7E5#5C00000000000000");
    test_expect(&t, "7E4#5C02000100000000");
    test_rx(&t, "7E5#5D00000000000000");
    test_expect(&t, "7E4#5D78563412000000");
    test_rx(&t, "7E5#5E00000000000000");
    test_expect(&t, "7E4#5E05000000000000");
    test_expect_none(&t);
}
END_TEST

START_TEST(configure_bit_timing)
{
    start(5, NULL);
    to_configuration();
    test_rx(&t, "7E5#1300040000000000"); /* no hook: only the present bit rate */
    test_expect(&t, "7E4#1301000000000000");
    start(5, &all_hooks);
    to_configuration();
    test_rx(&t, "7E5#1300040000000000");
    test_expect(&t, "7E4#1300000000000000");
    ck_assert_uint_eq(h.supported_index, 4);
    ck_assert_uint_eq(lss.bit_timing, 4);
    test_rx(&t, "7E5#1300080000000000"); /* the device cannot */
    test_expect(&t, "7E4#1301000000000000");
    test_rx(&t, "7E5#1300050000000000"); /* reserved index */
    test_rx(&t, "7E5#13000A0000000000"); /* beyond the table */
    test_rx(&t, "7E5#1301040000000000"); /* another table */
    test_expect(&t, "7E4#1301000000000000");
    test_expect(&t, "7E4#1301000000000000");
    test_expect(&t, "7E4#1301000000000000");
    ck_assert_uint_eq(h.supported_calls, 2); /* never asked about an invalid entry */
    ck_assert_uint_eq(lss.bit_timing, 4);
    test_rx(&t, "7E5#1300090000000000"); /* automatic detection: the device decides */
    test_expect(&t, "7E4#1300000000000000");
    ck_assert_uint_eq(lss.bit_timing, 9);
}
END_TEST

START_TEST(activate_bit_timing_keeps_still_on_its_delays)
{
    start(5, &all_hooks);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 50, 2), 0);
    test_advance(&t, 50000);
    test_expect(&t, "705#7F");
    to_configuration();
    test_rx(&t, "7E5#1300040000000000");
    test_expect(&t, "7E4#1300000000000000");
    co_time_t command = t.bus.now;
    test_rx(&t, "7E5#1564000000000000"); /* 100 ms */
    test_advance(&t, 99999);
    ck_assert_uint_eq(h.switch_calls, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(h.switch_calls, 1);
    ck_assert_uint_eq(h.switched_index, 4);
    ck_assert_uint_eq(h.switched_at, command + 100000);
    test_advance(&t, 99999);
    /* Nothing in the 200 ms; the heartbeat due at their end goes out. */
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "705#7F"), command + 200000);
    /* Without the hook the command is ignored. */
    start(5, NULL);
    to_configuration();
    test_rx(&t, "7E5#1564000000000000");
    ck_assert(!co_lss_slave_silent(&lss));
    /* In the waiting state too. */
    start(5, &all_hooks);
    test_rx(&t, "7E5#1564000000000000");
    ck_assert(!co_lss_slave_silent(&lss));
}
END_TEST

START_TEST(store_configuration_and_its_errors)
{
    start(5, NULL);
    to_configuration();
    test_rx(&t, "7E5#1700000000000000");
    test_expect(&t, "7E4#1701000000000000");
    start(5, &all_hooks);
    test_rx(&t, "7E5#1700000000000000"); /* waiting: ignored */
    test_expect_none(&t);
    to_configuration();
    test_rx(&t, "7E5#110A000000000000");
    test_expect(&t, "7E4#1100000000000000");
    test_rx(&t, "7E5#1700000000000000");
    test_expect(&t, "7E4#1700000000000000");
    ck_assert_uint_eq(h.stored_id, 10);
    ck_assert_uint_eq(h.stored_timing, 3);
    h.store_result = CO_LSS_STORE_MEDIA_ERROR;
    h.store_specific = 0x42; /* not sent with error 2 */
    test_rx(&t, "7E5#1700000000000000");
    test_expect(&t, "7E4#1702000000000000");
    h.store_result = CO_LSS_SPECIFIC_ERROR;
    test_rx(&t, "7E5#1700000000000000");
    test_expect(&t, "7E4#17FF420000000000");
    ck_assert_uint_eq(h.store_calls, 3);
}
END_TEST

START_TEST(identify_remote_slave_by_ranges)
{
    static const char *const in_range[] = {"7E5#465F000000000000", "7E5#4712030000000000",
                                           "7E5#4802000100000000", "7E5#4902000100000000",
                                           "7E5#4A00000000000000", "7E5#4BFFFFFFFF000000"};
    start(5, NULL);
    for (int state = 0; state < 2; state++) {
        for (size_t i = 0; i < 6; i++)
            test_rx(&t, in_range[i]);
        test_expect(&t, "7E4#4F00000000000000");
        test_expect_none(&t);
        to_configuration(); /* the same in the configuration state */
    }
    /* Bounds included, one off either side is out; out of order is nothing. */
    static const char *const serial_above[] = {"7E5#465F000000000000", "7E5#4712030000000000",
                                               "7E5#4800000000000000", "7E5#49FFFFFFFF000000",
                                               "7E5#4A79563412000000", "7E5#4BFFFFFFFF000000"};
    static const char *const revision_below[] = {"7E5#465F000000000000", "7E5#4712030000000000",
                                                 "7E5#4803000100000000", "7E5#49FFFFFFFF000000",
                                                 "7E5#4A00000000000000", "7E5#4B78563412000000"};
    static const char *const skipped[] = {"7E5#465F000000000000", "7E5#4712030000000000",
                                          "7E5#4902000100000000", "7E5#4A00000000000000",
                                          "7E5#4BFFFFFFFF000000"};
    for (size_t i = 0; i < 6; i++)
        test_rx(&t, serial_above[i]);
    for (size_t i = 0; i < 6; i++)
        test_rx(&t, revision_below[i]);
    for (size_t i = 0; i < 5; i++)
        test_rx(&t, skipped[i]);
    test_rx(&t, "7E5#465E000000000000"); /* another vendor */
    for (size_t i = 1; i < 6; i++)
        test_rx(&t, in_range[i]);
    test_expect_none(&t);
}
END_TEST

START_TEST(identify_non_configured)
{
    start(5, NULL);
    test_rx(&t, "7E5#4C00000000000000");
    test_expect_none(&t);
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    test_rx(&t, "7E5#4C00000000000000");
    test_expect(&t, "7E4#5000000000000000");
    to_configuration();
    test_rx(&t, "7E5#4C00000000000000");
    test_expect(&t, "7E4#5000000000000000");
    /* A pending node-id makes it configured. */
    test_rx(&t, "7E5#1107000000000000");
    test_expect(&t, "7E4#1100000000000000");
    test_rx(&t, "7E5#4C00000000000000");
    test_expect_none(&t);
}
END_TEST

/* A fastscan frame: ID number, bit checked, LSS sub, LSS next. */
static void fastscan(uint32_t id, uint8_t bit, uint8_t sub, uint8_t next)
{
    co_frame_t f = {.id = CO_LSS_ID_MASTER, .len = 8, .data = {CO_LSS_CS_FASTSCAN}};
    co_put_u32(&f.data[1], id);
    f.data[5] = bit;
    f.data[6] = sub;
    f.data[7] = next;
    test_rx_frame(&t, &f);
}

static bool answered(void)
{
    if (t.bus.next == t.bus.count)
        return false;
    test_expect(&t, "7E4#4F00000000000000");
    test_expect_none(&t);
    return true;
}

START_TEST(fastscan_finds_the_address_bit_by_bit)
{
    static const uint32_t address[4] = {0x5F, 0x312, 0x00010002, 0x12345678};
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    fastscan(0, CO_LSS_FASTSCAN_RESET, 0, 0);
    ck_assert(answered());
    for (uint8_t sub = 0; sub < 4; sub++) {
        uint32_t id = 0;
        for (int bit = 31; bit >= 0; bit--) {
            fastscan(id, (uint8_t)bit, sub, sub);
            bool yes = answered();
            /* The slave answers exactly when the guessed 0 is its bit. */
            ck_assert_int_eq(yes, ((address[sub] >> bit) & 1u) == 0);
            if (!yes)
                id |= 1u << bit;
        }
        ck_assert_uint_eq(id, address[sub]);
        /* Another part than the one the slave is at: no answer. */
        fastscan(id, 0, (uint8_t)((sub + 1) % 4), 0);
        ck_assert(!answered());
        ck_assert_uint_eq(lss.state, CO_LSS_WAITING);
        fastscan(id, 0, sub, (uint8_t)((sub + 1) % 4));
        ck_assert(answered());
    }
    ck_assert_uint_eq(lss.state, CO_LSS_CONFIGURATION);
    /* In the configuration state fastscan is not taken, and the node is at the master's call. */
    fastscan(0, CO_LSS_FASTSCAN_RESET, 0, 0);
    ck_assert(!answered());
    test_rx(&t, "7E5#5D00000000000000");
    test_expect(&t, "7E4#5D78563412000000");
}
END_TEST

START_TEST(fastscan_only_for_non_configured_and_valid_fields)
{
    start(5, NULL);
    fastscan(0, CO_LSS_FASTSCAN_RESET, 0, 0);
    ck_assert(!answered());
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    fastscan(0, 32, 0, 0);
    fastscan(0, 0x7F, 0, 0);
    fastscan(0, CO_LSS_FASTSCAN_RESET, 4, 0);
    fastscan(0, 31, 0, 4);
    fastscan(0x5F, 0, 4, 1);
    ck_assert(!answered());
    /* A known vendor-ID in one frame, straight to the product code. */
    fastscan(0, CO_LSS_FASTSCAN_RESET, 0, 0);
    ck_assert(answered());
    fastscan(0x5F, 0, 0, 1);
    ck_assert(answered());
    ck_assert_uint_eq(lss.fastscan_part, 1);
    /* A reset starts over at the vendor-ID. */
    fastscan(0, CO_LSS_FASTSCAN_RESET, 0, 0);
    ck_assert(answered());
    fastscan(0x312, 0, 1, 2);
    ck_assert(!answered());
}
END_TEST

START_TEST(malformed_frames_change_nothing)
{
    start(CO_LSS_NODE_ID_UNCONFIGURED, NULL);
    test_rx(&t, "7E5#04010000000000");   /* DLC 7 */
    test_rx(&t, "7E5#R8");               /* RTR */
    test_rx(&t, "7E5#0402000000000000"); /* no such state */
    test_rx(&t, "7E5#0500000000000000"); /* no such command */
    test_rx(&t, "7E4#0401000000000000"); /* a slave's COB-ID */
    co_frame_t eff = test_frame("7E5#0401000000000000");
    eff.flags = CO_FRAME_EFF;
    test_rx_frame(&t, &eff);
    test_expect_none(&t);
    ck_assert_uint_eq(lss.state, CO_LSS_WAITING);
    to_configuration();
    test_rx(&t, "7E5#11050000000000"); /* DLC 7 */
    test_rx(&t, "7E5#R8");
    test_expect_none(&t);
    ck_assert_uint_eq(lss.pending_node_id, CO_LSS_NODE_ID_UNCONFIGURED);
    test_rx(&t, "7E5#1105000000000000");
    test_expect(&t, "7E4#1100000000000000");
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("lss_slave");
    TCase *tc = tcase_create("lss_slave");
    tcase_add_test(tc, unconfigured_node_is_silent_but_for_lss);
    tcase_add_test(tc, configured_node_id_boots_on_switch_to_waiting);
    tcase_add_test(tc, switch_to_waiting_without_node_id_stays_silent);
    tcase_add_test(tc, new_node_id_waits_for_an_nmt_reset);
    tcase_add_test(tc, node_id_out_of_range_is_refused);
    tcase_add_test(tc, node_id_ff_needs_lss);
    tcase_add_test(tc, switch_selective_in_order_only);
    tcase_add_test(tc, inquire_identity_and_node_id);
    tcase_add_test(tc, configure_bit_timing);
    tcase_add_test(tc, activate_bit_timing_keeps_still_on_its_delays);
    tcase_add_test(tc, store_configuration_and_its_errors);
    tcase_add_test(tc, identify_remote_slave_by_ranges);
    tcase_add_test(tc, identify_non_configured);
    tcase_add_test(tc, fastscan_finds_the_address_bit_by_bit);
    tcase_add_test(tc, fastscan_only_for_non_configured_and_valid_fields);
    tcase_add_test(tc, malformed_frames_change_nothing);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
