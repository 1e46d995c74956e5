/* SPDX-License-Identifier: Apache-2.0 */
/* Node guarding and life guarding (CiA 301 7.2.8.3.1; 100Ch, 100Dh, 100Eh; co_guarding.h): the
 * reply to a guarding request, whose toggle starts at 0 and only Reset_Communication resets, and
 * the life timer. One of the two error control protocols: a request is ignored while the
 * heartbeat is produced (co_heartbeat_producing), and heartbeat.c stops life guarding when 1017h
 * is written (co_guarding_stop); neither file calls the other. */
#include "co/co_node.h"

/* The CAN-ID of requests and replies: 100Eh (COB-ID node guarding, which some dictionaries
 * have) when the dictionary has it, else 700h + node-id (CiA 301 7.2.8.3.1). Heartbeat
 * and boot-up stay on 700h + node-id (nmt.c, heartbeat.c). */
static uint32_t guarding_cob_id(const co_node_t *node)
{
    return co_od_param(node, CO_IDX_GUARD_COB_ID, 0, CO_CAN_ID_ERROR_CONTROL + node->node_id);
}

/* The life time, guard time (100Ch, ms) times life time factor (100Dh), from now while guarding
 * has started and is not lost; off when either is 0. */
static void restart_life_timer(co_node_t *node)
{
    co_guarding_t *g = &node->guarding;
    uint16_t guard_time_ms = (uint16_t)co_od_value(node, CO_IDX_GUARD_TIME, 0);
    uint8_t life_time_factor = (uint8_t)co_od_value(node, CO_IDX_LIFE_TIME_FACTOR, 0);
    co_time_t life_us = (co_time_t)guard_time_ms * life_time_factor * 1000u;
    bool armed = g->started && !g->lost && life_us != 0;
    g->deadline = armed ? node->now + life_us : CO_TIME_NEVER;
}

/* A loss is a communication error (1029h:01) before the application hears of it. */
static void guarding_report(co_node_t *node, bool lost)
{
    if (lost)
        co_node_communication_error(node);
    if (node->hooks != NULL && node->hooks->guarding != NULL)
        node->hooks->guarding(node, lost);
}

void co_guarding_reset(co_node_t *node)
{
    co_guarding_t *g = &node->guarding;
    g->toggle = 0;
    g->started = false;
    g->lost = false;
    g->deadline = CO_TIME_NEVER;
}

bool co_guarding_receive(co_node_t *node, const co_frame_t *frame)
{
    /* The RTR flag first: the COB-ID lookup is a dictionary search, and data frames are most. */
    if (!(frame->flags & CO_FRAME_RTR) || frame->id != guarding_cob_id(node))
        return false;
    /* A guarding request is a remote frame of DLC 0 or 1 (masters differ), of any DLC on a node of
     * 8-byte frames; a node runs only one error control protocol, so heartbeat production
     * silences guarding (docs/decisions.md, D-HEARTBEAT-GUARDING). */
    bool any_dlc = (node->options & CO_NODE_PAD_DLC8) != 0;
    if ((frame->len > 1 && !any_dlc) || co_heartbeat_producing(node))
        return true;
    co_guarding_t *g = &node->guarding;
    uint8_t reply = (uint8_t)(g->toggle | (uint8_t)node->nmt_state);
    g->toggle ^= CO_GUARD_TOGGLE;
    co_node_send_byte(node, frame->id, reply);
    g->started = true;
    bool resumed = g->lost;
    g->lost = false;
    restart_life_timer(node);
    if (resumed)
        guarding_report(node, false);
    return true;
}

co_time_t co_guarding_process(co_node_t *node, co_time_t now)
{
    co_guarding_t *g = &node->guarding;
    if (now < g->deadline)
        return g->deadline;
    g->lost = true;
    g->deadline = CO_TIME_NEVER;
    guarding_report(node, true);
    return CO_TIME_NEVER;
}

/* 100Eh (COB-ID node guarding): an 11-bit CAN-ID, bits 11-31 clear, else
 * 0x06090030; it applies from the next request. Its default 700h + node-id lies in the CiA 301
 * restricted range, which binds the configurable PDO/SYNC/EMCY COB-IDs only, so it is not checked.
 * 100Ch/100Dh: the new guard time or life time factor is stored, then a running life timer restarts
 * with both. */
uint32_t co_guarding_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              size_t len)
{
    if (entry->index == CO_IDX_GUARD_COB_ID)
        return co_get_u32(data) & ~CO_COB_ID_CAN_ID ? CO_SDO_ABORT_VALUE_RANGE : CO_SDO_OK;
    co_od_store(node, entry, data, len);
    restart_life_timer(node);
    return CO_OD_HANDLED;
}
