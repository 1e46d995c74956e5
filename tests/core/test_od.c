/* SPDX-License-Identifier: Apache-2.0 */
/* Object dictionary: table validation, binary search, type and limit checks of the write path,
 * defaults with node-id terms. */
#include "test_od.h"
#include "check_main.h"
#include "test_bus.h"

#include <stdlib.h>

static test_node_t t;

START_TEST(find_every_entry)
{
    for (uint16_t i = 0; i < test_od.count; i++) {
        const co_od_entry_t *e = &test_od.entries[i];
        ck_assert_ptr_eq(co_od_find(&test_od, e->index, e->subindex), e);
    }
    ck_assert_ptr_null(co_od_find(&test_od, 0x1004, 0));
    ck_assert_ptr_null(co_od_find(&test_od, 0x0000, 0));
    ck_assert_ptr_null(co_od_find(&test_od, 0xFFFF, 0xFF));
}
END_TEST

START_TEST(lookup_gives_most_specific_abort)
{
    const co_od_entry_t *e;
    ck_assert_uint_eq(co_od_lookup(&test_od, 0x1004, 0, &e), CO_SDO_ABORT_NO_OBJECT);
    ck_assert_uint_eq(co_od_lookup(&test_od, 0x1000, 1, &e), CO_SDO_ABORT_NO_SUBINDEX);
    ck_assert_uint_eq(co_od_lookup(&test_od, 0x1018, 5, &e), CO_SDO_ABORT_NO_SUBINDEX);
    ck_assert_uint_eq(co_od_lookup(&test_od, 0x1018, 4, &e), 0);
}
END_TEST

START_TEST(validate_rejects_unsorted_and_duplicate)
{
    co_od_entry_t entries[3] = {test_od.entries[0], test_od.entries[2], test_od.entries[1]};
    co_od_t od = test_od;
    od.entries = entries;
    od.count = 3;
    uint16_t pos;
    ck_assert_int_eq(co_od_validate(&od, &pos), CO_OD_ERR_UNSORTED);
    ck_assert_uint_eq(pos, 2);
    entries[2] = entries[1];
    ck_assert_int_eq(co_od_validate(&od, &pos), CO_OD_ERR_DUPLICATE);
    ck_assert_uint_eq(pos, 2);
    entries[2] = test_od.entries[3];
    entries[2].size = 3;
    ck_assert_int_eq(co_od_validate(&od, &pos), CO_OD_ERR_SIZE);
    entries[2].size = 4;
    entries[2].offset = test_od.data_size;
    ck_assert_int_eq(co_od_validate(&od, &pos), CO_OD_ERR_BOUNDS);
    od.count = 0;
    ck_assert_int_eq(co_od_validate(&od, &pos), CO_OD_ERR_EMPTY);
    ck_assert_int_eq(co_od_validate(&test_od, &pos), CO_OD_VALID);
}
END_TEST

START_TEST(node_id_relative_defaults)
{
    test_node_start(&t, 4, NULL, NULL);
    ck_assert_int_eq(co_od_value(&t.node, 0x1800, 1), 0x184);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 1), 0x80000284);
    ck_assert_int_eq(co_od_value(&t.node, 0x1200, 1), 0x604);
    ck_assert_int_eq(co_od_value(&t.node, 0x1014, 0), 0x84);
    ck_assert_int_eq(co_od_value(&t.node, 0x100B, 0), 4);
}
END_TEST

START_TEST(param_reads_value_or_absent_default)
{
    test_node_start(&t, 4, NULL, NULL);
    ck_assert_uint_eq(co_od_param(&t.node, 0x1800, 1, 0xDEAD), 0x184);
    ck_assert_uint_eq(co_od_param(&t.node, 0x1805, 1, 0), 0x80000284);
    ck_assert_uint_eq(co_od_param(&t.node, 0x1004, 0, 0x80000000), 0x80000000);
    ck_assert_uint_eq(co_od_param(&t.node, 0x1018, 5, 7), 7);
    uint8_t v[2] = {0x9C, 0xFF}; /* -100: the low 32 bits of the sign-extended value */
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0E, v, 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(co_od_param(&t.node, 0x2000, 0x0E, 0), 0xFFFFFF9Cu);
}
END_TEST

START_TEST(signed_values_and_limits)
{
    test_node_start(&t, 4, NULL, NULL);
    uint8_t v[2] = {0x9C, 0xFF}; /* -100 */
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0E, v, 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x0E), -100);
    v[0] = 0x9B; /* -101 */
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0E, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_LOW);
    v[0] = 101;
    v[1] = 0;
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0E, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_HIGH);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x0E), -100);
}
END_TEST

START_TEST(zero_allowed_below_low_limit)
{
    test_node_start(&t, 4, NULL, NULL);
    uint8_t zero[2] = {0, 0}, low[2] = {99, 0}, ok[2] = {100, 0};
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0F, ok, 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0F, zero, 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0F, low, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_LOW);
}
END_TEST

/* co_od_saturate: the nearest value the write checks take, by limits or by type. */
START_TEST(saturate_to_limits_or_type_range)
{
    static const co_od_limits_t i16_limits = {(uint64_t)-100, 100}, u16_limits = {100, 5000};
    co_od_entry_t e = {.type = CO_DT_INTEGER16, .size = 2, .limits = &i16_limits};
    ck_assert_int_eq(co_od_saturate(&e, -101), -100);
    ck_assert_int_eq(co_od_saturate(&e, 42), 42);
    ck_assert_int_eq(co_od_saturate(&e, 1000), 100);
    e = (co_od_entry_t){.type = CO_DT_UNSIGNED16, .size = 2, .limits = &u16_limits};
    ck_assert_int_eq(co_od_saturate(&e, -1), 100);
    ck_assert_int_eq(co_od_saturate(&e, 0), 100);
    ck_assert_int_eq(co_od_saturate(&e, 41310), 5000);
    e.flags = CO_OD_ZERO_OK;
    ck_assert_int_eq(co_od_saturate(&e, 0), 0);
    ck_assert_int_eq(co_od_saturate(&e, 1), 100);
    e = (co_od_entry_t){.type = CO_DT_INTEGER8, .size = 1};
    ck_assert_int_eq(co_od_saturate(&e, -129), -128);
    ck_assert_int_eq(co_od_saturate(&e, 128), 127);
    e = (co_od_entry_t){.type = CO_DT_INTEGER16, .size = 2};
    ck_assert_int_eq(co_od_saturate(&e, 1638350), 32767);
    ck_assert_int_eq(co_od_saturate(&e, -1638350), -32768);
    e = (co_od_entry_t){.type = CO_DT_UNSIGNED32, .size = 4};
    ck_assert_int_eq(co_od_saturate(&e, -5), 0);
    ck_assert_int_eq(co_od_saturate(&e, INT64_C(0x100000000)), 0xFFFFFFFF);
    e = (co_od_entry_t){.type = CO_DT_INTEGER64, .size = 8};
    ck_assert_int_eq(co_od_saturate(&e, INT64_MIN), INT64_MIN);
    e = (co_od_entry_t){.type = CO_DT_UNSIGNED64, .size = 8};
    ck_assert_int_eq(co_od_saturate(&e, INT64_MAX), INT64_MAX);
    ck_assert_int_eq(co_od_saturate(&e, -1), 0);
    e = (co_od_entry_t){.type = CO_DT_BOOLEAN, .size = 1};
    ck_assert_int_eq(co_od_saturate(&e, 2), 1);
    e = (co_od_entry_t){.type = CO_DT_VISIBLE_STRING, .size = 8};
    ck_assert_int_eq(co_od_saturate(&e, -7), -7);
}
END_TEST

START_TEST(length_and_access_checks)
{
    test_node_start(&t, 4, NULL, NULL);
    uint8_t b[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x02, b, 4, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_LENGTH_HIGH);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x03, b, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_LENGTH_LOW);
    ck_assert_uint_eq(co_od_write(&t.node, 0x1000, 0x00, b, 4, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_READ_ONLY);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0A, b + 1, 1, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_RANGE);
    const co_od_entry_t *e;
    ck_assert_uint_eq(co_od_read_check(&t.node, 0x2000, 0x0B, &e), CO_SDO_ABORT_WRITE_ONLY);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x08, b, 8, CO_OD_ORIGIN_SDO), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x08), 0x0807060504030201);
}
END_TEST

/* A fieldbus card on the same device writes for its own master: the checks of a client's
 * download, never the application's leave to write a read-only entry (co_od.h). */
START_TEST(a_card_is_checked_as_a_client)
{
    test_node_start(&t, 4, NULL, NULL);
    uint8_t b[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    ck_assert_uint_eq(co_od_write(&t.node, 0x1000, 0x00, b, 4, CO_OD_ORIGIN_CARD),
                      CO_SDO_ABORT_READ_ONLY);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x02, b, 4, CO_OD_ORIGIN_CARD),
                      CO_SDO_ABORT_LENGTH_HIGH);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x0A, b + 1, 1, CO_OD_ORIGIN_CARD),
                      CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x08, b, 8, CO_OD_ORIGIN_CARD), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x08), 0x0807060504030201);
}
END_TEST

START_TEST(strings_store_their_length)
{
    test_node_start(&t, 4, NULL, NULL);
    const co_od_entry_t *e = co_od_find(&test_od, 0x2000, 0x0C);
    ck_assert_uint_eq(co_od_length(&t.node, e), 5);
    ck_assert_uint_eq(
        co_od_write(&t.node, 0x2000, 0x0C, (const uint8_t *)"ab", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(co_od_length(&t.node, e), 2);
    e = co_od_find(&test_od, 0x1008, 0);
    ck_assert_uint_eq(co_od_length(&t.node, e), 6);
}
END_TEST

START_TEST(hook_refuses_and_counts)
{
    test_node_start(&t, 4, NULL, NULL);
    uint8_t b[2] = {1, 0};
    ck_assert_uint_eq(co_od_write(&t.node, 0x2000, 0x10, b, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_DATA_LOCAL);
    unsigned before = test_od_hook_reads;
    const co_od_entry_t *e;
    ck_assert_uint_eq(co_od_read_check(&t.node, 0x2000, 0x10, &e), 0);
    ck_assert_uint_eq(test_od_hook_reads, before + 1);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("od");
    TCase *tc = tcase_create("od");
    tcase_add_test(tc, find_every_entry);
    tcase_add_test(tc, lookup_gives_most_specific_abort);
    tcase_add_test(tc, validate_rejects_unsorted_and_duplicate);
    tcase_add_test(tc, node_id_relative_defaults);
    tcase_add_test(tc, param_reads_value_or_absent_default);
    tcase_add_test(tc, signed_values_and_limits);
    tcase_add_test(tc, zero_allowed_below_low_limit);
    tcase_add_test(tc, saturate_to_limits_or_type_range);
    tcase_add_test(tc, length_and_access_checks);
    tcase_add_test(tc, a_card_is_checked_as_a_client);
    tcase_add_test(tc, strings_store_their_length);
    tcase_add_test(tc, hook_refuses_and_counts);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
