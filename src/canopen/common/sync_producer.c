/* SPDX-License-Identifier: Apache-2.0 */
/* The SYNC producer (CiA 301 7.2.5: 1005h bit 30, period 1006h, counter 1019h), of a node and
 * of a master program without one (co_sync_producer_t). A node reaches it only through its
 * dictionary's co_od_t.sync_producer = co_sync_produce, which the generator sets when the
 * dictionary has 1006h: a firmware that never produces the SYNC does not link it. */
#include "co/co_node.h"

static bool sync_production_allowed(const co_node_t *node)
{
    return node->nmt_state == CO_NMT_PRE_OPERATIONAL || node->nmt_state == CO_NMT_OPERATIONAL;
}

static bool sync_producer_configured(const co_node_t *node)
{
    return (node->sync.cob_id & CO_SYNC_COBID_PRODUCER) && node->sync.period_us != 0;
}

bool co_sync_producer_init(co_sync_producer_t *producer, uint32_t can_id, uint32_t period_us,
                           uint8_t overflow)
{
    if (can_id > CO_SYNC_COBID_CAN_ID || co_can_id_restricted(can_id) || period_us == 0)
        return false;
    if (overflow != 0 && (overflow < CO_SYNC_OVERFLOW_MIN || overflow > CO_SYNC_OVERFLOW_MAX))
        return false;
    *producer = (co_sync_producer_t){
        .can_id = can_id, .period_us = period_us, .overflow = overflow, .next = CO_TIME_NEVER};
    return true;
}

void co_sync_producer_start(co_sync_producer_t *producer, co_time_t start)
{
    producer->counter = 0;
    producer->next = start + producer->period_us;
}

/* The counter starts at 1 and wraps from the overflow value back to 1 (CiA 301 7.2.5.2). */
static uint8_t sync_next_counter(uint8_t counter, uint8_t overflow)
{
    return counter < overflow ? (uint8_t)(counter + 1) : 1;
}

bool co_sync_producer_take(co_sync_producer_t *producer, co_time_t now, co_frame_t *frame)
{
    if (now < producer->next)
        return false;
    *frame = (co_frame_t){.id = producer->can_id};
    if (producer->overflow != 0) {
        producer->counter = sync_next_counter(producer->counter, producer->overflow);
        frame->len = 1;
        frame->data[0] = producer->counter;
    }
    producer->next = co_time_next_period(producer->next, producer->period_us, now);
    return true;
}

co_time_t co_sync_produce(co_node_t *node, co_time_t now)
{
    co_sync_producer_t *producer = &node->sync.producer;
    if (!sync_production_allowed(node)) {
        /* Leaving Pre-operational/Operational restarts the counter at 1. */
        producer->counter = 0;
        co_sync_producer_stop(producer);
        return CO_TIME_NEVER;
    }
    if (!sync_producer_configured(node)) {
        co_sync_producer_stop(producer);
        return CO_TIME_NEVER;
    }
    /* 1005h, 1006h and 1019h may have changed since the last call; their writes stop the
     * producer, so that a new configuration starts a fresh period here, counter kept. */
    producer->can_id = node->sync.cob_id & CO_SYNC_COBID_CAN_ID;
    producer->period_us = node->sync.period_us;
    producer->overflow = node->sync.overflow;
    if (producer->next == CO_TIME_NEVER)
        producer->next = now + producer->period_us;
    co_frame_t frame;
    if (co_sync_producer_take(producer, now, &frame)) {
        co_node_send(node, &frame);
        node->sync.deliver(node, frame.data[0]);
    }
    /* Read after the delivery: a 1005h or 1006h write by the PDOs or the application's sync hook
     * stops the producer. */
    return producer->next;
}
