/* SPDX-License-Identifier: Apache-2.0 */
/* The additional SDO server channels 1201h..: their COB-IDs and the rules of their parameters
 * (CiA 301 7.5.2.34), the routing of a frame to one of them, their reset and timeouts; the
 * transfers themselves are sdo_server.c's, channel by channel. Reached only through
 * co_sdo_servers_t, which co_sdo_servers_init fills. */
#include "co/co_node.h"
#include "co/co_sdo_servers.h"

#include <string.h>

/* The channel of 1201h + n. */
static uint16_t channel_index(uint8_t n)
{
    return (uint16_t)(CO_IDX_SDO_SERVER + 1u + n);
}

/* A channel's COB-IDs as its object holds them; it takes requests while both are valid (an object
 * the dictionary lacks: never). */
static void channel_load(co_node_t *node, co_sdo_server_t *sdo, uint16_t index)
{
    uint32_t rx = co_od_param(node, index, CO_SDO_PARAM_RX, CO_COB_ID_INVALID);
    uint32_t tx = co_od_param(node, index, CO_SDO_PARAM_TX, CO_COB_ID_INVALID);
    sdo->rx_id = (uint16_t)(rx & CO_COB_ID_CAN_ID);
    sdo->tx_id = (uint16_t)(tx & CO_COB_ID_CAN_ID);
    sdo->valid = !((rx | tx) & CO_COB_ID_INVALID);
}

static void servers_reset(co_node_t *node)
{
    const co_sdo_servers_t *servers = node->sdo_servers;
    for (uint8_t n = 0; n < servers->count; n++) {
        co_sdo_channel_idle(node, &servers->channels[n]);
        channel_load(node, &servers->channels[n], channel_index(n));
    }
}

/* The first valid channel of the frame's CAN-ID takes it, should two share it (a configuration
 * error). */
static bool servers_receive(co_node_t *node, const co_frame_t *frame)
{
    const co_sdo_servers_t *servers = node->sdo_servers;
    for (uint8_t n = 0; n < servers->count; n++) {
        co_sdo_server_t *sdo = &servers->channels[n];
        if (sdo->valid && sdo->rx_id == frame->id) {
            co_sdo_channel_receive(node, sdo, frame);
            return true;
        }
    }
    return false;
}

static co_time_t servers_process(co_node_t *node, co_time_t now)
{
    const co_sdo_servers_t *servers = node->sdo_servers;
    co_time_t next = CO_TIME_NEVER;
    for (uint8_t n = 0; n < servers->count; n++)
        next = co_time_min(next, co_sdo_channel_process(node, &servers->channels[n], now));
    return next;
}

/* CiA 301 7.5.2.34, "SDO server parameter" of the additional channels: bit 31 of a COB-ID is its
 * valid bit (0 valid), bit 30 (dynamic allocation) is kept, bit 29 (29-bit CAN-ID) and bits
 * 28..11 are refused, and so are a restricted CAN-ID (7.3.5) and a new CAN-ID while the COB-ID is
 * valid before and after (0x06090030, co_cob_id_check, as for PDO, SYNC, EMCY and TIME). The
 * client's node-id (sub-index 3) is 1..127. A channel whose COB-ID becomes not valid drops its
 * transfer silently: its client is gone with it. An object beyond the node's channels gets the
 * rules without a channel to follow them. */
static uint32_t servers_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len)
{
    if (entry->subindex == CO_SDO_PARAM_NODE_ID)
        return data[0] >= 1 && data[0] <= CO_NODE_ID_MAX ? CO_SDO_OK : CO_SDO_ABORT_VALUE_RANGE;
    if (entry->subindex != CO_SDO_PARAM_RX && entry->subindex != CO_SDO_PARAM_TX)
        return CO_SDO_OK;
    uint32_t abort = co_cob_id_check((uint32_t)co_od_get(node, entry), co_get_u32(data),
                                     CO_COB_ID_INVALID, CO_COB_ID_INVALID);
    if (abort != CO_SDO_OK)
        return abort;
    co_od_store(node, entry, data, len);
    const co_sdo_servers_t *servers = node->sdo_servers;
    unsigned n = (unsigned)(entry->index - CO_IDX_SDO_SERVER) - 1u;
    if (n < servers->count) {
        co_sdo_server_t *sdo = &servers->channels[n];
        channel_load(node, sdo, entry->index);
        if (!sdo->valid)
            co_sdo_channel_idle(node, sdo);
    }
    return CO_OD_HANDLED;
}

int co_sdo_servers_init(co_sdo_servers_t *servers, co_sdo_server_t *channels, uint8_t count,
                        co_sdo_buffer_t *buffer)
{
    if (channels == NULL || count == 0 || count > CO_CONFIG_SDO_SERVERS_MAX ||
        (buffer != NULL ? buffer->data == NULL : CO_CONFIG_SDO_BUFFER == 0))
        return -1;
    memset(servers, 0, sizeof(*servers));
    servers->channels = channels;
    servers->count = count;
    servers->receive = servers_receive;
    servers->reset = servers_reset;
    servers->process = servers_process;
    servers->od_write = servers_od_write;
    for (uint8_t n = 0; n < count; n++) {
        memset(&channels[n], 0, sizeof(channels[n]));
        co_sdo_channel_init(&channels[n], buffer);
    }
    return 0;
}
