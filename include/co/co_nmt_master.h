/* SPDX-License-Identifier: Apache-2.0 */
/* NMT master (CiA 301 sections 7.2.8.2 and 7.2.8.3): NMT commands to one node or to all, the NMT
 * state of every node 1..127 as its boot-up, heartbeat and guarding frames tell it, a heartbeat
 * consumer per node, and node guarding of the nodes that have no heartbeat. Independent of
 * co_node_t: a master program runs it with or without a node of its own. Passive and
 * deterministic like the rest of the core: frames and time are passed in, frames go out through
 * the send callback, what happens to a node comes out through the event callback. Its SYNC
 * producer is co_sync_producer_t (co_sync.h). Behaviour and decisions: docs/nmt-master.md. */
#ifndef CO_NMT_MASTER_H
#define CO_NMT_MASTER_H

#include "co_hb_monitor.h"
#include "co_node.h"

#define CO_NMT_MASTER_NODE_ID_MAX CO_NODE_ID_MAX /* the nodes an NMT master tracks, 1..127 */
/* NMT command to all nodes (CiA 301 7.2.8.3.1: node-ID 0 in the command frame). */
#define CO_NMT_MASTER_ALL_NODES 0u
/* The state of a node no frame has come from yet (not a CiA 301 state value). */
#define CO_NMT_MASTER_STATE_UNKNOWN 0xFFu

typedef enum co_nmt_master_event_kind {
    /* The node sent its boot-up frame: it is now in Pre-operational. */
    CO_NMT_MASTER_BOOT_UP,
    /* The node reported another state than the one known (old_state, state). */
    CO_NMT_MASTER_STATE_CHANGED,
    /* No heartbeat within the consumer time after the last one. */
    CO_NMT_MASTER_HEARTBEAT_LOST,
    /* No valid guarding reply within the life time (guard time x life time factor). */
    CO_NMT_MASTER_GUARDING_LOST,
    /* The lost node is heard again: a heartbeat, or a guarding reply with the right toggle. */
    CO_NMT_MASTER_RESUMED
} co_nmt_master_event_kind_t;

typedef struct co_nmt_master_event {
    co_nmt_master_event_kind_t kind;
    uint8_t node_id;
    uint8_t state;     /* the node's state after the event (CO_NMT_MASTER_STATE_UNKNOWN or 0x04,
                        * 0x05, 0x7F) */
    uint8_t old_state; /* before it; equal to state except for BOOT_UP and STATE_CHANGED */
} co_nmt_master_event_t;

typedef void (*co_nmt_master_event_fn)(void *user, const co_nmt_master_event_t *event);

/* What the master knows and does about one node. */
typedef struct co_nmt_master_slave {
    uint8_t state; /* CO_NMT_MASTER_STATE_UNKNOWN until a frame came from the node */
    /* Heartbeat consumer, like a 1016h entry (co_hb_monitor.h); time 0 = not monitored. */
    co_hb_monitor_t heartbeat;
    /* Node guarding: guard time 0 = not guarded. */
    uint32_t guard_us;
    uint8_t life_time_factor;
    uint8_t missed;          /* guard times in a row that ended without a valid reply */
    bool requested;          /* a request went out since guarding was configured */
    bool answered;           /* a valid reply came since the last request */
    bool guarding_lost;      /* the loss was reported and no valid reply came since */
    uint8_t expected_toggle; /* 0x00 or 0x80: the toggle bit of the next valid reply */
    co_time_t next_request;  /* next guarding request, on the grid start + k x guard time */
} co_nmt_master_slave_t;

typedef struct co_nmt_master_config {
    co_send_fn send;              /* required */
    void *user;                   /* passed to send and event */
    co_nmt_master_event_fn event; /* may be NULL */
} co_nmt_master_config_t;

typedef struct co_nmt_master {
    co_send_fn send;
    void *user;
    co_nmt_master_event_fn event;
    co_nmt_master_slave_t slave[CO_NMT_MASTER_NODE_ID_MAX]; /* node-id n at [n - 1] */
} co_nmt_master_t;

/* Every node unknown, none monitored or guarded. False without a send callback. Sends nothing. */
bool co_nmt_master_init(co_nmt_master_t *master, const co_nmt_master_config_t *config);

/* Sends the NMT command `command` (CO_NMT_CS_*, co_nmt.h) to node `node_id` 1..127 or to all
 * (CO_NMT_MASTER_ALL_NODES): 000h [command, node_id]. A reset (node or communication) makes the
 * guarding of the nodes it addresses expect the toggle bit 0 again. False, and nothing sent, for
 * an unknown command or a node-id above 127. */
bool co_nmt_master_command(co_nmt_master_t *master, uint8_t command, uint8_t node_id);

/* Heartbeat consumer for node `node_id`: `ms` is its consumer time (like a 1016h entry), 0 stops
 * monitoring. Monitoring starts with the next frame from the node. False for a node-id outside
 * 1..127 or a node that is guarded (CiA 301: one error control protocol per node). */
bool co_nmt_master_heartbeat(co_nmt_master_t *master, uint8_t node_id, uint16_t ms);

/* The same, but the consumer time runs from `now` as if a heartbeat had come then: a node that
 * sends none at all is lost at now + ms (CO_NMT_MASTER_HEARTBEAT_LOST), and its first heartbeat
 * after that resumes it (CO_NMT_MASTER_RESUMED). For a master that has just set the node's
 * producer time, where CiA 301's consumer would wait for the first heartbeat forever. */
bool co_nmt_master_await_heartbeat(co_nmt_master_t *master, uint8_t node_id, uint16_t ms,
                                   co_time_t now);

/* Guards node `node_id`: a request every `guard_ms` from `now` (the first one at `now`), lost when
 * `life_time_factor` guard times in a row pass without a valid reply. 0 in either stops guarding.
 * The toggle bit expected first is 0. False for a node-id outside 1..127 or a node whose heartbeat
 * is monitored. */
bool co_nmt_master_guard(co_nmt_master_t *master, uint8_t node_id, uint16_t guard_ms,
                         uint8_t life_time_factor, co_time_t now);

/* Consumes a boot-up, heartbeat or guarding reply frame (700h + node-id, 1 data byte). Returns
 * false for any other frame, and for a state byte that is not a CiA 301 state (ignored). */
bool co_nmt_master_receive(co_nmt_master_t *master, const co_frame_t *frame, co_time_t now);

/* Sends the guarding requests that are due, reports the losses that are due, and returns the next
 * deadline (CO_TIME_NEVER when nothing is monitored). */
co_time_t co_nmt_master_process(co_nmt_master_t *master, co_time_t now);

/* The last known state of a node, CO_NMT_MASTER_STATE_UNKNOWN for a node never heard or a
 * node-id outside 1..127. */
uint8_t co_nmt_master_state(const co_nmt_master_t *master, uint8_t node_id);
/* True while a loss of the node is reported and it was not heard since. */
bool co_nmt_master_lost(const co_nmt_master_t *master, uint8_t node_id);

#endif
