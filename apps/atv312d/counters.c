/* SPDX-License-Identifier: Apache-2.0 */
/* Per-drive service counters (counters.h). */
#include "atv312d/counters.h"

#include "co/co_emcy_consumer.h"

/* A data frame with an 11-bit COB-ID: remote requests and 29-bit frames carry no service here. */
static bool is_data(const co_frame_t *frame, uint32_t cob_id)
{
    return frame->id == cob_id && !(frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF));
}

bool atv312d_is_emcy(uint8_t node_id, const co_frame_t *frame)
{
    return is_data(frame, CO_CAN_ID_EMCY + node_id);
}

void atv312d_count_received(atv312d_counters_t *counters, uint8_t node_id, const co_frame_t *frame)
{
    if (is_data(frame, CO_CAN_ID_SDO_RX + node_id))
        counters->sdo_requests++;
}

void atv312d_count_sent(atv312d_counters_t *counters, uint8_t node_id, const co_frame_t *frame)
{
    if (atv312d_is_emcy(node_id, frame))
        counters->emcy++;
    else if (is_data(frame, CO_CAN_ID_SDO_TX + node_id) && frame->len > 0 &&
             frame->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT))
        counters->sdo_aborts++;
}
