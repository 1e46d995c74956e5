/* SPDX-License-Identifier: Apache-2.0 */
/* The COB-IDs a node consumes, read from the services' decoded state (the same fields their
 * receive functions compare a frame with), and the generation number that tells a runtime when
 * to read them again. Named for what it lists, not "consumers": it is none of CiA 301's consumer
 * roles (the SYNC, heartbeat and EMCY consumers); its header keeps the installed name
 * co/co_consumers.h. */
#include "co/co_consumers.h"

typedef struct cob_set {
    co_cob_t *cobs;
    size_t count;
} cob_set_t;

/* Each COB-ID once: two heartbeat consumers of one producer, or an RPDO on the SYNC COB-ID, are
 * still one route. */
static void add(cob_set_t *set, uint32_t can_id, bool rtr)
{
    can_id &= CO_COB_ID_CAN_ID;
    for (size_t i = 0; i < set->count; i++) {
        if (set->cobs[i].can_id == can_id && set->cobs[i].rtr == rtr)
            return;
    }
    set->cobs[set->count++] = (co_cob_t){.can_id = (uint16_t)can_id, .rtr = rtr};
}

static void add_sync(const co_node_t *node, cob_set_t *set)
{
    const co_od_entry_t *e = co_od_find(node->od, CO_IDX_SYNC_COB_ID, 0);
    if (e != NULL)
        add(set, (uint32_t)co_od_get(node, e) & CO_SYNC_COBID_CAN_ID, false);
}

/* TIME, for a node given the service whose 1012h says consume (bit 31). */
static void add_time(const co_node_t *node, cob_set_t *set)
{
    if (node->time_stamp != NULL && (node->time_cob_id & CO_TIME_COBID_CONSUMER))
        add(set, node->time_cob_id, false);
}

static void add_guarding(const co_node_t *node, cob_set_t *set)
{
    const co_od_entry_t *e = co_od_find(node->od, CO_IDX_GUARD_COB_ID, 0);
    add(set, e != NULL ? (uint32_t)co_od_get(node, e) : CO_CAN_ID_ERROR_CONTROL + node->node_id,
        true);
}

/* The default SDO server channel, and the additional ones while valid. */
static void add_sdo_servers(const co_node_t *node, cob_set_t *set)
{
    add(set, node->sdo.rx_id, false);
    const co_sdo_servers_t *servers = node->sdo_servers;
    for (uint8_t n = 0; servers != NULL && n < servers->count; n++) {
        if (servers->channels[n].valid)
            add(set, servers->channels[n].rx_id, false);
    }
}

/* The responses of the node's SDO client channels while valid. */
static void add_sdo_clients(const co_node_t *node, cob_set_t *set)
{
    const co_sdo_clients_t *clients = node->sdo_clients;
    for (uint8_t n = 0; clients != NULL && n < clients->count; n++) {
        if (clients->channels[n].valid)
            add(set, clients->channels[n].client.response_id, false);
    }
}

static void add_pdos(const co_node_t *node, cob_set_t *set)
{
    for (size_t n = 0; n < CO_CONFIG_RPDO_MAX; n++) {
        const co_rpdo_t *r = &node->pdo.rpdo[n];
        if (r->valid)
            add(set, r->can_id, false);
    }
    for (size_t n = 0; n < CO_CONFIG_TPDO_MAX; n++) {
        const co_tpdo_t *t = &node->pdo.tpdo[n];
        if (t->valid && t->rtr_allowed)
            add(set, t->can_id, true);
    }
}

static void add_heartbeats(const co_node_t *node, cob_set_t *set)
{
    for (size_t i = 0; i < CO_CONFIG_HB_CONSUMERS; i++) {
        uint8_t producer = node->heartbeat.consumer[i].node_id;
        if (producer != 0)
            add(set, CO_CAN_ID_ERROR_CONTROL + producer, false);
    }
}

size_t co_node_consumers(const co_node_t *node, co_cob_t *cobs)
{
    cob_set_t set = {.cobs = cobs, .count = 0};
    /* LSS is taken in every NMT state (CiA 305): a node without node-id is in Initialising and
     * consumes 7E5h alone, the frame that can give it one. */
    if (node->lss != NULL)
        add(&set, CO_LSS_ID_MASTER, false);
    if (node->nmt_state == CO_NMT_INITIALISING)
        return set.count;
    add(&set, CO_CAN_ID_NMT, false);
    add_sync(node, &set);
    add_time(node, &set);
    add_sdo_servers(node, &set);
    add_sdo_clients(node, &set);
    add_guarding(node, &set);
    add_pdos(node, &set);
    add_heartbeats(node, &set);
    return set.count;
}

bool co_node_consumes(const co_node_t *node, uint32_t can_id, bool rtr)
{
    co_cob_t cobs[CO_CONSUMERS_MAX];
    size_t count = co_node_consumers(node, cobs);
    for (size_t i = 0; i < count; i++) {
        if (cobs[i].can_id == can_id && cobs[i].rtr == rtr)
            return true;
    }
    return false;
}
