/* SPDX-License-Identifier: Apache-2.0 */
/* The COB-IDs a node consumes: what a runtime needs to hand a node only the frames it acts on
 * (routing among several nodes, a receive filter in the CAN controller or the kernel). The set
 * follows the node's configuration: NMT 000h, the SYNC COB-ID (1005h), the SDO servers' request
 * COB-IDs (1200h, and 1201h.. of the additional channels while valid), the server -> client
 * COB-IDs of the node's SDO client channels while valid (1280h..), the valid RPDOs' COB-IDs
 * (1400h..), remote requests for the valid TPDOs that allow them (1800h.. bit 30 clear), the node
 * guarding RTR (100Eh, else 700h + node-id) and the heartbeats of the monitored producers (1016h),
 * and the LSS master's 7E5h for a node with LSS (CiA 305). It does not depend on the NMT state: a
 * frame the state does not allow is still the node's to ignore. A generation number changes
 * whenever the set may have changed (a write of one of those objects, a reset), so a runtime
 * compares it instead of enumerating after every frame. */
#ifndef CO_CONSUMERS_H
#define CO_CONSUMERS_H

#include "co_node.h"

/* One consumed COB-ID: its 11-bit CAN-ID and whether the node consumes it as a remote request
 * (RTR) or as a data frame. */
typedef struct co_cob {
    uint16_t can_id;
    bool rtr;
} co_cob_t;

/* Most COB-IDs a node can consume: LSS, NMT, SYNC, TIME, SDO, guarding, one per RPDO, TPDO,
 * heartbeat consumer, additional SDO server and SDO client channel. */
#define CO_CONSUMERS_MAX                                                                           \
    (6 + CO_CONFIG_RPDO_MAX + CO_CONFIG_TPDO_MAX + CO_CONFIG_HB_CONSUMERS +                        \
     CO_CONFIG_SDO_SERVERS_MAX + CO_CONFIG_SDO_CLIENTS_MAX)

/* Fills cobs (CO_CONSUMERS_MAX entries) with the COB-IDs the node consumes now, each once, and
 * returns how many. A node in Initialising (before co_node_start, or without node-id) consumes
 * nothing but 7E5h when it has LSS. */
size_t co_node_consumers(const co_node_t *node, co_cob_t *cobs);

/* Whether the node consumes frames of this CAN-ID (remote requests when rtr is set). */
bool co_node_consumes(const co_node_t *node, uint32_t can_id, bool rtr);

/* Changes whenever the consumed set may have changed; equal values mean an unchanged set. */
static inline uint32_t co_node_consumer_generation(const co_node_t *node)
{
    return node->consumer_generation;
}

/* Moves the generation on (NMT after a reset, which reloads every COB-ID). */
static inline void co_consumers_changed(co_node_t *node)
{
    node->consumer_generation++;
}

/* Called by the node after a stored write of an entry of `index`: moves the generation on when
 * that object holds a consumed COB-ID or decides whether one is used (1005h, 1012h, 100Eh, 1016h,
 * 1200h..12FFh, the PDO parameters 1400h..1BFFh, whose mapping decides validity). Inline, as
 * co_consumers_changed: a few comparisons that its one caller folds in. */
static inline void co_consumers_written(co_node_t *node, uint16_t index)
{
    if (index == CO_IDX_SYNC_COB_ID || index == CO_IDX_TIME_COB_ID ||
        index == CO_IDX_GUARD_COB_ID || index == CO_IDX_HB_CONSUMER ||
        (index >= CO_IDX_SDO_SERVER && index <= CO_IDX_SDO_CLIENT_LAST) ||
        (index >= CO_PDO_RPDO_COMM && index <= CO_PDO_LAST_INDEX))
        co_consumers_changed(node);
}

#endif
