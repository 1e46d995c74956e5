/* SPDX-License-Identifier: Apache-2.0 */
/* The error behaviour service (co_error_behaviour.h): an error's class to an NMT state, and the
 * rules of 1029h. */
#include "co/co_error_behaviour.h"

#include "co/co_node.h"

static void raise_error(co_node_t *node, uint8_t subindex)
{
    uint32_t behaviour =
        co_od_param(node, CO_IDX_ERROR_BEHAVIOUR, subindex, CO_ERROR_BEHAVIOUR_PRE_OPERATIONAL);
    if (behaviour == CO_ERROR_BEHAVIOUR_STOPPED)
        co_nmt_enter(node, CO_NMT_STOPPED);
    else if (behaviour == CO_ERROR_BEHAVIOUR_PRE_OPERATIONAL &&
             node->nmt_state == CO_NMT_OPERATIONAL)
        co_nmt_enter(node, CO_NMT_PRE_OPERATIONAL);
}

/* CiA 301 7.5.2.32, table "Error behaviour value definition": 0, 1 and 2 are defined, 3..127
 * reserved (refused, 0x06090030), 128..255 manufacturer-specific, which no node of this project
 * defines, so they are taken and behave as 1, no change (docs/decisions.md, D-ERROR-BEHAVIOUR).
 * Sub-index 0, the count, is read-only in the dictionary and never comes here. */
static uint32_t od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len)
{
    (void)node;
    (void)entry;
    (void)len;
    uint8_t value = data[0];
    if (value > CO_ERROR_BEHAVIOUR_STOPPED && value <= CO_ERROR_BEHAVIOUR_RESERVED_LAST)
        return CO_SDO_ABORT_VALUE_RANGE;
    return CO_SDO_OK;
}

const co_error_behaviour_code_t co_error_behaviour = {
    .raise = raise_error,
    .od_write = od_write,
};
