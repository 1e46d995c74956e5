/* SPDX-License-Identifier: Apache-2.0 */
/* The process image addressed as the PLC300 manual's network markers (CANopen communication
 * manual, 5.4 "Manufacturer specific objects" and 7.2 "Characteristics of the CANopen master"):
 * %IB/%IW/%ID for the 512 bytes of inputs, %QB/%QW/%QD for the 512 bytes of outputs, numbered by
 * byte from 2000 (%IB2000 .. %IB2511, %IW2000 .. %IW2510 even, %ID2000 .. %ID2508 multiples of
 * 4). Byte, word and double word share the same bytes, least significant byte first
 * (docs/decisions.md, D-IMAGE-ADDRESS). Owns the parsing of an address and the value read from or
 * put into the image's bytes; the network master sends what changed (co_net_master_write_output).
 */
#ifndef CO_IMAGE_ADDRESS_H
#define CO_IMAGE_ADDRESS_H

#include "co_types.h"

#define CO_IMAGE_ADDRESS_FIRST 2000u /* %IB2000: the first byte of the image */
#define CO_IMAGE_ADDRESS_IMAGE_SIZE 512u

typedef enum co_image_area {
    CO_IMAGE_INPUT,  /* %I: the slaves' TPDOs, read by the master */
    CO_IMAGE_OUTPUT, /* %Q: the slaves' RPDOs, written by the master */
} co_image_area_t;

typedef struct co_image_address {
    co_image_area_t area;
    uint8_t size;    /* 1 (B), 2 (W) or 4 (D) bytes */
    uint16_t offset; /* of its first byte in the image: the address minus 2000 */
} co_image_address_t;

/* "%IW2002" as an address: % then I or Q, B, W or D, the decimal byte number (no sign, no
 * spaces, upper or lower case). False for anything else, an address outside the 512 bytes, or a
 * word or double word not aligned to its size (%IW2001). */
bool co_image_address_parse(const char *text, co_image_address_t *address);

/* The value at `address` in an image of 512 bytes (little-endian, zero-extended). */
uint32_t co_image_address_get(const uint8_t *image, const co_image_address_t *address);

/* Writes `value`'s low address->size bytes, least significant first, to bytes[0 .. size): the
 * bytes to give co_net_master_write_output at address->offset. False when the value does not
 * fit in the size (a value above 255 for a byte). */
bool co_image_address_bytes(const co_image_address_t *address, uint32_t value, uint8_t *bytes);

#endif
