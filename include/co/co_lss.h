/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 layer setting services (LSS): the wire vocabulary both sides share. The COB-IDs, the
 * command specifiers, the error codes of the confirmed services, the bit timing table and the
 * fastscan fields; the LSS address (the identity object 1018h, sub 1..4). Every LSS frame has
 * DLC 8, byte 0 its command specifier, the reserved bytes 0. The slave is co_lss_slave.h, the
 * master co_lss_master.h; what they do is in docs/lss.md. */
#ifndef CO_LSS_H
#define CO_LSS_H

#include "co_types.h"

#define CO_LSS_ID_MASTER 0x7E5u /* master -> slaves */
#define CO_LSS_ID_SLAVE 0x7E4u  /* slave -> master */
#define CO_LSS_FRAME_LEN 8u

/* A node-id of FFh: the node has none (CiA 305 "not configured"); a node-id to configure is
 * 1..127 or this value. */
#define CO_LSS_NODE_ID_UNCONFIGURED 0xFFu

/* Command specifiers (byte 0). */
enum co_lss_cs {
    CO_LSS_CS_SWITCH_GLOBAL = 0x04,        /* byte 1: co_lss_state_t; not confirmed */
    CO_LSS_CS_CONFIGURE_NODE_ID = 0x11,    /* byte 1: node-id; confirmed with error, spec error */
    CO_LSS_CS_CONFIGURE_BIT_TIMING = 0x13, /* byte 1: table selector, byte 2: table index */
    CO_LSS_CS_ACTIVATE_BIT_TIMING = 0x15,  /* bytes 1-2: switch delay, ms; not confirmed */
    CO_LSS_CS_STORE = 0x17,                /* confirmed with error, spec error */
    CO_LSS_CS_SWITCH_SELECTIVE_VENDOR = 0x40, /* bytes 1-4 of the four: the part of the address */
    CO_LSS_CS_SWITCH_SELECTIVE_PRODUCT = 0x41,
    CO_LSS_CS_SWITCH_SELECTIVE_REVISION = 0x42,
    CO_LSS_CS_SWITCH_SELECTIVE_SERIAL = 0x43,
    CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE = 0x44, /* the selected slave, now configuring */
    CO_LSS_CS_IDENTIFY_VENDOR = 0x46,           /* bytes 1-4: vendor-ID */
    CO_LSS_CS_IDENTIFY_PRODUCT = 0x47,          /* bytes 1-4: product code */
    CO_LSS_CS_IDENTIFY_REVISION_LOW = 0x48,     /* bytes 1-4: the ranges, bounds included */
    CO_LSS_CS_IDENTIFY_REVISION_HIGH = 0x49,
    CO_LSS_CS_IDENTIFY_SERIAL_LOW = 0x4A,
    CO_LSS_CS_IDENTIFY_SERIAL_HIGH = 0x4B,
    CO_LSS_CS_IDENTIFY_NON_CONFIGURED = 0x4C,
    CO_LSS_CS_IDENTIFY_SLAVE = 0x4F, /* the answer to identify remote slave and fastscan */
    CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE = 0x50, /* the answer to 4Ch */
    CO_LSS_CS_FASTSCAN = 0x51,                      /* co_lss_fastscan_* fields below */
    CO_LSS_CS_INQUIRE_VENDOR = 0x5A,                /* answer bytes 1-4: the value */
    CO_LSS_CS_INQUIRE_PRODUCT = 0x5B,
    CO_LSS_CS_INQUIRE_REVISION = 0x5C,
    CO_LSS_CS_INQUIRE_SERIAL = 0x5D,
    CO_LSS_CS_INQUIRE_NODE_ID = 0x5E /* answer byte 1: the active node-id */
};

/* The two states of an LSS slave (switch state global, byte 1). */
typedef enum co_lss_state { CO_LSS_WAITING = 0, CO_LSS_CONFIGURATION = 1 } co_lss_state_t;

/* Error codes (byte 1) of the confirmations; 255 says that byte 2 holds the device's own code. */
#define CO_LSS_OK 0u
#define CO_LSS_NODE_ID_OUT_OF_RANGE 1u
#define CO_LSS_BIT_TIMING_NOT_SUPPORTED 1u
#define CO_LSS_STORE_NOT_SUPPORTED 1u
#define CO_LSS_STORE_MEDIA_ERROR 2u
#define CO_LSS_SPECIFIC_ERROR 255u

/* Bit timing table 0, the CiA table: index 0..9 (5 is reserved, 9 automatic bit rate detection). */
#define CO_LSS_BIT_TIMING_TABLE 0u
#define CO_LSS_BIT_TIMING_INDEX_MAX 9u
#define CO_LSS_BIT_TIMING_AUTO 9u

/* The bit rate of an index of table 0 in kbit/s, 0 for the reserved index, automatic detection
 * and anything above 9 (src/canopen/common/lss_wire.c). */
uint16_t co_lss_bit_rate_kbit(uint8_t index);
/* The index of table 0 for a bit rate in kbit/s, CO_LSS_BIT_TIMING_INDEX_MAX + 1 when none. */
uint8_t co_lss_bit_timing_index(uint16_t kbit);

/* Fastscan (51h): bytes 1-4 the ID number, byte 5 the bit checked (31..0: the bits 31..bit of
 * the ID number are compared; 80h: every non-configured slave in waiting state answers and starts
 * over), byte 6 the part of the address checked (LSS sub), byte 7 the part the slave checks next
 * once bit 0 matched (LSS next); a slave whose sub 3 matched to bit 0, next below sub, enters the
 * configuration state. */
#define CO_LSS_FASTSCAN_RESET 0x80u
#define CO_LSS_FASTSCAN_BIT_MAX 31u
#define CO_LSS_FASTSCAN_PARTS 4u

/* The LSS address: 1018h sub 1..4, also the order of the fastscan parts. */
typedef enum co_lss_part {
    CO_LSS_VENDOR = 0,
    CO_LSS_PRODUCT = 1,
    CO_LSS_REVISION = 2,
    CO_LSS_SERIAL = 3
} co_lss_part_t;

typedef struct co_lss_address {
    uint32_t part[CO_LSS_FASTSCAN_PARTS]; /* co_lss_part_t order */
} co_lss_address_t;

/* Fills an LSS frame: command specifier, then len bytes of data after it, the rest 0. */
void co_lss_frame(co_frame_t *frame, uint32_t id, uint8_t cs, const uint8_t *data, size_t len);

/* The name of a command specifier ("switch state global", ...), NULL when none: for the
 * tools; a firmware that never calls it links none of it. */
const char *co_lss_cs_name(uint8_t cs);

#endif
