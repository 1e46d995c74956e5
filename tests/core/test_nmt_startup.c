/* SPDX-License-Identifier: Apache-2.0 */
/* NMT start-up of a slave (1F80h, CiA 302-2): bit 2 clear, the node enters Operational by itself
 * after every boot-up (its first heartbeat says 05h); set, or without the service, it waits in
 * Pre-operational; a slave refuses the master's bits. */
#include "check_main.h"
#include "memory_storage.h"
#include "test_bus.h"
#include "test_od.h"

static test_node_t t;
static memory_storage_t memory;
static co_storage_t storage;

static void start(const co_nmt_startup_code_t *code)
{
    memory_storage_init(&memory, &storage);
    co_node_config_t config = {
        .node_id = 4, .od = &test_od, .storage = &storage, .nmt_startup = code};
    test_node_start_config(&t, &config);
}

/* The state after the boot-up, as the first heartbeat (1017h 100 ms) shows it. */
static void expect_first_heartbeat(const char *frame)
{
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    test_advance(&t, 100000);
    test_expect(&t, frame);
    test_expect_none(&t);
}

START_TEST(bit_2_set_waits_for_the_master)
{
    start(&co_nmt_startup);
    ck_assert_int_eq(co_od_value(&t.node, 0x1F80, 0), 0x04);
    expect_first_heartbeat("704#7F");
}
END_TEST

/* 1F80h is a communication parameter: stored (1010h:02), it governs every boot-up after. */
START_TEST(bit_2_clear_starts_itself_at_every_boot_up)
{
    start(&co_nmt_startup);
    ck_assert_uint_eq(test_write(&t, 0x1F80, 0, 0, 4), 0);
    ck_assert_uint_eq(t.node.nmt_state, CO_NMT_PRE_OPERATIONAL); /* from the next boot-up */
    ck_assert_uint_eq(test_write(&t, 0x1017, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0); /* no TPDO in Operational */
    ck_assert_uint_eq(test_write(&t, 0x1010, 2, 0x65766173, 4), 0);
    test_drain(&t);
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
    test_advance(&t, 100000);
    test_expect(&t, "704#05");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    test_advance(&t, 100000);
    test_expect(&t, "704#05");
    test_expect_none(&t);
}
END_TEST

START_TEST(master_bits_refused)
{
    start(&co_nmt_startup);
    ck_assert_uint_eq(test_write(&t, 0x1F80, 0, 0x05, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_write(&t, 0x1F80, 0, 0x0E, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1F80, 0), 0x04);
    ck_assert_uint_eq(test_write(&t, 0x1F80, 0, 0x00, 4), 0);
}
END_TEST

/* Bit 2 clear, stored so that the reset keeps it: without the service, still no start. */
START_TEST(node_without_the_service_waits)
{
    start(NULL);
    ck_assert_uint_eq(test_write(&t, 0x1F80, 0, 0, 4), 0);
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000184, 4), 0); /* no TPDO in Operational */
    ck_assert_uint_eq(test_write(&t, 0x1010, 2, 0x65766173, 4), 0);
    test_drain(&t);
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x1F80, 0), 0);
    expect_first_heartbeat("704#7F");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("nmt_startup");
    TCase *tc = tcase_create("nmt_startup");
    tcase_add_test(tc, bit_2_set_waits_for_the_master);
    tcase_add_test(tc, bit_2_clear_starts_itself_at_every_boot_up);
    tcase_add_test(tc, master_bits_refused);
    tcase_add_test(tc, node_without_the_service_waits);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
