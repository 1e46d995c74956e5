/* SPDX-License-Identifier: Apache-2.0 */
/* co_node_init's check of the dictionary against the node's tables: a dictionary with one RPDO or
 * TPDO more than co_config.h gives a node is refused (CO_NODE_ERR_TABLES), so that a firmware
 * sizing the tables to its dictionary cannot lose a PDO silently. */
#include "check_main.h"
#include "co/co_node.h"
#include "test_od.h"

#include <string.h>

#define EXTRA_MAX 300

static co_od_entry_t entries[EXTRA_MAX];
static uint8_t data[4096];

static void ignore(void *user, const co_frame_t *frame)
{
    (void)user;
    (void)frame;
}

/* test_od with one more UNSIGNED8 entry, in its sorted place, stored at offset 0. */
static int init_with(uint16_t index, uint8_t subindex)
{
    ck_assert_uint_lt(test_od.count, EXTRA_MAX);
    ck_assert_uint_le(test_od.data_size, sizeof(data));
    uint16_t n = 0;
    bool placed = false;
    for (uint16_t i = 0; i < test_od.count; i++) {
        const co_od_entry_t *e = &test_od.entries[i];
        if (!placed && (e->index > index || (e->index == index && e->subindex > subindex))) {
            entries[n++] = (co_od_entry_t){index, subindex, CO_DT_UNSIGNED8, CO_OD_ACCESS_RO, 1, 0,
                                           NULL,  NULL};
            placed = true;
        }
        entries[n++] = *e;
    }
    co_od_t od = test_od;
    od.entries = entries;
    od.count = n;
    od.names = NULL;
    co_node_config_t config = {.node_id = 4, .od = &od, .od_data = data, .send = ignore};
    co_node_t node;
    return co_node_init(&node, &config);
}

START_TEST(tables_fit_the_dictionary)
{
    ck_assert_int_eq(init_with(0x1400 + CO_CONFIG_RPDO_MAX - 1, 0), 0);
    ck_assert_int_eq(init_with(0x1400 + CO_CONFIG_RPDO_MAX, 0), CO_NODE_ERR_TABLES);
    ck_assert_int_eq(init_with(0x1600 + CO_CONFIG_RPDO_MAX, 0), CO_NODE_ERR_TABLES);
    ck_assert_int_eq(init_with(0x1800 + CO_CONFIG_TPDO_MAX - 1, 0), 0);
    ck_assert_int_eq(init_with(0x1800 + CO_CONFIG_TPDO_MAX, 0), CO_NODE_ERR_TABLES);
    ck_assert_int_eq(init_with(0x1A00 + CO_CONFIG_TPDO_MAX, 0), CO_NODE_ERR_TABLES);
    ck_assert_int_eq(init_with(0x1BFF, 0), CO_NODE_ERR_TABLES);
    ck_assert_int_eq(init_with(0x1C00, 0), 0); /* past the TPDO mapping parameters */
}
END_TEST

int main(void)
{
    Suite *s = suite_create("node");
    TCase *tc = tcase_create("init");
    tcase_add_test(tc, tables_fit_the_dictionary);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
