/* PLACEHOLDER until the EMCY service is implemented. */
#include "co/co_node.h"

void co_emcy_reset(co_node_t *node)
{
    (void)node;
}

co_time_t co_emcy_process(co_node_t *node, co_time_t now)
{
    (void)node;
    (void)now;
    return CO_TIME_NEVER;
}

uint32_t co_emcy_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len)
{
    (void)node;
    (void)entry;
    (void)data;
    (void)len;
    return 0;
}

void co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg, const uint8_t msef[5])
{
    (void)node;
    (void)code;
    (void)reg;
    (void)msef;
}

void co_emcy_clear(co_node_t *node, uint16_t code)
{
    (void)node;
    (void)code;
}

bool co_emcy_is_active(const co_node_t *node, uint16_t code)
{
    (void)node;
    (void)code;
    return false;
}
