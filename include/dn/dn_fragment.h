/* SPDX-License-Identifier: Apache-2.0 */
/* The explicit messaging fragmentation protocol, both ways, as the slave (src/devicenet) and the
 * scanner (src/devicenet/scanner) share it: a fragment is [header|0x80][type|count][up to 6
 * bytes]; first (0x00), middle (0x40) and last (0x80) fragments each wait for an acknowledgement
 * (0xC0) carrying a status (00 success, 01 too much data). These functions keep a dn_fragments_t
 * and build frames; sending, timers and retries stay with their callers. */
#ifndef DN_FRAGMENT_H
#define DN_FRAGMENT_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_types.h" /* co_time_t */
#include "dn_cip.h"

/* Produced and consumed connection size of the explicit connection (Connection attributes 7 and
 * 8): a request or response body of up to 64 bytes, fragmented above 7. */
#define DN_MESSAGE_MAX 64u
/* Bytes of an unfragmented explicit frame's message body: the frame less the header byte. */
#define DN_FRAME_BODY 7u

/* An explicit message received or sent in fragments. */
typedef struct dn_fragments {
    bool active;
    uint8_t header;     /* byte 0 of every fragment: frag bit, XID, the MAC ID */
    uint8_t count;      /* received: the last fragment's count; sent: the fragment awaiting ack */
    uint8_t len;        /* received: bytes so far; sent: the whole body */
    uint8_t offset;     /* sent: the first byte of the fragment awaiting its acknowledgement */
    uint8_t retries;    /* sent: retransmissions of that fragment */
    co_time_t deadline; /* the caller's timer */
    uint8_t body[DN_MESSAGE_MAX];
} dn_fragments_t;

/* ---- sending -------------------------------------------------------------------------------- */

/* Starts sending `body` (8..DN_MESSAGE_MAX bytes) in fragments under `header` (its frag bit is
 * set here): the first fragment is then dn_fragment_frame's. */
void dn_fragment_start(dn_fragments_t *tx, uint8_t header, const uint8_t *body, uint8_t len);
/* The fragment in flight as a frame's data; returns its length (3..8). */
uint8_t dn_fragment_frame(const dn_fragments_t *tx, uint8_t frame[8]);

typedef enum dn_fragment_ack {
    DN_FRAGMENT_ACK_IGNORED, /* nothing in flight, or another fragment's count */
    DN_FRAGMENT_ACK_NEXT,    /* the next fragment is in flight: send it */
    DN_FRAGMENT_ACK_DONE,    /* the last fragment was acknowledged: the message went through */
    DN_FRAGMENT_ACK_REFUSED  /* acknowledged with an error status: the message is given up */
} dn_fragment_ack_t;

/* An acknowledgement (type 0xC0, this count, this status) of the fragment in flight. */
dn_fragment_ack_t dn_fragment_acknowledged(dn_fragments_t *tx, uint8_t count, uint8_t status);

/* ---- receiving ------------------------------------------------------------------------------ */

typedef enum dn_fragment_rx {
    DN_FRAGMENT_RX_IGNORED,  /* a middle or last fragment with no message in progress */
    DN_FRAGMENT_RX_TAKEN,    /* acknowledge it (success); more fragments to come */
    DN_FRAGMENT_RX_REPEATED, /* the previous fragment again: acknowledge it again, drop it */
    DN_FRAGMENT_RX_LOST,     /* a count out of sequence: the message is dropped, no ack */
    DN_FRAGMENT_RX_TOO_MUCH, /* over DN_MESSAGE_MAX: acknowledge with 01, message dropped */
    DN_FRAGMENT_RX_COMPLETE  /* the last fragment: acknowledge it; rx->body, rx->len hold it */
} dn_fragment_rx_t;

/* A received fragment (frame data of `len` >= 2 bytes, not an acknowledgement); a first
 * fragment starts over. rx->header keeps the first fragment's byte 0. */
dn_fragment_rx_t dn_fragment_receive(dn_fragments_t *rx, const uint8_t *data, uint8_t len);

/* An acknowledgement frame of fragment `count`: [header|0x80][0xC0|count][status]; 3 bytes. */
uint8_t dn_fragment_ack_frame(uint8_t header, uint8_t count, uint8_t status, uint8_t frame[8]);

#endif
