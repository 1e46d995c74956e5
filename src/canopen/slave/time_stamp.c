/* SPDX-License-Identifier: Apache-2.0 */
/* The TIME service (co_time_stamp.h): the consumer, the producer and the rules of 1012h; the
 * TIME_OF_DAY codec is common/time_of_day.c. */
#include "co/co_node.h"
#include "co/co_time_stamp.h"

static uint32_t time_cob_id(const co_node_t *node)
{
    return (uint32_t)co_od_value(node, CO_IDX_TIME_COB_ID, 0);
}

static void time_reset(co_node_t *node)
{
    node->time_cob_id = time_cob_id(node);
}

static bool time_receive(co_node_t *node, const co_frame_t *frame)
{
    uint32_t cob_id = node->time_cob_id;
    if (!(cob_id & CO_TIME_COBID_CONSUMER) || frame->id != (cob_id & CO_TIME_COBID_CAN_ID) ||
        (frame->flags & CO_FRAME_RTR))
        return false;
    co_time_of_day_t time;
    /* CiA 301 gives a wrong TIME length no EMCY: the frame is dropped. */
    if (co_time_of_day_decode(frame->data, frame->len, &time) && node->hooks != NULL &&
        node->hooks->time_stamp != NULL)
        node->hooks->time_stamp(node, &time);
    return true;
}

/* CiA 301 7.5.2.12: bits 31 (consume) and 30 (produce), an 11-bit CAN-ID that is not restricted
 * (7.3.5; bit 29 and bits 28..11 refused, co_cob_id_check), and no new CAN-ID while the object
 * exists (bit 31 or 30) before and after the write. */
static uint32_t time_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              size_t len)
{
    if (entry->index != CO_IDX_TIME_COB_ID)
        return CO_SDO_OK;
    uint32_t old = node->time_cob_id;
    uint32_t value = co_get_u32(data);
    uint32_t abort =
        co_cob_id_check(old, value, CO_TIME_COBID_CONSUMER | CO_TIME_COBID_PRODUCER, 0);
    if (abort != CO_SDO_OK)
        return abort;
    co_od_store(node, entry, data, len);
    node->time_cob_id = value;
    return CO_OD_HANDLED;
}

const co_time_stamp_code_t co_time_stamp = {
    .reset = time_reset,
    .receive = time_receive,
    .od_write = time_od_write,
};

bool co_time_stamp_send(co_node_t *node, const co_time_of_day_t *time)
{
    uint32_t cob_id = time_cob_id(node);
    if (!(cob_id & CO_TIME_COBID_PRODUCER) ||
        (node->nmt_state != CO_NMT_PRE_OPERATIONAL && node->nmt_state != CO_NMT_OPERATIONAL))
        return false;
    co_frame_t frame = {.id = cob_id & CO_TIME_COBID_CAN_ID, .len = CO_TIME_OF_DAY_LEN};
    co_time_of_day_encode(time, frame.data);
    co_node_send(node, &frame);
    return true;
}
