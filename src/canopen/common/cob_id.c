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

/* The rules but the restricted CAN-IDs, which the caller has looked at. */
static uint32_t cob_id_rules(uint32_t old, uint32_t value, uint32_t in_use_mask, uint32_t idle,
                             bool restricted)
{
    if ((value & ~CO_COB_ID_ALLOWED) || restricted)
        return CO_SDO_ABORT_VALUE_RANGE;
    bool both_in_use = (value & in_use_mask) != idle && (old & in_use_mask) != idle;
    return both_in_use && ((old ^ value) & CO_COB_ID_CAN_ID) != 0 ? CO_SDO_ABORT_VALUE_RANGE
                                                                  : CO_SDO_OK;
}

uint32_t co_cob_id_check(uint32_t old, uint32_t value, uint32_t in_use_mask, uint32_t idle)
{
    return cob_id_rules(old, value, in_use_mask, idle,
                        co_can_id_restricted(value & CO_COB_ID_CAN_ID));
}

/* A server's default channel (CiA 301 7.3.5's 601h-67Fh and 581h-5FFh): restricted for every
 * other configurable object, they are what a client channel addresses that server with
 * (docs/decisions.md D-SDO-CLIENT-DEFAULT-COB-IDS). */
static bool default_sdo_can_id(uint32_t can_id)
{
    return (can_id > CO_CAN_ID_SDO_RX && can_id <= CO_CAN_ID_SDO_RX + CO_NODE_ID_MAX) ||
           (can_id > CO_CAN_ID_SDO_TX && can_id <= CO_CAN_ID_SDO_TX + CO_NODE_ID_MAX);
}

uint32_t co_sdo_client_cob_id_check(uint32_t old, uint32_t value)
{
    uint32_t can_id = value & CO_COB_ID_CAN_ID;
    return cob_id_rules(old, value, CO_COB_ID_INVALID, CO_COB_ID_INVALID,
                        co_can_id_restricted(can_id) && !default_sdo_can_id(can_id));
}
