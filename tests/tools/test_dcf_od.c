/* SPDX-License-Identifier: Apache-2.0 */
/* The table co_generate_od() makes from a DCF (examples/netmaster/drive4.dcf, node 4 of the
 * network master's example), used by a real node: it starts with the DCF's configuration, its
 * ParameterValues and its $NODEID terms taken as [DeviceComissioning] NodeID=4. */
#include "check_main.h"
#include "co/co_node.h"
#include "drive4_od.h"

#include <check.h>

#define NODE_ID 4
#define MS 1000u

static co_frame_t sent[8];
static size_t sent_count;
static uint8_t data[DRIVE4_OD_DATA_SIZE];
static co_node_t node;

static void record_frame(void *user, const co_frame_t *frame)
{
    (void)user;
    if (sent_count < sizeof sent / sizeof sent[0])
        sent[sent_count++] = *frame;
}

static void start_node(void)
{
    co_node_config_t config = {
        .node_id = NODE_ID, .od = &drive4_od, .od_data = data, .send = record_frame};
    sent_count = 0;
    ck_assert_int_eq(co_node_init(&node, &config), 0);
    co_node_start(&node, 0);
    ck_assert_uint_eq(sent_count, 1);
    ck_assert_uint_eq(sent[0].id, 0x700u + NODE_ID); /* boot-up */
    sent_count = 0;
}

START_TEST(parameter_values_are_the_defaults)
{
    uint16_t position = 0;
    ck_assert_int_eq(co_od_validate(&drive4_od, &position), CO_OD_VALID);
    start_node();
    ck_assert_int_eq(co_od_value(&node, 0x1017, 0), 100);             /* ParameterValue=100 */
    ck_assert_int_eq(co_od_value(&node, 0x1405, 1), 0x304);           /* ParameterValue=0x304 */
    ck_assert_int_eq(co_od_value(&node, 0x1805, 1), 0x284);           /* ParameterValue=0x284 */
    ck_assert_int_eq(co_od_value(&node, 0x1800, 1), 0x180 + NODE_ID); /* $NODEID+0x180 */
    ck_assert_int_eq(co_od_value(&node, 0x1014, 0), 0x80 + NODE_ID);  /* $NODEID+0x80 */
}
END_TEST

START_TEST(heartbeat_of_the_configured_period)
{
    start_node();
    co_node_process(&node, 99 * MS);
    ck_assert_uint_eq(sent_count, 0);
    co_node_process(&node, 100 * MS);
    ck_assert_uint_eq(sent_count, 1);
    ck_assert_uint_eq(sent[0].id, 0x700u + NODE_ID);
    ck_assert_uint_eq(sent[0].len, 1);
    ck_assert_uint_eq(sent[0].data[0], 0x7F); /* Pre-operational */
}
END_TEST

int main(void)
{
    Suite *s = suite_create("dcf_od");
    TCase *tc = tcase_create("dcf_od");
    tcase_add_test(tc, parameter_values_are_the_defaults);
    tcase_add_test(tc, heartbeat_of_the_configured_period);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
