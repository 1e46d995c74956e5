/* SPDX-License-Identifier: Apache-2.0 */
/* comaster's values: the CiA 301 data types by name, a value's text parsed into the bytes of an
 * SDO download and an upload's bytes printed, per data type; an object named on the command
 * line (0x203C:2, or a ParameterName of an EDS). Pure functions: tests/comaster tests them. */
#ifndef COMASTER_VALUE_H
#define COMASTER_VALUE_H

#include "co/co_types.h"
#include "eds/eds_reader.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct comaster_type {
    const char *name;  /* CiA 301 name: UNSIGNED16 */
    const char *alias; /* short name: u16 */
    uint16_t code;     /* co_dtype_t */
    uint8_t size;      /* bytes; 0 for the types of any length (strings, DOMAIN) */
} comaster_type_t;

/* By its CiA 301 name or alias, case-insensitive; NULL when unknown. */
const comaster_type_t *comaster_type_by_name(const char *name);
/* By its data type code (an EDS DataType); NULL when comaster does not know it. */
const comaster_type_t *comaster_type_by_code(uint16_t code);
/* The names a user may give, for error messages: "u8 u16 ... domain". */
const char *comaster_type_names(void);

/* A number of the command line or of a network file: decimal, 0x hexadecimal or 0 octal, no
 * sign, 0..max. */
bool comaster_parse_number(const char *text, uint32_t max, uint32_t *out);

/* Parses `text` as a value of `type` into out (cap bytes), *len its length. Integers in decimal
 * or 0x hexadecimal within the type's range, BOOLEAN 0/1/true/false, REAL32/REAL64 as numbers,
 * VISIBLE_STRING as is, OCTET_STRING and DOMAIN as hexadecimal bytes ("01 02 0A" or "01020A").
 * False with a one-line reason in err. */
bool comaster_value_parse(const comaster_type_t *type, const char *text, uint8_t *out, size_t cap,
                          size_t *len, char *err, size_t err_len);

/* The bytes of a DCF entry's value (eds_entry_t) for its DataType, as the master downloads it:
 * an integer type's number as the EDS reader read it (decimal, 0x hexadecimal, 0 octal, $NODEID+
 * number, a '-' sign on a lone number), within the type's range (a sign only for INTEGERn,
 * BOOLEAN 0 or 1); REAL32/REAL64 a decimal number; VISIBLE_STRING its text, OCTET_STRING and
 * DOMAIN hexadecimal bytes, none of them empty. False with the reason (without the entry's name)
 * in err. */
bool comaster_value_from_dcf(const eds_entry_t *e, uint8_t *out, size_t cap, size_t *len, char *err,
                             size_t err_len);

/* How comaster_value_format prints BOOLEAN and the unsigned integers. */
typedef enum comaster_value_style {
    COMASTER_VALUE_DECIMAL = 0, /* 100: what read, get and status show */
    COMASTER_VALUE_HEX          /* 0x64: a DCF's ParameterValue, as comaster concise decode
                                 * writes it */
} comaster_value_style_t;

/* Prints an upload's len bytes as `type` into out. Integers and reals in decimal (BOOLEAN and
 * the unsigned integers in 0x hexadecimal for COMASTER_VALUE_HEX), strings as they are,
 * OCTET_STRING / DOMAIN as hexadecimal bytes. *is_text tells a JSON writer to quote the result.
 * False, with the reason in out, when len does not fit the type. */
bool comaster_value_format(const comaster_type_t *type, const uint8_t *data, size_t len,
                           comaster_value_style_t style, char *out, size_t cap, bool *is_text);

/* An object of the command line. */
typedef struct comaster_object {
    uint16_t index;
    uint8_t sub;
    const char *name;   /* its ParameterName in the EDS, or NULL */
    uint16_t data_type; /* its DataType in the EDS, or 0 */
} comaster_object_t;

/* "0x203C:2", "203C:02", "0x1008" (sub-index 0), or with an EDS (may be NULL) a ParameterName
 * (see eds_find_by_name). False with a one-line reason in err. */
bool comaster_object_parse(const char *text, const eds_t *eds, comaster_object_t *object, char *err,
                           size_t err_len);

#endif
