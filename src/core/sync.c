/* PLACEHOLDER until the sync service is implemented. */
#include "co/co_node.h"

void co_sync_reset(co_node_t *node)
{
    (void)node;
}

bool co_sync_receive(co_node_t *node, const co_frame_t *frame)
{
    (void)node;
    (void)frame;
    return false;
}

co_time_t co_sync_process(co_node_t *node, co_time_t now)
{
    (void)node;
    (void)now;
    return CO_TIME_NEVER;
}

uint32_t co_sync_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len)
{
    (void)node;
    (void)entry;
    (void)data;
    (void)len;
    return 0;
}
