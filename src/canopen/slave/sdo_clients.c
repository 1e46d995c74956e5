/* SPDX-License-Identifier: Apache-2.0 */
/* The SDO client channels 1280h..12FFh of a node: their COB-IDs and the rules of their parameters
 * (CiA 301, "SDO client parameter"), the routing of a response to one of them, their reset and
 * timeouts, and the application's requests on them; the transfers themselves are
 * sdo_client.c's, channel by channel. Reached only through co_sdo_clients_t, which
 * co_sdo_clients_init fills. */
#include "co/co_node.h"
#include "co/co_sdo_clients.h"

#include <string.h>

/* The channel of 1280h + n. */
static uint16_t channel_index(uint8_t n)
{
    return (uint16_t)(CO_IDX_SDO_CLIENT + n);
}

/* A transfer whose channel becomes not valid, or whose node resets its communication, ends at
 * once, reported as the client's abort with 08000022h and without an abort frame: a channel not
 * valid has no COB-ID to send it on, and a reset reloads the COB-IDs it would go on
 * (docs/decisions.md D-SDO-CLIENT-INVALIDATED). */
static void channel_stop(co_sdo_client_channel_t *channel)
{
    co_sdo_client_end(&channel->client, CO_SDO_ABORT_DATA_STATE);
}

/* A channel's COB-IDs as its object holds them; it may run transfers while both are valid (an
 * object the dictionary lacks: never). */
static void channel_load(co_node_t *node, co_sdo_client_channel_t *channel, uint16_t index)
{
    uint32_t request = co_od_param(node, index, CO_SDO_PARAM_RX, CO_COB_ID_INVALID);
    uint32_t response = co_od_param(node, index, CO_SDO_PARAM_TX, CO_COB_ID_INVALID);
    channel->client.request_id = (uint16_t)(request & CO_COB_ID_CAN_ID);
    channel->client.response_id = (uint16_t)(response & CO_COB_ID_CAN_ID);
    channel->valid = !((request | response) & CO_COB_ID_INVALID);
}

static void clients_reset(co_node_t *node)
{
    co_sdo_clients_t *clients = node->sdo_clients;
    clients->node = node;
    for (uint8_t n = 0; n < clients->count; n++) {
        channel_stop(&clients->channels[n]);
        channel_load(node, &clients->channels[n], channel_index(n));
    }
}

/* The first valid channel of the frame's CAN-ID takes it, should two share it (a configuration
 * error). */
static bool clients_receive(co_node_t *node, const co_frame_t *frame)
{
    const co_sdo_clients_t *clients = node->sdo_clients;
    for (uint8_t n = 0; n < clients->count; n++) {
        co_sdo_client_channel_t *channel = &clients->channels[n];
        if (channel->valid && co_sdo_client_receive(&channel->client, frame, node->now)) {
            /* The frame moved the transfer's timeout, or ended it. */
            co_node_reschedule(node);
            return true;
        }
    }
    return false;
}

static co_time_t clients_process(co_node_t *node, co_time_t now)
{
    const co_sdo_clients_t *clients = node->sdo_clients;
    co_time_t next = CO_TIME_NEVER;
    for (uint8_t n = 0; n < clients->count; n++)
        next = co_time_min(next, co_sdo_client_process(&clients->channels[n].client, now));
    return next;
}

/* CiA 301, "SDO client parameter" (1280h..12FFh): bit 31 of a COB-ID is its valid bit (0
 * valid), bit 30 (dynamic allocation) is kept, bit 29 (29-bit CAN-ID) and bits 28..11 are
 * refused, and so are a restricted CAN-ID other than a server's default channel (600h + node-id,
 * 580h + node-id) and a new CAN-ID while the COB-ID is valid before and after (0x06090030,
 * co_sdo_client_cob_id_check, co_cob_id_check's rules for PDO, SYNC, EMCY, TIME and the SDO
 * servers). The server's node-id (sub-index 3) is 1..127. A channel whose COB-ID becomes not
 * valid ends its transfer (channel_stop). An object beyond the node's channels gets the rules
 * without a channel to follow them. */
static uint32_t clients_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len)
{
    if (entry->subindex == CO_SDO_PARAM_NODE_ID)
        return data[0] >= 1 && data[0] <= CO_NODE_ID_MAX ? CO_SDO_OK : CO_SDO_ABORT_VALUE_RANGE;
    if (entry->subindex != CO_SDO_PARAM_RX && entry->subindex != CO_SDO_PARAM_TX)
        return CO_SDO_OK;
    uint32_t abort = co_sdo_client_cob_id_check((uint32_t)co_od_get(node, entry), co_get_u32(data));
    if (abort != CO_SDO_OK)
        return abort;
    co_od_store(node, entry, data, len);
    const co_sdo_clients_t *clients = node->sdo_clients;
    unsigned n = (unsigned)(entry->index - CO_IDX_SDO_CLIENT);
    if (n < clients->count) {
        co_sdo_client_channel_t *channel = &clients->channels[n];
        channel_load(node, channel, entry->index);
        if (!channel->valid)
            channel_stop(channel);
    }
    return CO_OD_HANDLED;
}

/* The client's callbacks: its frames leave through the node, its results go to the channel's
 * application callback. */
static void channel_send(void *user, const co_frame_t *frame)
{
    co_sdo_client_channel_t *channel = user;
    co_node_send(channel->clients->node, frame);
}

static void channel_done(void *user, const co_sdo_client_result_t *result)
{
    co_sdo_client_channel_t *channel = user;
    channel->done(channel->user, result);
}

int co_sdo_clients_init(co_sdo_clients_t *clients, co_sdo_client_channel_t *channels, uint8_t count,
                        co_sdo_client_done_fn done, void *user)
{
    if (channels == NULL || done == NULL || count == 0 || count > CO_CONFIG_SDO_CLIENTS_MAX)
        return -1;
    memset(clients, 0, sizeof(*clients));
    clients->channels = channels;
    clients->count = count;
    clients->receive = clients_receive;
    clients->reset = clients_reset;
    clients->process = clients_process;
    clients->od_write = clients_od_write;
    /* The COB-IDs come from the dictionary at the node's reset; these stand until then. */
    const co_sdo_client_config_t config = {
        .server_node_id = 1, .send = channel_send, .done = channel_done};
    for (uint8_t n = 0; n < count; n++) {
        co_sdo_client_channel_t *channel = &channels[n];
        memset(channel, 0, sizeof(*channel));
        co_sdo_client_init(&channel->client, &config);
        channel->client.user = channel;
        channel->done = done;
        channel->user = user;
        channel->clients = clients;
    }
    return 0;
}

/* The channel a request may start on, or NULL: the node's own, valid, in an NMT state where SDO
 * runs (CiA 301 table 74). */
static co_sdo_client_channel_t *request_channel(co_node_t *node, uint8_t n, int *err)
{
    co_sdo_clients_t *clients = node->sdo_clients;
    if (clients == NULL || n >= clients->count) {
        *err = CO_SDO_CLIENT_ERR_CHANNEL;
        return NULL;
    }
    co_sdo_client_channel_t *channel = &clients->channels[n];
    if (!channel->valid ||
        (node->nmt_state != CO_NMT_PRE_OPERATIONAL && node->nmt_state != CO_NMT_OPERATIONAL)) {
        *err = CO_SDO_CLIENT_ERR_INVALID;
        return NULL;
    }
    return channel;
}

/* A request sent has a timeout, which the node's next process call must see. */
static int requested(co_node_t *node, int err)
{
    if (err == 0)
        co_node_reschedule(node);
    return err;
}

int co_node_sdo_upload(co_node_t *node, uint8_t channel, uint16_t index, uint8_t subindex,
                       uint8_t *buf, uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                       co_time_t now)
{
    int err = 0;
    co_sdo_client_channel_t *c = request_channel(node, channel, &err);
    if (c == NULL)
        return err;
    return requested(
        node, co_sdo_client_upload(&c->client, index, subindex, buf, cap, mode, timeout_ms, now));
}

int co_node_sdo_download(co_node_t *node, uint8_t channel, uint16_t index, uint8_t subindex,
                         const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                         uint32_t timeout_ms, co_time_t now)
{
    int err = 0;
    co_sdo_client_channel_t *c = request_channel(node, channel, &err);
    if (c == NULL)
        return err;
    return requested(node, co_sdo_client_download(&c->client, index, subindex, data, len, mode,
                                                  timeout_ms, now));
}
