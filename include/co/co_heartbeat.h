/* SPDX-License-Identifier: Apache-2.0 */
/* Heartbeat (CiA 301 section 7.2.8.3.2): the producer (1017h, ms) and the consumers (1016h,
 * node-id << 16 | ms).
 *
 * Producer: the first heartbeat goes out one period after the reset or after 1017h is written,
 * then exactly every period; its state byte is the node's NMT state. 1017h = 0 stops it. With
 * CO_NODE_HEARTBEAT_GRID (co_node.h) the beats fall on the multiples of the period from time 0
 * of the node's clock instead, the first at most one period after the reset or the write.
 * Consumers: an entry with node-id 0 (or > 127) or time 0 is unused. Monitoring of a producer
 * starts with the first frame received from it; a loss is reported once (hooks->heartbeat(lost =
 * true)) and re-armed by the next frame (hooks->heartbeat(lost = false)). A boot-up frame (state
 * 0) counts as a sign of life like any heartbeat: CiA 301 defines the heartbeat event as a
 * timeout only. */
#ifndef CO_HEARTBEAT_H
#define CO_HEARTBEAT_H

#include "co_config.h"
#include "co_hb_monitor.h"
#include "co_od.h"

typedef struct co_hb_consumer {
    uint8_t node_id; /* 0: entry unused */
    uint8_t state;   /* last state byte received from the producer */
    co_hb_monitor_t monitor;
} co_hb_consumer_t;

typedef struct co_heartbeat {
    co_time_t period;    /* 1017h in microseconds, loaded at each reset and 1017h write */
    co_time_t next_beat; /* CO_TIME_NEVER while 1017h = 0 */
    co_hb_consumer_t consumer[CO_CONFIG_HB_CONSUMERS];
    co_time_t consumers_next; /* earliest consumer deadline */
} co_heartbeat_t;

/* Reset communication: restarts the producer period and reloads the consumers from 1016h. */
void co_heartbeat_reset(co_node_t *node);
/* Consumes a heartbeat or boot-up frame of a monitored producer. */
bool co_heartbeat_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_heartbeat_process(co_node_t *node, co_time_t now);
uint32_t co_heartbeat_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                               size_t len);

/* True while the heartbeat producer runs (1017h != 0): node guarding is then off. Inline: its
 * one caller, guarding.c, folds it in and calls nothing of heartbeat.c. */
static inline bool co_heartbeat_producing(const co_node_t *node)
{
    return co_od_value(node, CO_IDX_HB_PRODUCER, 0) != 0;
}

#endif
