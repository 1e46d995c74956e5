/* SPDX-License-Identifier: Apache-2.0 */
/* SDO client (CiA 301 section 7.2.4, client side): expedited, segmented and block upload and
 * download between the application's buffer and one server. Uploads are written straight into
 * the application's buffer, downloads are sent from the application's data, so the client needs
 * no buffer of its own; the block CRC is co_sdo_crc16, shared with the server. */
#include "co/co_sdo_client.h"

#include "co/co_node.h" /* co_sdo_client_config_from_od reads a node's 1280h */

#include <string.h>

#define US_PER_MS 1000u
#define SDO_CLIENT_CHANNELS 128u /* 1280h..12FFh */

/* Client command bytes (ccs in bits 7..5). */

int co_sdo_client_init(co_sdo_client_t *client, const co_sdo_client_config_t *config)
{
    bool default_ids = config->request_id == 0 || config->response_id == 0;
    if (config->send == NULL || config->done == NULL || config->blksize > CO_SDO_BLKSIZE_MAX ||
        config->request_id > CO_COB_ID_CAN_ID || config->response_id > CO_COB_ID_CAN_ID ||
        (default_ids && (config->server_node_id == 0 || config->server_node_id > CO_NODE_ID_MAX)))
        return CO_SDO_CLIENT_ERR_CONFIG;
    memset(client, 0, sizeof(*client));
    client->request_id = config->request_id != 0
                             ? config->request_id
                             : (uint16_t)(CO_CAN_ID_SDO_RX + config->server_node_id);
    client->response_id = config->response_id != 0
                              ? config->response_id
                              : (uint16_t)(CO_CAN_ID_SDO_TX + config->server_node_id);
    client->send = config->send;
    client->user = config->user;
    client->done = config->done;
    client->upload_blksize = config->blksize != 0 ? config->blksize : CO_SDO_BLKSIZE_MAX;
    client->pst = config->pst;
    return 0;
}

int co_sdo_client_config_from_od(co_sdo_client_config_t *config, const co_node_t *node,
                                 uint8_t channel)
{
    uint16_t index = (uint16_t)(CO_IDX_SDO_CLIENT + channel);
    const co_od_entry_t *request = co_od_find(node->od, index, 1);
    const co_od_entry_t *response = co_od_find(node->od, index, 2);
    const co_od_entry_t *server = co_od_find(node->od, index, 3);
    if (channel >= SDO_CLIENT_CHANNELS || request == NULL || response == NULL || server == NULL)
        return CO_SDO_CLIENT_ERR_NO_OBJECT;
    uint32_t request_cob = (uint32_t)co_od_get(node, request);
    uint32_t response_cob = (uint32_t)co_od_get(node, response);
    if ((request_cob | response_cob) & CO_COB_ID_INVALID)
        return CO_SDO_CLIENT_ERR_INVALID;
    config->request_id = (uint16_t)(request_cob & CO_COB_ID_CAN_ID);
    config->response_id = (uint16_t)(response_cob & CO_COB_ID_CAN_ID);
    config->server_node_id = (uint8_t)co_od_get(node, server);
    return 0;
}

bool co_sdo_client_busy(const co_sdo_client_t *client)
{
    return client->state != CO_SDO_CLIENT_IDLE;
}

/* Every SDO frame is 8 bytes; unused bytes are 0. */
static void send_request(co_sdo_client_t *client, const uint8_t payload[8])
{
    co_frame_t f = {.id = client->request_id, .len = 8, .flags = 0};
    memcpy(f.data, payload, 8);
    client->send(client->user, &f);
}

static void send_with_mux(co_sdo_client_t *client, uint8_t command, uint32_t value)
{
    uint8_t p[8] = {command};
    co_put_u16(&p[1], client->index);
    p[3] = client->subindex;
    co_put_u32(&p[4], value);
    send_request(client, p);
}

static void send_command(co_sdo_client_t *client, uint8_t command)
{
    uint8_t p[8] = {command};
    send_request(client, p);
}

/* Ends the transfer; the client is idle before the callback runs, so it may start another. */
static void finish(co_sdo_client_t *client, co_sdo_client_status_t status, uint32_t abort_code)
{
    co_sdo_client_result_t result = {
        .status = status,
        .abort_code = abort_code,
        .size = status == CO_SDO_CLIENT_OK ? client->offset : 0,
        .index = client->index,
        .subindex = client->subindex,
    };
    client->state = CO_SDO_CLIENT_IDLE;
    client->done(client->user, &result);
}

/* The client's own abort: CiA 301 has the abort frame sent to the server in every case. */
static void client_abort(co_sdo_client_t *client, uint32_t code)
{
    send_with_mux(client, CO_SDO_COMMAND(CO_SDO_CS_ABORT), code);
    finish(client, CO_SDO_CLIENT_CLIENT_ABORT, code);
}

static int start(co_sdo_client_t *client, uint16_t index, uint8_t subindex, uint32_t timeout_ms,
                 co_time_t now)
{
    if (client->state != CO_SDO_CLIENT_IDLE)
        return CO_SDO_CLIENT_ERR_BUSY;
    if (timeout_ms == 0)
        return CO_SDO_CLIENT_ERR_ARG;
    client->index = index;
    client->subindex = subindex;
    client->timeout_us = (co_time_t)timeout_ms * US_PER_MS;
    client->deadline = now + client->timeout_us;
    client->offset = 0;
    client->toggle = 0;
    client->seqno = 0;
    client->size_indicated = false;
    client->last_in_block = false;
    return 0;
}

static bool mode_valid(co_sdo_client_mode_t mode)
{
    return mode == CO_SDO_CLIENT_AUTO || mode == CO_SDO_CLIENT_SEGMENTED ||
           mode == CO_SDO_CLIENT_BLOCK;
}

int co_sdo_client_upload(co_sdo_client_t *client, uint16_t index, uint8_t subindex, uint8_t *buf,
                         uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                         co_time_t now)
{
    if (!mode_valid(mode) || (buf == NULL && cap != 0))
        return CO_SDO_CLIENT_ERR_ARG;
    int err = start(client, index, subindex, timeout_ms, now);
    if (err != 0)
        return err;
    client->rx_data = buf;
    client->capacity = cap;
    bool block = mode == CO_SDO_CLIENT_BLOCK ||
                 (mode == CO_SDO_CLIENT_AUTO && client->pst != 0 && cap > client->pst);
    if (!block) {
        client->state = CO_SDO_CLIENT_UPLOAD_INITIATE;
        send_with_mux(client, CO_SDO_COMMAND(CO_SDO_CCS_UPLOAD_INITIATE), 0);
        return 0;
    }
    uint8_t pst = mode == CO_SDO_CLIENT_BLOCK ? 0 : client->pst;
    client->state = CO_SDO_CLIENT_BLOCK_UPLOAD_INITIATE;
    send_with_mux(client,
                  CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLOCK_CRC |
                      CO_SDO_SUB_UPLOAD_INITIATE,
                  (uint32_t)client->upload_blksize | (uint32_t)pst << 8);
    return 0;
}

int co_sdo_client_download(co_sdo_client_t *client, uint16_t index, uint8_t subindex,
                           const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                           uint32_t timeout_ms, co_time_t now)
{
    if (!mode_valid(mode) || (data == NULL && len != 0))
        return CO_SDO_CLIENT_ERR_ARG;
    int err = start(client, index, subindex, timeout_ms, now);
    if (err != 0)
        return err;
    client->tx_data = data;
    client->size = len;
    bool expedited = mode == CO_SDO_CLIENT_AUTO && len >= 1 && len <= CO_SDO_EXPEDITED_BYTES;
    bool block = mode == CO_SDO_CLIENT_BLOCK ||
                 (mode == CO_SDO_CLIENT_AUTO && client->pst != 0 && len > client->pst);
    if (expedited) {
        uint8_t p[8] = {(uint8_t)(CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_INITIATE) |
                                  (CO_SDO_EXPEDITED_BYTES - len) << 2 | CO_SDO_EXPEDITED |
                                  CO_SDO_SIZE_INDICATED)};
        co_put_u16(&p[1], index);
        p[3] = subindex;
        memcpy(&p[4], data, len);
        client->state = CO_SDO_CLIENT_DOWNLOAD_EXPEDITED;
        send_request(client, p);
    } else if (block) {
        client->state = CO_SDO_CLIENT_BLOCK_DOWNLOAD_INITIATE;
        send_with_mux(client,
                      CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_DOWNLOAD) | CO_SDO_BLOCK_CRC |
                          CO_SDO_BLOCK_SIZE_INDICATED | CO_SDO_SUB_DOWNLOAD_INITIATE,
                      len);
    } else {
        client->state = CO_SDO_CLIENT_DOWNLOAD_INITIATE;
        send_with_mux(client, CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_INITIATE) | CO_SDO_SIZE_INDICATED,
                      len);
    }
    return 0;
}

/* An initiate response must answer the request's index and sub-index. */
static bool mux_matches(const co_sdo_client_t *client, const co_frame_t *frame)
{
    return frame->len >= CO_SDO_INITIATE_LEN && co_get_u16(&frame->data[1]) == client->index &&
           frame->data[3] == client->subindex;
}

/* Sends the segment at client->offset: up to 7 bytes, c = 1 on the final one (an empty value is
 * one segment without data). */
static void download_send_segment(co_sdo_client_t *client)
{
    uint32_t count = client->size - client->offset;
    if (count > CO_SDO_SEGMENT_BYTES)
        count = CO_SDO_SEGMENT_BYTES;
    bool last = client->offset + count == client->size;
    uint8_t p[8] = {(uint8_t)(CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_SEGMENT) | client->toggle |
                              (CO_SDO_SEGMENT_BYTES - count) << 1 |
                              (last ? CO_SDO_LAST_SEGMENT : 0))};
    if (count > 0)
        memcpy(&p[1], &client->tx_data[client->offset], count);
    send_request(client, p);
    client->state = CO_SDO_CLIENT_DOWNLOAD_SEGMENT;
}

static void download_initiated(co_sdo_client_t *client, const co_frame_t *frame)
{
    if (frame->data[0] != CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_INITIATE) ||
        !mux_matches(client, frame)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    if (client->state == CO_SDO_CLIENT_DOWNLOAD_EXPEDITED) {
        client->offset = client->size;
        finish(client, CO_SDO_CLIENT_OK, 0);
        return;
    }
    download_send_segment(client);
}

/* A server's segment answer must carry the expected command and the toggle of the request it
 * answers; otherwise the client aborts with the code CiA 301 gives (false). */
static bool segment_answer_valid(co_sdo_client_t *client, uint8_t command, uint8_t scs)
{
    if ((command & CO_SDO_CS_MASK) != scs) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return false;
    }
    if ((command & CO_SDO_TOGGLE) != client->toggle) {
        client_abort(client, CO_SDO_ABORT_TOGGLE);
        return false;
    }
    return true;
}

static void download_segment_confirmed(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if (!segment_answer_valid(client, command, CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_SEGMENT)))
        return;
    uint32_t count = client->size - client->offset;
    client->offset += count > CO_SDO_SEGMENT_BYTES ? CO_SDO_SEGMENT_BYTES : count;
    if (client->offset == client->size) {
        finish(client, CO_SDO_CLIENT_OK, 0);
        return;
    }
    client->toggle ^= CO_SDO_TOGGLE;
    download_send_segment(client);
}

/* Stores uploaded bytes at `pos` of the application's buffer; 0x05040005 when they do not fit. */
static uint32_t upload_store(co_sdo_client_t *client, uint32_t pos, const uint8_t *data,
                             uint32_t count)
{
    if (pos > client->capacity || count > client->capacity - pos)
        return CO_SDO_ABORT_NO_MEMORY;
    if (count > 0)
        memcpy(&client->rx_data[pos], data, count);
    return CO_SDO_OK;
}

/* The answer to an upload initiate (also to a block upload initiate that the server switched to
 * the plain protocol below pst): expedited data, or the start of a segmented upload. */
static void upload_initiated(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if ((command & CO_SDO_CS_MASK) != CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE) ||
        !mux_matches(client, frame)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    bool size_indicated = (command & CO_SDO_SIZE_INDICATED) != 0;
    if (command & CO_SDO_EXPEDITED) {
        uint32_t count = size_indicated ? CO_SDO_EXPEDITED_BYTES - ((command >> 2) & 3u)
                                        : CO_SDO_EXPEDITED_BYTES;
        uint32_t abort = frame->len < CO_SDO_INITIATE_LEN + count
                             ? CO_SDO_ABORT_COMMAND
                             : upload_store(client, 0, &frame->data[4], count);
        if (abort != CO_SDO_OK) {
            client_abort(client, abort);
            return;
        }
        client->offset = count;
        finish(client, CO_SDO_CLIENT_OK, 0);
        return;
    }
    if (size_indicated && frame->len < CO_SDO_INITIATE_SIZE_LEN) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    client->size_indicated = size_indicated;
    client->size = size_indicated ? co_get_u32(&frame->data[4]) : 0;
    if (size_indicated && client->size > client->capacity) {
        client_abort(client, CO_SDO_ABORT_NO_MEMORY);
        return;
    }
    client->state = CO_SDO_CLIENT_UPLOAD_SEGMENT;
    send_command(client, CO_SDO_COMMAND(CO_SDO_CCS_UPLOAD_SEGMENT) | client->toggle);
}

static void upload_segment(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if (!segment_answer_valid(client, command, CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_SEGMENT)))
        return;
    uint32_t count = CO_SDO_SEGMENT_BYTES - ((command >> 1) & 7u);
    uint32_t abort = frame->len < 1 + count
                         ? CO_SDO_ABORT_COMMAND
                         : upload_store(client, client->offset, &frame->data[1], count);
    if (abort != CO_SDO_OK) {
        client_abort(client, abort);
        return;
    }
    client->offset += count;
    bool last = (command & CO_SDO_LAST_SEGMENT) != 0;
    if (client->size_indicated &&
        (client->offset > client->size || (last && client->offset != client->size))) {
        client_abort(client, CO_SDO_ABORT_TYPE_LENGTH);
        return;
    }
    if (last) {
        finish(client, CO_SDO_CLIENT_OK, 0);
        return;
    }
    client->toggle ^= CO_SDO_TOGGLE;
    send_command(client, CO_SDO_COMMAND(CO_SDO_CCS_UPLOAD_SEGMENT) | client->toggle);
}

/* Sends up to blksize segments from client->offset, numbered from 1; the final segment of the
 * data carries c = 1. A retransmission after a partial acknowledge comes through here too. */
static void block_download_send_subblock(co_sdo_client_t *client)
{
    client->last_in_block = false;
    client->seqno = 0;
    for (uint8_t seqno = 1; seqno <= client->blksize && !client->last_in_block; seqno++) {
        uint32_t pos = client->offset + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES;
        uint32_t count =
            client->size - pos < CO_SDO_SEGMENT_BYTES ? client->size - pos : CO_SDO_SEGMENT_BYTES;
        client->last_in_block = pos + count == client->size;
        uint8_t p[8] = {(uint8_t)(seqno | (client->last_in_block ? CO_SDO_BLOCK_LAST : 0))};
        if (count > 0)
            memcpy(&p[1], &client->tx_data[pos], count);
        send_request(client, p);
        client->seqno = seqno;
    }
    client->state = CO_SDO_CLIENT_BLOCK_DOWNLOAD_ACK;
}

/* The server's block size (initiate response and every acknowledge): 1..127. */
static bool blksize_valid(uint8_t blksize)
{
    return blksize >= 1 && blksize <= CO_SDO_BLKSIZE_MAX;
}

static void block_download_initiated(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if ((command & ~CO_SDO_BLOCK_CRC) != CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) ||
        frame->len < 5 || !mux_matches(client, frame)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    if (!blksize_valid(frame->data[4])) {
        client_abort(client, CO_SDO_ABORT_BLOCK_SIZE);
        return;
    }
    client->crc = (command & CO_SDO_BLOCK_CRC) != 0;
    client->blksize = frame->data[4];
    block_download_send_subblock(client);
}

/* CiA 301 download SDO block end: n is the number of bytes of the final segment without data. */
static void block_download_send_end(co_sdo_client_t *client)
{
    uint32_t last_pos = client->offset - CO_SDO_SEGMENT_BYTES;
    uint32_t unused = CO_SDO_SEGMENT_BYTES - (client->size - last_pos);
    uint8_t p[8] = {(uint8_t)(CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_DOWNLOAD) | unused << 2 |
                              CO_SDO_SUB_DOWNLOAD_END)};
    if (client->crc)
        co_put_u16(&p[1], co_sdo_crc16(client->tx_data, client->size));
    send_request(client, p);
    client->offset = client->size;
    client->state = CO_SDO_CLIENT_BLOCK_DOWNLOAD_END;
}

/* The sub-block acknowledge: ackseq is the last segment the server received in sequence; the
 * client goes on (or resends) from the segment after it with the server's new block size. */
static void block_download_acknowledged(co_sdo_client_t *client, const co_frame_t *frame)
{
    if (frame->data[0] != (CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_SUB_DOWNLOAD_ACK) ||
        frame->len < CO_SDO_BLOCK_ACK_LEN) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    uint8_t ackseq = frame->data[1];
    uint8_t blksize = frame->data[2];
    if (ackseq > client->seqno) {
        client_abort(client, CO_SDO_ABORT_SEQUENCE);
        return;
    }
    if (!blksize_valid(blksize)) {
        client_abort(client, CO_SDO_ABORT_BLOCK_SIZE);
        return;
    }
    client->offset += (uint32_t)ackseq * CO_SDO_SEGMENT_BYTES;
    client->blksize = blksize;
    if (ackseq == client->seqno && client->last_in_block)
        block_download_send_end(client);
    else
        block_download_send_subblock(client);
}

static void block_download_ended(co_sdo_client_t *client, const co_frame_t *frame)
{
    if (frame->data[0] != (CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_SUB_DOWNLOAD_END)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    finish(client, CO_SDO_CLIENT_OK, 0);
}

static void block_upload_initiated(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if ((command & CO_SDO_CS_MASK) == CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE)) {
        upload_initiated(client, frame);
        return;
    }
    if ((command & ~(CO_SDO_BLOCK_CRC | CO_SDO_BLOCK_SIZE_INDICATED)) !=
            CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_UPLOAD) ||
        !mux_matches(client, frame)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    bool size_indicated = (command & CO_SDO_BLOCK_SIZE_INDICATED) != 0;
    if (size_indicated && frame->len < CO_SDO_INITIATE_SIZE_LEN) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    client->size_indicated = size_indicated;
    client->size = size_indicated ? co_get_u32(&frame->data[4]) : 0;
    if (size_indicated && client->size > client->capacity) {
        client_abort(client, CO_SDO_ABORT_NO_MEMORY);
        return;
    }
    client->crc = (command & CO_SDO_BLOCK_CRC) != 0;
    client->blksize = client->upload_blksize;
    client->state = CO_SDO_CLIENT_BLOCK_UPLOAD_SUB;
    send_command(client, CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_START);
}

/* Acknowledges the sub-block with the last segment received in sequence; the server resends
 * from the one after it. */
static void block_upload_acknowledge(co_sdo_client_t *client)
{
    uint8_t p[8] = {CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_ACK, client->seqno,
                    client->upload_blksize};
    send_request(client, p);
    client->offset += (uint32_t)client->seqno * CO_SDO_SEGMENT_BYTES;
    client->seqno = 0;
    client->blksize = client->upload_blksize;
    client->state =
        client->last_in_block ? CO_SDO_CLIENT_BLOCK_UPLOAD_END : CO_SDO_CLIENT_BLOCK_UPLOAD_SUB;
}

/* A segment of a sub-block. Only the one after the last good segment is stored: a repeated one is
 * ignored, and after a lost one the rest of the sub-block is dropped; the acknowledge at the end of
 * the sub-block (seqno = blksize, or c = 1) carries the last good seqno, and the server resends
 * from the segment after it. */
static void block_upload_segment(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t seqno = frame->data[0] & CO_SDO_BLOCK_SEQNO;
    bool last = (frame->data[0] & CO_SDO_BLOCK_LAST) != 0;
    if (seqno == 0 || seqno > client->blksize) {
        client_abort(client, CO_SDO_ABORT_SEQUENCE);
        return;
    }
    if (seqno == client->seqno + 1) {
        uint32_t pos = client->offset + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES;
        /* Only the final segment may hold fewer than 7 data bytes, which the end frame's n tells:
         * until then its padding is stored only as far as the buffer goes. */
        uint32_t count = CO_SDO_SEGMENT_BYTES;
        if (last && pos + count > client->capacity)
            count = pos < client->capacity ? client->capacity - pos : 0;
        uint32_t abort = frame->len < 1 + CO_SDO_SEGMENT_BYTES && !last
                             ? CO_SDO_ABORT_COMMAND
                             : upload_store(client, pos, &frame->data[1], count);
        if (abort != CO_SDO_OK) {
            client_abort(client, abort);
            return;
        }
        client->seqno = seqno;
        client->last_in_block = last;
    }
    if (last || seqno == client->blksize)
        block_upload_acknowledge(client);
}

/* The server's end: n unused bytes in the final segment, and the CRC of the whole value. */
static void block_upload_ended(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if ((command & ~(7u << 2)) !=
            (CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_END) ||
        (client->crc && frame->len < CO_SDO_BLOCK_END_CRC_LEN)) {
        client_abort(client, CO_SDO_ABORT_COMMAND);
        return;
    }
    uint32_t unused = (command >> 2) & 7u;
    client->offset -= unused;
    uint32_t abort = CO_SDO_OK;
    if (client->offset > client->capacity)
        abort = CO_SDO_ABORT_NO_MEMORY;
    else if (client->size_indicated && client->offset != client->size)
        abort = CO_SDO_ABORT_TYPE_LENGTH;
    else if (client->crc &&
             co_sdo_crc16(client->rx_data, client->offset) != co_get_u16(&frame->data[1]))
        abort = CO_SDO_ABORT_CRC;
    if (abort != CO_SDO_OK) {
        client_abort(client, abort);
        return;
    }
    send_command(client, CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_END);
    finish(client, CO_SDO_CLIENT_OK, 0);
}

static void dispatch(co_sdo_client_t *client, const co_frame_t *frame)
{
    switch (client->state) {
    case CO_SDO_CLIENT_DOWNLOAD_EXPEDITED:
    case CO_SDO_CLIENT_DOWNLOAD_INITIATE:
        download_initiated(client, frame);
        break;
    case CO_SDO_CLIENT_DOWNLOAD_SEGMENT:
        download_segment_confirmed(client, frame);
        break;
    case CO_SDO_CLIENT_UPLOAD_INITIATE:
        upload_initiated(client, frame);
        break;
    case CO_SDO_CLIENT_UPLOAD_SEGMENT:
        upload_segment(client, frame);
        break;
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_INITIATE:
        block_download_initiated(client, frame);
        break;
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_ACK:
        block_download_acknowledged(client, frame);
        break;
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_END:
        block_download_ended(client, frame);
        break;
    case CO_SDO_CLIENT_BLOCK_UPLOAD_INITIATE:
        block_upload_initiated(client, frame);
        break;
    case CO_SDO_CLIENT_BLOCK_UPLOAD_SUB:
        block_upload_segment(client, frame);
        break;
    default:
        block_upload_ended(client, frame);
        break;
    }
}

/* The server's abort ends the transfer whatever its state. One shorter than 8 bytes carries no
 * code, and one carrying 0 none that CiA 301 (table 22) defines, 0 being the result's "OK": both
 * are reported as a general error. */
static void server_abort(co_sdo_client_t *client, const co_frame_t *frame)
{
    uint32_t code = frame->len >= 8 ? co_get_u32(&frame->data[4]) : CO_SDO_OK;
    finish(client, CO_SDO_CLIENT_SERVER_ABORT, code != CO_SDO_OK ? code : CO_SDO_ABORT_GENERAL);
}

bool co_sdo_client_receive(co_sdo_client_t *client, const co_frame_t *frame, co_time_t now)
{
    if (frame->id != client->response_id || (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF)))
        return false;
    if (client->state == CO_SDO_CLIENT_IDLE || frame->len == 0)
        return true;
    client->deadline = now + client->timeout_us;
    if (frame->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT))
        server_abort(client, frame);
    else
        dispatch(client, frame);
    return true;
}

void co_sdo_client_cancel(co_sdo_client_t *client)
{
    client->state = CO_SDO_CLIENT_IDLE;
}

void co_sdo_client_end(co_sdo_client_t *client, uint32_t code)
{
    if (client->state != CO_SDO_CLIENT_IDLE)
        finish(client, CO_SDO_CLIENT_CLIENT_ABORT, code);
}

co_time_t co_sdo_client_process(co_sdo_client_t *client, co_time_t now)
{
    if (client->state == CO_SDO_CLIENT_IDLE)
        return CO_TIME_NEVER;
    if (now >= client->deadline) {
        client_abort(client, CO_SDO_ABORT_TIMEOUT);
        return client->state == CO_SDO_CLIENT_IDLE ? CO_TIME_NEVER : client->deadline;
    }
    return client->deadline;
}
