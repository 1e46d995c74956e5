/* SPDX-License-Identifier: Apache-2.0 */
/* The I/O assemblies of the Altivar 312 DeviceNet card by the names of its manual's tables:
 * 20, 21, 100 (consumed) and 70, 71, 101 (produced), 4 bytes each, little-endian. One table for
 * every program that shows or sets I/O data by name (cotrace's DeviceNet decoder, dnscan poll);
 * the drive builds the same bytes in src/drive/devicenet/odva.c and needs no names. */
#ifndef CIP_ASSEMBLY_H
#define CIP_ASSEMBLY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* What a field holds, and so how it is read and shown. */
typedef enum cip_field_kind {
    CIP_FIELD_BIT,          /* one bit of a byte */
    CIP_FIELD_STATE,        /* a byte: the Control supervisor's state (0x29 attribute 6) */
    CIP_FIELD_RPM,          /* an INT word: a speed in rpm */
    CIP_FIELD_CONTROL_WORD, /* a UINT word: the DRIVECOM control word, 6040h */
    CIP_FIELD_STATUS_WORD   /* a UINT word: the DRIVECOM status word, 6041h */
} cip_field_kind_t;

typedef struct cip_field {
    const char *name; /* the manual's name */
    cip_field_kind_t kind;
    uint8_t byte; /* its (first) byte */
    uint8_t bit;  /* CIP_FIELD_BIT: 0..7 */
} cip_field_t;

typedef struct cip_assembly {
    uint16_t instance;
    const char *title;
    bool produced; /* input data (drive to scanner) */
    uint8_t field_count;
    const cip_field_t *fields;
} cip_assembly_t;

#define CIP_ASSEMBLY_SIZE 4u /* every assembly of the card: 4 bytes */

/* The assembly of that instance, or NULL. */
const cip_assembly_t *cip_assembly(uint16_t instance);
/* A field's value in data (CIP_ASSEMBLY_SIZE bytes): a speed signed, the words unsigned. */
int32_t cip_field_get(const cip_field_t *field, const uint8_t *data);
/* The field named `name` (case and '_' for ' ' ignored), or NULL. */
const cip_field_t *cip_field_by_name(const cip_assembly_t *assembly, const char *name);
/* Sets a field; false when the value does not fit (a bit 0/1, a byte 0..255, a word
 * -32768..65535). */
bool cip_field_set(const cip_field_t *field, long value, uint8_t *data);
/* The name of the Control supervisor's state (0 "Vendor specific" .. 7 "Faulted", else
 * "reserved"). */
const char *cip_supervisor_state_name(uint8_t state);

#endif
