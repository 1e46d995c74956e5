/* SPDX-License-Identifier: Apache-2.0 */
/* Basic types shared by every module of the portable core: CAN frames, time, CiA 301 data types;
 * the wire vocabulary (COB-IDs, indexes, SDO layout, abort codes) is in co_cia301.h, which this
 * header includes. No OS headers, no globals. */
#ifndef CO_TYPES_H
#define CO_TYPES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co_cia301.h"

/* Monotonic time in microseconds, supplied by the caller. */
typedef uint64_t co_time_t;

/* "No deadline": the runtime may sleep until the next frame arrives. */
#define CO_TIME_NEVER UINT64_MAX

/* Earlier of two deadlines. */
static inline co_time_t co_time_min(co_time_t a, co_time_t b)
{
    return a < b ? a : b;
}

/* The next due time of a periodic frame sent at `now` for the one `due`: one period after `due`,
 * so the period stays exact; when the call came so late that this has passed too, one period
 * after `now`, so that a late wake-up moves the schedule rather than send a burst. */
static inline co_time_t co_time_next_period(co_time_t due, co_time_t period, co_time_t now)
{
    return due + period > now ? due + period : now + period;
}

/* A classic CAN frame. Only 11-bit identifiers are used by the stack; 29-bit frames are ignored. */
#define CO_FRAME_RTR 0x01u /* remote transmission request */
#define CO_FRAME_EFF 0x02u /* 29-bit (extended) identifier */

#define CO_FRAME_DLC_MAX 8u

typedef struct co_frame {
    uint32_t id;
    uint8_t len; /* data length code, 0..CO_FRAME_DLC_MAX */
    uint8_t flags;
    uint8_t data[8];
} co_frame_t;

/* Transmits one frame. The core never waits for it: a runtime queues what it cannot send. */
typedef void (*co_send_fn)(void *user, const co_frame_t *frame);

/* CiA 301 7.3.5, table "restricted CAN-IDs": identifiers no configurable COB-ID (PDO, SYNC, EMCY)
 * may use, since NMT, the default SDO channels and NMT error control own them, or they are
 * reserved: 000h, 001h-07Fh, 101h-180h, 581h-5FFh, 601h-67Fh, 6E0h-6FFh, 701h-77Fh, 780h-7FFh.
 * The defaults 080h (SYNC) and 081h-0FFh (EMCY) are allowed. `can_id` is the 11-bit CAN-ID
 * (src/canopen/common/cob_id.c). */
bool co_can_id_restricted(uint32_t can_id);

/* The bits a configurable COB-ID (PDO 1400h/1800h:01, SYNC 1005h, EMCY 1014h) may have: bit 31,
 * bit 30 and an 11-bit CAN-ID; bit 29 (29-bit CAN-ID) and bits 28..11 are refused. */
#define CO_COB_ID_ALLOWED 0xC00007FFu
#define CO_COB_ID_CAN_ID 0x7FFu
/* Bit 31 of a COB-ID parameter (PDO, EMCY, SDO channel): the object is not valid (disabled). */
#define CO_COB_ID_INVALID 0x80000000u

/* CiA 301's rules of a COB-ID write shared by PDO, SYNC, EMCY and TIME: only CO_COB_ID_ALLOWED
 * bits, no restricted CAN-ID, and no new CAN-ID while the old and the new value are both in use,
 * which (cob_id & in_use_mask) != idle says (the PDO or EMCY valid: bit 31 not set; the SYNC
 * produced: bit 30 not clear; the TIME consumed or produced: bits 31 and 30 not both clear).
 * 0 or CO_SDO_ABORT_VALUE_RANGE. */
uint32_t co_cob_id_check(uint32_t old, uint32_t value, uint32_t in_use_mask, uint32_t idle);

/* The same rules for a COB-ID of an SDO client parameter (1280h..12FFh, valid while bit 31 is
 * clear), whose CAN-ID may also be one of a server's default channel, 600h + node-id or
 * 580h + node-id. */
uint32_t co_sdo_client_cob_id_check(uint32_t old, uint32_t value);

/* CiA 301 table 44: static data types, by their object dictionary index. */
typedef enum co_dtype {
    CO_DT_BOOLEAN = 0x01,
    CO_DT_INTEGER8 = 0x02,
    CO_DT_INTEGER16 = 0x03,
    CO_DT_INTEGER32 = 0x04,
    CO_DT_UNSIGNED8 = 0x05,
    CO_DT_UNSIGNED16 = 0x06,
    CO_DT_UNSIGNED32 = 0x07,
    CO_DT_REAL32 = 0x08,
    CO_DT_VISIBLE_STRING = 0x09,
    CO_DT_OCTET_STRING = 0x0A,
    CO_DT_UNICODE_STRING = 0x0B,
    CO_DT_DOMAIN = 0x0F,
    CO_DT_REAL64 = 0x11,
    CO_DT_INTEGER64 = 0x15,
    CO_DT_UNSIGNED64 = 0x1B
} co_dtype_t;

/* What an abort code means, after CiA 301 table 22, for logs and tools ("unknown abort code" for
 * a code outside the table). */
const char *co_sdo_abort_text(uint32_t code);

/* Little-endian helpers for frame payloads (CANopen is little-endian on the wire). */
static inline uint16_t co_get_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

static inline uint32_t co_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static inline void co_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static inline void co_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

#endif
