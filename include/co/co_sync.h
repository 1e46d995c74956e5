/* SYNC consumer and producer: 1005h COB-ID (bit 30 = produce), 1006h period, 1007h window and the
 * 1019h counter (CiA 301 section 7.2.5). */
#ifndef CO_SYNC_H
#define CO_SYNC_H

#include "co_od.h"

typedef struct co_sync {
    uint8_t counter;
} co_sync_t;

void co_sync_reset(co_node_t *node);
bool co_sync_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_sync_process(co_node_t *node, co_time_t now);
uint32_t co_sync_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len);

#endif
