/* Heartbeat: the producer (1017h, ms) and the consumers (1016h, node-id << 16 | ms), each
 * reporting a loss once and re-armed by the next heartbeat (CiA 301 section 7.2.8.3.2). */
#ifndef CO_HEARTBEAT_H
#define CO_HEARTBEAT_H

#include "co_config.h"
#include "co_od.h"

typedef struct co_hb_consumer {
    uint8_t node_id;
    uint8_t state;
    co_time_t deadline;
} co_hb_consumer_t;

typedef struct co_heartbeat {
    co_time_t next_beat;
    co_hb_consumer_t consumer[CO_CONFIG_HB_CONSUMERS];
} co_heartbeat_t;

void co_heartbeat_reset(co_node_t *node);
bool co_heartbeat_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_heartbeat_process(co_node_t *node, co_time_t now);
uint32_t co_heartbeat_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                               size_t len);

#endif
