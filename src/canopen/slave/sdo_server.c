/* SPDX-License-Identifier: Apache-2.0 */
/* SDO server (CiA 301 section 7.2.4) of the default channel 1200h and of the additional channels
 * 1201h.. a node is given (co_sdo_servers_t), each with its own transfer: expedited, segmented and
 * block transfers. Downloads other than expedited are collected in the transfer buffer and written
 * to the dictionary in one co_od_write() when complete; uploads other than expedited take a
 * snapshot of the value into the buffer at initiate, so the client reads one consistent value. The
 * buffer may be shared by several nodes (co_sdo_buffer_t): a transfer holds it until it goes idle.
 * A streamed DOMAIN (co_od_stream_t) needs no buffer: its segments are read from and written to
 * the application as they go, and its download's end is reported to the application however the
 * transfer ends. The node's SDO client channels (co_sdo_clients_t) are reset, fed and timed from
 * here too, after the servers, so that the node has one SDO entry for each. */
#include "co/co_node.h"

#include <string.h>

static bool in_download(const co_sdo_server_t *sdo)
{
    return sdo->state == CO_SDO_DOWNLOAD_SEGMENT || sdo->state == CO_SDO_BLOCK_DOWNLOAD_SUB ||
           sdo->state == CO_SDO_BLOCK_DOWNLOAD_END;
}

/* Every end of a transfer comes here, so that a shared buffer is never left held and the
 * application hears of every streamed download that did not complete. A stream is set only in a
 * dictionary with streaming code (co_od_t.streaming, od_stream.c). */
void co_sdo_channel_idle(co_node_t *node, co_sdo_server_t *sdo)
{
    const co_od_entry_t *stream = sdo->stream;
    bool download = in_download(sdo);
    sdo->stream = NULL;
    sdo->state = CO_SDO_IDLE;
    if (sdo->buffer->owner == sdo)
        sdo->buffer->owner = NULL;
    if (stream != NULL)
        node->od->streaming->sdo_abandoned(node, sdo, stream, download);
}

/* Reads `len` bytes of the value being uploaded, at `offset`: from the application's stream, or
 * from the snapshot in the buffer. */
static uint32_t value_read(co_node_t *node, co_sdo_server_t *sdo, uint32_t offset, uint8_t *buf,
                           uint32_t len)
{
    if (len == 0)
        return CO_SDO_OK;
    if (sdo->stream != NULL)
        return node->od->streaming->sdo_read(node, sdo, offset, buf, len);
    memcpy(buf, &sdo->buffer->data[offset], len);
    return CO_SDO_OK;
}

/* Takes `len` bytes of a download at `offset`: into the application's stream, or into the buffer
 * while it has room. */
static uint32_t value_write(co_node_t *node, co_sdo_server_t *sdo, uint32_t offset,
                            const uint8_t *data, uint32_t len)
{
    if (len == 0)
        return CO_SDO_OK;
    if (sdo->stream != NULL)
        return node->od->streaming->sdo_write(node, sdo, offset, data, len);
    if (len > sdo->buffer->size || offset > sdo->buffer->size - len)
        return CO_SDO_ABORT_NO_MEMORY;
    memcpy(&sdo->buffer->data[offset], data, len);
    return CO_SDO_OK;
}

/* Takes the transfer buffer for the transfer being initiated, and checks that `size` bytes fit. */
static uint32_t buffer_take(co_sdo_server_t *sdo, uint32_t size)
{
    co_sdo_buffer_t *buffer = sdo->buffer;
    if (buffer->owner != NULL && buffer->owner != sdo)
        return CO_SDO_ABORT_NO_RESOURCE;
    if (size > buffer->size)
        return CO_SDO_ABORT_NO_MEMORY;
    buffer->owner = sdo;
    return CO_SDO_OK;
}

/* The default channel's COB-ID (1200h), CiA 301's base + node-id without it. */
static uint16_t default_cob_id(co_node_t *node, uint8_t subindex, uint16_t base)
{
    return (uint16_t)(co_od_param(node, CO_IDX_SDO_SERVER, subindex, base + node->node_id) &
                      CO_COB_ID_CAN_ID);
}

void co_sdo_reset(co_node_t *node)
{
    co_sdo_server_t *sdo = &node->sdo;
    co_sdo_channel_idle(node, sdo);
    sdo->rx_id = default_cob_id(node, CO_SDO_PARAM_RX, CO_CAN_ID_SDO_RX);
    sdo->tx_id = default_cob_id(node, CO_SDO_PARAM_TX, CO_CAN_ID_SDO_TX);
    if (node->sdo_servers != NULL)
        node->sdo_servers->reset(node);
    if (node->sdo_clients != NULL)
        node->sdo_clients->reset(node);
}

void co_sdo_channel_init(co_sdo_server_t *sdo, co_sdo_buffer_t *buffer)
{
    sdo->buffer = buffer;
#if CO_CONFIG_SDO_BUFFER > 0
    if (buffer == NULL) {
        /* Member by member on the zeroed state: a compound literal copied in would bring its
         * padding from the stack (clang -O0), and the node's bytes would depend on what the
         * stack held (tests/drive/test_init.c). */
        sdo->own.data = sdo->own_data;
        sdo->own.size = CO_CONFIG_SDO_BUFFER;
        sdo->buffer = &sdo->own;
    }
#endif
}

void co_sdo_set_timeout(co_node_t *node, co_time_t timeout_us)
{
    node->sdo.timeout_us = timeout_us;
}

static void send_response(co_node_t *node, co_sdo_server_t *sdo, const uint8_t payload[8])
{
    co_frame_t f = {.id = sdo->tx_id, .len = 8, .flags = 0};
    memcpy(f.data, payload, 8);
    co_node_send(node, &f);
}

/* Responses that echo the multiplexer (index, sub-index) in bytes 1..3. */
static void send_with_mux(co_node_t *node, co_sdo_server_t *sdo, uint8_t command, uint32_t value)
{
    uint8_t p[8] = {command};
    co_put_u16(&p[1], sdo->index);
    p[3] = sdo->subindex;
    co_put_u32(&p[4], value);
    send_response(node, sdo, p);
}

static void transfer_abort(co_node_t *node, co_sdo_server_t *sdo, uint32_t code)
{
    if (node->options & CO_NODE_SDO_ERROR_CLASS)
        code = node->options_code->sdo_abort_code(code);
    send_with_mux(node, sdo, CO_SDO_COMMAND(CO_SDO_CS_ABORT), code);
    co_sdo_channel_idle(node, sdo);
}

/* Ends a transfer with the result of a dictionary access: the response, or the abort code for
 * co_sdo_receive to send. */
static uint32_t finish(co_node_t *node, co_sdo_server_t *sdo, uint32_t abort, uint8_t command,
                       bool with_mux)
{
    if (abort != CO_SDO_OK)
        return abort;
    if (with_mux) {
        send_with_mux(node, sdo, command, 0);
    } else {
        uint8_t p[8] = {command};
        send_response(node, sdo, p);
    }
    co_sdo_channel_idle(node, sdo);
    return CO_SDO_OK;
}

/* Initiate of a segmented or block download: an announced size must be in the frame and fit the
 * buffer, the target must exist and be writable and the buffer must be free before any data is
 * accepted; the remaining checks run in co_od_write once the value is complete. A streamed DOMAIN
 * asks the application instead, which may refuse the announced size. */
static uint32_t download_prepare(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame,
                                 bool size_indicated)
{
    if (size_indicated && frame->len < CO_SDO_INITIATE_SIZE_LEN)
        return CO_SDO_ABORT_COMMAND;
    sdo->size_indicated = size_indicated;
    sdo->size = size_indicated ? co_get_u32(&frame->data[4]) : 0;
    sdo->offset = 0;
    const co_od_entry_t *e;
    uint32_t abort = co_od_lookup(node->od, sdo->index, sdo->subindex, &e);
    if (abort == CO_SDO_OK && !(e->flags & CO_OD_WRITE))
        abort = CO_SDO_ABORT_READ_ONLY;
    if (abort != CO_SDO_OK)
        return abort;
    if (!(e->flags & CO_OD_STREAM))
        return buffer_take(sdo, sdo->size);
    return node->od->streaming->sdo_begin(node, sdo, e);
}

/* Expedited download without size indicated (e = 1, s = 0): the entry's size for fixed types that
 * fit in the frame, otherwise all four bytes. */
static uint32_t unindicated_length(co_node_t *node, co_sdo_server_t *sdo, size_t *len)
{
    const co_od_entry_t *e;
    uint32_t abort = co_od_lookup(node->od, sdo->index, sdo->subindex, &e);
    size_t fixed = abort == CO_SDO_OK ? co_od_type_size(e->type) : 0;
    *len = fixed != 0 && fixed <= CO_SDO_EXPEDITED_BYTES ? fixed : CO_SDO_EXPEDITED_BYTES;
    return abort;
}

/* CO_NODE_SDO_LONG_EXPEDITED: a write longer than its object, the extra bytes 0, is taken. */
static size_t without_zero_extension(co_node_t *node, co_sdo_server_t *sdo, const uint8_t *value,
                                     size_t len)
{
    if (!(node->options & CO_NODE_SDO_LONG_EXPEDITED))
        return len;
    const co_od_entry_t *e = co_od_find(node->od, sdo->index, sdo->subindex);
    return node->options_code->sdo_expedited_length(e, value, len);
}

static uint32_t download_initiate(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    if (command & CO_SDO_EXPEDITED) {
        size_t len = CO_SDO_EXPEDITED_BYTES - ((command >> 2) & 3u);
        uint32_t abort = CO_SDO_OK;
        if (!(command & CO_SDO_SIZE_INDICATED))
            abort = unindicated_length(node, sdo, &len);
        if (abort == CO_SDO_OK && frame->len < CO_SDO_INITIATE_LEN + len)
            abort = CO_SDO_ABORT_COMMAND;
        if (abort == CO_SDO_OK)
            len = without_zero_extension(node, sdo, &frame->data[4], len);
        if (abort == CO_SDO_OK)
            abort = co_od_write(node, sdo->index, sdo->subindex, &frame->data[4], len,
                                CO_OD_ORIGIN_SDO);
        return finish(node, sdo, abort, CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_INITIATE), true);
    }
    uint32_t abort = download_prepare(node, sdo, frame, (command & CO_SDO_SIZE_INDICATED) != 0);
    if (abort != CO_SDO_OK)
        return abort;
    sdo->toggle = 0;
    sdo->state = CO_SDO_DOWNLOAD_SEGMENT;
    send_with_mux(node, sdo, CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_INITIATE), 0);
    return CO_SDO_OK;
}

/* A completed segmented or block download: its length against the announced size, then the write
 * (0x06070010 when the client sent another amount than it announced), or the commit of a streamed
 * value (the application's end, once: the transfer no longer counts as a stream to abort). */
static uint32_t download_complete(co_node_t *node, co_sdo_server_t *sdo)
{
    if (sdo->size_indicated && sdo->offset != sdo->size)
        return CO_SDO_ABORT_TYPE_LENGTH;
    if (sdo->stream != NULL)
        return node->od->streaming->sdo_commit(node, sdo);
    return co_od_write(node, sdo->index, sdo->subindex, sdo->buffer->data, sdo->offset,
                       CO_OD_ORIGIN_SDO);
}

/* Reads the whole value into the buffer; sdo->size is its current length (strings: up to NUL). */
static uint32_t upload_snapshot(co_node_t *node, co_sdo_server_t *sdo, const co_od_entry_t *entry)
{
    size_t len = co_od_length(node, entry);
    uint32_t abort = buffer_take(sdo, len > UINT32_MAX ? UINT32_MAX : (uint32_t)len);
    if (abort != CO_SDO_OK)
        return abort;
    memcpy(sdo->buffer->data, co_od_bytes(node, entry), len);
    sdo->size = (uint32_t)len;
    return CO_SDO_OK;
}

static void upload_expedited(co_node_t *node, co_sdo_server_t *sdo, const uint8_t *value,
                             size_t len)
{
    uint8_t data[CO_SDO_EXPEDITED_BYTES] = {0}; /* the bytes after the value are 0 */
    memcpy(data, value, len);
    send_with_mux(node, sdo,
                  (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE) |
                            ((CO_SDO_EXPEDITED_BYTES - len) << 2) | CO_SDO_EXPEDITED |
                            CO_SDO_SIZE_INDICATED),
                  co_get_u32(data));
    co_sdo_channel_idle(node, sdo);
}

/* The value to upload when it is not sent expedited straight from the dictionary: a streamed
 * DOMAIN's size from the application, or a snapshot in the buffer. */
static uint32_t upload_open(co_node_t *node, co_sdo_server_t *sdo, const co_od_entry_t *entry)
{
    if (!(entry->flags & CO_OD_STREAM))
        return upload_snapshot(node, sdo, entry);
    return node->od->streaming->sdo_open(node, sdo, entry);
}

static bool fits_expedited(uint32_t size)
{
    return size >= 1 && size <= CO_SDO_EXPEDITED_BYTES;
}

/* Expedited when 1..4 bytes, else segmented with the size indicated (an empty string too): a
 * value opened by upload_open. */
static uint32_t upload_response(co_node_t *node, co_sdo_server_t *sdo)
{
    if (fits_expedited(sdo->size)) {
        uint8_t value[CO_SDO_EXPEDITED_BYTES];
        uint32_t abort = value_read(node, sdo, 0, value, sdo->size);
        if (abort == CO_SDO_OK)
            upload_expedited(node, sdo, value, sdo->size);
        return abort;
    }
    sdo->offset = 0;
    sdo->toggle = 0;
    sdo->state = CO_SDO_UPLOAD_SEGMENT;
    send_with_mux(node, sdo, CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE) | CO_SDO_SIZE_INDICATED,
                  sdo->size);
    return CO_SDO_OK;
}

/* A value of 1..4 bytes goes out expedited straight from the dictionary: the buffer, which
 * another node may hold, is needed only for a segmented upload. A streamed DOMAIN's size is known
 * only once it is opened. */
static uint32_t upload_initiate(co_node_t *node, co_sdo_server_t *sdo)
{
    const co_od_entry_t *e;
    uint32_t abort = co_od_read_check(node, sdo->index, sdo->subindex, &e);
    if (abort != CO_SDO_OK)
        return abort;
    bool expedited_only = (node->options & CO_NODE_SDO_EXPEDITED_ONLY) != 0;
    if (!(e->flags & CO_OD_STREAM)) {
        size_t len = co_od_length(node, e);
        if (len >= 1 && len <= CO_SDO_EXPEDITED_BYTES) {
            upload_expedited(node, sdo, co_od_bytes(node, e), len);
            return CO_SDO_OK;
        }
        /* Refused before the snapshot would take the buffer. */
        if (expedited_only)
            return CO_SDO_ABORT_UNSUPPORTED_ACCESS;
    }
    abort = upload_open(node, sdo, e);
    if (abort == CO_SDO_OK && expedited_only && !fits_expedited(sdo->size))
        abort = CO_SDO_ABORT_UNSUPPORTED_ACCESS;
    if (abort != CO_SDO_OK)
        return abort;
    return upload_response(node, sdo);
}

/* A segment of a segmented transfer, either way (CiA 301 7.2.4.3.4, 7.2.4.3.7): the toggle
 * alternates from 0; a download segment's data goes to the value, an upload segment's comes from
 * it, and the last one ends the transfer (a download: with its write). */
static uint32_t transfer_segment(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    uint8_t toggle = command & CO_SDO_TOGGLE;
    if (toggle != sdo->toggle)
        return CO_SDO_ABORT_TOGGLE;
    bool upload = sdo->state == CO_SDO_UPLOAD_SEGMENT;
    uint8_t p[8] = {0};
    uint32_t count;
    bool last;
    uint32_t abort;
    if (upload) {
        count = sdo->size - sdo->offset < CO_SDO_SEGMENT_BYTES ? sdo->size - sdo->offset
                                                               : CO_SDO_SEGMENT_BYTES;
        last = sdo->offset + count == sdo->size;
        p[0] = (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_SEGMENT) | toggle |
                         ((CO_SDO_SEGMENT_BYTES - count) << 1) | (last ? CO_SDO_LAST_SEGMENT : 0));
        abort = value_read(node, sdo, sdo->offset, &p[1], count);
    } else {
        count = CO_SDO_SEGMENT_BYTES - ((command >> 1) & 7u);
        last = (command & CO_SDO_LAST_SEGMENT) != 0;
        if (frame->len < 1 + count)
            return CO_SDO_ABORT_COMMAND;
        p[0] = (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_SEGMENT) | toggle);
        abort = value_write(node, sdo, sdo->offset, &frame->data[1], count);
    }
    if (abort != CO_SDO_OK)
        return abort;
    sdo->offset += count;
    sdo->toggle ^= CO_SDO_TOGGLE;
    if (last && !upload)
        return finish(node, sdo, download_complete(node, sdo), p[0], false);
    send_response(node, sdo, p);
    if (last)
        co_sdo_channel_idle(node, sdo);
    return CO_SDO_OK;
}

/* The server can always compute the CRC, but the CRC is used only when both sides support it, and
 * clients (python-canopen among them) read the server's sc bit as "CRC in use": so sc echoes the
 * client's cc. */
static uint8_t crc_bit(const co_sdo_server_t *sdo)
{
    return sdo->crc ? CO_SDO_BLOCK_CRC : 0;
}

/* The server's block size: up to 127 segments, no more than the buffer can still take (a stream
 * takes whatever comes: the application refuses in its write). */
static uint8_t download_blksize(const co_sdo_server_t *sdo)
{
    if (sdo->stream != NULL)
        return CO_SDO_BLKSIZE_MAX;
    uint32_t capacity = sdo->buffer->size;
    uint32_t room = sdo->offset < capacity ? capacity - sdo->offset : 0;
    uint32_t segments = (room + CO_SDO_SEGMENT_BYTES - 1) / CO_SDO_SEGMENT_BYTES;
    if (segments > CO_SDO_BLKSIZE_MAX)
        segments = CO_SDO_BLKSIZE_MAX;
    return (uint8_t)(segments == 0 ? 1 : segments);
}

static uint32_t block_download_initiate(co_node_t *node, co_sdo_server_t *sdo,
                                        const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    uint32_t abort =
        download_prepare(node, sdo, frame, (command & CO_SDO_BLOCK_SIZE_INDICATED) != 0);
    if (abort != CO_SDO_OK)
        return abort;
    sdo->crc = (command & CO_SDO_BLOCK_CRC) != 0;
    sdo->crc_sum = 0;
    sdo->seqno = 0;
    sdo->block_broken = false;
    sdo->last_in_block = false;
    sdo->blksize = download_blksize(sdo);
    sdo->state = CO_SDO_BLOCK_DOWNLOAD_SUB;
    send_with_mux(node, sdo, (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | crc_bit(sdo)),
                  sdo->blksize);
    return CO_SDO_OK;
}

/* Stores an in-sequence segment, so that the value is written in order, each byte once, and its
 * CRC follows. Returns an abort code, 0 when stored. The final segment is held until the end
 * request tells its unused bytes; only it may be short. */
static uint32_t block_download_store(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame,
                                     bool last)
{
    uint32_t count = (uint32_t)frame->len - 1;
    /* The segment's end, offset + (seqno + 1) * 7 bytes, must be a 32-bit position. */
    if (sdo->offset > UINT32_MAX - (sdo->seqno + 1u) * CO_SDO_SEGMENT_BYTES)
        return CO_SDO_ABORT_NO_MEMORY;
    uint32_t pos = sdo->offset + sdo->seqno * CO_SDO_SEGMENT_BYTES;
    if (last) {
        memcpy(sdo->last_segment, &frame->data[1], count);
        sdo->last_len = (uint8_t)count;
        return CO_SDO_OK;
    }
    if (count < CO_SDO_SEGMENT_BYTES)
        return CO_SDO_ABORT_COMMAND;
    uint32_t abort = value_write(node, sdo, pos, &frame->data[1], CO_SDO_SEGMENT_BYTES);
    if (abort == CO_SDO_OK && sdo->crc)
        sdo->crc_sum = co_sdo_crc16_update(sdo->crc_sum, &frame->data[1], CO_SDO_SEGMENT_BYTES);
    return abort;
}

/* CiA 301, download SDO block segment protocol: after the last segment of a sub-block the server
 * acknowledges the last segment received in sequence; the client resends from the one after it. */
static void block_download_acknowledge(co_node_t *node, co_sdo_server_t *sdo)
{
    uint8_t ackseq = sdo->seqno;
    sdo->offset += (uint32_t)ackseq * CO_SDO_SEGMENT_BYTES;
    sdo->blksize = download_blksize(sdo);
    sdo->seqno = 0;
    sdo->block_broken = false;
    if (sdo->last_in_block)
        sdo->state = CO_SDO_BLOCK_DOWNLOAD_END;
    uint8_t p[8] = {CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_SUB_DOWNLOAD_ACK, ackseq,
                    sdo->blksize};
    send_response(node, sdo, p);
}

static uint32_t block_download_segment(co_node_t *node, co_sdo_server_t *sdo,
                                       const co_frame_t *frame)
{
    uint8_t seqno = frame->data[0] & CO_SDO_BLOCK_SEQNO;
    bool last = (frame->data[0] & CO_SDO_BLOCK_LAST) != 0;
    if (seqno == 0 || seqno > sdo->blksize)
        return CO_SDO_ABORT_SEQUENCE;
    if (sdo->block_broken || seqno != sdo->seqno + 1) {
        sdo->block_broken = true;
    } else {
        uint32_t abort = block_download_store(node, sdo, frame, last);
        if (abort != CO_SDO_OK)
            return abort;
        sdo->seqno = seqno;
        sdo->last_in_block = last;
    }
    if (last || seqno == sdo->blksize)
        block_download_acknowledge(node, sdo);
    return CO_SDO_OK;
}

static uint32_t block_download_end(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t unused = (frame->data[0] >> 2) & 7u;
    if ((sdo->crc && frame->len < CO_SDO_BLOCK_END_CRC_LEN) ||
        CO_SDO_SEGMENT_BYTES - unused > sdo->last_len)
        return CO_SDO_ABORT_COMMAND;
    uint32_t final_len = CO_SDO_SEGMENT_BYTES - unused;
    uint32_t final_pos = sdo->offset - CO_SDO_SEGMENT_BYTES;
    uint32_t abort = value_write(node, sdo, final_pos, sdo->last_segment, final_len);
    if (abort != CO_SDO_OK)
        return abort;
    sdo->offset = final_pos + final_len;
    uint16_t crc = co_sdo_crc16_update(sdo->crc_sum, sdo->last_segment, final_len);
    if (sdo->crc && crc != co_get_u16(&frame->data[1]))
        return CO_SDO_ABORT_CRC;
    return finish(node, sdo, download_complete(node, sdo),
                  CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_SUB_DOWNLOAD_END, false);
}

static uint32_t block_upload_initiate(co_node_t *node, co_sdo_server_t *sdo,
                                      const co_frame_t *frame)
{
    if (frame->len < CO_SDO_BLOCK_UPLOAD_INITIATE_LEN)
        return CO_SDO_ABORT_COMMAND;
    uint8_t blksize = frame->data[4];
    uint8_t pst = frame->len > CO_SDO_BLOCK_UPLOAD_INITIATE_LEN ? frame->data[5] : 0;
    const co_od_entry_t *e;
    uint32_t abort = co_od_read_check(node, sdo->index, sdo->subindex, &e);
    if (abort == CO_SDO_OK)
        abort = upload_open(node, sdo, e);
    if (abort == CO_SDO_OK && (blksize == 0 || blksize > CO_SDO_BLKSIZE_MAX))
        abort = CO_SDO_ABORT_BLOCK_SIZE;
    if (abort != CO_SDO_OK)
        return abort;
    /* CiA 301, initiate SDO block upload protocol: at or below the client's protocol switch
     * threshold the server may answer with the plain upload protocol. */
    if (pst != 0 && sdo->size <= pst)
        return upload_response(node, sdo);
    sdo->crc = (frame->data[0] & CO_SDO_BLOCK_CRC) != 0;
    sdo->crc_sum = 0;
    sdo->blksize = blksize;
    sdo->offset = 0;
    sdo->state = CO_SDO_BLOCK_UPLOAD_START;
    send_with_mux(node, sdo,
                  (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_UPLOAD) | crc_bit(sdo) |
                            CO_SDO_BLOCK_SIZE_INDICATED),
                  sdo->size);
    return CO_SDO_OK;
}

/* Sends up to blksize segments from sdo->offset; the final segment of the value carries c = 1
 * (an empty value is one segment with no data). crc_sent follows what was sent. */
static uint32_t block_upload_send_subblock(co_node_t *node, co_sdo_server_t *sdo)
{
    sdo->last_in_block = false;
    sdo->crc_sent = sdo->crc_sum;
    for (uint8_t seqno = 1; seqno <= sdo->blksize && !sdo->last_in_block; seqno++) {
        uint32_t pos = sdo->offset + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES;
        uint32_t count =
            sdo->size - pos < CO_SDO_SEGMENT_BYTES ? sdo->size - pos : CO_SDO_SEGMENT_BYTES;
        sdo->last_in_block = pos + count == sdo->size;
        uint8_t p[8] = {(uint8_t)(seqno | (sdo->last_in_block ? CO_SDO_BLOCK_LAST : 0))};
        uint32_t abort = value_read(node, sdo, pos, &p[1], count);
        if (abort != CO_SDO_OK)
            return abort;
        if (sdo->crc)
            sdo->crc_sent = co_sdo_crc16_update(sdo->crc_sent, &p[1], count);
        send_response(node, sdo, p);
        sdo->seqno = seqno;
    }
    sdo->state = CO_SDO_BLOCK_UPLOAD_ACK;
    return CO_SDO_OK;
}

/* The CRC up to the client's acknowledge: of everything sent when it got the whole sub-block,
 * else read again over the segments it got (a rare retransmission). */
static uint32_t block_upload_crc_acknowledged(co_node_t *node, co_sdo_server_t *sdo, uint8_t ackseq)
{
    if (!sdo->crc)
        return CO_SDO_OK;
    if (ackseq == sdo->seqno) {
        sdo->crc_sum = sdo->crc_sent;
        return CO_SDO_OK;
    }
    for (uint8_t seqno = 1; seqno <= ackseq; seqno++) {
        uint8_t segment[CO_SDO_SEGMENT_BYTES];
        uint32_t pos = sdo->offset + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES;
        uint32_t abort = value_read(node, sdo, pos, segment, CO_SDO_SEGMENT_BYTES);
        if (abort != CO_SDO_OK)
            return abort;
        sdo->crc_sum = co_sdo_crc16_update(sdo->crc_sum, segment, CO_SDO_SEGMENT_BYTES);
    }
    return CO_SDO_OK;
}

static void block_upload_end(co_node_t *node, co_sdo_server_t *sdo)
{
    uint32_t last_pos = sdo->offset + (uint32_t)(sdo->seqno - 1) * CO_SDO_SEGMENT_BYTES;
    uint32_t unused = CO_SDO_SEGMENT_BYTES - (sdo->size - last_pos);
    uint8_t p[8] = {
        (uint8_t)(CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_UPLOAD) | (unused << 2) | CO_SDO_SUB_UPLOAD_END)};
    if (sdo->crc)
        co_put_u16(&p[1], sdo->crc_sum);
    send_response(node, sdo, p);
    sdo->state = CO_SDO_BLOCK_UPLOAD_END;
}

static uint32_t block_upload_acknowledged(co_node_t *node, co_sdo_server_t *sdo,
                                          const co_frame_t *frame)
{
    if (frame->len < CO_SDO_BLOCK_ACK_LEN)
        return CO_SDO_ABORT_COMMAND;
    uint8_t ackseq = frame->data[1];
    uint8_t blksize = frame->data[2];
    if (ackseq > sdo->seqno)
        return CO_SDO_ABORT_SEQUENCE;
    if (blksize == 0 || blksize > CO_SDO_BLKSIZE_MAX)
        return CO_SDO_ABORT_BLOCK_SIZE;
    uint32_t abort = block_upload_crc_acknowledged(node, sdo, ackseq);
    if (abort != CO_SDO_OK)
        return abort;
    if (ackseq == sdo->seqno && sdo->last_in_block) {
        block_upload_end(node, sdo);
        return CO_SDO_OK;
    }
    sdo->offset += (uint32_t)ackseq * CO_SDO_SEGMENT_BYTES;
    sdo->blksize = blksize;
    return block_upload_send_subblock(node, sdo);
}

static uint32_t block_upload_command(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t cs = frame->data[0] & 3u;
    if (sdo->state == CO_SDO_BLOCK_UPLOAD_START && cs == CO_SDO_SUB_UPLOAD_START)
        return block_upload_send_subblock(node, sdo);
    if (sdo->state == CO_SDO_BLOCK_UPLOAD_ACK && cs == CO_SDO_SUB_UPLOAD_ACK)
        return block_upload_acknowledged(node, sdo, frame);
    if (sdo->state != CO_SDO_BLOCK_UPLOAD_END || cs != CO_SDO_SUB_UPLOAD_END)
        return CO_SDO_ABORT_COMMAND;
    co_sdo_channel_idle(node, sdo);
    return CO_SDO_OK;
}

static bool is_initiate(uint8_t command)
{
    switch (command >> 5) {
    case CO_SDO_CCS_DOWNLOAD_INITIATE:
    case CO_SDO_CCS_UPLOAD_INITIATE:
        return true;
    case CO_SDO_CCS_BLOCK_UPLOAD:
        return (command & 3u) == CO_SDO_SUB_UPLOAD_INITIATE;
    case CO_SDO_CCS_BLOCK_DOWNLOAD:
        return (command & 1u) == CO_SDO_SUB_DOWNLOAD_INITIATE;
    default:
        return false;
    }
}

/* A new request replaces whatever transfer was under way: the client has given up on it, and an
 * abort for the old multiplexer would be taken by the client as the answer to its new request.
 * CO_NODE_SDO_EXPEDITED_ONLY refuses the initiates of segmented and block transfers. */
static uint32_t initiate(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t ccs = frame->data[0] >> 5;
    co_sdo_channel_idle(node, sdo);
    sdo->index = co_get_u16(&frame->data[1]);
    sdo->subindex = frame->data[3];
    if ((node->options & CO_NODE_SDO_EXPEDITED_ONLY) &&
        node->options_code->sdo_refused_initiate(frame->data[0]))
        return CO_SDO_ABORT_COMMAND;
    if (ccs == CO_SDO_CCS_DOWNLOAD_INITIATE)
        return download_initiate(node, sdo, frame);
    if (ccs == CO_SDO_CCS_UPLOAD_INITIATE)
        return upload_initiate(node, sdo);
    if (ccs == CO_SDO_CCS_BLOCK_DOWNLOAD)
        return block_download_initiate(node, sdo, frame);
    return block_upload_initiate(node, sdo, frame);
}

/* A command that does not belong to the current state. Outside a transfer there is no
 * multiplexer to report, except for an unknown specifier shaped like an initiate. */
static uint32_t unexpected_command(co_sdo_server_t *sdo, const co_frame_t *frame)
{
    if (sdo->state == CO_SDO_IDLE) {
        bool has_mux = frame->len >= CO_SDO_INITIATE_LEN && (frame->data[0] >> 5) == 7u;
        sdo->index = has_mux ? co_get_u16(&frame->data[1]) : 0;
        sdo->subindex = has_mux ? frame->data[3] : 0;
    }
    return CO_SDO_ABORT_COMMAND;
}

static bool in_block_upload(const co_sdo_server_t *sdo)
{
    return sdo->state == CO_SDO_BLOCK_UPLOAD_START || sdo->state == CO_SDO_BLOCK_UPLOAD_ACK ||
           sdo->state == CO_SDO_BLOCK_UPLOAD_END;
}

static uint32_t dispatch(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    uint8_t ccs = frame->data[0] >> 5;
    if (sdo->state == CO_SDO_BLOCK_DOWNLOAD_SUB)
        return block_download_segment(node, sdo, frame);
    if (is_initiate(frame->data[0]))
        return initiate(node, sdo, frame);
    if ((sdo->state == CO_SDO_DOWNLOAD_SEGMENT && ccs == CO_SDO_CCS_DOWNLOAD_SEGMENT) ||
        (sdo->state == CO_SDO_UPLOAD_SEGMENT && ccs == CO_SDO_CCS_UPLOAD_SEGMENT))
        return transfer_segment(node, sdo, frame);
    if (sdo->state == CO_SDO_BLOCK_DOWNLOAD_END && ccs == CO_SDO_CCS_BLOCK_DOWNLOAD)
        return block_download_end(node, sdo, frame);
    if (in_block_upload(sdo) && ccs == CO_SDO_CCS_BLOCK_UPLOAD)
        return block_upload_command(node, sdo, frame);
    return unexpected_command(sdo, frame);
}

static void channel_frame(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    if ((frame->flags & CO_FRAME_RTR) || frame->len == 0)
        return;
    uint8_t command = frame->data[0];
    /* 0x80 means abort in every state, and nothing else: inside a block download sub-block it
     * would be segment 0, which does not exist. An abort is unconfirmed, so whatever its DLC the
     * transfer ends silently: the server takes a short frame whenever its meaning is unambiguous
     * (docs/sdo.md, "Short frames"), and it has no use for the multiplexer or the code. */
    if (command == CO_SDO_COMMAND(CO_SDO_CS_ABORT)) {
        co_sdo_channel_idle(node, sdo);
        return;
    }
    /* Without index and sub-index there is nobody to answer an initiate. */
    if (sdo->state != CO_SDO_BLOCK_DOWNLOAD_SUB && is_initiate(command) &&
        frame->len < CO_SDO_INITIATE_LEN)
        return;
    /* Every refusal of every state ends here: one abort path. */
    uint32_t abort = dispatch(node, sdo, frame);
    if (abort != CO_SDO_OK)
        transfer_abort(node, sdo, abort);
    /* The node's timeout, the default channel's, serves every channel. */
    sdo->deadline = node->now + node->sdo.timeout_us;
}

void co_sdo_channel_receive(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame)
{
    bool was_busy = sdo->state != CO_SDO_IDLE;
    channel_frame(node, sdo, frame);
    /* A transfer under way has a timeout, which each of its frames moves; an expedited transfer
     * leaves the channel idle, with none. */
    if (was_busy || sdo->state != CO_SDO_IDLE)
        co_node_reschedule(node);
}

bool co_sdo_receive(co_node_t *node, const co_frame_t *frame)
{
    if (frame->id == node->sdo.rx_id) {
        co_sdo_channel_receive(node, &node->sdo, frame);
        return true;
    }
    if (node->sdo_servers != NULL && node->sdo_servers->receive(node, frame))
        return true;
    return node->sdo_clients != NULL && node->sdo_clients->receive(node, frame);
}

co_time_t co_sdo_channel_process(co_node_t *node, co_sdo_server_t *sdo, co_time_t now)
{
    if (sdo->state == CO_SDO_IDLE)
        return CO_TIME_NEVER;
    if (now >= sdo->deadline) {
        transfer_abort(node, sdo, CO_SDO_ABORT_TIMEOUT);
        return CO_TIME_NEVER;
    }
    return sdo->deadline;
}

co_time_t co_sdo_process(co_node_t *node, co_time_t now)
{
    co_time_t next = co_sdo_channel_process(node, &node->sdo, now);
    if (node->sdo_servers != NULL)
        next = co_time_min(next, node->sdo_servers->process(node, now));
    if (node->sdo_clients != NULL)
        next = co_time_min(next, node->sdo_clients->process(node, now));
    return next;
}
