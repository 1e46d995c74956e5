/* SPDX-License-Identifier: Apache-2.0 */
/* SDO client (CiA 301 section 7.2.4, client side): one channel to one SDO server, expedited,
 * segmented and block upload and download of any size up to a buffer the application gives. A
 * passive state machine that needs no co_node_t: the application feeds it the frames of its
 * response COB-ID and the monotonic time, it sends through a callback and reports the end of each
 * transfer through another. Several clients (one per server) coexist; no malloc, no globals. */
#ifndef CO_SDO_CLIENT_H
#define CO_SDO_CLIENT_H

#include "co_od.h"

/* How a transfer ends. */
typedef enum co_sdo_client_status {
    CO_SDO_CLIENT_OK = 0,
    CO_SDO_CLIENT_SERVER_ABORT, /* the server sent an abort frame: abort_code is its code, or
                                 * 08000000h when it carries none (short, or 0) */
    CO_SDO_CLIENT_CLIENT_ABORT  /* the client aborted (and told the server): abort_code says why */
} co_sdo_client_status_t;

/* The result of one transfer; co_sdo_abort_text(abort_code) gives the CiA 301 text. */
typedef struct co_sdo_client_result {
    co_sdo_client_status_t status;
    uint32_t abort_code; /* 0 when OK */
    uint32_t size;       /* bytes transferred: the upload's value size, or the bytes downloaded */
    uint16_t index;
    uint8_t subindex;
} co_sdo_client_result_t;

/* Called once at the end of every accepted request, from co_sdo_client_receive() or
 * co_sdo_client_process(); the client is idle again, so the callback may start the next request.
 */
typedef void (*co_sdo_client_done_fn)(void *user, const co_sdo_client_result_t *result);

/* The transfer protocol of a request. */
typedef enum co_sdo_client_mode {
    /* Download: expedited for 1..4 bytes, block above the switch threshold (pst, when not 0),
     * segmented otherwise. Upload: block when pst is not 0 and the buffer is larger than pst
     * (the server falls back to expedited or segmented for a value of at most pst bytes, as CiA
     * 301 allows), otherwise the plain upload (the server chooses expedited or segmented). */
    CO_SDO_CLIENT_AUTO = 0,
    CO_SDO_CLIENT_SEGMENTED, /* never block, never expedited download (upload: the server's choice)
                              */
    CO_SDO_CLIENT_BLOCK      /* block transfer whatever the size (upload: with pst = 0) */
} co_sdo_client_mode_t;

typedef struct co_sdo_client_config {
    uint8_t server_node_id; /* 1..127: default COB-IDs 600h+id (request) and 580h+id (response) */
    /* Explicit COB-IDs (11-bit CAN-IDs) as 1280h gives them; 0 takes the default above. */
    uint16_t request_id;
    uint16_t response_id;
    co_send_fn send;
    void *user; /* passed to send and done */
    co_sdo_client_done_fn done;
    uint8_t blksize; /* block upload: segments per sub-block the client takes, 1..127; 0: 127 */
    uint8_t pst;     /* protocol switch threshold in bytes (CiA 301 block upload); 0: none */
} co_sdo_client_config_t;

/* Where the client is; every state but IDLE waits for the server under the request's timeout. */
typedef enum co_sdo_client_state {
    CO_SDO_CLIENT_IDLE = 0,
    CO_SDO_CLIENT_DOWNLOAD_EXPEDITED,      /* expedited download sent */
    CO_SDO_CLIENT_DOWNLOAD_INITIATE,       /* segmented download initiate sent */
    CO_SDO_CLIENT_DOWNLOAD_SEGMENT,        /* segment sent, waiting for its confirmation */
    CO_SDO_CLIENT_UPLOAD_INITIATE,         /* upload initiate sent */
    CO_SDO_CLIENT_UPLOAD_SEGMENT,          /* segment request sent */
    CO_SDO_CLIENT_BLOCK_DOWNLOAD_INITIATE, /* block download initiate sent */
    CO_SDO_CLIENT_BLOCK_DOWNLOAD_ACK,      /* sub-block sent, waiting for its acknowledge */
    CO_SDO_CLIENT_BLOCK_DOWNLOAD_END,      /* end request sent */
    CO_SDO_CLIENT_BLOCK_UPLOAD_INITIATE,   /* block upload initiate sent (pst may switch) */
    CO_SDO_CLIENT_BLOCK_UPLOAD_SUB,        /* receiving a sub-block */
    CO_SDO_CLIENT_BLOCK_UPLOAD_END         /* final sub-block acknowledged, waiting for the end */
} co_sdo_client_state_t;

typedef struct co_sdo_client {
    uint8_t state; /* co_sdo_client_state_t */
    uint16_t request_id;
    uint16_t response_id;
    co_send_fn send;
    void *user;
    co_sdo_client_done_fn done;
    uint8_t upload_blksize;
    uint8_t pst;

    uint16_t index;
    uint8_t subindex;
    co_time_t timeout_us;
    co_time_t deadline;
    const uint8_t *tx_data; /* download: the application's data */
    uint8_t *rx_data;       /* upload: the application's buffer */
    uint32_t capacity;      /* upload: size of rx_data */
    uint32_t size;          /* download: its length; upload: the size the server indicated */
    bool size_indicated;    /* upload: the server indicated `size` */
    uint32_t offset;        /* bytes transferred and confirmed so far */
    uint8_t toggle;         /* segmented: toggle bit of the next segment */
    bool crc;               /* block: both sides use the CRC */
    uint8_t blksize;        /* block: segments in the current sub-block */
    uint8_t seqno;          /* block: last sent (download) or last good (upload) seqno */
    bool last_in_block;     /* block: the final segment is in the current sub-block */
} co_sdo_client_t;

/* Results of co_sdo_client_init, co_sdo_client_config_from_od and the requests. */
#define CO_SDO_CLIENT_ERR_CONFIG 1    /* node-id outside 1..127, COB-ID above 7FFh, no callback */
#define CO_SDO_CLIENT_ERR_BUSY 2      /* a transfer is under way: nothing was sent */
#define CO_SDO_CLIENT_ERR_ARG 3       /* timeout 0, buffer NULL, unknown mode: nothing was sent */
#define CO_SDO_CLIENT_ERR_NO_OBJECT 4 /* the dictionary has no such 1280h..12FFh record */
#define CO_SDO_CLIENT_ERR_INVALID 5   /* the 1280h record's COB-ID has bit 31 (not valid) set */

/* Prepares an idle client. Returns 0 or CO_SDO_CLIENT_ERR_CONFIG. */
int co_sdo_client_init(co_sdo_client_t *client, const co_sdo_client_config_t *config);

/* Fills the channel of `config` (COB-IDs, server node-id) from the SDO client parameter
 * 1280h + channel (channel 0..127) of a node's dictionary: sub 1 client -> server COB-ID, sub 2
 * server -> client COB-ID, sub 3 the server's node-id. The other fields are left as they are.
 * Returns 0, CO_SDO_CLIENT_ERR_NO_OBJECT or CO_SDO_CLIENT_ERR_INVALID. */
int co_sdo_client_config_from_od(co_sdo_client_config_t *config, const co_node_t *node,
                                 uint8_t channel);

/* Reads index:subindex into buf (cap bytes). timeout_ms bounds each wait for the server (it
 * restarts with every frame of the transfer). Returns 0 when the request was sent. */
int co_sdo_client_upload(co_sdo_client_t *client, uint16_t index, uint8_t subindex, uint8_t *buf,
                         uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                         co_time_t now);

/* Writes len bytes of data (which must stay valid until the transfer ends) to index:subindex. */
int co_sdo_client_download(co_sdo_client_t *client, uint16_t index, uint8_t subindex,
                           const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                           uint32_t timeout_ms, co_time_t now);

/* Handles a frame; returns whether it was on the client's response COB-ID (its own). */
bool co_sdo_client_receive(co_sdo_client_t *client, const co_frame_t *frame, co_time_t now);

/* Runs the timeout: at the deadline the client aborts with 0x05040000. Returns the next
 * deadline, CO_TIME_NEVER when idle. */
co_time_t co_sdo_client_process(co_sdo_client_t *client, co_time_t now);

/* Whether a transfer is under way. */
bool co_sdo_client_busy(const co_sdo_client_t *client);

/* Forgets the transfer under way: no frame, no `done` call, idle at once. For a server known to
 * have forgotten it too (it was reset, or its boot-up came), to which an abort would say nothing;
 * any other end of a transfer is an abort (CiA 301). */
void co_sdo_client_cancel(co_sdo_client_t *client);

/* Ends the transfer under way as the client's abort with `code`, without the abort frame: for a
 * channel that can no longer send one (its COB-ID made not valid, the node's reset:
 * co_sdo_clients.h). The `done` call follows; nothing when idle. */
void co_sdo_client_end(co_sdo_client_t *client, uint32_t code);

#endif
