/* SPDX-License-Identifier: Apache-2.0 */
/* EMCY producer, CiA 301 section 7.2.7 and objects 1001h, 1003h, 1014h, 1015h (7.5.2). */
#include "co/co_node.h"

#include <string.h>

#define INHIBIT_UNIT_US 100u
#define MSEF_LEN 5u

static bool service_allowed(const co_node_t *node)
{
    return node->nmt_state == CO_NMT_PRE_OPERATIONAL || node->nmt_state == CO_NMT_OPERATIONAL;
}

static uint8_t active_register(const co_emcy_t *emcy)
{
    uint8_t reg = emcy->active_count != 0 ? CO_ERR_REG_GENERIC : 0;
    for (uint8_t i = 0; i < emcy->active_count; i++)
        reg |= emcy->active[i].reg;
    return reg;
}

/* 1001h, which every EMCY frame copies into its byte 2: under CO_NODE_ERROR_REGISTER_GENERIC the
 * generic bit alone, whatever classes the raisers gave. */
static void update_register(co_node_t *node)
{
    uint8_t reg = active_register(&node->emcy);
    if (node->options & CO_NODE_ERROR_REGISTER_GENERIC)
        reg &= CO_ERR_REG_GENERIC;
    co_od_set_value(node, CO_IDX_ERROR_REGISTER, 0, reg);
}

static void queue_drop(co_emcy_t *emcy)
{
    emcy->queue_head = 0;
    emcy->queue_count = 0;
}

static void send_now(co_node_t *node, const co_frame_t *frame)
{
    co_node_send(node, frame);
    uint16_t inhibit = (uint16_t)co_od_value(node, CO_IDX_EMCY_INHIBIT, 0);
    node->emcy.inhibit_end = node->now + (co_time_t)inhibit * INHIBIT_UNIT_US;
}

/* Sends at once when the inhibit time allows and nothing waits, else queues behind the others. */
static void emit(co_node_t *node, uint16_t code, const uint8_t msef[5])
{
    /* CiA 301 7.2.7.1: without 1014h the EMCY is on its predefined CAN-ID, 80h + node-id. */
    uint32_t cobid = co_od_param(node, CO_IDX_EMCY_COB_ID, 0, CO_CAN_ID_EMCY + node->node_id);
    if ((cobid & CO_COB_ID_INVALID) || !service_allowed(node))
        return;
    co_emcy_t *emcy = &node->emcy;
    co_frame_t frame = {.id = cobid & CO_COB_ID_CAN_ID, .len = 8};
    co_put_u16(frame.data, code);
    frame.data[2] = (uint8_t)co_od_value(node, CO_IDX_ERROR_REGISTER, 0);
    if (msef != NULL)
        memcpy(&frame.data[3], msef, MSEF_LEN);
    if (emcy->queue_count == 0 && node->now >= emcy->inhibit_end) {
        send_now(node, &frame);
        return;
    }
    if (emcy->queue_count == CO_CONFIG_EMCY_QUEUE)
        return;
    uint8_t tail = (uint8_t)((emcy->queue_head + emcy->queue_count) % CO_CONFIG_EMCY_QUEUE);
    emcy->queue[tail] = frame;
    emcy->queue_count++;
    co_node_reschedule(node);
}

co_time_t co_emcy_process(co_node_t *node, co_time_t now)
{
    co_emcy_t *emcy = &node->emcy;
    if (!service_allowed(node))
        queue_drop(emcy);
    while (emcy->queue_count != 0 && now >= emcy->inhibit_end) {
        send_now(node, &emcy->queue[emcy->queue_head]);
        emcy->queue_head = (uint8_t)((emcy->queue_head + 1) % CO_CONFIG_EMCY_QUEUE);
        emcy->queue_count--;
    }
    return emcy->queue_count != 0 ? emcy->inhibit_end : CO_TIME_NEVER;
}

/* Sub-indexes 1.. of 1003h present in the dictionary (the history's depth). */
static uint8_t history_depth(const co_node_t *node)
{
    uint8_t n = 0;
    while (n < 0xFE && co_od_find(node->od, CO_IDX_ERROR_HISTORY, (uint8_t)(n + 1)) != NULL)
        n++;
    return n;
}

/* CiA 301 1003h: the newest error at sub-index 1, older ones move down, sub 0 counts them. */
static void history_push(co_node_t *node, uint16_t code)
{
    uint8_t depth = history_depth(node);
    if (depth == 0)
        return;
    for (uint8_t sub = depth; sub > 1; sub--)
        co_od_set_value(node, CO_IDX_ERROR_HISTORY, sub,
                        co_od_value(node, CO_IDX_ERROR_HISTORY, (uint8_t)(sub - 1)));
    co_od_set_value(node, CO_IDX_ERROR_HISTORY, 1, code);
    uint8_t count = (uint8_t)co_od_value(node, CO_IDX_ERROR_HISTORY, 0);
    co_od_set_value(node, CO_IDX_ERROR_HISTORY, 0, count < depth ? count + 1 : depth);
}

static void history_clear(co_node_t *node)
{
    uint8_t depth = history_depth(node);
    for (uint8_t sub = 1; sub <= depth; sub++)
        co_od_set_value(node, CO_IDX_ERROR_HISTORY, sub, 0);
}

static int active_position(const co_emcy_t *emcy, uint16_t code)
{
    for (uint8_t i = 0; i < emcy->active_count; i++)
        if (emcy->active[i].code == code)
            return i;
    return -1;
}

bool co_emcy_is_active(const co_node_t *node, uint16_t code)
{
    return active_position(&node->emcy, code) >= 0;
}

bool co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg, const uint8_t msef[5])
{
    co_emcy_t *emcy = &node->emcy;
    if (code == CO_EMCY_NO_ERROR || co_emcy_is_active(node, code) ||
        emcy->active_count == CO_CONFIG_EMCY_HISTORY)
        return false;
    emcy->active[emcy->active_count++] = (co_emcy_error_t){.code = code, .reg = reg};
    update_register(node);
    history_push(node, code);
    emit(node, code, msef);
    return true;
}

void co_emcy_clear(co_node_t *node, uint16_t code)
{
    co_emcy_t *emcy = &node->emcy;
    int pos = active_position(emcy, code);
    if (pos < 0)
        return;
    emcy->active[pos] = emcy->active[--emcy->active_count];
    update_register(node);
    if (emcy->active_count == 0)
        emit(node, CO_EMCY_NO_ERROR, NULL);
}

void co_emcy_reset(co_node_t *node, co_nmt_reset_t scope)
{
    co_emcy_t *emcy = &node->emcy;
    if (scope == CO_NMT_RESET_NODE)
        emcy->active_count = 0;
    queue_drop(emcy);
    emcy->inhibit_end = 0;
    update_register(node);
}

/* CiA 301 1014h: the CAN-ID may change only while the EMCY is invalid (bit 31 set before or
 * after the write); 29-bit identifiers (bit 29) are not supported. A restricted CAN-ID (7.3.5,
 * co_can_id_restricted) is refused even with bit 31 set, so the EMCY can never be made valid on
 * one; the default 080h + node-id (081h-0FFh) is allowed. */
static uint32_t write_cobid(co_node_t *node, uint32_t cobid)
{
    return co_cob_id_check((uint32_t)co_od_value(node, CO_IDX_EMCY_COB_ID, 0), cobid,
                           CO_COB_ID_INVALID, CO_COB_ID_INVALID);
}

/* CiA 301 1003h: only 0 may be written to sub-index 0, and it clears the history. */
static uint32_t write_history(co_node_t *node, const co_od_entry_t *entry, uint8_t value)
{
    if (entry->subindex != 0)
        return CO_SDO_OK;
    if (value != 0)
        return CO_SDO_ABORT_VALUE_RANGE;
    history_clear(node);
    return CO_SDO_OK;
}

uint32_t co_emcy_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len)
{
    (void)len;
    if (entry->index == CO_IDX_ERROR_HISTORY)
        return write_history(node, entry, data[0]);
    if (entry->index == CO_IDX_EMCY_COB_ID)
        return write_cobid(node, co_get_u32(data));
    /* 1015h: CiA 301 sets no condition; the new inhibit time applies from the next EMCY. */
    return CO_SDO_OK;
}
