/* SPDX-License-Identifier: Apache-2.0 */
/* NMT start-up of a slave (CiA 302-2, object 1F80h): with bit 2 clear the node enters Operational
 * by itself after its boot-up, without waiting for the master's start (a self-starting device).
 * The network master's 1F80h is co_net_master.h's. Selectable per node: a node gets the service
 * with co_node_config_t.nmt_startup = &co_nmt_startup; one without it links none of it and waits
 * for an NMT start whatever its dictionary holds. docs/error-control.md. */
#ifndef CO_NMT_STARTUP_H
#define CO_NMT_STARTUP_H

#include "co_od.h"

#define CO_IDX_NMT_STARTUP 0x1F80u
/* The bits of 1F80h (CiA 302-2, "NMT start-up"): bit 0 set makes the device the NMT master, bit 2
 * set keeps it from entering Operational by itself; the other bits configure a master. */
#define CO_NMT_STARTUP_NMT_MASTER 0x01u
#define CO_NMT_STARTUP_NO_SELF_START 0x04u

typedef struct co_nmt_startup_code {
    /* The node has just entered Pre-operational after its boot-up: on to Operational when 1F80h
     * bit 2 is clear (an absent 1F80h reads as bit 2 set: no self start). */
    void (*booted)(co_node_t *node);
    /* The write rules of 1F80h on a slave (co_node_t.parameter_write). */
    uint32_t (*od_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
} co_nmt_startup_code_t;

extern const co_nmt_startup_code_t co_nmt_startup;

#endif
