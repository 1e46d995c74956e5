/* Node guarding and life guarding: RTR on 0x700+id answered with state and toggle bit, life time
 * = 100Ch x 100Dh started by the first guarding request; off while 1017h is non-zero (CiA 301
 * section 7.2.8.3.1). */
#ifndef CO_GUARDING_H
#define CO_GUARDING_H

#include "co_od.h"

typedef struct co_guarding {
    uint8_t toggle;
    bool started;
    bool lost;
    co_time_t deadline;
} co_guarding_t;

void co_guarding_reset(co_node_t *node);
bool co_guarding_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_guarding_process(co_node_t *node, co_time_t now);
uint32_t co_guarding_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              size_t len);

#endif
