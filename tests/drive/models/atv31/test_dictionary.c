/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 31's communication profile area as its manual's object dictionary table prints it
 * (*Altivar 31 CANopen user's manual*, "Object dictionary"), transcribed row by row: the sub-index
 * 0 of every record and array, every sub-index, type and access. The reserved sub-index 4 of
 * 1800h/1805h is there, RW U8 as printed, and 1010h, 1011h, 1015h, 1019h are the
 * project's additions (docs/atv31.md, deviations). */
#include "../manual_table.h"
#include "atv31/atv31.h"

static const manual_row_t manual_rows[] = {
    {0x1000, 0x00, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1001, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1003, 0x00, CO_DT_UNSIGNED8, MANUAL_RW, 0},
    {0x1003, 0x01, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1005, 0x00, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1008, 0x00, CO_DT_VISIBLE_STRING, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x100A, 0x00, CO_DT_VISIBLE_STRING, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x100B, 0x00, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x100C, 0x00, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x100D, 0x00, CO_DT_UNSIGNED8, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x100E, 0x00, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x100F, 0x00, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1014, 0x00, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1016, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 1},
    {0x1016, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1017, 0x00, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1018, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 1},
    {0x1018, 0x01, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1200, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 2},
    {0x1200, 0x01, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1200, 0x02, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1400, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 2},
    {0x1400, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1400, 0x02, CO_DT_UNSIGNED8, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1405, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 2},
    {0x1405, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1405, 0x02, CO_DT_UNSIGNED8, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1600, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 1},
    {0x1600, 0x01, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1605, 0x00, CO_DT_UNSIGNED8, MANUAL_RW, 2},
    {0x1605, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1605, 0x02, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1605, 0x03, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1605, 0x04, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1800, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 5},
    {0x1800, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1800, 0x02, CO_DT_UNSIGNED8, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1800, 0x03, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1800, 0x04, CO_DT_UNSIGNED8, MANUAL_RW, MANUAL_NOT_COUNT}, /* "Reserved" */
    {0x1800, 0x05, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1805, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 5},
    {0x1805, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1805, 0x02, CO_DT_UNSIGNED8, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1805, 0x03, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1805, 0x04, CO_DT_UNSIGNED8, MANUAL_RW, MANUAL_NOT_COUNT}, /* "Reserved" */
    {0x1805, 0x05, CO_DT_UNSIGNED16, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1A00, 0x00, CO_DT_UNSIGNED8, MANUAL_RO, 1},
    {0x1A00, 0x01, CO_DT_UNSIGNED32, MANUAL_RO, MANUAL_NOT_COUNT},
    {0x1A05, 0x00, CO_DT_UNSIGNED8, MANUAL_RW, 2},
    {0x1A05, 0x01, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1A05, 0x02, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1A05, 0x03, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
    {0x1A05, 0x04, CO_DT_UNSIGNED32, MANUAL_RW, MANUAL_NOT_COUNT},
};

/* Not in the table: store and restore, the EMCY inhibit time and the SYNC counter overflow value
 * (docs/decisions.md, D-DICTIONARY). */
static const uint16_t added[] = {0x1010, 0x1011, 0x1015, 0x1019};

START_TEST(dictionary_shape_as_the_manual_table)
{
    bench_t b;
    bench_start_model(&b, &atv31_profile, NULL);
    manual_table_check(&b, manual_rows, sizeof manual_rows / sizeof manual_rows[0], added,
                       sizeof added / sizeof added[0]);
}
END_TEST

/* Before firmware V1.2 the same table less 1016h and 1017h, which the manual says only V1.2 and
 * later have (docs/atv31.md). */
START_TEST(v1_1_dictionary_shape_without_heartbeat)
{
    manual_row_t rows[sizeof manual_rows / sizeof manual_rows[0]];
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        rows[i] = manual_rows[i];
        if (rows[i].index == 0x1016 || rows[i].index == 0x1017)
            rows[i].access = MANUAL_ABSENT;
    }
    bench_t b;
    bench_start_model(&b, &atv31_v11_profile, NULL);
    manual_table_check(&b, rows, sizeof rows / sizeof rows[0], added,
                       sizeof added / sizeof added[0]);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv31_dictionary");
    TCase *tc = tcase_create("dictionary");
    tcase_add_test(tc, dictionary_shape_as_the_manual_table);
    tcase_add_test(tc, v1_1_dictionary_shape_without_heartbeat);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
