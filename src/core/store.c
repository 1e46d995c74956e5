/* PLACEHOLDER until store/restore is implemented. */
#include "co/co_node.h"

uint32_t co_store_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len)
{
    (void)node;
    (void)entry;
    (void)data;
    (void)len;
    return SDO_ABORT_DATA_STORE;
}

void co_store_apply(co_node_t *node, uint16_t first, uint16_t last)
{
    (void)node;
    (void)first;
    (void)last;
}
