/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the SDO client (src/canopen/master/sdo_client.c): a client of server 5
 * (requests on 605h, answers on 585h) runs the transfers the input asks for, and the input plays
 * the server: its frames and time steps (steps.h) are the server's answers, right or wrong. The
 * harness follows each transfer the way a server would see it, from the frames the client sends,
 * and holds the client to what CiA 301 and co_sdo_client.h promise (docs/fuzzing.md). Input: a
 * header of 3 bytes, then steps:
 *
 *     header:     the client's blksize for block uploads (above 127 init refuses it; the run goes
 *                 on with it mod 128), its pst, flags (bit 0: the done callback starts the same
 *                 transfer again, at most CHAIN_MAX times in a row)
 *     E0h..EFh:   a request: bit 0 upload (else download), bits 1-2 the mode (3 is no mode),
 *                 bit 3 a NULL buffer; then index (u16 LE), sub-index, size (u16 LE, mod 4096:
 *                 the download's length or the upload's buffer) and the timeout in ms (0, which
 *                 the client refuses, or 1..255)
 *
 * fuzz/seeds.py writes the seeds from readable requests and candump frames. */
#include "co/co_sdo_client.h"
#include "rig.h"
#include "steps.h"

#include <stdlib.h>
#include <string.h>

#define SERVER_NODE_ID 5
#define REQUEST_ID (CO_CAN_ID_SDO_RX + SERVER_NODE_ID)
#define RESPONSE_ID (CO_CAN_ID_SDO_TX + SERVER_NODE_ID)
#define HEADER_SIZE 3
#define FLAG_CHAIN 0x01u
#define CHAIN_MAX 4u
#define REQUEST_ARGS 6
#define REQUEST_UPLOAD 0x01u
#define REQUEST_NULL_BUFFER 0x08u
#define SIZE_MASK 0x0FFFu
#define US_PER_MS 1000u
/* As in rig.c: deadlines handled one by one within a time step, then the rig wakes up late. */
#define DEADLINES_PER_STEP 64

typedef struct request {
    bool upload;
    co_sdo_client_mode_t mode;
    bool null_buffer;
    uint16_t index;
    uint8_t subindex;
    uint32_t size;
    uint32_t timeout_ms;
} request_t;

/* Where the transfer is, as the server sees it. */
typedef enum phase {
    PHASE_INITIATE,    /* the initiate request was sent, its answer not yet delivered */
    PHASE_SEGMENTS,    /* segmented (or, for a download, expedited): segment after segment */
    PHASE_BLOCK_START, /* block upload: the client's start command is next */
    PHASE_BLOCK_SUB,   /* block: sub-blocks */
    PHASE_BLOCK_END    /* block: the end request (download) or the end (upload) was sent */
} phase_t;

/* What one call of the client (a request, a frame delivered, a process) did. */
typedef struct call {
    const co_frame_t *answer; /* the server's frame delivered, NULL for a request or process */
    size_t frames;            /* frames sent, those of a transfer its done callback starts aside */
    bool abort_sent;
    uint32_t abort_code;
    bool ack_sent; /* block upload: an acknowledge */
} call_t;

/* The transfer under way, as the server sees it. */
typedef struct transfer {
    request_t request;
    uint8_t *buffer;    /* the download's data or the upload's buffer, exactly its size */
    co_time_t deadline; /* its start or the server's last answer, plus the timeout */
    phase_t phase;
    bool initiated;    /* the initiate request was sent */
    bool block;        /* the client chose the block protocol */
    bool crc;          /* block: the server answered with the CRC bit */
    uint8_t blksize;   /* block download: the server's block size */
    uint32_t base;     /* block: where the current sub-block starts */
    uint8_t seqno;     /* block download: the last segment sent; upload: the last one in order */
    bool last_in_sub;  /* block upload: the final segment came in order */
    uint32_t sent;     /* download: the bytes sent so far */
    bool sent_last;    /* download: the segment with c (or the expedited initiate) was sent */
    bool size_given;   /* upload: the server indicated the size */
    uint32_t size;     /* upload: that size */
    uint32_t received; /* upload: the bytes the server sent, kept in `model` */
    uint8_t toggle;    /* segmented: the toggle bit of the next segment */
} transfer_t;

static struct harness {
    co_sdo_client_t client;
    co_time_t now;
    bool chain;
    unsigned chained;
    uint8_t upload_blksize; /* the client's */
    uint8_t pst;
    bool pending;       /* a transfer is under way */
    unsigned started;   /* transfers started: one a done callback starts is another */
    unsigned succeeded; /* transfers that ended with success */
    transfer_t t;
    uint8_t model[SIZE_MASK + 1]; /* upload: the value the server sent, as far as the buffer goes */
    call_t call;
} h;

static uint8_t pattern(uint32_t i)
{
    return (uint8_t)(i * 31u + 7u);
}

static bool mux_is_request(const uint8_t *data)
{
    return co_get_u16(&data[1]) == h.t.request.index && data[3] == h.t.request.subindex;
}

/* Whether `bytes` are the `n` bytes at `pos` of `buffer`, which is NULL when empty. */
static bool same_bytes(const uint8_t *bytes, const uint8_t *buffer, uint32_t pos, uint32_t n)
{
    return n == 0 || memcmp(bytes, buffer + pos, n) == 0;
}

static bool frame_is(const co_frame_t *frame, const uint8_t expected[8])
{
    return memcmp(frame->data, expected, 8) == 0;
}

static bool block_for(uint32_t size, co_sdo_client_mode_t mode)
{
    return mode == CO_SDO_CLIENT_BLOCK ||
           (mode == CO_SDO_CLIENT_AUTO && h.pst != 0 && size > h.pst);
}

/* The initiate request: the protocol co_sdo_client.h gives the mode, the size and pst. */
static void check_initiate(const co_frame_t *frame)
{
    const request_t *r = &h.t.request;
    uint8_t want[8] = {0};
    co_put_u16(&want[1], r->index);
    want[3] = r->subindex;
    bool expedited = !r->upload && r->mode == CO_SDO_CLIENT_AUTO && r->size >= 1 &&
                     r->size <= CO_SDO_EXPEDITED_BYTES;
    h.t.block = !expedited && block_for(r->size, r->mode);
    if (r->upload && h.t.block) {
        want[0] =
            CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLOCK_CRC | CO_SDO_SUB_UPLOAD_INITIATE;
        want[4] = h.upload_blksize;
        want[5] = r->mode == CO_SDO_CLIENT_BLOCK ? 0 : h.pst;
    } else if (r->upload) {
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_UPLOAD_INITIATE);
    } else if (expedited) {
        want[0] = (uint8_t)(CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_INITIATE) |
                            (CO_SDO_EXPEDITED_BYTES - r->size) << 2 | CO_SDO_EXPEDITED |
                            CO_SDO_SIZE_INDICATED);
        memcpy(&want[4], h.t.buffer, r->size);
        h.t.sent = r->size;
        h.t.sent_last = true;
    } else if (h.t.block) {
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_DOWNLOAD) | CO_SDO_BLOCK_CRC |
                  CO_SDO_BLOCK_SIZE_INDICATED | CO_SDO_SUB_DOWNLOAD_INITIATE;
        co_put_u32(&want[4], r->size);
    } else {
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_INITIATE) | CO_SDO_SIZE_INDICATED;
        co_put_u32(&want[4], r->size);
    }
    rig_check(frame_is(frame, want), "an initiate request that is not the one the mode gives");
    h.t.initiated = true;
}

/* The bytes of the segment at `pos`: 7, fewer in the last one (none for an empty value). */
static uint32_t segment_bytes(uint32_t pos)
{
    uint32_t left = h.t.request.size - pos;
    return left < CO_SDO_SEGMENT_BYTES ? left : CO_SDO_SEGMENT_BYTES;
}

/* A segment of a segmented download: the next bytes of the data, the toggle alternating from 0,
 * c on the last. */
static void check_download_segment(const co_frame_t *frame)
{
    uint8_t command = frame->data[0];
    uint32_t count = segment_bytes(h.t.sent);
    bool last = h.t.sent + count == h.t.request.size;
    rig_check(h.t.phase == PHASE_SEGMENTS && !h.t.sent_last,
              "a download segment after the last one");
    rig_check((command & CO_SDO_CS_MASK) == CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_SEGMENT) &&
                  (command & CO_SDO_TOGGLE) == h.t.toggle &&
                  ((command >> 1) & 7u) == CO_SDO_SEGMENT_BYTES - count &&
                  ((command & CO_SDO_LAST_SEGMENT) != 0) == last,
              "a download segment with a wrong command byte");
    rig_check(same_bytes(&frame->data[1], h.t.buffer, h.t.sent, count),
              "a download segment that is not the next bytes of the data");
    h.t.sent += count;
    h.t.sent_last = last;
    h.t.toggle ^= CO_SDO_TOGGLE;
}

/* Block download: the server acknowledged every segment up to the one with c. */
static bool block_download_acknowledged(void)
{
    uint32_t size = h.t.request.size;
    return h.t.base >= (size == 0 ? CO_SDO_SEGMENT_BYTES : size);
}

/* A segment of a block download: seqno 1, 2, ... up to the server's block size, each the bytes
 * at its place after the acknowledged ones, c on the one holding the end of the data. */
static void check_block_segment(const co_frame_t *frame)
{
    uint8_t seqno = frame->data[0] & CO_SDO_BLOCK_SEQNO;
    rig_check(seqno == h.t.seqno + 1 && seqno <= h.t.blksize,
              "a block download segment out of sequence or past the server's block size");
    uint32_t pos = h.t.base + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES;
    rig_check(pos < h.t.request.size || pos == 0, "a block download segment past the data's end");
    uint32_t count = segment_bytes(pos);
    rig_check(((frame->data[0] & CO_SDO_BLOCK_LAST) != 0) == (pos + count == h.t.request.size),
              "a block download segment with c on the wrong segment");
    rig_check(same_bytes(&frame->data[1], h.t.buffer, pos, count),
              "a block download segment that is not the data at its place");
    h.t.seqno = seqno;
}

/* The end request: n bytes of the last segment are padding; the CRC of the whole data when the
 * server agreed to it. */
static void check_block_download_end(const co_frame_t *frame)
{
    uint32_t size = h.t.request.size;
    uint32_t unused = h.t.base - size;
    uint8_t want[8] = {(uint8_t)(CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_DOWNLOAD) | unused << 2 |
                                 CO_SDO_SUB_DOWNLOAD_END)};
    if (h.t.crc)
        co_put_u16(&want[1], co_sdo_crc16(h.t.buffer, size));
    rig_check(frame_is(frame, want), "a block download end with a wrong n or CRC");
    h.t.phase = PHASE_BLOCK_END;
}

/* What the client sends in an upload after the initiate: segment requests, the block upload's
 * start, its acknowledges and its end. */
static void check_upload_frame(const co_frame_t *frame)
{
    uint8_t want[8] = {0};
    switch (h.t.phase) {
    case PHASE_SEGMENTS:
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_UPLOAD_SEGMENT) | h.t.toggle;
        rig_check(frame_is(frame, want), "a segment request with a wrong command byte");
        h.t.toggle ^= CO_SDO_TOGGLE;
        break;
    case PHASE_BLOCK_START:
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_START;
        rig_check(frame_is(frame, want), "a block upload without its start command");
        h.t.phase = PHASE_BLOCK_SUB;
        break;
    case PHASE_BLOCK_SUB:
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_ACK;
        want[1] = h.t.seqno;
        want[2] = h.upload_blksize;
        rig_check(frame_is(frame, want),
                  "a block upload acknowledge that is not the last segment received in order");
        h.call.ack_sent = true;
        h.t.base += (uint32_t)h.t.seqno * CO_SDO_SEGMENT_BYTES;
        h.t.seqno = 0;
        if (h.t.last_in_sub)
            h.t.phase = PHASE_BLOCK_END;
        break;
    default:
        want[0] = CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_SUB_UPLOAD_END;
        rig_check(h.t.phase == PHASE_BLOCK_END && h.call.answer != NULL && frame_is(frame, want),
                  "a frame the upload's protocol has no place for");
        break;
    }
}

static void on_send(void *user, const co_frame_t *frame)
{
    (void)user;
    rig_check(frame->id == REQUEST_ID && frame->len == 8 && frame->flags == 0,
              "a frame that is not an 8-byte frame on the request COB-ID");
    rig_check(h.pending, "a frame sent with no transfer under way");
    rig_check(!h.call.abort_sent, "a frame after the abort frame");
    bool abort = frame->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT);
    bool segment = !abort && !h.t.request.upload && h.t.block && h.t.phase == PHASE_BLOCK_SUB &&
                   !block_download_acknowledged();
    /* One request per answer; only a sub-block of a block download is several frames. */
    rig_check(h.call.frames == 0 || segment, "two requests sent for one answer");
    h.call.frames++;
    if (abort) {
        rig_check(mux_is_request(frame->data), "an abort frame for another object");
        h.call.abort_sent = true;
        h.call.abort_code = co_get_u32(&frame->data[4]);
    } else if (!h.t.initiated) {
        check_initiate(frame);
    } else if (h.t.request.upload) {
        check_upload_frame(frame);
    } else if (segment) {
        check_block_segment(frame);
    } else if (h.t.block) {
        rig_check(h.t.phase == PHASE_BLOCK_SUB, "a block download frame out of place");
        check_block_download_end(frame);
    } else {
        check_download_segment(frame);
    }
}

/* Codes of the client's own aborts (CiA 301 table 22). */
static bool client_abort_code(uint32_t code)
{
    switch (code) {
    case CO_SDO_ABORT_TIMEOUT:
    case CO_SDO_ABORT_COMMAND:
    case CO_SDO_ABORT_TOGGLE:
    case CO_SDO_ABORT_NO_MEMORY:
    case CO_SDO_ABORT_TYPE_LENGTH:
    case CO_SDO_ABORT_SEQUENCE:
    case CO_SDO_ABORT_BLOCK_SIZE:
    case CO_SDO_ABORT_CRC:
        return true;
    default:
        return false;
    }
}

static void check_success(const co_sdo_client_result_t *result)
{
    const request_t *r = &h.t.request;
    rig_check(result->abort_code == 0, "a successful transfer with an abort code");
    rig_check(h.call.answer != NULL, "a transfer that succeeds without an answer");
    if (!r->upload) {
        rig_check(result->size == r->size, "a download that reports another size");
        rig_check(h.t.block ? h.t.phase == PHASE_BLOCK_END : h.t.sent_last,
                  "a download done before all its data was sent");
        return;
    }
    rig_check(result->size <= r->size, "an upload larger than its buffer");
    rig_check(result->size == h.t.received, "an upload whose size is not what the server sent");
    rig_check(!h.t.size_given || result->size == h.t.size,
              "an upload whose size is not the one the server indicated");
    rig_check(same_bytes(h.model, h.t.buffer, 0, result->size),
              "an upload whose bytes are not the server's");
}

static void check_abort(const co_sdo_client_result_t *result)
{
    rig_check(result->size == 0, "an aborted transfer with a size");
    const co_frame_t *answer = h.call.answer;
    if (result->status == CO_SDO_CLIENT_SERVER_ABORT) {
        rig_check(answer != NULL && answer->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT),
                  "a server abort without the server's abort frame");
        uint32_t code = answer->len >= 8 ? co_get_u32(&answer->data[4]) : CO_SDO_OK;
        if (code == CO_SDO_OK)
            code = CO_SDO_ABORT_GENERAL; /* no code, or 0: the server's general error */
        rig_check(result->abort_code == code, "a server abort with another code than the server's");
        return;
    }
    rig_check(h.call.abort_sent && h.call.abort_code == result->abort_code,
              "a client abort not told to the server with its code");
    rig_check(client_abort_code(result->abort_code), "a client abort with an unexpected code");
    rig_check((result->abort_code == CO_SDO_ABORT_TIMEOUT) == (answer == NULL),
              "a timeout on an answer, or another abort without one");
    rig_check(answer != NULL || h.now >= h.t.deadline, "a timeout before the deadline");
}

static void start_request(const request_t *r);

static void on_done(void *user, const co_sdo_client_result_t *result)
{
    (void)user;
    rig_check(h.pending, "a done callback with no transfer under way");
    rig_check(!co_sdo_client_busy(&h.client), "the client busy in its own done callback");
    rig_check(result->index == h.t.request.index && result->subindex == h.t.request.subindex,
              "a result for another object");
    rig_check(result->status == CO_SDO_CLIENT_OK || result->status == CO_SDO_CLIENT_SERVER_ABORT ||
                  result->status == CO_SDO_CLIENT_CLIENT_ABORT,
              "a result with an unknown status");
    if (result->status == CO_SDO_CLIENT_OK) {
        check_success(result);
        h.succeeded++;
    } else {
        check_abort(result);
    }
    h.pending = false;
    free(h.t.buffer);
    h.t.buffer = NULL;
    /* The client is idle again: the callback may start the next transfer. */
    if (h.chain && h.chained < CHAIN_MAX) {
        h.chained++;
        request_t again = h.t.request;
        start_request(&again);
    }
}

static bool mode_valid(co_sdo_client_mode_t mode)
{
    return mode == CO_SDO_CLIENT_AUTO || mode == CO_SDO_CLIENT_SEGMENTED ||
           mode == CO_SDO_CLIENT_BLOCK;
}

/* co_sdo_client.h: a bad argument is refused first, then a busy client, then a timeout of 0. */
static int expected_result(const request_t *r)
{
    if (!mode_valid(r->mode) || (r->null_buffer && r->size != 0))
        return CO_SDO_CLIENT_ERR_ARG;
    if (h.pending)
        return CO_SDO_CLIENT_ERR_BUSY;
    return r->timeout_ms == 0 ? CO_SDO_CLIENT_ERR_ARG : 0;
}

static void start_request(const request_t *r)
{
    int want = expected_result(r);
    uint8_t *buffer = NULL;
    if (!r->null_buffer && r->size != 0) {
        buffer = malloc(r->size);
        rig_check(buffer != NULL, "out of memory");
        for (uint32_t i = 0; i < r->size; i++)
            buffer[i] = r->upload ? 0 : pattern(i);
    }
    if (want == 0) {
        h.pending = true;
        h.started++;
        h.t = (transfer_t){
            .request = *r,
            .buffer = buffer,
            .deadline = h.now + (co_time_t)r->timeout_ms * US_PER_MS,
            .phase = PHASE_INITIATE,
        };
    }
    /* A request from a done callback is a call of its own inside the callback's. */
    call_t outer = h.call;
    h.call = (call_t){0};
    int got = r->upload ? co_sdo_client_upload(&h.client, r->index, r->subindex, buffer, r->size,
                                               r->mode, r->timeout_ms, h.now)
                        : co_sdo_client_download(&h.client, r->index, r->subindex, buffer, r->size,
                                                 r->mode, r->timeout_ms, h.now);
    rig_check(got == want, "a request answered otherwise than co_sdo_client.h says");
    rig_check(h.call.frames == (got == 0 ? 1u : 0u), "a request that sent other than its initiate");
    h.call = outer;
    if (got != 0)
        free(buffer);
}

/* The upload's value as the server sent it, where the client must keep it. */
static void model_store(uint32_t pos, const uint8_t *data, uint32_t count)
{
    for (uint32_t k = 0; k < count && pos + k < h.t.request.size; k++)
        h.model[pos + k] = data[k];
}

static void follow_upload_initiate(const co_frame_t *f)
{
    uint8_t command = f->data[0];
    bool size_given = (command & CO_SDO_SIZE_INDICATED) != 0;
    /* The plain answer, also to a block upload initiate that the server switched below pst. */
    if ((command & CO_SDO_CS_MASK) == CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE)) {
        if (command & CO_SDO_EXPEDITED) {
            uint32_t count = size_given ? CO_SDO_EXPEDITED_BYTES - ((command >> 2) & 3u)
                                        : CO_SDO_EXPEDITED_BYTES;
            model_store(0, &f->data[4], count);
            h.t.received = count;
            return;
        }
        h.t.phase = PHASE_SEGMENTS;
    } else {
        h.t.phase = PHASE_BLOCK_START;
        h.t.crc = (command & CO_SDO_BLOCK_CRC) != 0;
        size_given = (command & CO_SDO_BLOCK_SIZE_INDICATED) != 0;
    }
    h.t.size_given = size_given;
    h.t.size = size_given ? co_get_u32(&f->data[4]) : 0;
}

static void follow_upload(const co_frame_t *f)
{
    uint8_t command = f->data[0];
    switch (h.t.phase) {
    case PHASE_INITIATE:
        follow_upload_initiate(f);
        break;
    case PHASE_SEGMENTS: {
        uint32_t count = CO_SDO_SEGMENT_BYTES - ((command >> 1) & 7u);
        model_store(h.t.received, &f->data[1], count);
        h.t.received += count;
        break;
    }
    case PHASE_BLOCK_SUB: {
        uint8_t seqno = command & CO_SDO_BLOCK_SEQNO;
        if (seqno == h.t.seqno + 1) {
            model_store(h.t.base + (uint32_t)(seqno - 1) * CO_SDO_SEGMENT_BYTES, &f->data[1],
                        CO_SDO_SEGMENT_BYTES);
            h.t.seqno = seqno;
            h.t.last_in_sub = (command & CO_SDO_BLOCK_LAST) != 0;
        }
        break;
    }
    default: {
        uint32_t unused = (command >> 2) & 7u;
        h.t.received = h.t.base >= unused ? h.t.base - unused : 0;
        break;
    }
    }
}

static void follow_download(const co_frame_t *f)
{
    if (!h.t.block) {
        h.t.phase = PHASE_SEGMENTS;
    } else if (h.t.phase == PHASE_INITIATE) {
        h.t.phase = PHASE_BLOCK_SUB;
        h.t.crc = (f->data[0] & CO_SDO_BLOCK_CRC) != 0;
        h.t.blksize = f->data[4];
    } else if (h.t.phase == PHASE_BLOCK_SUB) {
        h.t.base += (uint32_t)f->data[1] * CO_SDO_SEGMENT_BYTES;
        h.t.blksize = f->data[2];
        h.t.seqno = 0;
    }
}

/* Follows the server's answer before the client gets it. The client may find it wrong and
 * abort: the transfer then ends, and what was made of the answer here with it. */
static void follow_answer(const co_frame_t *f)
{
    h.t.deadline = h.now + (co_time_t)h.t.request.timeout_ms * US_PER_MS;
    if (f->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT))
        return;
    if (h.t.request.upload)
        follow_upload(f);
    else
        follow_download(f);
}

/* The server's right answer to the client's last request, which completes the transfer: the
 * confirmation of an expedited download, of the last segment, of a block download's end, or an
 * expedited upload of 4 bytes into a buffer that holds them. */
static bool final_answer(const co_frame_t *f)
{
    const request_t *r = &h.t.request;
    uint8_t command = f->data[0];
    bool mux = f->len >= CO_SDO_INITIATE_LEN && mux_is_request(f->data);
    if (r->upload)
        return h.t.phase == PHASE_INITIATE && mux && f->len == 8 && r->size >= 4 &&
               command == (CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE) | CO_SDO_EXPEDITED |
                           CO_SDO_SIZE_INDICATED);
    if (h.t.phase == PHASE_INITIATE)
        return h.t.sent_last && mux && command == CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_INITIATE);
    if (h.t.phase == PHASE_SEGMENTS)
        return h.t.sent_last && command == (CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_SEGMENT) |
                                            (h.t.toggle ^ CO_SDO_TOGGLE));
    return h.t.phase == PHASE_BLOCK_END &&
           command == (CO_SDO_COMMAND(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_SUB_DOWNLOAD_END);
}

static void check_busy(void)
{
    rig_check(co_sdo_client_busy(&h.client) == h.pending,
              "the client busy without a transfer, or idle during one");
}

/* As the runtime does after every frame and at every deadline. */
static void process(void)
{
    h.call = (call_t){0};
    co_time_t next = co_sdo_client_process(&h.client, h.now);
    check_busy();
    if (h.pending)
        rig_check(next == h.t.deadline && next > h.now,
                  "a deadline other than the last answer plus the timeout");
    else
        rig_check(next == CO_TIME_NEVER, "an idle client with a deadline");
}

static void deliver(const co_frame_t *frame)
{
    bool own = frame->id == RESPONSE_ID && !(frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF));
    bool pending = h.pending;
    unsigned started = h.started;
    unsigned succeeded = h.succeeded;
    bool block_upload_segment = pending && h.t.request.upload && h.t.phase == PHASE_BLOCK_SUB;
    bool final = own && pending && frame->len > 0 && final_answer(frame);
    if (own && pending && frame->len > 0)
        follow_answer(frame);
    h.call = (call_t){.answer = frame};
    bool used = co_sdo_client_receive(&h.client, frame, h.now);
    rig_check(used == own, "a frame taken that is not on the response COB-ID, or the reverse");
    rig_check(pending || h.call.frames == 0, "a frame sent in answer while idle");
    check_busy();
    rig_check(!final || h.succeeded == succeeded + 1, "a right last answer that does not complete");
    /* A block upload acknowledges at the sub-block's end: seqno = blksize, or c. */
    if (own && block_upload_segment && h.pending && h.started == started && frame->len > 0) {
        uint8_t seqno = frame->data[0] & CO_SDO_BLOCK_SEQNO;
        bool end = seqno == h.upload_blksize || (frame->data[0] & CO_SDO_BLOCK_LAST) != 0;
        rig_check(h.call.ack_sent == end, "a block upload acknowledge missing or out of place");
    }
    process();
}

static void advance(co_time_t us)
{
    co_time_t end = h.now + us;
    for (int i = 0; i < DEADLINES_PER_STEP && h.pending && h.t.deadline <= end; i++) {
        h.now = h.t.deadline;
        process();
    }
    h.now = end;
    process();
}

static request_t decode_request(uint8_t command, const uint8_t *args)
{
    return (request_t){
        .upload = (command & REQUEST_UPLOAD) != 0,
        .mode = (co_sdo_client_mode_t)((command >> 1) & 3u),
        .null_buffer = (command & REQUEST_NULL_BUFFER) != 0,
        .index = co_get_u16(&args[0]),
        .subindex = args[2],
        .size = co_get_u16(&args[3]) & SIZE_MASK,
        .timeout_ms = args[5],
    };
}

static void setup(const uint8_t *header)
{
    memset(&h, 0, sizeof h);
    h.chain = (header[2] & FLAG_CHAIN) != 0;
    co_sdo_client_config_t config = {
        .server_node_id = SERVER_NODE_ID,
        .send = on_send,
        .done = on_done,
        .blksize = header[0],
        .pst = header[1],
    };
    int refused = config.blksize > CO_SDO_BLKSIZE_MAX ? CO_SDO_CLIENT_ERR_CONFIG : 0;
    rig_check(co_sdo_client_init(&h.client, &config) == refused, "init's answer to the blksize");
    config.blksize &= CO_SDO_BLKSIZE_MAX;
    rig_check(co_sdo_client_init(&h.client, &config) == 0, "init refused a valid configuration");
    h.upload_blksize = config.blksize != 0 ? config.blksize : CO_SDO_BLKSIZE_MAX;
    h.pst = config.pst;
    process();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input_t input = {data, size};
    const uint8_t *header = fuzz_take(&input, HEADER_SIZE);
    if (header == NULL)
        return 0;
    setup(header);
    fuzz_step_t step;
    while (fuzz_next_step(&input, true, &step)) {
        if (step.kind == FUZZ_STEP_TIME) {
            advance(step.us);
        } else if (step.kind == FUZZ_STEP_FRAME) {
            deliver(&step.frame);
        } else {
            const uint8_t *args = fuzz_take(&input, REQUEST_ARGS);
            if (args == NULL)
                break;
            request_t r = decode_request(step.command, args);
            h.chained = 0;
            start_request(&r);
        }
    }
    /* Every transfer ends: without answers, by its timeout. */
    h.chain = false;
    if (h.pending)
        advance(h.t.deadline - h.now);
    rig_check(!h.pending, "a transfer that never ends");
    return 0;
}
