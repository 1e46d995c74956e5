/* SPDX-License-Identifier: Apache-2.0 */
#include "eds/eds_reader.h"

#include "eds/ini_reader.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* CiA 306: an object's section is named by its index in four hexadecimal digits, a sub-index's
 * adds "sub" and the sub-index (00h..FFh) in one or two. */
#define EDS_INDEX_DIGITS 4u
#define EDS_SUB_WORD "sub"
#define EDS_SUB_WORD_LEN 3u
#define EDS_SUB_DIGITS_MAX 2u

/* The value of an ASCII hexadecimal digit, or -1. */
static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* The number of hexadecimal digits `s` starts with. */
static size_t hex_run(const char *s)
{
    size_t n = 0;
    while (hex_digit(s[n]) >= 0)
        n++;
    return n;
}

static unsigned hex_value(const char *s, size_t digits)
{
    unsigned value = 0;
    for (size_t i = 0; i < digits; i++)
        value = value << 4 | (unsigned)hex_digit(s[i]);
    return value;
}

typedef enum section_kind {
    SECTION_OTHER,    /* [FileInfo], [DeviceInfo], [1F22Value]...: not an object's */
    SECTION_OBJECT,   /* [1A05], [1A05sub1] */
    SECTION_MALFORMED /* meant as an object's, in a notation CiA 306 does not have */
} section_kind_t;

/* A name that starts as a number would (a sign, 0x, hex digits) and stops there or goes on with
 * "sub" or a blank is meant as an object's section ([0x12], [12], [1018sub], [1018 sub1]); one
 * that goes on with a word is a section of another kind ([1F22Value], [DeviceInfo]). */
static bool looks_like_an_object(const char *name)
{
    const char *p = name;
    if (*p == '+' || *p == '-')
        p++;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
        p += 2;
    size_t digits = hex_run(p);
    const char *rest = p + digits;
    return digits > 0 && (*rest == '\0' || isspace((unsigned char)*rest) ||
                          strncasecmp(rest, EDS_SUB_WORD, EDS_SUB_WORD_LEN) == 0);
}

/* CiA 306 names an object's section by its index in four hexadecimal digits ([1A05]) and a
 * sub-index's by the index, "sub" and the sub-index in one or two ([1A05sub1]), in any case. */
static section_kind_t parse_section(const char *name, uint16_t *index, uint16_t *sub)
{
    if (hex_run(name) == EDS_INDEX_DIGITS) {
        const char *rest = name + EDS_INDEX_DIGITS;
        *index = (uint16_t)hex_value(name, EDS_INDEX_DIGITS);
        *sub = EDS_OBJECT;
        if (*rest == '\0')
            return SECTION_OBJECT;
        bool has_sub = strncasecmp(rest, EDS_SUB_WORD, EDS_SUB_WORD_LEN) == 0;
        const char *sub_digits = has_sub ? rest + EDS_SUB_WORD_LEN : rest;
        size_t digits = has_sub ? hex_run(sub_digits) : 0;
        if (digits >= 1 && digits <= EDS_SUB_DIGITS_MAX && sub_digits[digits] == '\0') {
            *sub = (uint16_t)hex_value(sub_digits, digits);
            return SECTION_OBJECT;
        }
    }
    return looks_like_an_object(name) ? SECTION_MALFORMED : SECTION_OTHER;
}

/* CiA 306 values: decimal, 0x hexadecimal, octal with a leading 0, and "$NODEID+x" / "x+$NODEID";
 * blanks around the terms. A term starts with a digit (no sign), and the sum fits 64 bits. */
static bool parse_sum(const char *text, uint8_t node_id, uint64_t *value)
{
    *value = 0;
    const char *p = text;
    if (*p == '\0')
        return false;
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        uint64_t term;
        if (strncasecmp(p, "$NODEID", 7) == 0) {
            term = node_id;
            p += 7;
        } else if (isdigit((unsigned char)*p)) {
            char *end;
            errno = 0;
            term = strtoull(p, &end, 0);
            if (errno != 0)
                return false;
            p = end;
        } else {
            return false;
        }
        if (term > UINT64_MAX - *value)
            return false;
        *value += term;
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '\0')
            return true;
        if (*p++ != '+')
            return false;
    }
}

/* A value as parse_sum reads it, or a lone number with a '-' sign (-1234, -0x10, -010), which
 * CiA 306 allows for the signed types: *value is then its two's complement. A sign is never part
 * of a $NODEID expression, whose terms are unsigned (docs/decisions.md, D-DCF-VALUES). */
static bool parse_signed_value(const char *text, uint8_t node_id, uint64_t *value, bool *negative)
{
    const char *p = text;
    while (isspace((unsigned char)*p))
        p++;
    if (*p != '-')
        return parse_sum(text, node_id, value);
    if (!isdigit((unsigned char)p[1]))
        return false;
    char *end;
    errno = 0;
    long long v = strtoll(p, &end, 0);
    while (isspace((unsigned char)*end))
        end++;
    if (errno != 0 || *end != '\0')
        return false;
    *value = (uint64_t)v;
    *negative = v < 0;
    return true;
}

/* A value that is no number leaves 0, not what an earlier value of the entry or a part of this
 * one left. */
static bool parse_value(const char *text, uint8_t node_id, uint64_t *value, bool *negative)
{
    *value = 0;
    *negative = false;
    if (parse_signed_value(text, node_id, value, negative))
        return true;
    *value = 0;
    *negative = false;
    return false;
}

static eds_entry_t *add_entry(eds_t *eds, uint16_t index, uint16_t sub)
{
    if (eds->count == eds->capacity) {
        size_t capacity = eds->capacity ? 2 * eds->capacity : 256;
        eds_entry_t *grown = realloc(eds->entries, capacity * sizeof *grown);
        if (!grown)
            return NULL;
        eds->entries = grown;
        eds->capacity = capacity;
    }
    eds_entry_t *e = &eds->entries[eds->count++];
    memset(e, 0, sizeof *e);
    e->index = index;
    e->sub = sub;
    return e;
}

typedef struct parse_state {
    eds_t *eds;
    eds_entry_t *entry;      /* the section being read, NULL outside object sections */
    bool in_device_info;     /* [DeviceInfo] is being read */
    bool value_is_parameter; /* a DCF ParameterValue was read: it wins over DefaultValue */
    uint8_t node_id;
} parse_state_t;

static bool out_of_memory(const ini_line_t *line, char *err, size_t err_len)
{
    snprintf(err, err_len, "%s: out of memory", line->path);
    return false;
}

static bool set_key(parse_state_t *st, const ini_line_t *line, char *err, size_t err_len)
{
    eds_entry_t *e = st->entry;
    const char *key = line->key, *value = line->value;
    if (strcasecmp(key, "ParameterName") == 0) {
        free(e->name);
        e->name = strdup(value);
        if (!e->name)
            return out_of_memory(line, err, err_len);
    } else if (strcasecmp(key, "DataType") == 0) {
        uint64_t type;
        if (!parse_sum(value, st->node_id, &type) || type > 0xFFFF) {
            snprintf(err, err_len, "%s:%u: DataType '%s' is not a number such as 0x0006",
                     line->path, line->number, value);
            return false;
        }
        e->data_type = (uint16_t)type;
    } else if (strcasecmp(key, "Denotation") == 0) {
        free(e->denotation);
        e->denotation = strdup(value);
        if (!e->denotation)
            return out_of_memory(line, err, err_len);
    } else if (strcasecmp(key, "AccessType") == 0) {
        e->writable = strcasecmp(value, "rw") == 0 || strcasecmp(value, "wo") == 0 ||
                      strcasecmp(value, "rww") == 0 || strcasecmp(value, "rwr") == 0;
    } else if (strcasecmp(key, "ParameterValue") == 0 || strcasecmp(key, "DefaultValue") == 0) {
        bool is_default = strcasecmp(key, "DefaultValue") == 0;
        if (is_default) {
            bool negative;
            e->has_default =
                parse_value(value, st->node_id, &e->default_value, &negative) && !negative;
        }
        if (is_default && st->value_is_parameter)
            return true; /* the ParameterValue read before it wins */
        /* Strings and domains have values that are not numbers: they are only not decoded. */
        e->has_value = parse_value(value, st->node_id, &e->value, &e->negative);
        e->value_line = line->number;
        free(e->text);
        e->text = strdup(value);
        if (!e->text)
            return out_of_memory(line, err, err_len);
        st->value_is_parameter = st->value_is_parameter || strcasecmp(key, "ParameterValue") == 0;
        e->configured = st->value_is_parameter;
    }
    return true;
}

/* The identity keys of [DeviceInfo]; a value that is not a number leaves 0 (unknown). */
static void set_device_info(eds_t *eds, const char *key, const char *value)
{
    uint64_t number;
    if (!parse_sum(value, 0, &number) || number > UINT32_MAX)
        return;
    if (strcasecmp(key, "VendorNumber") == 0)
        eds->vendor_number = (uint32_t)number;
    else if (strcasecmp(key, "ProductNumber") == 0)
        eds->product_number = (uint32_t)number;
}

/* Every header starts a section: an object's ([1A05], [1A05sub1]) is a new entry; one meant as an
 * object's in another notation stops the reading, rather than be read as another object. */
static bool on_section(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    parse_state_t *st = ctx;
    uint16_t index, sub;
    st->entry = NULL;
    st->value_is_parameter = false;
    st->in_device_info = strcasecmp(line->section, "DeviceInfo") == 0;
    switch (parse_section(line->section, &index, &sub)) {
    case SECTION_OTHER:
        return true;
    case SECTION_MALFORMED:
        snprintf(err, err_len,
                 "%s:%u: section [%s] is not an object's: write its index in four hex digits "
                 "([1018]), a sub-index's with sub and one or two ([1018sub1])",
                 line->path, line->number, line->section);
        return false;
    case SECTION_OBJECT:
        break;
    }
    st->entry = add_entry(st->eds, index, sub);
    return st->entry || out_of_memory(line, err, err_len);
}

static bool on_key(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    parse_state_t *st = ctx;
    if (st->in_device_info)
        set_device_info(st->eds, line->key, line->value);
    return !st->entry || set_key(st, line, err, err_len);
}

/* CiA 306: comments are lines of their own. */
static const ini_reader_t cia306_syntax = {
    .trailing_comments = false,
    .key_line = "key=value",
    .on_section = on_section,
    .on_key = on_key,
};

eds_result_t eds_load(eds_t *eds, const char *path, uint8_t node_id, char *err, size_t err_len)
{
    memset(eds, 0, sizeof *eds);
    FILE *f = fopen(path, "re");
    if (!f) {
        snprintf(err, err_len, "cannot read the EDS '%s': %s", path, strerror(errno));
        return EDS_CANNOT_READ;
    }
    parse_state_t st = {.eds = eds, .node_id = node_id};
    bool ok = ini_read(f, path, &cia306_syntax, &st, err, err_len);
    fclose(f);
    if (ok && eds->count == 0) {
        snprintf(err, err_len, "%s: no object sections such as [1000]: not an EDS or DCF", path);
        ok = false;
    }
    if (ok)
        return EDS_OK;
    eds_free(eds);
    return EDS_MALFORMED;
}

void eds_free(eds_t *eds)
{
    for (size_t i = 0; i < eds->count; i++) {
        free(eds->entries[i].name);
        free(eds->entries[i].text);
        free(eds->entries[i].denotation);
    }
    free(eds->entries);
    memset(eds, 0, sizeof *eds);
}

static const eds_entry_t *find_exact(const eds_t *eds, uint16_t index, uint16_t sub)
{
    for (size_t i = 0; i < eds->count; i++) {
        if (eds->entries[i].index == index && eds->entries[i].sub == sub)
            return &eds->entries[i];
    }
    return NULL;
}

const eds_entry_t *eds_find(const eds_t *eds, uint16_t index, uint8_t sub)
{
    const eds_entry_t *e = find_exact(eds, index, sub);
    if (!e && sub == 0)
        e = find_exact(eds, index, EDS_OBJECT);
    return e;
}

const char *eds_name(const eds_t *eds, uint16_t index, uint8_t sub)
{
    const eds_entry_t *e = eds_find(eds, index, sub);
    if (!e || !e->name)
        e = find_exact(eds, index, EDS_OBJECT);
    return e ? e->name : NULL;
}

bool eds_set_value(eds_t *eds, uint16_t index, uint8_t sub, uint64_t value)
{
    eds_entry_t *e = (eds_entry_t *)find_exact(eds, index, sub);
    if (!e && sub == 0)
        e = (eds_entry_t *)find_exact(eds, index, EDS_OBJECT);
    if (!e)
        e = add_entry(eds, index, sub);
    if (!e)
        return false;
    e->has_value = true;
    e->value = value;
    e->negative = false;
    return true;
}

/* The length of a name's first word: the code of a manufacturer parameter ("ACC acceleration"). */
static size_t first_word_len(const char *name)
{
    return strcspn(name, " ");
}

static bool first_word_is(const char *name, const char *word)
{
    size_t len = first_word_len(name);
    return len == strlen(word) && strncasecmp(name, word, len) == 0;
}

static bool is_word_char(char c)
{
    return isalnum((unsigned char)c) != 0;
}

/* The words of needle stand as whole words in haystack: "acceleration time" is in "ACC
 * acceleration time (0.1 s)", but "NOPE" is not in "COL CANopen fault management". */
static bool contains_words_nocase(const char *haystack, const char *needle)
{
    size_t len = strlen(needle);
    for (const char *p = haystack; *p; p++) {
        if (strncasecmp(p, needle, len) != 0)
            continue;
        bool starts_word = p == haystack || !is_word_char(p[-1]) || !is_word_char(needle[0]);
        bool ends_word = !is_word_char(p[len]) || !is_word_char(needle[len - 1]);
        if (starts_word && ends_word)
            return true;
    }
    return false;
}

typedef enum name_match { MATCH_WHOLE, MATCH_FIRST_WORD, MATCH_WORDS, MATCH_KINDS } name_match_t;

static bool name_matches(const char *entry_name, const char *name, name_match_t kind)
{
    switch (kind) {
    case MATCH_WHOLE:
        return strcasecmp(entry_name, name) == 0;
    case MATCH_FIRST_WORD:
        return first_word_is(entry_name, name);
    case MATCH_WORDS:
    case MATCH_KINDS:
        break;
    }
    return contains_words_nocase(entry_name, name);
}

/* A variable: a sub-index section, or the section of an object that has no sub-index sections. */
static bool is_variable(const eds_t *eds, const eds_entry_t *e)
{
    return e->sub != EDS_OBJECT || !find_exact(eds, e->index, 0);
}

eds_lookup_t eds_find_by_name(const eds_t *eds, const char *name, const eds_entry_t **found)
{
    *found = NULL;
    if (*name == '\0')
        return EDS_LOOKUP_NONE;
    for (name_match_t kind = MATCH_WHOLE; kind < MATCH_KINDS; kind++) {
        size_t matches = 0;
        for (size_t i = 0; i < eds->count; i++) {
            const eds_entry_t *e = &eds->entries[i];
            bool denoted =
                kind == MATCH_WHOLE && e->denotation && strcasecmp(e->denotation, name) == 0;
            if (e->name && is_variable(eds, e) && (denoted || name_matches(e->name, name, kind))) {
                if (!*found)
                    *found = e;
                matches++;
            }
        }
        if (matches)
            return matches == 1 ? EDS_LOOKUP_FOUND : EDS_LOOKUP_AMBIGUOUS;
    }
    return EDS_LOOKUP_NONE;
}

/* CiA 301 7.4.1: the manufacturer-specific profile area. */
#define MANUFACTURER_AREA_FIRST 0x2000u
#define MANUFACTURER_AREA_LAST 0x5FFFu
/* Longer names are phrases, never near a parameter code: no suggestion is looked for. */
#define SUGGEST_NAME_MAX 32u

/* A manufacturer parameter, whose name starts with its code: a variable of the manufacturer area
 * other than a record's sub-index 0 ("Highest sub-index supported"). */
static bool has_code(const eds_t *eds, const eds_entry_t *e)
{
    return e->name && e->index >= MANUFACTURER_AREA_FIRST && e->index <= MANUFACTURER_AREA_LAST &&
           e->sub != 0 && is_variable(eds, e);
}

/* Levenshtein distance between a and the first b_len characters of b, ignoring case;
 * strlen(a) <= SUGGEST_NAME_MAX. */
static size_t edit_distance(const char *a, const char *b, size_t b_len)
{
    size_t a_len = strlen(a);
    size_t row[SUGGEST_NAME_MAX + 1];
    for (size_t i = 0; i <= a_len; i++)
        row[i] = i;
    for (size_t j = 1; j <= b_len; j++) {
        size_t diagonal = row[0];
        row[0] = j;
        for (size_t i = 1; i <= a_len; i++) {
            size_t substitute =
                diagonal + (tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]));
            size_t best = row[i] + 1 < row[i - 1] + 1 ? row[i] + 1 : row[i - 1] + 1;
            diagonal = row[i];
            row[i] = substitute < best ? substitute : best;
        }
    }
    return row[a_len];
}

static bool code_listed(const eds_entry_t *const *codes, size_t count, const eds_entry_t *e)
{
    size_t len = first_word_len(e->name);
    for (size_t i = 0; i < count; i++) {
        if (first_word_len(codes[i]->name) == len && strncasecmp(codes[i]->name, e->name, len) == 0)
            return true;
    }
    return false;
}

size_t eds_closest_codes(const eds_t *eds, const char *name, const eds_entry_t **codes, size_t max)
{
    size_t name_len = strlen(name);
    if (name_len == 0 || name_len > SUGGEST_NAME_MAX)
        return 0;
    /* At most half the name's letters changed (at least one): "ACX" is near ACC, "NOPE" near NSP,
     * "speed reference" near no code. Nearest first, in the file's order among equals. */
    size_t limit = name_len / 2 > 1 ? name_len / 2 : 1;
    size_t count = 0;
    for (size_t distance = 0; distance <= limit && count < max; distance++) {
        for (size_t i = 0; i < eds->count && count < max; i++) {
            const eds_entry_t *e = &eds->entries[i];
            if (has_code(eds, e) &&
                edit_distance(name, e->name, first_word_len(e->name)) == distance &&
                !code_listed(codes, count, e))
                codes[count++] = e;
        }
    }
    return count;
}

static bool has_eds_suffix(const char *file)
{
    size_t len = strlen(file);
    return len > 4 && strcasecmp(file + len - 4, ".eds") == 0;
}

/* 2: vendor, product and name match; 1: vendor and product; 0: not this device. */
static int identity_score(const char *path, const eds_identity_t *identity)
{
    eds_t eds;
    char err[256];
    if (eds_load(&eds, path, 0, err, sizeof err) != EDS_OK)
        return 0;
    int score = 0;
    if (eds.vendor_number == identity->vendor && eds.product_number == identity->product) {
        const eds_entry_t *name = eds_find(&eds, 0x1008, 0);
        score = identity->device_name && name && name->text &&
                        strcmp(name->text, identity->device_name) == 0
                    ? 2
                    : 1;
    }
    eds_free(&eds);
    return score;
}

bool eds_find_for_identity(const char *dir, const eds_identity_t *identity, char *path,
                           size_t path_len)
{
    DIR *d = opendir(dir);
    if (!d)
        return false;
    int best = 0;
    char candidate[4096];
    struct dirent *de;
    while (best < 2 && (de = readdir(d)) != NULL) {
        if (!has_eds_suffix(de->d_name))
            continue;
        int n = snprintf(candidate, sizeof candidate, "%s/%s", dir, de->d_name);
        if (n < 0 || (size_t)n >= sizeof candidate || (size_t)n >= path_len)
            continue;
        int score = identity_score(candidate, identity);
        if (score > best) {
            best = score;
            memcpy(path, candidate, (size_t)n + 1);
        }
    }
    closedir(d);
    return best > 0;
}
