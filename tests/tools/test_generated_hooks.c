/* SPDX-License-Identifier: Apache-2.0 */
/* The hooks that fixtures/device.hooks names, in their own file of a static library so the test
 * proves co_generate_od() resolves hooks no other code refers to. */
#include "co/co_od.h"

unsigned test_hook_serial_reads;

static uint32_t refuse_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                             size_t len, co_od_origin_t origin)
{
    (void)node;
    (void)entry;
    (void)data;
    (void)len;
    (void)origin;
    return CO_SDO_ABORT_DATA_LOCAL;
}

static uint32_t count_read(co_node_t *node, const co_od_entry_t *entry)
{
    (void)node;
    (void)entry;
    test_hook_serial_reads++;
    return 0;
}

const co_od_hook_t test_hook_refuse = {refuse_write, NULL};
const co_od_hook_t test_hook_serial = {NULL, count_read};
