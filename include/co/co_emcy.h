/* SPDX-License-Identifier: Apache-2.0 */
/* EMCY producer (CiA 301 section 7.2.7): 1014h COB-ID, 1015h inhibit time, 1001h error register,
 * 1003h pre-defined error field (history), and the application API to raise and clear errors.
 *
 * Frames: [code LSB, code MSB, 1001h, msef[0..4]] on the CAN-ID of 1014h, none while 1014h bit 31
 * (invalid) is set. EMCY is a Pre-operational and Operational service (CiA 301 table 74):
 * an error raised or cleared in Stopped updates 1001h and 1003h but sends no frame, and frames
 * still waiting for their inhibit time are dropped when the node stops. Successive frames are at
 * least 1015h x 100 us apart; the ones that must wait are queued (CO_CONFIG_EMCY_QUEUE frames; a
 * frame that finds the queue full is dropped, the history still records the error). */
#ifndef CO_EMCY_H
#define CO_EMCY_H

#include "co_config.h"
#include "co_nmt.h"
#include "co_od.h"

/* Error register 1001h bits (CiA 301 table 48). */
#define CO_ERR_REG_GENERIC 0x01u
#define CO_ERR_REG_CURRENT 0x02u
#define CO_ERR_REG_VOLTAGE 0x04u
#define CO_ERR_REG_TEMPERATURE 0x08u
#define CO_ERR_REG_COMMUNICATION 0x10u
#define CO_ERR_REG_PROFILE 0x20u
#define CO_ERR_REG_MANUFACTURER 0x80u

/* Emergency error codes used by the stack (CiA 301 table 21). */
enum co_emcy_code {
    CO_EMCY_NO_ERROR = 0x0000,
    CO_EMCY_GENERIC = 0x1000,
    CO_EMCY_COMMUNICATION = 0x8100, /* generic: the SYNC consumer's time-out (D-SYNC-TIMEOUT) */
    CO_EMCY_CAN_OVERRUN = 0x8110,
    CO_EMCY_CAN_PASSIVE = 0x8120,
    CO_EMCY_HEARTBEAT = 0x8130, /* life guard or heartbeat error */
    CO_EMCY_BUS_OFF = 0x8140,   /* recovered from bus-off */
    CO_EMCY_PDO_LENGTH = 0x8210,
    CO_EMCY_PDO_LENGTH_EXCEEDED = 0x8220,
    CO_EMCY_SYNC_LENGTH = 0x8240,
    CO_EMCY_RPDO_TIMEOUT = 0x8250
};

typedef struct co_emcy_error {
    uint16_t code;
    uint8_t reg;
} co_emcy_error_t;

typedef struct co_emcy {
    co_emcy_error_t active[CO_CONFIG_EMCY_HISTORY]; /* errors raised and not cleared */
    uint8_t active_count;
    co_frame_t queue[CO_CONFIG_EMCY_QUEUE]; /* frames waiting for the inhibit time */
    uint8_t queue_head;
    uint8_t queue_count;
    co_time_t inhibit_end; /* no EMCY may be sent before this time */
} co_emcy_t;

/* Reset communication keeps the active errors and recomputes 1001h after the dictionary was
 * restored: the PDO engine and the SYNC consumer end theirs in their own reset, the application's
 * stay (it is not reset). Reset node forgets them all (the application restarts). Queued frames
 * and the inhibit time are dropped by both (docs/error-control.md, "Errors and resets"). */
void co_emcy_reset(co_node_t *node, co_nmt_reset_t scope);
/* Sends queued frames whose inhibit time elapsed; returns when the next one may go. */
co_time_t co_emcy_process(co_node_t *node, co_time_t now);
uint32_t co_emcy_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len);

/* Raises an error: records it as active, sets 1001h (the generic bit and `reg`), puts it at the
 * top of 1003h and sends the EMCY frame (subject to the inhibit time). msef may be NULL (five
 * zero bytes). Returns false, and does nothing, for code 0, for an error that is already active
 * or when CO_CONFIG_EMCY_HISTORY errors are active. */
bool co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg, const uint8_t msef[5]);
/* Clears an active error and recomputes 1001h from the errors still active; when the last one
 * clears, the "error reset" EMCY (code 0, 1001h, zeros) is sent. Unknown codes are ignored. */
void co_emcy_clear(co_node_t *node, uint16_t code);
bool co_emcy_is_active(const co_node_t *node, uint16_t code);

#endif
