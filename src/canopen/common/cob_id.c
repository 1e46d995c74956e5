/* SPDX-License-Identifier: Apache-2.0 */
/* The COB-ID rules of CiA 301 that PDO, SYNC, EMCY and TIME share, with the restricted CAN-IDs as a
 * table (7.3.5). */
#include "co/co_types.h"

typedef struct can_id_range {
    uint16_t first;
    uint16_t last;
} can_id_range_t;

/* CiA 301 7.3.5, table "restricted CAN-IDs" (701h-77Fh and 780h-7FFh as one range). */
static const can_id_range_t restricted[] = {
    {0x000, 0x07F}, {0x101, 0x180}, {0x581, 0x5FF}, {0x601, 0x67F}, {0x6E0, 0x6FF}, {0x701, 0x7FF},
};

bool co_can_id_restricted(uint32_t can_id)
{
    for (size_t i = 0; i < sizeof(restricted) / sizeof(restricted[0]); i++)
        if (can_id >= restricted[i].first && can_id <= restricted[i].last)
            return true;
    return false;
}

uint32_t co_cob_id_check(uint32_t old, uint32_t value, uint32_t in_use_mask, uint32_t idle)
{
    if ((value & ~CO_COB_ID_ALLOWED) || co_can_id_restricted(value & CO_COB_ID_CAN_ID))
        return CO_SDO_ABORT_VALUE_RANGE;
    bool both_in_use = (value & in_use_mask) != idle && (old & in_use_mask) != idle;
    return both_in_use && ((old ^ value) & CO_COB_ID_CAN_ID) != 0 ? CO_SDO_ABORT_VALUE_RANGE
                                                                  : CO_SDO_OK;
}
