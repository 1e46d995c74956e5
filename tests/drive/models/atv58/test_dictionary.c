/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 58 card's communication profile area as its manual prints it (*Altivar 58 CANopen
 * communication card VW3-A58308 user manual*, "Communication profile area" and the PDO and
 * SDO objects), transcribed row by row: every object and sub-index, the types where the table
 * gives them (the PDO and SDO tables give values only, and no table gives an access), and the
 * number of entries of each record. The card adds nothing to the area: 1018h, which the manual
 * does not list, is absent from the running drive (docs/atv58.md). */
#include "../manual_table.h"
#include "atv58/atv58.h"

#define NOT_PRINTED MANUAL_TYPE_NOT_PRINTED

static const manual_row_t manual_rows[] = {
    {0x1000, 0x00, CO_DT_UNSIGNED32, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1001, 0x00, CO_DT_UNSIGNED32, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1008, 0x00, CO_DT_VISIBLE_STRING, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1009, 0x00, CO_DT_UNSIGNED32, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x100A, 0x00, CO_DT_UNSIGNED32, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x100C, 0x00, CO_DT_UNSIGNED16, MANUAL_ANY, MANUAL_NOT_COUNT}, /* "Word" */
    {0x100D, 0x00, CO_DT_UNSIGNED8, MANUAL_ANY, MANUAL_NOT_COUNT},  /* "Byte" */
    {0x1014, 0x00, CO_DT_UNSIGNED32, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1018, 0x00, NOT_PRINTED, MANUAL_ABSENT, MANUAL_NOT_COUNT}, /* not listed */
    {0x1400, 0x00, NOT_PRINTED, MANUAL_ANY, 2},
    {0x1400, 0x01, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1400, 0x02, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1600, 0x00, NOT_PRINTED, MANUAL_ANY, 2},
    {0x1600, 0x01, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1600, 0x02, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1800, 0x00, NOT_PRINTED, MANUAL_ANY, 2},
    {0x1800, 0x01, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1800, 0x02, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1A00, 0x00, NOT_PRINTED, MANUAL_ANY, 2},
    {0x1A00, 0x01, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1A00, 0x02, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1200, 0x00, NOT_PRINTED, MANUAL_ANY, 2},
    {0x1200, 0x01, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
    {0x1200, 0x02, NOT_PRINTED, MANUAL_ANY, MANUAL_NOT_COUNT},
};

START_TEST(dictionary_shape_as_the_manual_table)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    manual_table_check(&b, manual_rows, sizeof manual_rows / sizeof manual_rows[0], NULL, 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv58_dictionary");
    TCase *tc = tcase_create("dictionary");
    tcase_add_test(tc, dictionary_shape_as_the_manual_table);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
