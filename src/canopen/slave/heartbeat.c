/* SPDX-License-Identifier: Apache-2.0 */
/* Heartbeat (CiA 301 7.2.8.3.2; co_heartbeat.h): the producer (1017h) and the consumers (1016h),
 * each consumer's timer a co_hb_monitor_t (co_hb_monitor.h). Writing 1017h stops life guarding
 * (co_guarding_stop, inline in co_guarding.h): a node runs one error control protocol. */
#include "co/co_node.h"

#define HB_TIME_MASK 0xFFFFu
#define HB_RESERVED_MASK 0xFF000000u /* CiA 301 1016h value definition: bits 24..31 are 0 */

static uint32_t consumer_node(uint32_t value)
{
    return (value >> 16) & 0xFFu;
}

/* CiA 301 1016h: an entry with time 0 or a node-id outside 1..127 is not used. */
static bool consumer_in_use(uint32_t value)
{
    uint32_t id = consumer_node(value);
    return (value & HB_TIME_MASK) != 0 && id >= 1 && id <= CO_NODE_ID_MAX;
}

static co_time_t producer_period_us(uint16_t ms)
{
    return (co_time_t)ms * 1000u;
}

/* The first beat after `now` of a producer whose period (re)starts or whose call came late. By
 * default the period counts from `now`. With CO_NODE_HEARTBEAT_GRID the beats fall on the
 * multiples of the period from time 0 of the node's clock, at most one period after `now`
 * (docs/error-control.md): every producer of a runtime with the same or a commensurate period is
 * then due at the same instants, and they send in one wake-up however their periods started. */
static co_time_t beat_after(const co_node_t *node, co_time_t now, co_time_t period)
{
    if (node->options & CO_NODE_HEARTBEAT_GRID)
        return node->options_code->beat_on_grid(now, period);
    return now + period;
}

/* CiA 301 7.2.8.3.2.2: the protocol begins when 1017h is written, or at the boot-up, which is
 * then the first heartbeat; the next one is due within one period. */
static void producer_restart(co_node_t *node, uint16_t ms)
{
    co_heartbeat_t *hb = &node->heartbeat;
    hb->period = producer_period_us(ms);
    hb->next_beat = ms != 0 ? beat_after(node, node->now, hb->period) : CO_TIME_NEVER;
}

/* The earliest deadline of the consumers, kept exact after every change of one of them, so that a
 * process call with no consumer due looks at none of them. */
static void consumers_schedule(co_heartbeat_t *hb)
{
    co_time_t next = CO_TIME_NEVER;
    for (uint8_t i = 0; i < CO_CONFIG_HB_CONSUMERS; i++)
        next = co_time_min(next, hb->consumer[i].monitor.deadline);
    hb->consumers_next = next;
}

/* Consumer i takes a 1016h value: its monitoring restarts, and with it the consumers' schedule. */
static void consumer_configure(co_heartbeat_t *hb, uint8_t i, uint32_t value)
{
    co_hb_consumer_t *c = &hb->consumer[i];
    bool used = consumer_in_use(value);
    c->node_id = used ? (uint8_t)consumer_node(value) : 0;
    c->state = 0;
    co_hb_monitor_configure(&c->monitor, (uint32_t)(value & HB_TIME_MASK) * 1000u);
    consumers_schedule(hb);
}

void co_heartbeat_reset(co_node_t *node)
{
    co_heartbeat_t *hb = &node->heartbeat;
    producer_restart(node, (uint16_t)co_od_value(node, CO_IDX_HB_PRODUCER, 0));
    for (uint8_t i = 0; i < CO_CONFIG_HB_CONSUMERS; i++)
        consumer_configure(hb, i,
                           (uint32_t)co_od_value(node, CO_IDX_HB_CONSUMER, (uint8_t)(i + 1)));
}

/* A loss is a communication error (1029h:01) before the application hears of it. */
static void heartbeat_report(co_node_t *node, uint8_t producer, bool lost)
{
    if (lost)
        co_node_communication_error(node);
    if (node->hooks != NULL && node->hooks->heartbeat != NULL)
        node->hooks->heartbeat(node, producer, lost);
}

bool co_heartbeat_receive(co_node_t *node, const co_frame_t *frame)
{
    /* A heartbeat (or boot-up) is exactly one data byte. */
    if (frame->id <= CO_CAN_ID_ERROR_CONTROL ||
        frame->id > CO_CAN_ID_ERROR_CONTROL + CO_NODE_ID_MAX || (frame->flags & CO_FRAME_RTR) ||
        frame->len != 1)
        return false;
    uint8_t producer = (uint8_t)(frame->id - CO_CAN_ID_ERROR_CONTROL);
    bool consumed = false;
    for (uint8_t i = 0; i < CO_CONFIG_HB_CONSUMERS; i++) {
        co_hb_consumer_t *c = &node->heartbeat.consumer[i];
        if (c->node_id != producer)
            continue;
        consumed = true;
        c->state = frame->data[0];
        if (co_hb_monitor_alive(&c->monitor, node->now))
            heartbeat_report(node, producer, false);
    }
    if (consumed)
        consumers_schedule(&node->heartbeat);
    return consumed;
}

static co_time_t consumers_process(co_node_t *node, co_time_t now)
{
    if (now < node->heartbeat.consumers_next)
        return node->heartbeat.consumers_next;
    for (uint8_t i = 0; i < CO_CONFIG_HB_CONSUMERS; i++) {
        co_hb_consumer_t *c = &node->heartbeat.consumer[i];
        if (co_hb_monitor_expired(&c->monitor, now))
            heartbeat_report(node, c->node_id, true);
    }
    /* After the reports: their hooks may have reconfigured a consumer. */
    consumers_schedule(&node->heartbeat);
    return node->heartbeat.consumers_next;
}

static co_time_t producer_process(co_node_t *node, co_time_t now)
{
    co_heartbeat_t *hb = &node->heartbeat;
    if (now < hb->next_beat)
        return hb->next_beat;
    co_node_send_byte(node, CO_CAN_ID_ERROR_CONTROL + node->node_id, (uint8_t)node->nmt_state);
    /* One period after the beat that was due, so the period stays exact; a late call skips the
     * beats it missed. */
    hb->next_beat += hb->period;
    if (hb->next_beat <= now)
        hb->next_beat = beat_after(node, now, hb->period);
    return hb->next_beat;
}

co_time_t co_heartbeat_process(co_node_t *node, co_time_t now)
{
    return co_time_min(producer_process(node, now), consumers_process(node, now));
}

/* CiA 301 1016h note: two entries monitoring the same node-id with non-zero times abort
 * 0x06040043. */
static uint32_t check_duplicate_consumer(co_node_t *node, uint8_t subindex, uint32_t value)
{
    if (!consumer_in_use(value))
        return CO_SDO_OK;
    for (uint16_t i = 0; i < node->od->count; i++) {
        const co_od_entry_t *other = &node->od->entries[i];
        if (other->index != CO_IDX_HB_CONSUMER || other->subindex == 0 ||
            other->subindex == subindex)
            continue;
        uint32_t v = (uint32_t)co_od_get(node, other);
        if (consumer_in_use(v) && consumer_node(v) == consumer_node(value))
            return CO_SDO_ABORT_PARAM_INCOMPATIBLE;
    }
    return CO_SDO_OK;
}

static uint32_t write_consumer(co_node_t *node, uint8_t subindex, uint32_t value)
{
    if (value & HB_RESERVED_MASK)
        return CO_SDO_ABORT_VALUE_RANGE;
    uint32_t abort = check_duplicate_consumer(node, subindex, value);
    if (abort != CO_SDO_OK)
        return abort;
    if (subindex > CO_CONFIG_HB_CONSUMERS) {
        /* The dictionary has more entries than the node can monitor: refuse to enable one. */
        return consumer_in_use(value) ? CO_SDO_ABORT_INTERNAL_INCOMPATIBLE : CO_SDO_OK;
    }
    consumer_configure(&node->heartbeat, (uint8_t)(subindex - 1), value);
    return CO_SDO_OK;
}

uint32_t co_heartbeat_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                               size_t len)
{
    (void)len;
    if (entry->index == CO_IDX_HB_PRODUCER) {
        uint16_t ms = co_get_u16(data);
        producer_restart(node, ms);
        if (ms != 0)
            co_guarding_stop(&node->guarding);
        return CO_SDO_OK;
    }
    if (entry->subindex == 0)
        return CO_SDO_OK;
    return write_consumer(node, entry->subindex, co_get_u32(data));
}
