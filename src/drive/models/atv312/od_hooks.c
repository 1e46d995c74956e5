/* SPDX-License-Identifier: Apache-2.0 */
/* Hooks of the ATV312's own, named in atv312.hooks (which the ATV31's dictionary is generated with
 * too, src/drive/models/atv31/CMakeLists.txt): the transmission types its PDO6 accepts
 * (docs/decisions.md, D-TRANSMISSION-TYPES). The drive's parameter hooks are the drive layer's
 * (drive/drive.h). */
#include "atv312/atv312.h"

/* D-TRANSMISSION-TYPES: RPDO6 accepts 1-240 (synchronous), 254 and 255 (asynchronous). */
static uint32_t rpdo6_type_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len, co_od_origin_t origin)
{
    (void)node, (void)entry, (void)len, (void)origin;
    uint8_t type = data[0];
    return (type >= 1 && type <= 240) || type >= 254 ? CO_SDO_OK : CO_SDO_ABORT_VALUE_RANGE;
}

/* D-TRANSMISSION-TYPES: TPDO6 accepts 0 (synchronous acyclic), 1-240, 254 and 255. */
static uint32_t tpdo6_type_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len, co_od_origin_t origin)
{
    (void)node, (void)entry, (void)len, (void)origin;
    uint8_t type = data[0];
    return type <= 240 || type >= 254 ? CO_SDO_OK : CO_SDO_ABORT_VALUE_RANGE;
}

const co_od_hook_t atv312_rpdo6_type = {rpdo6_type_write, NULL};
const co_od_hook_t atv312_tpdo6_type = {tpdo6_type_write, NULL};
