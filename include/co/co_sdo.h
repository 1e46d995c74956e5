/* SPDX-License-Identifier: Apache-2.0 */
/* SDO server: expedited, segmented and block transfers (CiA 301 section 7.2.4) on the default SDO
 * channel 0x600+id / 0x580+id (1200h) and on the additional server channels 1201h.. a node is
 * given (co_sdo_servers.h), each with its own transfer, with the protocol timeout and the complete
 * set of abort codes.
 * Segmented and block transfers go through the transfer buffer, except those of a streamed DOMAIN
 * (co_od_stream_t, co_od.h), which pass segment by segment between the client and the
 * application: any size up to 2^32-1 bytes (a block download: 2^32-8). */
#ifndef CO_SDO_H
#define CO_SDO_H

#include "co_config.h"
#include "co_od.h"

/* Where the server is in a transfer; every state but IDLE waits for the client under the timeout.
 */
typedef enum co_sdo_state {
    CO_SDO_IDLE = 0,
    CO_SDO_DOWNLOAD_SEGMENT,   /* segmented download: waiting for the next segment */
    CO_SDO_BLOCK_DOWNLOAD_SUB, /* block download: receiving a sub-block */
    CO_SDO_BLOCK_DOWNLOAD_END, /* block download: waiting for the end request */
    CO_SDO_UPLOAD_SEGMENT,     /* segmented upload: waiting for the next segment request */
    CO_SDO_BLOCK_UPLOAD_START, /* block upload: waiting for the start command */
    CO_SDO_BLOCK_UPLOAD_ACK,   /* block upload: sub-block sent, waiting for its acknowledge */
    CO_SDO_BLOCK_UPLOAD_END    /* block upload: end sent, waiting for the end response */
} co_sdo_state_t;

/* The transfer buffer of segmented and block transfers: a download is collected in it, an upload's
 * value is copied into it at initiate. One buffer may serve several nodes of an application (their
 * co_node_config_t.sdo_buffer), since a node needs it only during such a transfer: the transfer
 * holds it from its initiate until it ends (completed, aborted, timed out, replaced by a new
 * request or by a reset), and another transfer that needs it meanwhile, of another node or of
 * another server channel of the same node, is refused with CO_SDO_ABORT_NO_RESOURCE. Expedited
 * transfers never use it. The nodes sharing a buffer must be run from one thread, like the calls
 * of one node. Set `data` and `size`, and `owner` to NULL. */
typedef struct co_sdo_buffer {
    uint8_t *data;
    uint32_t size; /* largest segmented or block transfer, bytes */
    /* The server channel whose transfer holds the buffer, NULL when free. */
    const struct co_sdo_server *owner;
} co_sdo_buffer_t;

typedef struct co_sdo_server {
    uint8_t state; /* co_sdo_state_t */
    uint16_t index;
    uint8_t subindex;
    uint16_t rx_id; /* client -> server COB-ID, from 12xxh:01 at reset (1201h..: on its write) */
    uint16_t tx_id; /* server -> client COB-ID, from 12xxh:02 at reset (1201h..: on its write) */
    /* An additional channel takes requests while both its COB-IDs are valid (bit 31 clear); the
     * default channel does not look at it. In what was padding. */
    bool valid;
    /* The default channel's: the protocol timeout of every channel of the node. */
    co_time_t timeout_us; /* restarted by every received frame */
    co_time_t deadline;
    uint8_t toggle;          /* segmented transfers: toggle bit expected in the next frame */
    bool size_indicated;     /* downloads: the client announced `size` */
    bool crc;                /* block transfers: both sides use the CRC */
    bool last_in_block;      /* block transfers: the final segment is in the current sub-block */
    bool block_broken;       /* block download: a segment of this sub-block was out of sequence */
    uint8_t blksize;         /* block transfers: segments in the current sub-block */
    uint8_t seqno;           /* block transfers: last good (download) or last sent (upload) seqno */
    uint8_t last_len;        /* block download: data bytes carried by the final segment's frame */
    uint32_t size;           /* announced download size, or the upload's total size */
    uint32_t offset;         /* bytes transferred and acknowledged so far */
    uint16_t crc_sum;        /* block transfers: CRC of the bytes before `offset` */
    uint16_t crc_sent;       /* block upload: CRC of the bytes sent so far */
    uint8_t last_segment[7]; /* block download: the final segment, until the end request */
    /* The streamed DOMAIN (co_od_stream_t) of the transfer, which then needs no buffer. */
    const co_od_entry_t *stream;
    co_sdo_buffer_t *buffer; /* the application's (co_node_config_t.sdo_buffer) or `own` */
#if CO_CONFIG_SDO_BUFFER > 0
    /* The node's own buffer, for an application that gives none. */
    co_sdo_buffer_t own;
    uint8_t own_data[CO_CONFIG_SDO_BUFFER];
#endif
} co_sdo_server_t;

/* The server channels of a node, and its SDO client channels (co_sdo_clients.h) after them:
 * reset (COB-IDs reloaded, transfers ended), a received frame routed to the server channel whose
 * client -> server COB-ID it has or to the client channel whose server -> client COB-ID it has
 * (true when one took it), the timeouts. */
void co_sdo_reset(co_node_t *node);
bool co_sdo_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_sdo_process(co_node_t *node, co_time_t now);

/* One channel, for the additional channels' module (co_sdo_servers.h): its transfer buffer (NULL:
 * its own CO_CONFIG_SDO_BUFFER bytes) on a zeroed state, a frame of its client, its transfer
 * ended silently, its timeout run. */
void co_sdo_channel_init(co_sdo_server_t *sdo, co_sdo_buffer_t *buffer);
void co_sdo_channel_receive(co_node_t *node, co_sdo_server_t *sdo, const co_frame_t *frame);
void co_sdo_channel_idle(co_node_t *node, co_sdo_server_t *sdo);
co_time_t co_sdo_channel_process(co_node_t *node, co_sdo_server_t *sdo, co_time_t now);

/* Sets the protocol timeout of the node's server channels, one for all of them (default
 * CO_CONFIG_SDO_TIMEOUT_US). */
void co_sdo_set_timeout(co_node_t *node, co_time_t timeout_us);

/* CRC-16-CCITT (polynomial 0x1021, initial value 0) of SDO block transfers (CiA 301). */
uint16_t co_sdo_crc16(const uint8_t *data, size_t len);
/* Continues a CRC over more bytes, so that a streamed value's CRC is built segment by segment. */
uint16_t co_sdo_crc16_update(uint16_t crc, const uint8_t *data, size_t len);

#endif
