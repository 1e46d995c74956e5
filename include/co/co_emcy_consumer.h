/* SPDX-License-Identifier: Apache-2.0 */
/* EMCY consumer (CiA 301 section 7.2.7): decodes the emergency frames of other nodes (COB-ID
 * 080h + node-id, node-id 1..127) into node-id, error code, error register and the five
 * manufacturer-specific bytes, hands those of the watched nodes to a callback, and says what an
 * error code means: the CiA 301 and CiA 402 tables, optionally preceded by a vendor's own table
 * (a device model supplies its manual's: co_emcy_code_table_t).
 *
 * The consumer listens on the default COB-IDs only; a node whose 1014h was moved elsewhere is not
 * recognised. Several consumers may coexist: each is a plain struct the caller owns. */
#ifndef CO_EMCY_CONSUMER_H
#define CO_EMCY_CONSUMER_H

#include "co_types.h"

/* CiA 301: an EMCY frame is exactly 8 bytes. */
#define CO_EMCY_FRAME_LEN 8u
#define CO_EMCY_MSEF_LEN 5u
/* CO_CAN_ID_EMCY under its release 0.1 name, kept for one more release. */
#define CO_EMCY_COB_ID_BASE CO_CAN_ID_EMCY

typedef enum co_emcy_decode {
    CO_EMCY_DECODE_OK = 0,
    CO_EMCY_DECODE_NOT_EMCY, /* not 080h + 1..127, a 29-bit identifier or a remote frame */
    CO_EMCY_DECODE_SHORT     /* an EMCY COB-ID with fewer than 8 bytes: malformed */
} co_emcy_decode_t;

typedef struct co_emcy_message {
    uint8_t node_id;
    uint16_t code;
    uint8_t reg; /* the sender's error register 1001h */
    uint8_t msef[CO_EMCY_MSEF_LEN];
} co_emcy_message_t;

/* Decodes one frame. Reads no byte beyond frame->len; `out` is filled only for OK, and its
 * node_id also for SHORT. */
co_emcy_decode_t co_emcy_decode(const co_frame_t *frame, co_emcy_message_t *out);
/* "EMCY frame", "not an EMCY frame", "EMCY frame shorter than 8 bytes". */
const char *co_emcy_decode_text(co_emcy_decode_t result);

/* The masks of a meaning: one code, a subclass xxyy (any yy) or a class xyyy (any yyy). */
#define CO_EMCY_MASK_EXACT 0xFFFFu
#define CO_EMCY_MASK_SUBCLASS 0xFF00u
#define CO_EMCY_MASK_CLASS 0xF000u

/* One meaning: codes c with (c & mask) == code. A wider mask is more specific. */
typedef struct co_emcy_meaning {
    uint16_t code;
    uint16_t mask;
    const char *text;
} co_emcy_meaning_t;

typedef struct co_emcy_code_table {
    const co_emcy_meaning_t *meanings;
    size_t count;
} co_emcy_code_table_t;

/* The meaning of an error code after CiA 301 (table 21) and CiA 402: the most specific match
 * (0x8130 "life guard or heartbeat error" before 0x81xx "communication", before 0x8xxx
 * "monitoring"). Never NULL: "unknown error code" for a code no table covers. */
const char *co_emcy_code_text(uint16_t code);
/* The same with a vendor table consulted first (NULL: none): a vendor's match wins over a
 * standard one that is no more specific. */
const char *co_emcy_code_text_in(const co_emcy_code_table_t *vendor, uint16_t code);

/* Called for each EMCY frame of a watched node, well formed (OK, msg complete) or not (SHORT,
 * only msg->node_id is meaningful). */
typedef void (*co_emcy_consumer_fn)(void *user, co_emcy_decode_t result,
                                    const co_emcy_message_t *msg, co_time_t now);

typedef struct co_emcy_consumer {
    uint8_t watched[16]; /* one bit per node-id 0..127 */
    co_emcy_consumer_fn on_emcy;
    void *user;
} co_emcy_consumer_t;

/* A consumer watching no node. */
void co_emcy_consumer_init(co_emcy_consumer_t *consumer, co_emcy_consumer_fn on_emcy, void *user);
/* Starts or stops watching node_id (1..127); returns false for another node-id. */
bool co_emcy_consumer_watch(co_emcy_consumer_t *consumer, uint8_t node_id, bool watch);
/* Offers a frame; returns true when it was an EMCY of a watched node (the callback ran). */
bool co_emcy_consumer_receive(co_emcy_consumer_t *consumer, const co_frame_t *frame, co_time_t now);

#endif
