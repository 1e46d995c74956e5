/* SPDX-License-Identifier: Apache-2.0 */
/* The node's configuration checks, the Identity status bits the application and the switches
 * set, and the MS LED. */
#include "check_main.h"
#include "dn_bench.h"

static dn_bench_t b;
static const dn_stored_t defaults = {0, 0, false};

START_TEST(init_refusals)
{
    bench_init(&b, 63, defaults);
    dn_config_t config = b.config;
    config.mac_id = 64;
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_MAC_ID);
    config = b.config;
    config.default_consumed_assembly = 71; /* produced */
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_ASSEMBLY);
    config = b.config;
    config.default_produced_assembly = 72;
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_ASSEMBLY);
    dn_assembly_t big[2] = {{21, 4, false}, {71, 9, true}};
    config = b.config;
    config.assemblies = big;
    config.assembly_count = 2;
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_ASSEMBLY);
    config = b.config;
    dn_object_t unsorted[2] = {b.objects[1], b.objects[0]};
    config.objects = unsorted;
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_CONFIG);
    dn_app_t app = b.app;
    app.send = NULL;
    config = b.config;
    config.app = &app;
    ck_assert_int_eq(dn_node_init(&b.node, &config), DN_INIT_BAD_CONFIG);
}
END_TEST

START_TEST(application_faults_and_ms_led)
{
    bench_online(&b, 63);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
    dn_node_set_faults(&b.node, DN_STATUS_MAJOR_RECOVERABLE | 0x0001);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0430); /* bit 0 is not the app's */
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
    dn_node_set_faults(&b.node, DN_STATUS_MAJOR_UNRECOVERABLE);
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0830);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_RED);
    dn_node_set_faults(&b.node, DN_STATUS_MINOR_UNRECOVERABLE);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_RED);
    dn_node_set_faults(&b.node, 0);
    ck_assert_int_eq(dn_node_ms_led(&b.node), DN_LED_GREEN);
}
END_TEST

START_TEST(switch_changed_is_minor_recoverable)
{
    bench_init(&b, 63, defaults);
    b.config.mac_switch_changed = true;
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0130);
    b.config.mac_switch_changed = false;
    b.config.baud_switch_changed = true;
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0130);
    b.config.baud_switch_changed = false;
    b.config.configured = true;
    ck_assert_uint_eq(dn_node_identity_status(&b.node), 0x0034);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet node");
    TCase *tc = tcase_create("node");
    tcase_add_test(tc, init_refusals);
    tcase_add_test(tc, application_faults_and_ms_led);
    tcase_add_test(tc, switch_changed_is_minor_recoverable);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
