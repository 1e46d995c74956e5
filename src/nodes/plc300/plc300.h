/* SPDX-License-Identifier: Apache-2.0 */
/* The WEG PLC300 programmable controller as a CANopen slave (its CANopen User's Manual, sections
 * 5 and 6): a plain node (nodes/plain_node.h) whose dictionary (eds/PLC300.eds) holds the
 * network markers, 512 bytes of inputs (3000h-39FCh, %IB/%IW/%ID2000..) that the master writes
 * by SDO or RPDO, and 512 bytes of outputs (4000h-49FCh, %QB/%QW/%QD2000..) that the PLC program
 * writes and TPDOs send. The byte, word and double word objects of an area are views of one
 * memory (Table 5.4's note): a write to one changes every object it overlaps. docs/plc300.md. */
#ifndef NODES_PLC300_H
#define NODES_PLC300_H

#include "nodes/plain_node.h"

#include <stddef.h>

/* Bytes of each marker area, and the number of its first marker (%IB2000 is byte 0). */
#define PLC300_AREA_BYTES 512u
#define PLC300_MARKER_FIRST 2000u

/* The first objects of the views (Table 5.4): the byte, word and double word markers. */
#define PLC300_INPUT_BYTES 0x3000u
#define PLC300_INPUT_WORDS 0x3400u
#define PLC300_INPUT_DWORDS 0x3800u
#define PLC300_OUTPUT_BYTES 0x4000u
#define PLC300_OUTPUT_WORDS 0x4400u
#define PLC300_OUTPUT_DWORDS 0x4800u

/* The manual's identity (6.1.4): WEG's vendor-ID and the PLC300's product code. */
#define PLC300_VENDOR_ID 0x00000123u
#define PLC300_PRODUCT_CODE 0x00000220u

extern const plain_model_t plc300_model;

/* A marker as the PLC300's programming software names it: %IB2000, %QW2004, %ID2508. */
typedef struct plc300_marker {
    bool output;     /* %Q: an output marker; %I: an input marker */
    uint8_t size;    /* 1 (B), 2 (W) or 4 (D) bytes */
    uint16_t index;  /* its object */
    uint16_t offset; /* of its first byte in the area */
} plc300_marker_t;

/* Parses "%IB2000" (the % may be left out, any case); false when it names no marker: a word's
 * number is even, a double word's a multiple of 4, each within its area's 512 bytes. */
bool plc300_marker_parse(const char *text, plc300_marker_t *marker);
/* "%QW2004". */
void plc300_marker_name(const plc300_marker_t *marker, char *buf, size_t len);

/* The marker's value, its bytes little-endian as CANopen sends them. */
uint32_t plc300_marker_get(const plain_node_t *plc, const plc300_marker_t *marker);
/* The PLC program writes the marker (every view of those bytes follows); 0 or the abort code a
 * client would have had. */
uint32_t plc300_marker_set(plain_node_t *plc, const plc300_marker_t *marker, uint32_t value);

/* Byte `offset` (0..511) of the input or output memory. */
uint8_t plc300_area_byte(const plain_node_t *plc, bool output, uint16_t offset);

#endif
