/* SPDX-License-Identifier: Apache-2.0 */
/* The COB-IDs a node consumes (co_consumers.h): the set after start, its changes on writes of
 * COB-ID objects and resets with the generation number, and that the node ignores every frame
 * outside the set (so a runtime may drop those frames unseen). */
#include "check_main.h"
#include "co/co_consumers.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdio.h>

static test_node_t t;

static void setup(void)
{
    test_node_start(&t, 4, NULL, NULL);
}

/* The set as "204 704R ..." in enumeration order, for exact comparisons. */
static const char *consumed(char *buf, size_t len)
{
    co_cob_t cobs[CO_CONSUMERS_MAX];
    size_t count = co_node_consumers(&t.node, cobs);
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < count && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%03X%s", i ? " " : "",
                                 (unsigned)cobs[i].can_id, cobs[i].rtr ? "R" : "");
    return buf;
}

START_TEST(a_started_node_consumes_nmt_sync_sdo_guarding_and_its_valid_pdos)
{
    char buf[256];
    /* RPDO1 204h valid, RPDO6 (80000300h) invalid; TPDO1 184h allows RTR; TPDO6 invalid. */
    ck_assert_str_eq(consumed(buf, sizeof buf), "000 080 604 704R 204 184R");
    ck_assert(co_node_consumes(&t.node, 0x604, false));
    ck_assert(!co_node_consumes(&t.node, 0x604, true));
    ck_assert(co_node_consumes(&t.node, 0x704, true));
    ck_assert(!co_node_consumes(&t.node, 0x704, false));
    ck_assert(!co_node_consumes(&t.node, 0x605, false));
    ck_assert(!co_node_consumes(&t.node, 0x304, false));
}
END_TEST

START_TEST(a_node_in_initialising_consumes_nothing)
{
    static test_node_t fresh;
    co_node_config_t config = {.node_id = 5,
                               .od = t.node.od,
                               .od_data = fresh.data,
                               .send = t.node.send,
                               .user = &fresh.bus};
    ck_assert_int_eq(co_node_init(&fresh.node, &config), 0);
    co_cob_t cobs[CO_CONSUMERS_MAX];
    ck_assert_uint_eq(co_node_consumers(&fresh.node, cobs), 0);
    ck_assert(!co_node_consumes(&fresh.node, 0x000, false));
}
END_TEST

/* A node with LSS takes 7E5h in every NMT state (CiA 305), Initialising included: a node without
 * node-id consumes that and nothing else, then its node's set once LSS has booted it. */
START_TEST(a_node_with_lss_consumes_7e5_with_or_without_node_id)
{
    static test_node_t unconfigured;
    static co_lss_slave_t lss;
    char buf[256];
    co_lss_slave_init(&lss, NULL, 3);
    co_node_config_t config = {.node_id = CO_LSS_NODE_ID_UNCONFIGURED, .od = &test_od, .lss = &lss};
    test_node_start_config(&unconfigured, &config);
    co_cob_t cobs[CO_CONSUMERS_MAX];
    ck_assert_uint_eq(co_node_consumers(&unconfigured.node, cobs), 1);
    ck_assert_uint_eq(cobs[0].can_id, CO_LSS_ID_MASTER);
    ck_assert(!cobs[0].rtr);
    ck_assert(co_node_consumes(&unconfigured.node, CO_LSS_ID_MASTER, false));
    uint32_t generation = co_node_consumer_generation(&unconfigured.node);
    test_rx(&unconfigured, "7E5#0401000000000000"); /* configuration state */
    test_rx(&unconfigured, "7E5#1106000000000000"); /* node-id 6 */
    test_expect(&unconfigured, "7E4#1100000000000000");
    test_rx(&unconfigured, "7E5#0400000000000000"); /* waiting: it boots */
    test_expect(&unconfigured, "706#00");
    ck_assert_uint_ne(co_node_consumer_generation(&unconfigured.node), generation);
    size_t count = co_node_consumers(&unconfigured.node, cobs);
    size_t used = 0;
    for (size_t i = 0; i < count; i++)
        used += (size_t)snprintf(buf + used, sizeof buf - used, "%s%03X%s", i ? " " : "",
                                 (unsigned)cobs[i].can_id, cobs[i].rtr ? "R" : "");
    ck_assert_str_eq(buf, "7E5 000 080 606 706R 206 186R");
}
END_TEST

START_TEST(writing_a_cob_id_object_changes_the_set_and_the_generation)
{
    char buf[256];
    uint32_t generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_write(&t, 0x1400, 1, 0x80000204u, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert_str_eq(consumed(buf, sizeof buf), "000 080 604 704R 184R");

    generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_write(&t, 0x1005, 0, 0x81, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(co_node_consumes(&t.node, 0x081, false));
    ck_assert(!co_node_consumes(&t.node, 0x080, false));

    generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_write(&t, 0x1016, 2, 0x00050064u, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(co_node_consumes(&t.node, 0x705, false));

    generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x40000184u, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(!co_node_consumes(&t.node, 0x184, true));
    ck_assert_str_eq(consumed(buf, sizeof buf), "000 081 604 704R 705");
}
END_TEST

START_TEST(other_writes_and_refused_writes_keep_the_generation)
{
    uint32_t generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 100, 2), 0);
    /* Another CAN-ID for a valid RPDO is refused: nothing changed. */
    ck_assert_uint_eq(test_write(&t, 0x1400, 1, 0x00000205u, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(co_node_consumer_generation(&t.node), generation);
}
END_TEST

START_TEST(reset_communication_restores_the_set_and_changes_the_generation)
{
    char buf[256];
    ck_assert_uint_eq(test_write(&t, 0x1400, 1, 0x80000204u, 4), 0);
    uint32_t generation = co_node_consumer_generation(&t.node);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert_str_eq(consumed(buf, sizeof buf), "000 080 604 704R 204 184R");
}
END_TEST

/* The contract a runtime relies on: a frame outside the set, data or remote, changes nothing
 * and sends nothing, in every state where the node would act on it. */
START_TEST(frames_outside_the_set_are_ignored)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, 0x00050064u, 4), 0);
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000"); /* TPDO1's first transmission in Operational */
    for (uint32_t id = 0; id <= 0x7FF; id++) {
        for (int rtr = 0; rtr <= 1; rtr++) {
            if (co_node_consumes(&t.node, id, rtr))
                continue;
            co_frame_t frame = test_frame(rtr ? "000#R8" : "000#4000100000000000");
            frame.id = id;
            test_rx_frame(&t, &frame);
            frame.len = 1;
            test_rx_frame(&t, &frame);
        }
    }
    test_expect_none(&t);
    ck_assert_int_eq(t.node.nmt_state, CO_NMT_OPERATIONAL);
    ck_assert(!t.node.heartbeat.consumer[0].monitor.monitoring);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("consumers");
    TCase *tc = tcase_create("consumers");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, a_started_node_consumes_nmt_sync_sdo_guarding_and_its_valid_pdos);
    tcase_add_test(tc, a_node_in_initialising_consumes_nothing);
    tcase_add_test(tc, a_node_with_lss_consumes_7e5_with_or_without_node_id);
    tcase_add_test(tc, writing_a_cob_id_object_changes_the_set_and_the_generation);
    tcase_add_test(tc, other_writes_and_refused_writes_keep_the_generation);
    tcase_add_test(tc, reset_communication_restores_the_set_and_changes_the_generation);
    tcase_add_test(tc, frames_outside_the_set_are_ignored);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
