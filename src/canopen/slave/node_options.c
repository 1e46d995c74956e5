/* SPDX-License-Identifier: Apache-2.0 */
/* The code of the per-node options (CO_NODE_*, co_node.h), reached only through
 * co_node_config_t.options_code = &co_node_options: a firmware that names none of them links none
 * of this (docs/footprint.md). The rules that are a test of the flag alone (the DLC accepted by
 * NMT, guarding and RPDOs, NMT Disconnect, the expedited-only upload) stay in their services. */
#include "co/co_node.h"

#include <string.h>

/* The DS301 V3 abort layout (CO_NODE_SDO_ERROR_CLASS): error class in the top byte, error code
 * below it, no additional code. Its codes for a missing sub-index and an unsupported request, as
 * such a device documents them (docs/architecture.md, "Node options"); the other two are CiA 301's
 * CO_SDO_ABORT_NO_OBJECT and CO_SDO_ABORT_UNSUPPORTED_ACCESS. */
#define SDO_ERROR_CLASS_NO_SUBINDEX 0x06090000u
#define SDO_ERROR_CLASS_NOT_SUPPORTED 0x05030000u

/* CO_NODE_PAD_DLC8: the older profile's "8 bytes, fixed length" user data, unused bytes 0. */
static void send_padded(co_node_t *node, const co_frame_t *frame)
{
    co_frame_t out = *frame;
    memset(&out.data[out.len], 0, CO_FRAME_DLC_MAX - out.len);
    out.len = CO_FRAME_DLC_MAX;
    node->send(node->user, &out);
}

/* CO_NODE_SDO_EXPEDITED_ONLY: the initiates of segmented and block transfers. */
static bool sdo_refused_initiate(uint8_t command)
{
    uint8_t ccs = command >> 5;
    if (ccs == CO_SDO_CCS_UPLOAD_INITIATE)
        return false;
    return ccs != CO_SDO_CCS_DOWNLOAD_INITIATE || !(command & CO_SDO_EXPEDITED);
}

/* CO_NODE_SDO_LONG_EXPEDITED: the length of the object itself when the write is longer and
 * every extra byte is 0 (a device of the older profile documents 4-byte writes, command 0x23, of
 * its 16-bit objects). */
static size_t sdo_expedited_length(const co_od_entry_t *entry, const uint8_t *value, size_t len)
{
    size_t fixed = entry != NULL ? co_od_type_size(entry->type) : 0;
    if (fixed == 0 || fixed >= len)
        return len;
    for (size_t i = fixed; i < len; i++)
        if (value[i] != 0)
            return len;
    return fixed;
}

/* CO_NODE_SDO_ERROR_CLASS: a CiA 301 abort code in the DS301 V3 layout: the error class and code
 * its cause has there, the nearest of the four for the others (command specifiers: not
 * supported; every refusal of an existing object's access, value or state: access not
 * supported). */
static uint32_t sdo_abort_code(uint32_t code)
{
    if (code == CO_SDO_ABORT_NO_OBJECT)
        return CO_SDO_ABORT_NO_OBJECT;
    if (code == CO_SDO_ABORT_NO_SUBINDEX)
        return SDO_ERROR_CLASS_NO_SUBINDEX;
    if ((code >> 16) == (CO_SDO_ABORT_COMMAND >> 16) || (code >> 16) == (CO_SDO_ABORT_TOGGLE >> 16))
        return SDO_ERROR_CLASS_NOT_SUPPORTED;
    return CO_SDO_ABORT_UNSUPPORTED_ACCESS;
}

/* CO_NODE_HEARTBEAT_GRID: the first multiple of the period after `now` (a 64-bit division, which
 * a Cortex-M links as a 700-byte library routine). */
static co_time_t beat_on_grid(co_time_t now, co_time_t period)
{
    return (now / period + 1u) * period;
}

const co_node_options_code_t co_node_options = {
    .send_padded = send_padded,
    .sdo_refused_initiate = sdo_refused_initiate,
    .sdo_expedited_length = sdo_expedited_length,
    .sdo_abort_code = sdo_abort_code,
    .beat_on_grid = beat_on_grid,
};
