/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace's decoder: says what one CAN frame means in CANopen terms, one line per frame (the
 * format is documented in docs/cotrace.md and is stable: scripts and tests compare it).
 *
 * It keeps what a meaning needs from earlier frames: the SDO transfer under way per server node
 * (segmented and block transfers are followed across frames, in both directions) and a node
 * guarding request waiting for its reply. PDOs are named by the predefined connection set, and
 * decoded into objects and values when an EDS or DCF of their node is given. */
#ifndef COTRACE_DECODER_H
#define COTRACE_DECODER_H

#include "co/co_emcy_consumer.h"
#include "eds/eds_reader.h"

#include <linux/can.h>

#define COTRACE_NODE_MAX 127u
/* Bytes of a segmented or block transfer kept to show its value when it completes. */
#define COTRACE_SDO_KEEP 64u

typedef enum cotrace_sdo_kind {
    COTRACE_SDO_IDLE,
    COTRACE_SDO_DOWNLOAD,
    COTRACE_SDO_UPLOAD,
    COTRACE_SDO_BLOCK_DOWNLOAD,
    COTRACE_SDO_BLOCK_UPLOAD
} cotrace_sdo_kind_t;

/* The SDO transfer of one server node, as far as the trace shows it. */
typedef struct cotrace_sdo {
    cotrace_sdo_kind_t kind;
    uint16_t index;
    uint8_t sub;
    bool expedited;     /* a download initiate that carried its data */
    bool in_subblock;   /* block transfer: the next frames of the data direction are segments */
    bool last_sent;     /* block transfer: the segment flagged last was seen */
    uint8_t block_size; /* segments per block, from the server (download) or client (upload) */
    uint32_t size;      /* indicated size, 0 when not indicated */
    uint32_t count;     /* bytes transferred so far (committed by acknowledgements in blocks) */
    uint32_t block_start;
    uint8_t data[COTRACE_SDO_KEEP];
} cotrace_sdo_t;

/* Most PDOs read from an EDS (a device has at most 512 of each direction; real ones a few). */
#define COTRACE_PDO_MAX 64u

typedef struct cotrace_pdo {
    uint16_t cob_id;
    bool transmit; /* TPDO: sent by the node */
    uint16_t number;
    uint16_t mapping; /* 1600h.. / 1A00h.. in the EDS, 0 when there is no EDS */
} cotrace_pdo_t;

typedef struct cotrace_decoder {
    cotrace_sdo_t sdo[COTRACE_NODE_MAX + 1];
    bool guard_pending[COTRACE_NODE_MAX + 1];
    const eds_t *eds; /* dictionary of eds_node, or NULL */
    uint8_t eds_node;
    const co_emcy_code_table_t *vendor;  /* EMCY codes consulted first, or NULL */
    cotrace_pdo_t pdos[COTRACE_PDO_MAX]; /* the PDOs of the EDS */
    size_t pdo_count;
} cotrace_decoder_t;

/* A decoder with no transfer under way; eds (with its node-id) and vendor may be NULL / 0. */
void cotrace_decoder_init(cotrace_decoder_t *dec, const eds_t *eds, uint8_t eds_node,
                          const co_emcy_code_table_t *vendor);

/* The CiA 402 command a control word 6040h gives: "Shutdown", "Enable operation", ...; NULL for
 * one CiA 402 does not define. The state a status word shows is the CiA 402 master helper's
 * (co_cia402_master.h), as comaster drive prints it. */
const char *cotrace_control_word_command(uint16_t word);

/* Writes the meaning of `frame` into out (always NUL-terminated, truncated to cap). */
void cotrace_decode(cotrace_decoder_t *dec, const struct can_frame *frame, char *out, size_t cap);

#endif
