/* SPDX-License-Identifier: Apache-2.0 */
/* NMT start-up of a slave (co_nmt_startup.h): the self start and the rules of 1F80h. */
#include "co/co_nmt_startup.h"

#include "co/co_node.h"

static void booted(co_node_t *node)
{
    uint32_t startup = co_od_param(node, CO_IDX_NMT_STARTUP, 0, CO_NMT_STARTUP_NO_SELF_START);
    if (!(startup & CO_NMT_STARTUP_NO_SELF_START))
        co_nmt_enter(node, CO_NMT_OPERATIONAL);
}

/* CiA 302-2, 1F80h: of its bits only bit 2 (self start) means something to a slave; the others
 * make the device an NMT master (bit 0) or configure one (bits 1, 3..6), which a slave is not,
 * so a value with any of them is refused with 0x06090030 (docs/decisions.md,
 * D-NMT-STARTUP-SLAVE). The new value governs from the next boot-up. */
static uint32_t od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len)
{
    (void)node;
    (void)entry;
    (void)len;
    return co_get_u32(data) & ~CO_NMT_STARTUP_NO_SELF_START ? CO_SDO_ABORT_VALUE_RANGE : CO_SDO_OK;
}

const co_nmt_startup_code_t co_nmt_startup = {
    .booted = booted,
    .od_write = od_write,
};
