/* SPDX-License-Identifier: Apache-2.0 */
#include "comaster/value.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const comaster_type_t types[] = {
    {"BOOLEAN", "bool", CO_DT_BOOLEAN, 1},
    {"INTEGER8", "i8", CO_DT_INTEGER8, 1},
    {"INTEGER16", "i16", CO_DT_INTEGER16, 2},
    {"INTEGER32", "i32", CO_DT_INTEGER32, 4},
    {"INTEGER64", "i64", CO_DT_INTEGER64, 8},
    {"UNSIGNED8", "u8", CO_DT_UNSIGNED8, 1},
    {"UNSIGNED16", "u16", CO_DT_UNSIGNED16, 2},
    {"UNSIGNED32", "u32", CO_DT_UNSIGNED32, 4},
    {"UNSIGNED64", "u64", CO_DT_UNSIGNED64, 8},
    {"REAL32", "f32", CO_DT_REAL32, 4},
    {"REAL64", "f64", CO_DT_REAL64, 8},
    {"VISIBLE_STRING", "string", CO_DT_VISIBLE_STRING, 0},
    {"OCTET_STRING", "octets", CO_DT_OCTET_STRING, 0},
    {"DOMAIN", "domain", CO_DT_DOMAIN, 0},
};

#define TYPE_COUNT (sizeof types / sizeof types[0])

const comaster_type_t *comaster_type_by_name(const char *name)
{
    for (size_t i = 0; i < TYPE_COUNT; i++) {
        if (strcasecmp(types[i].name, name) == 0 || strcasecmp(types[i].alias, name) == 0)
            return &types[i];
    }
    return NULL;
}

const comaster_type_t *comaster_type_by_code(uint16_t code)
{
    for (size_t i = 0; i < TYPE_COUNT; i++) {
        if (types[i].code == code)
            return &types[i];
    }
    return NULL;
}

const char *comaster_type_names(void)
{
    return "bool i8 i16 i32 i64 u8 u16 u32 u64 f32 f64 string octets domain (or the CiA 301 "
           "names: UNSIGNED16, REAL32, VISIBLE_STRING ...)";
}

bool comaster_parse_number(const char *text, uint32_t max, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (end == text || *end != '\0' || errno != 0 || text[0] == '-' || v > max)
        return false;
    *out = (uint32_t)v;
    return true;
}

static bool is_signed(const comaster_type_t *type)
{
    return type->code == CO_DT_INTEGER8 || type->code == CO_DT_INTEGER16 ||
           type->code == CO_DT_INTEGER32 || type->code == CO_DT_INTEGER64;
}

static bool is_real(const comaster_type_t *type)
{
    return type->code == CO_DT_REAL32 || type->code == CO_DT_REAL64;
}

static bool is_hex_bytes(const comaster_type_t *type)
{
    return type->code == CO_DT_OCTET_STRING || type->code == CO_DT_DOMAIN;
}

static void put_le(uint8_t *out, uint64_t value, size_t size)
{
    for (size_t i = 0; i < size; i++)
        out[i] = (uint8_t)(value >> (8 * i));
}

static uint64_t get_le(const uint8_t *data, size_t size)
{
    uint64_t value = 0;
    for (size_t i = 0; i < size; i++)
        value |= (uint64_t)data[i] << (8 * i);
    return value;
}

static bool parse_signed(const comaster_type_t *type, const char *text, uint64_t *bits, char *err,
                         size_t err_len)
{
    int64_t max =
        type->size == 8 ? INT64_MAX : (int64_t)((UINT64_C(1) << (8 * type->size - 1)) - 1);
    int64_t min = -max - 1;
    char *end;
    errno = 0;
    long long v = strtoll(text, &end, 0);
    if (end == text || *end != '\0') {
        snprintf(err, err_len, "'%s' is not an integer: give a number such as -12 or 0x1F", text);
        return false;
    }
    if (errno == ERANGE || v < min || v > max) {
        snprintf(err, err_len, "%s is out of range for %s (%" PRId64 "..%" PRId64 ")", text,
                 type->name, min, max);
        return false;
    }
    *bits = (uint64_t)v;
    return true;
}

static bool parse_unsigned(const comaster_type_t *type, const char *text, uint64_t *bits, char *err,
                           size_t err_len)
{
    uint64_t max = type->size == 8 ? UINT64_MAX : (UINT64_C(1) << (8 * type->size)) - 1;
    if (type->code == CO_DT_BOOLEAN) {
        if (strcasecmp(text, "true") == 0 || strcasecmp(text, "false") == 0) {
            *bits = strcasecmp(text, "true") == 0;
            return true;
        }
        max = 1;
    }
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (end == text || *end != '\0' || text[strspn(text, " \t")] == '-') {
        snprintf(err, err_len, "'%s' is not a %s: give a number such as 12 or 0x1F%s", text,
                 type->name, type->code == CO_DT_BOOLEAN ? ", or true/false" : "");
        return false;
    }
    if (errno == ERANGE || v > max) {
        snprintf(err, err_len, "%s is out of range for %s (0..%" PRIu64 ")", text, type->name, max);
        return false;
    }
    *bits = v;
    return true;
}

static bool parse_real(const comaster_type_t *type, const char *text, uint64_t *bits, char *err,
                       size_t err_len)
{
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        snprintf(err, err_len, "'%s' is not a %s: give a finite number such as 1.5 or -2e3", text,
                 type->name);
        return false;
    }
    if (type->code == CO_DT_REAL32) {
        if (fabs(v) > FLT_MAX) {
            snprintf(err, err_len, "%s is out of range for REAL32 (at most %g in magnitude)", text,
                     (double)FLT_MAX);
            return false;
        }
        float f = (float)v;
        uint32_t u;
        memcpy(&u, &f, sizeof u);
        *bits = u;
    } else {
        memcpy(bits, &v, sizeof *bits);
    }
    return true;
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = (char)tolower((unsigned char)c);
    return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

static bool parse_hex_bytes(const char *text, uint8_t *out, size_t cap, size_t *len, char *err,
                            size_t err_len)
{
    *len = 0;
    for (const char *p = text; *p;) {
        if (isspace((unsigned char)*p)) {
            p++;
            continue;
        }
        int hi = hex_digit(p[0]);
        int lo = hi < 0 ? -1 : hex_digit(p[1]);
        if (lo < 0) {
            snprintf(err, err_len, "'%s' is not hexadecimal bytes: give them as 01 02 0A or 01020A",
                     text);
            return false;
        }
        if (*len == cap) {
            snprintf(err, err_len, "more than %zu bytes", cap);
            return false;
        }
        out[(*len)++] = (uint8_t)(hi << 4 | lo);
        p += 2;
    }
    return true;
}

bool comaster_value_parse(const comaster_type_t *type, const char *text, uint8_t *out, size_t cap,
                          size_t *len, char *err, size_t err_len)
{
    if (is_hex_bytes(type))
        return parse_hex_bytes(text, out, cap, len, err, err_len);
    if (type->code == CO_DT_VISIBLE_STRING) {
        *len = strlen(text);
        if (*len > cap) {
            snprintf(err, err_len, "the string is longer than %zu bytes", cap);
            return false;
        }
        memcpy(out, text, *len);
        return true;
    }
    uint64_t bits;
    bool ok = is_real(type)     ? parse_real(type, text, &bits, err, err_len)
              : is_signed(type) ? parse_signed(type, text, &bits, err, err_len)
                                : parse_unsigned(type, text, &bits, err, err_len);
    if (!ok)
        return false;
    put_le(out, bits, type->size);
    *len = type->size;
    return true;
}

/* The range of an integer type (BOOLEAN: 0..1) as signed and unsigned bounds. */
static void integer_range(const comaster_type_t *type, int64_t *min, uint64_t *max)
{
    unsigned bits = 8u * type->size;
    if (type->code == CO_DT_BOOLEAN) {
        *min = 0;
        *max = 1;
    } else if (is_signed(type)) {
        *max = (UINT64_C(1) << (bits - 1)) - 1;
        *min = -(int64_t)*max - 1;
    } else {
        *min = 0;
        *max = bits == 64 ? UINT64_MAX : (UINT64_C(1) << bits) - 1;
    }
}

/* An integer of the reader ($NODEID resolved, negative in two's complement) within the type's
 * range: a hexadecimal bit pattern of a negative number (0xFFFF for an INTEGER16) is out of it
 * (docs/decisions.md, D-DCF-VALUES). */
static bool dcf_integer(const comaster_type_t *type, const eds_entry_t *e, uint64_t *bits,
                        char *err, size_t err_len)
{
    int64_t min;
    uint64_t max;
    integer_range(type, &min, &max);
    if (!e->has_value) {
        snprintf(err, err_len,
                 "not a number for %s: give 12, -12 (a signed type), 0x1F, 017 or "
                 "$NODEID+number",
                 type->name);
        return false;
    }
    bool fits = e->negative ? (int64_t)e->value >= min : e->value <= max;
    if (!fits) {
        if (min < 0)
            snprintf(err, err_len, "out of range for %s (%" PRId64 "..%" PRIu64 ")", type->name,
                     min, max);
        else
            snprintf(err, err_len, "out of range for %s (0..%" PRIu64 "%s)", type->name, max,
                     e->negative ? ", no sign" : "");
        return false;
    }
    *bits = e->value;
    return true;
}

bool comaster_value_from_dcf(const eds_entry_t *e, uint8_t *out, size_t cap, size_t *len, char *err,
                             size_t err_len)
{
    const comaster_type_t *type = comaster_type_by_code(e->data_type);
    const char *text = e->text ? e->text : "";
    if (!type) {
        snprintf(err, err_len, "comaster cannot write a value of DataType 0x%04X (it writes %s)",
                 e->data_type,
                 "BOOLEAN, INTEGER8..64, UNSIGNED8..64, REAL32, REAL64, "
                 "VISIBLE_STRING, OCTET_STRING and DOMAIN");
        return false;
    }
    if (type->size == 0 && text[0] == '\0') {
        snprintf(err, err_len, "an empty %s: nothing to write", type->name);
        return false;
    }
    if (is_real(type) && strspn(text, "0123456789+-.eE") != strlen(text)) {
        snprintf(err, err_len, "not a number for %s: give a decimal number such as 1.5 or -2e3",
                 type->name);
        return false;
    }
    if (type->size == 0 || is_real(type))
        return comaster_value_parse(type, text, out, cap, len, err, err_len);
    uint64_t bits;
    if (!dcf_integer(type, e, &bits, err, err_len))
        return false;
    if (cap < type->size) {
        snprintf(err, err_len, "more than %zu bytes", cap);
        return false;
    }
    put_le(out, bits, type->size);
    *len = type->size;
    return true;
}

static void format_hex_bytes(const uint8_t *data, size_t len, char *out, size_t cap)
{
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < len && used + 4 <= cap; i++)
        used += (size_t)snprintf(out + used, cap - used, i ? " %02X" : "%02X", data[i]);
}

static void format_number(const comaster_type_t *type, uint64_t bits, comaster_value_style_t style,
                          char *out, size_t cap)
{
    if (type->code == CO_DT_REAL32) {
        uint32_t u = (uint32_t)bits;
        float f;
        memcpy(&f, &u, sizeof f);
        snprintf(out, cap, "%.9g", (double)f);
    } else if (type->code == CO_DT_REAL64) {
        double d;
        memcpy(&d, &bits, sizeof d);
        snprintf(out, cap, "%.17g", d);
    } else if (is_signed(type)) {
        unsigned shift = 64u - 8u * type->size;
        int64_t v = (int64_t)(bits << shift) >> shift; /* sign-extends the type's top bit */
        snprintf(out, cap, "%" PRId64, v);
    } else if (style == COMASTER_VALUE_HEX) {
        snprintf(out, cap, "0x%" PRIX64, bits);
    } else {
        snprintf(out, cap, "%" PRIu64, bits);
    }
}

bool comaster_value_format(const comaster_type_t *type, const uint8_t *data, size_t len,
                           comaster_value_style_t style, char *out, size_t cap, bool *is_text)
{
    *is_text = type->size == 0;
    if (is_hex_bytes(type)) {
        format_hex_bytes(data, len, out, cap);
        return true;
    }
    if (type->code == CO_DT_VISIBLE_STRING) {
        /* A string ends at its first NUL, if the server sent one. */
        size_t n = strnlen((const char *)data, len);
        snprintf(out, cap, "%.*s", (int)n, (const char *)data);
        return true;
    }
    if (len != type->size) {
        *is_text = true;
        snprintf(out, cap, "%zu bytes do not fit %s (%u bytes)", len, type->name, type->size);
        return false;
    }
    format_number(type, get_le(data, len), style, out, cap);
    /* A NaN or an infinity is no JSON number: it goes as the string printf wrote ("nan"); nor is
     * a hexadecimal one. */
    *is_text = is_real(type) ? !isdigit((unsigned char)out[out[0] == '-'])
                             : style == COMASTER_VALUE_HEX && !is_signed(type);
    return true;
}

/* "0x203C:2", "203C:2", "0x1008": index in hexadecimal (four digits without 0x, so that a
 * parameter code such as ACC is a name), sub-index in decimal or 0x hexadecimal. */
static bool parse_numeric_object(const char *text, comaster_object_t *object)
{
    const char *p = text;
    bool prefixed = p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
    if (prefixed)
        p += 2;
    if (!isxdigit((unsigned char)*p))
        return false;
    char *end;
    unsigned long index = strtoul(p, &end, 16);
    if (end - p > 4 || (!prefixed && end - p != 4))
        return false;
    unsigned long sub = 0;
    if (*end == ':') {
        const char *s = end + 1;
        if (!isdigit((unsigned char)*s))
            return false;
        errno = 0;
        sub = strtoul(s, &end, 0);
        if (errno || sub > 0xFF)
            return false;
    }
    if (*end != '\0')
        return false;
    object->index = (uint16_t)index;
    object->sub = (uint8_t)sub;
    return true;
}

/* Up to this many codes are suggested for a name the EDS does not know. */
#define SUGGESTED_CODES_MAX 3u

/* "no object of the EDS is named 'ACX' (the closest codes are ACC, AC2): ..." */
static void unknown_name(const eds_t *eds, const char *text, char *err, size_t err_len)
{
    const eds_entry_t *codes[SUGGESTED_CODES_MAX];
    size_t count = eds_closest_codes(eds, text, codes, SUGGESTED_CODES_MAX);
    char closest[256] = "";
    size_t used = 0;
    for (size_t i = 0; i < count && used < sizeof closest; i++) {
        const char *lead = i > 0        ? ", "
                           : count == 1 ? " (the closest code is "
                                        : " (the closest codes are ";
        int code_len = (int)strcspn(codes[i]->name, " ");
        used += (size_t)snprintf(closest + used, sizeof closest - used, "%s%.*s%s", lead, code_len,
                                 codes[i]->name, i + 1 == count ? ")" : "");
    }
    snprintf(err, err_len,
             "no object of the EDS is named '%s'%s: give its ParameterName (or code, ACC), or "
             "INDEX:SUB such as 0x203C:2",
             text, closest);
}

bool comaster_object_parse(const char *text, const eds_t *eds, comaster_object_t *object, char *err,
                           size_t err_len)
{
    memset(object, 0, sizeof *object);
    if (parse_numeric_object(text, object)) {
        const eds_entry_t *e = eds ? eds_find(eds, object->index, object->sub) : NULL;
        if (e) {
            object->name = eds_name(eds, object->index, object->sub);
            object->data_type = e->data_type;
        }
        return true;
    }
    if (!eds || eds->count == 0) {
        snprintf(err, err_len,
                 "'%s' is not an object: give INDEX:SUB such as 0x203C:2, or a name with --eds "
                 "FILE (or an EDS for the node's identity in the EDS directory)",
                 text);
        return false;
    }
    const eds_entry_t *e;
    switch (eds_find_by_name(eds, text, &e)) {
    case EDS_LOOKUP_FOUND:
        break;
    case EDS_LOOKUP_AMBIGUOUS:
        snprintf(err, err_len,
                 "'%s' names several objects of the EDS (one is %04X:%02X '%s'): give more of "
                 "the name, or INDEX:SUB",
                 text, e->index, e->sub == EDS_OBJECT ? 0 : e->sub, e->name);
        return false;
    case EDS_LOOKUP_NONE:
        unknown_name(eds, text, err, err_len);
        return false;
    }
    object->index = e->index;
    object->sub = e->sub == EDS_OBJECT ? 0 : (uint8_t)e->sub;
    object->name = e->name;
    object->data_type = e->data_type;
    return true;
}
