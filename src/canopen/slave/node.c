/* SPDX-License-Identifier: Apache-2.0 */
/* The node, the composition root of the slave services: initialisation, the routing of received
 * frames to the services that the current NMT state allows (CiA 301 table 74), the owner of each
 * communication parameter, the SYNC handed from its service to the PDOs and the application
 * (co_sync_event), and the earliest deadline. The services call one another only downwards; what
 * crosses between them goes through here. */
#include "co/co_consumers.h"
#include "co/co_node.h"

#include <string.h>

/* Every PDO of the dictionary has its place in co_node_t, whose tables a firmware may size to its
 * dictionary (CO_CONFIG_RPDO_MAX, CO_CONFIG_TPDO_MAX): one too many would be a PDO that silently
 * does nothing. (A heartbeat consumer beyond CO_CONFIG_HB_CONSUMERS is refused when it is enabled,
 * 0x06040047, so that a dictionary may offer more than a node monitors.) */
static bool tables_fit(const co_od_t *od)
{
    for (const co_od_entry_t *e = od->entries; e < od->entries + od->count; e++) {
        uint16_t offset = (uint16_t)(e->index - CO_PDO_RPDO_COMM);
        if (offset >= 4 * CO_PDO_INDEX_SPAN)
            continue;
        unsigned max =
            offset >= CO_PDO_TPDO_COMM - CO_PDO_RPDO_COMM ? CO_CONFIG_TPDO_MAX : CO_CONFIG_RPDO_MAX;
        if (offset % CO_PDO_INDEX_SPAN >= max)
            return false;
    }
    return true;
}

/* The service that owns each communication parameter and enforces its CiA 301 rules, by index
 * range. 1200h, the default SDO server channel, has none: CiA 301 makes its COB-IDs read-only,
 * which the dictionary's access type enforces; a dictionary that makes them writable gets the
 * new values at the next reset (co_sdo_reset). The additional channels' 1201h..127Fh have, and
 * so have the client channels' 1280h..12FFh. */
typedef struct service_range {
    uint16_t first;
    uint16_t last;
    uint32_t (*write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data, size_t len);
} service_range_t;

/* 1012h: the TIME service's rules, or, for a node without it, no consumer and no producer
 * (bits 31 and 30 refused: such a node could do neither). */
static uint32_t time_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len)
{
    if (node->time_stamp != NULL)
        return node->time_stamp->od_write(node, entry, data, len);
    return co_get_u32(data) & (CO_TIME_COBID_CONSUMER | CO_TIME_COBID_PRODUCER)
               ? CO_SDO_ABORT_VALUE_RANGE
               : CO_SDO_OK;
}

/* 1029h and 1F80h: their service's rules; a node without the service takes any value, which
 * changes nothing there. */
static uint32_t error_behaviour_write(co_node_t *node, const co_od_entry_t *entry,
                                      const uint8_t *data, size_t len)
{
    if (node->error_behaviour != NULL)
        return node->error_behaviour->od_write(node, entry, data, len);
    return CO_SDO_OK;
}

/* 1201h..127Fh: the additional SDO servers' rules (co_sdo_servers.h); a node given none takes
 * any value, which changes nothing there. */
static uint32_t sdo_servers_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                  size_t len)
{
    if (node->sdo_servers != NULL)
        return node->sdo_servers->od_write(node, entry, data, len);
    return CO_SDO_OK;
}

/* 1280h..12FFh: the SDO client channels' rules (co_sdo_clients.h); a node given none takes any
 * value, which changes nothing there. */
static uint32_t sdo_clients_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                  size_t len)
{
    if (node->sdo_clients != NULL)
        return node->sdo_clients->od_write(node, entry, data, len);
    return CO_SDO_OK;
}

static uint32_t nmt_startup_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                  size_t len)
{
    if (node->nmt_startup != NULL)
        return node->nmt_startup->od_write(node, entry, data, len);
    return CO_SDO_OK;
}

static const service_range_t service_ranges[] = {
    {CO_IDX_ERROR_HISTORY, CO_IDX_ERROR_HISTORY, co_emcy_od_write},
    {CO_IDX_SYNC_COB_ID, CO_IDX_SYNC_WINDOW, co_sync_od_write},
    {CO_IDX_GUARD_TIME, CO_IDX_GUARD_COB_ID, co_guarding_od_write},
    {CO_IDX_STORE, CO_IDX_RESTORE, co_store_od_write},
    {CO_IDX_TIME_COB_ID, CO_IDX_TIME_COB_ID, time_write},
    {CO_IDX_EMCY_COB_ID, CO_IDX_EMCY_INHIBIT, co_emcy_od_write},
    {CO_IDX_HB_CONSUMER, CO_IDX_HB_PRODUCER, co_heartbeat_od_write},
    {CO_IDX_SDO_SERVER + 1u, CO_IDX_SDO_SERVER_LAST, sdo_servers_write},
    {CO_IDX_SDO_CLIENT, CO_IDX_SDO_CLIENT_LAST, sdo_clients_write},
    {CO_IDX_SYNC_OVERFLOW, CO_IDX_SYNC_OVERFLOW, co_sync_od_write},
    {CO_IDX_ERROR_BEHAVIOUR, CO_IDX_ERROR_BEHAVIOUR, error_behaviour_write},
    {CO_PDO_RPDO_COMM, CO_PDO_LAST_INDEX, co_pdo_od_write},
    {CO_IDX_NMT_STARTUP, CO_IDX_NMT_STARTUP, nmt_startup_write},
};

static uint32_t service_write(co_node_t *node, const co_od_entry_t *e, const uint8_t *data,
                              size_t len)
{
    uint16_t i = e->index;
    if (i < CO_IDX_COMM_FIRST || i > CO_IDX_COMM_LAST)
        return CO_SDO_OK;
    /* A communication parameter may move a service's deadline. */
    co_node_reschedule(node);
    for (size_t r = 0; r < sizeof(service_ranges) / sizeof(service_ranges[0]); r++)
        if (i >= service_ranges[r].first && i <= service_ranges[r].last)
            return service_ranges[r].write(node, e, data, len);
    return CO_SDO_OK;
}

/* co_node_t.parameter_write: the owning service's rules, then, once the value is taken, the
 * consumed COB-IDs that it may have changed. */
static uint32_t parameter_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                size_t len)
{
    uint32_t abort = service_write(node, entry, data, len);
    if (abort == CO_SDO_OK || abort == CO_OD_HANDLED)
        co_consumers_written(node, entry->index);
    return abort;
}

int co_node_init(co_node_t *node, const co_node_config_t *config)
{
    bool unconfigured = config->node_id == CO_LSS_NODE_ID_UNCONFIGURED && config->lss != NULL;
    if ((config->node_id < 1 || config->node_id > CO_NODE_ID_MAX) && !unconfigured)
        return CO_NODE_ERR_NODE_ID;
    if (config->od == NULL || config->od_data == NULL || config->send == NULL)
        return CO_NODE_ERR_CONFIG;
    if (config->sdo_buffer != NULL ? config->sdo_buffer->data == NULL : CO_CONFIG_SDO_BUFFER == 0)
        return CO_NODE_ERR_CONFIG;
    if (config->options != 0 && config->options_code == NULL)
        return CO_NODE_ERR_OPTIONS;
    if (config->sdo_servers != NULL && config->sdo_servers->receive == NULL)
        return CO_NODE_ERR_CONFIG; /* not prepared by co_sdo_servers_init */
    if (config->sdo_clients != NULL && config->sdo_clients->receive == NULL)
        return CO_NODE_ERR_CONFIG; /* not prepared by co_sdo_clients_init */
    uint16_t position;
    co_od_error_t err = co_od_validate(config->od, &position);
    if (err != CO_OD_VALID)
        return (int)err;
    if (!tables_fit(config->od))
        return CO_NODE_ERR_TABLES;
    memset(node, 0, sizeof(*node));
    node->node_id = config->node_id;
    node->nmt_state = CO_NMT_INITIALISING;
    node->od = config->od;
    node->od_data = config->od_data;
    node->send = config->send;
    node->user = config->user;
    node->hooks = config->hooks;
    node->storage = config->storage;
    node->options = config->options;
    node->options_code = config->options_code;
    node->lss = config->lss;
    if (node->lss != NULL)
        node->lss->pending_node_id = config->node_id;
    node->time_stamp = config->time_stamp;
    node->error_behaviour = config->error_behaviour;
    node->nmt_startup = config->nmt_startup;
    node->parameter_write = parameter_write;
    node->sync.deliver = co_sync_event;
    node->sdo.timeout_us = CO_CONFIG_SDO_TIMEOUT_US;
    node->pdo.inhibit_ms = config->tpdo_inhibit_ms;
    co_sdo_channel_init(&node->sdo, config->sdo_buffer);
    node->sdo_servers = config->sdo_servers;
    node->sdo_clients = config->sdo_clients;
    co_od_restore_defaults(node, 0x0000, 0xFFFF);
    co_sync_init(node);
    return 0;
}

void co_node_start(co_node_t *node, co_time_t now)
{
    node->now = now;
    co_nmt_reset(node, CO_NMT_RESET_NODE);
}

void co_sync_event(co_node_t *node, uint8_t counter)
{
    co_pdo_sync(node, counter);
    if (node->hooks != NULL && node->hooks->sync != NULL)
        node->hooks->sync(node, counter);
}

void co_node_receive(co_node_t *node, const co_frame_t *frame, co_time_t now)
{
    node->now = now;
    if ((frame->flags & CO_FRAME_EFF) || frame->len > CO_FRAME_DLC_MAX)
        return;
    /* LSS works in every NMT state, Initialising included (CiA 305). */
    /* Its deadlines are looked at by every co_node_process, and the reset that boots a node
     * reschedules by its state change. */
    if (node->lss != NULL && frame->id == CO_LSS_ID_MASTER) {
        node->lss->receive(node, frame);
        return;
    }
    if (node->nmt_state == CO_NMT_INITIALISING)
        return;
    if (co_nmt_receive(node, frame))
        return;
    /* Node guarding and heartbeat consumption work in every state. */
    if (co_guarding_receive(node, frame) || co_heartbeat_receive(node, frame)) {
        co_node_reschedule(node);
        return;
    }
    if (node->nmt_state == CO_NMT_STOPPED)
        return;
    if (co_sync_receive(node, frame))
        return;
    if (node->time_stamp != NULL && node->time_stamp->receive(node, frame))
        return;
    if (co_sdo_receive(node, frame))
        return;
    if (node->nmt_state == CO_NMT_OPERATIONAL)
        co_pdo_receive(node, frame);
}

/* Heartbeat, guarding, SDO, SYNC and EMCY: what they do and their next deadline change only with
 * time, frames and the calls that mark the node changed (co_node_reschedule), so while neither
 * happened a process call looks at none of them. */
static co_time_t (*const services[])(co_node_t *node, co_time_t now) = {
    co_heartbeat_process, co_guarding_process, co_sdo_process, co_sync_process, co_emcy_process,
};

static co_time_t services_process(co_node_t *node, co_time_t now)
{
    if (!node->schedule_changed && now < node->services_due)
        return node->services_due;
    node->schedule_changed = false;
    co_time_t next = CO_TIME_NEVER;
    for (size_t i = 0; i < sizeof(services) / sizeof(services[0]); i++)
        next = co_time_min(next, services[i](node, now));
    node->services_due = next;
    return next;
}

co_time_t co_node_process(co_node_t *node, co_time_t now)
{
    node->now = now;
    co_time_t lss_due = node->lss != NULL ? node->lss->process(node, now) : CO_TIME_NEVER;
    if (node->nmt_state == CO_NMT_INITIALISING)
        return lss_due;
    co_time_t next = co_time_min(lss_due, services_process(node, now));
    /* The PDOs run on every call: the application changes mapped data without telling the core,
     * and an event-driven TPDO compares it here. */
    return co_time_min(next, co_pdo_process(node, now));
}
