/* The ATV312's I/O assemblies by the names of the Altivar 312 DeviceNet manual: their fields
 * (bits, a byte, a 16-bit word), printed by name and set by name (dnscan poll). */
#ifndef DNSCAN_ASSEMBLIES_H
#define DNSCAN_ASSEMBLIES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct dnscan_field {
    const char *name; /* the manual's name */
    uint8_t byte;     /* first byte */
    uint8_t bit;      /* a bit: 0..7; a byte: 8; a little-endian word: 16 */
} dnscan_field_t;

#define DNSCAN_FIELD_BYTE 8u
#define DNSCAN_FIELD_WORD 16u

typedef struct dnscan_assembly {
    uint16_t instance;
    const char *title;
    bool produced; /* input data (drive to scanner) */
    uint8_t field_count;
    const dnscan_field_t *fields;
} dnscan_assembly_t;

#define DNSCAN_ASSEMBLY_SIZE 4u /* every ATV312 assembly: 4 bytes */

const dnscan_assembly_t *dnscan_assembly(uint16_t instance);
/* A field's value in data (DNSCAN_ASSEMBLY_SIZE bytes); a word is signed (speeds in rpm). */
int32_t dnscan_field_get(const dnscan_field_t *field, const uint8_t *data);
/* The field named `name` (case and '_' for ' ' ignored), or NULL. */
const dnscan_field_t *dnscan_field_by_name(const dnscan_assembly_t *assembly, const char *name);
/* Sets a field; false when the value does not fit (a bit 0/1, a byte 0..255, a word
 * -32768..65535). */
bool dnscan_field_set(const dnscan_field_t *field, long value, uint8_t *data);

#endif
