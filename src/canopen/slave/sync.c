/* SPDX-License-Identifier: Apache-2.0 */
/* SYNC consumer and the producer's parameters (CiA 301 section 7.2.5; parameters 7.5.2.5-7.5.2.7
 * and 7.5.2.41); the producer itself is in sync_producer.c. Every SYNC, received or produced, goes
 * through co_sync_t.deliver to the node, which hands it to the PDO engine and to the
 * application. */
#include "co/co_node.h"

/* The SYNC parameters are read from the dictionary at init, at each reset (after the defaults and
 * the stored values are in place) and after each write of one of them, so that a frame reads
 * them from the service's state; an absent one reads as 0, as co_od_value() reads it. */
static void sync_load(co_node_t *node)
{
    co_sync_t *sync = &node->sync;
    sync->cob_id = (uint32_t)co_od_value(node, CO_IDX_SYNC_COB_ID, 0);
    sync->period_us = (uint32_t)co_od_value(node, CO_IDX_SYNC_PERIOD, 0);
    sync->window_us = (uint32_t)co_od_value(node, CO_IDX_SYNC_WINDOW, 0);
    sync->overflow = (uint8_t)co_od_value(node, CO_IDX_SYNC_OVERFLOW, 0);
}

void co_sync_init(co_node_t *node)
{
    sync_load(node);
    node->sync.timeout_at = CO_TIME_NEVER;
}

static uint32_t sync_cob_id(const co_node_t *node)
{
    return node->sync.cob_id;
}

static uint32_t sync_period_us(const co_node_t *node)
{
    return node->sync.period_us;
}

uint8_t co_sync_overflow(const co_node_t *node)
{
    return node->sync.overflow;
}

uint32_t co_sync_window_us(const co_node_t *node)
{
    return node->sync.window_us;
}

/* The length error and its EMCY end together: a flag left without its EMCY would swallow the
 * next wrong SYNC's EMCY, an EMCY left without its flag would never be cleared. */
static void sync_length_error_end(co_node_t *node)
{
    if (!node->sync.length_error)
        return;
    node->sync.length_error = false;
    co_emcy_clear(node, CO_EMCY_SYNC_LENGTH);
}

/* The consumer's time-out ends with its EMCY, as the length error does. */
static void sync_timeout_end(co_node_t *node)
{
    node->sync.timeout_at = CO_TIME_NEVER;
    if (!node->sync.timeout_error)
        return;
    node->sync.timeout_error = false;
    co_emcy_clear(node, CO_EMCY_COMMUNICATION);
}

/* Reset node and reset communication restart the consumer from restored parameters, so a length
 * error it detected is no longer detected (docs/error-control.md, "Errors and resets"). The node
 * is in Initialising: clearing the EMCY sends no error reset, the boot-up says it. */
void co_sync_reset(co_node_t *node)
{
    sync_load(node);
    co_sync_producer_stop(&node->sync.producer);
    node->sync.producer.counter = 0;
    sync_length_error_end(node);
    sync_timeout_end(node);
}

/* 1.5 x 1006h after the last SYNC without the next one (CiA 301 7.5.2.6): EMCY 0x8100 once, until
 * a SYNC comes. Only a consumer (1005h bit 30 clear) with a period, in Pre-operational or
 * Operational (a Stopped node receives no SYNC: the watch starts again at the next one). */
static co_time_t sync_watch(co_node_t *node, co_time_t now)
{
    co_sync_t *sync = &node->sync;
    if (node->nmt_state == CO_NMT_STOPPED)
        sync->timeout_at = CO_TIME_NEVER;
    if (now < sync->timeout_at)
        return sync->timeout_at;
    sync->timeout_at = CO_TIME_NEVER;
    sync->timeout_error = true;
    co_emcy_raise(node, CO_EMCY_COMMUNICATION, CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION, NULL);
    return CO_TIME_NEVER;
}

/* The producer's code is linked only by a dictionary that has it (co_od_t.sync_producer,
 * sync_producer.c). */
co_time_t co_sync_process(co_node_t *node, co_time_t now)
{
    co_time_t (*produce)(co_node_t *, co_time_t) = node->od->sync_producer;
    co_time_t next = produce != NULL ? produce(node, now) : CO_TIME_NEVER;
    return co_time_min(next, sync_watch(node, now));
}

bool co_sync_receive(co_node_t *node, const co_frame_t *frame)
{
    if (frame->id != (sync_cob_id(node) & CO_SYNC_COBID_CAN_ID))
        return false;
    if (frame->flags & CO_FRAME_RTR)
        return true;
    uint8_t overflow = co_sync_overflow(node);
    uint8_t expected = overflow != 0 ? 1 : 0;
    if (frame->len != expected) {
        /* CiA 301 table 21: unexpected SYNC data length; the SYNC is ignored. */
        uint8_t msef[5] = {frame->len, expected, 0, 0, 0};
        co_emcy_raise(node, CO_EMCY_SYNC_LENGTH, CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION,
                      msef);
        node->sync.length_error = true;
        return true;
    }
    bool watched = node->sync.timeout_at != CO_TIME_NEVER;
    sync_length_error_end(node);
    sync_timeout_end(node);
    uint32_t period = sync_period_us(node);
    if (period != 0 && !(sync_cob_id(node) & CO_SYNC_COBID_PRODUCER)) {
        node->sync.timeout_at = node->now + period + period / 2;
        /* Only a first watch can be due before the node's kept deadline; a watch moved later
         * costs one early look at most, not a run of every service at each SYNC. */
        if (!watched)
            co_node_reschedule(node);
    }
    node->sync.deliver(node, overflow != 0 ? frame->data[0] : 0);
    return true;
}

/* CiA 301 7.5.2.5: 11-bit CAN-IDs only, no restricted CAN-ID (7.3.5, co_can_id_restricted; the
 * default 080h is not one), and the CAN-ID may not change while this node produces the SYNC and
 * keeps producing it. Bit 30 (producer) needs the producer's code, which the generator gives a
 * dictionary that has the communication cycle period 1006h (7.5.2.6): one without could never
 * produce, so it refuses the bit. Bit 31 is "do not care". */
static uint32_t sync_write_cob_id(co_node_t *node, uint32_t value)
{
    if ((value & CO_SYNC_COBID_PRODUCER) && node->od->sync_producer == NULL)
        return CO_SDO_ABORT_VALUE_RANGE;
    return co_cob_id_check(sync_cob_id(node), value, CO_SYNC_COBID_PRODUCER, 0);
}

/* CiA 301 7.5.2.41: 0 or 2..240, and only while no SYNC period is set (1006h = 0). */
static uint32_t sync_write_overflow(co_node_t *node, uint8_t value)
{
    if (sync_period_us(node) != 0)
        return CO_SDO_ABORT_DATA_STATE;
    if (value != 0 && (value < CO_SYNC_OVERFLOW_MIN || value > CO_SYNC_OVERFLOW_MAX))
        return CO_SDO_ABORT_VALUE_RANGE;
    return CO_SDO_OK;
}

uint32_t co_sync_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len)
{
    uint32_t abort = CO_SDO_OK;
    if (entry->index == CO_IDX_SYNC_COB_ID)
        abort = sync_write_cob_id(node, co_get_u32(data));
    else if (entry->index == CO_IDX_SYNC_OVERFLOW)
        abort = sync_write_overflow(node, data[0]);
    if (abort != CO_SDO_OK)
        return abort;
    /* A new producer configuration starts a fresh period at the next co_sync_process(). */
    if (entry->index == CO_IDX_SYNC_COB_ID || entry->index == CO_IDX_SYNC_PERIOD) {
        co_sync_producer_stop(&node->sync.producer);
        sync_timeout_end(node);
    }
    co_od_store(node, entry, data, len);
    sync_load(node);
    return CO_OD_HANDLED;
}
