/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the C EDS/DCF reader (src/eds/eds_reader.c on src/eds/ini_reader.c, what
 * comaster reads DCFs and cotrace EDS files with): the input is a whole file, read by eds_load
 * from memory (a memfd) for node 5. The harness reads the text's lines itself, the way CiA 306
 * and ini_reader.h say, and holds the reader to invariants of its own (docs/fuzzing.md): the same
 * file gives the same result twice; an accepted file has one entry per object section header,
 * in order, each named by exactly four hexadecimal digits (and `sub` and one or two hexadecimal
 * digits); the entries, written back in canonical form and read again, are the same; eds_find,
 * eds_name, eds_find_by_name and eds_set_value agree with the entries; a refused file says why,
 * on one line, naming a line of the file that is wrong and no wrong line before it. */
#include "eds/eds_reader.h"
#include "eds/ini_reader.h"
#include "rig.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <unistd.h>

#define NODE_ID 5
#define ERR_SIZE 512
#define INDEX_DIGITS 4u
#define SUB_WORD_LEN 3u
#define SUB_DIGITS_MAX 2u

/* What the harness makes of one line of the file. */
typedef enum line_kind {
    LINE_BLANK,       /* blank, or a comment */
    LINE_HEADER,      /* [name] */
    LINE_OPEN_HEADER, /* '[' without ']' */
    LINE_KEY,         /* key = value */
    LINE_OTHER        /* none of these: an error */
} line_kind_t;

typedef struct line {
    line_kind_t kind;
    bool object;    /* a header naming an object section; a key line in one */
    bool data_type; /* a key line of DataType in an object section */
    bool too_long;  /* longer than ini_reader.c reads as one line (INI_LINE_MAX - 2 characters) */
    bool nul;       /* holding a NUL byte, which no line of a text file has */
} line_t;

/* A value as the file writes it, blanks trimmed. */
typedef struct span {
    const char *s;
    size_t len;
    bool set;
} span_t;

/* An object section and what its keys say (eds_reader.h): the last ParameterName, Denotation and
 * AccessType; the last ParameterValue, or without one the last DefaultValue. */
typedef struct object {
    uint16_t index, sub;
    span_t name, denotation, text;
    bool configured;
    bool writable;
} object_t;

/* The file as the harness reads it: its lines and its object sections in order. */
typedef struct text {
    line_t *lines;
    size_t line_count;
    object_t *objects;
    size_t object_count;
    bool in_object; /* the last header named an object section */
} text_t;

typedef struct memfile {
    int fd;
    char path[32];
} memfile_t;

static memfile_t input_file, canonical_file;

static void memfile_open(memfile_t *f, const char *name)
{
    if (f->path[0] != '\0')
        return;
    f->fd = memfd_create(name, 0);
    rig_check(f->fd >= 0, "memfd_create failed");
    snprintf(f->path, sizeof f->path, "/proc/self/fd/%d", f->fd);
}

static void memfile_write(memfile_t *f, const void *data, size_t size)
{
    rig_check(ftruncate(f->fd, 0) == 0 && pwrite(f->fd, data, size, 0) == (ssize_t)size,
              "cannot write the memfd");
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = (char)tolower((unsigned char)c);
    return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

/* `n` (at most four) hexadecimal digits and nothing else, as a number. */
static bool hex_number(const char *s, size_t n, unsigned *value)
{
    *value = 0;
    for (size_t i = 0; i < n; i++) {
        int d = hex_digit(s[i]);
        if (d < 0)
            return false;
        *value = *value * 16u + (unsigned)d;
    }
    return n > 0;
}

/* CiA 306 object section names: the index in four hexadecimal digits ("1A05"), then for a
 * sub-index "sub" and the sub-index in one or two ("1A05sub1", "1A05SUB0A"). */
static bool object_name(const char *name, size_t len, object_t *object)
{
    unsigned index, sub;
    if (len < INDEX_DIGITS || !hex_number(name, INDEX_DIGITS, &index))
        return false;
    object->index = (uint16_t)index;
    object->sub = EDS_OBJECT;
    if (len == INDEX_DIGITS)
        return true;
    size_t digits = len - INDEX_DIGITS - SUB_WORD_LEN;
    if (len <= INDEX_DIGITS + SUB_WORD_LEN || digits > SUB_DIGITS_MAX ||
        strncasecmp(name + INDEX_DIGITS, "sub", SUB_WORD_LEN) != 0 ||
        !hex_number(name + INDEX_DIGITS + SUB_WORD_LEN, digits, &sub))
        return false;
    object->sub = (uint16_t)sub;
    return true;
}

/* The blanks ini_reader.c trims: isspace in the C locale. */
static bool blank(char c)
{
    return isspace((unsigned char)c) != 0;
}

static void trim(const char **s, size_t *len)
{
    while (*len > 0 && blank(**s)) {
        (*s)++;
        (*len)--;
    }
    while (*len > 0 && blank((*s)[*len - 1]))
        (*len)--;
}

static bool is_word(const char *s, size_t len, const char *word)
{
    return len == strlen(word) && strncasecmp(s, word, len) == 0;
}

static void read_key(object_t *o, const char *key, size_t key_len, span_t value)
{
    if (is_word(key, key_len, "ParameterName")) {
        o->name = value;
    } else if (is_word(key, key_len, "Denotation")) {
        o->denotation = value;
    } else if (is_word(key, key_len, "AccessType")) {
        o->writable = is_word(value.s, value.len, "rw") || is_word(value.s, value.len, "wo") ||
                      is_word(value.s, value.len, "rww") || is_word(value.s, value.len, "rwr");
    } else if (is_word(key, key_len, "ParameterValue")) {
        o->text = value;
        o->configured = true;
    } else if (is_word(key, key_len, "DefaultValue") && !o->configured) {
        o->text = value;
    }
}

/* One line: its text ends at the newline, or at a NUL byte (where C strings end). */
static line_t read_line(text_t *t, const char *s, size_t len)
{
    line_t line = {0};
    trim(&s, &len);
    if (len == 0 || s[0] == ';' || s[0] == '#')
        return line;
    if (s[0] == '[') {
        const char *close = memchr(s, ']', len);
        if (close == NULL) {
            line.kind = LINE_OPEN_HEADER;
            return line;
        }
        const char *name = s + 1;
        size_t name_len = (size_t)(close - name);
        trim(&name, &name_len);
        object_t object = {0};
        line.kind = LINE_HEADER;
        line.object = object_name(name, name_len, &object);
        if (line.object)
            t->objects[t->object_count++] = object;
        t->in_object = line.object;
        return line;
    }
    const char *eq = memchr(s, '=', len);
    if (eq == NULL) {
        line.kind = LINE_OTHER;
        return line;
    }
    const char *key = s;
    size_t key_len = (size_t)(eq - s);
    trim(&key, &key_len);
    span_t value = {eq + 1, (size_t)(s + len - (eq + 1)), true};
    trim(&value.s, &value.len);
    line.kind = LINE_KEY;
    line.object = t->in_object;
    line.data_type = t->in_object && is_word(key, key_len, "DataType");
    if (t->in_object)
        read_key(&t->objects[t->object_count - 1], key, key_len, value);
    return line;
}

static void read_text(text_t *t, const uint8_t *data, size_t size)
{
    t->lines = calloc(size + 1, sizeof *t->lines);
    t->objects = calloc(size + 1, sizeof *t->objects);
    rig_check(t->lines && t->objects, "out of memory");
    t->line_count = t->object_count = 0;
    t->in_object = false;
    for (size_t pos = 0; pos < size;) {
        const char *s = (const char *)data + pos;
        const char *newline = memchr(s, '\n', size - pos);
        size_t len = newline ? (size_t)(newline - s) : size - pos;
        pos += len + (newline != NULL);
        const char *nul = memchr(s, '\0', len);
        line_t *line = &t->lines[t->line_count++];
        *line = read_line(t, s, nul ? (size_t)(nul - s) : len);
        line->too_long = len > INI_LINE_MAX - 2;
        line->nul = nul != NULL;
    }
}

static void free_text(text_t *t)
{
    free(t->lines);
    free(t->objects);
}

static bool same_string(const char *a, const char *b)
{
    return (a == NULL && b == NULL) || (a && b && strcmp(a, b) == 0);
}

static bool same_span(const char *a, const span_t *b)
{
    return b->set ? a != NULL && strlen(a) == b->len && memcmp(a, b->s, b->len) == 0 : a == NULL;
}

static bool same_entry(const eds_entry_t *a, const eds_entry_t *b)
{
    return a->index == b->index && a->sub == b->sub && a->data_type == b->data_type &&
           a->has_value == b->has_value && a->value == b->value && a->negative == b->negative &&
           same_string(a->name, b->name) && same_string(a->text, b->text) &&
           a->configured == b->configured && same_string(a->denotation, b->denotation) &&
           a->writable == b->writable;
}

static bool same_eds(const eds_t *a, const eds_t *b)
{
    if (a->count != b->count || a->vendor_number != b->vendor_number ||
        a->product_number != b->product_number)
        return false;
    for (size_t i = 0; i < a->count; i++) {
        if (!same_entry(&a->entries[i], &b->entries[i]))
            return false;
    }
    return true;
}

/* The reader's result, written back in the canonical form of CiA 306. */
static void write_canonical(FILE *f, const eds_t *eds)
{
    fprintf(f, "[DeviceInfo]\nVendorNumber=%u\nProductNumber=%u\n", eds->vendor_number,
            eds->product_number);
    for (size_t i = 0; i < eds->count; i++) {
        const eds_entry_t *e = &eds->entries[i];
        if (e->sub == EDS_OBJECT)
            fprintf(f, "[%04X]\n", e->index);
        else
            fprintf(f, "[%04Xsub%X]\n", e->index, e->sub);
        if (e->name)
            fprintf(f, "ParameterName=%s\n", e->name);
        fprintf(f, "DataType=0x%04X\nAccessType=%s\n", e->data_type, e->writable ? "rw" : "ro");
        if (e->denotation)
            fprintf(f, "Denotation=%s\n", e->denotation);
        if (e->text)
            fprintf(f, "%s=%s\n", e->configured ? "ParameterValue" : "DefaultValue", e->text);
    }
}

static void check_round_trip(const eds_t *eds)
{
    char *canonical = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&canonical, &size);
    rig_check(f != NULL, "out of memory");
    write_canonical(f, eds);
    fclose(f);
    memfile_write(&canonical_file, canonical, size);
    free(canonical);
    eds_t again;
    char err[ERR_SIZE];
    rig_check(eds_load(&again, canonical_file.path, NODE_ID, err, sizeof err) == EDS_OK,
              "the canonical form of an accepted file refused");
    rig_check(same_eds(eds, &again), "the canonical form of a file read otherwise than the file");
    eds_free(&again);
}

static bool is_variable(const eds_t *eds, const eds_entry_t *e)
{
    return e->sub != EDS_OBJECT || eds_find(eds, e->index, 0) == e;
}

/* eds_find gives the first entry of an index and sub-index (for sub-index 0, the object's own
 * section when there is no sub-index section); eds_name its name; eds_find_by_name finds every
 * variable by its whole name. */
static void check_lookups(const eds_t *eds)
{
    for (size_t k = 0; k < eds->count; k++) {
        const eds_entry_t *e = &eds->entries[k];
        if (e->sub == EDS_OBJECT)
            continue;
        const eds_entry_t *found = eds_find(eds, e->index, (uint8_t)e->sub);
        rig_check(found != NULL && found <= e && found->index == e->index && found->sub == e->sub,
                  "eds_find does not give the first entry of an index and sub-index");
        if (found == e && e->name)
            rig_check(eds_name(eds, e->index, (uint8_t)e->sub) == e->name,
                      "eds_name is not the entry's name");
    }
    for (size_t k = 0; k < eds->count; k++) {
        const eds_entry_t *e = &eds->entries[k], *found;
        if (e->name == NULL || e->name[0] == '\0' || !is_variable(eds, e))
            continue;
        rig_check(eds_find_by_name(eds, e->name, &found) != EDS_LOOKUP_NONE && found != NULL,
                  "eds_find_by_name misses a variable by its whole name");
    }
}

static void check_set_value(eds_t *eds)
{
    for (size_t k = 0; k < eds->count; k++) {
        uint16_t index = eds->entries[k].index, sub = eds->entries[k].sub;
        uint8_t at = sub == EDS_OBJECT ? 0 : (uint8_t)sub;
        uint64_t value = 0x0123456789ABCDEFu ^ k;
        rig_check(eds_set_value(eds, index, at, value), "eds_set_value failed");
        const eds_entry_t *e = eds_find(eds, index, at);
        rig_check(e != NULL && e->has_value && e->value == value && !e->negative,
                  "eds_find does not give the value eds_set_value set");
    }
}

static void check_accepted(eds_t *eds, const text_t *t)
{
    rig_check(eds->count == t->object_count, "entries other than the file's object sections");
    for (size_t k = 0; k < eds->count; k++) {
        const eds_entry_t *e = &eds->entries[k];
        const object_t *o = &t->objects[k];
        rig_check(e->index == o->index && e->sub == o->sub,
                  "an entry that is not the object section at its place (a section name not "
                  "exactly four hexadecimal digits, and sub and one or two)");
        rig_check(same_span(e->name, &o->name) && same_span(e->denotation, &o->denotation),
                  "an entry whose name or denotation is not its section's");
        rig_check(same_span(e->text, &o->text) && e->configured == o->configured,
                  "an entry whose value is not its section's ParameterValue or DefaultValue");
        rig_check(e->writable == o->writable, "an entry writable otherwise than its AccessType");
        rig_check(!e->has_value || e->text != NULL, "a value without its text");
        rig_check(!e->configured || e->text != NULL, "a ParameterValue without its text");
    }
    check_round_trip(eds);
    check_lookups(eds);
    check_set_value(eds);
}

/* A line the reader may refuse: a header without ']' or one it does not take as a name, a line
 * that is neither a header nor a key line, a DataType that may be no number, a line longer than
 * it reads at once, a line with a NUL byte. */
static bool wrong_line(const line_t *line)
{
    return line->kind == LINE_OPEN_HEADER || line->kind == LINE_OTHER ||
           (line->kind == LINE_HEADER && !line->object) || line->data_type || line->too_long ||
           line->nul;
}

static bool surely_wrong_line(const line_t *line)
{
    return line->kind == LINE_OPEN_HEADER || line->kind == LINE_OTHER || line->too_long ||
           line->nul;
}

static void check_refused(const eds_t *eds, const text_t *t, const char *err)
{
    rig_check(eds->entries == NULL && eds->count == 0, "a refused file leaves entries");
    size_t path_len = strlen(input_file.path);
    rig_check(strncmp(err, input_file.path, path_len) == 0, "an error that does not name the file");
    rig_check(strchr(err, '\n') == NULL, "an error of more than one line");
    const char *rest = err + path_len;
    if (strncmp(rest, ": no object sections", 20) == 0) {
        rig_check(t->object_count == 0, "a file with object sections refused for having none");
        return;
    }
    unsigned long number;
    int used = 0;
    rig_check(sscanf(rest, ":%lu: %n", &number, &used) == 1 && used > 0,
              "an error without the line number");
    rig_check(number >= 1 && number <= t->line_count, "an error naming a line past the file's end");
    rig_check(wrong_line(&t->lines[number - 1]), "an error naming a line that is not wrong");
    for (size_t n = 1; n < number; n++)
        rig_check(!surely_wrong_line(&t->lines[n - 1]), "an error past the first wrong line");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    memfile_open(&input_file, "fuzz.eds");
    memfile_open(&canonical_file, "canonical.eds");
    memfile_write(&input_file, data, size);
    eds_t eds, again;
    char err[ERR_SIZE] = "", err_again[ERR_SIZE] = "";
    eds_result_t result = eds_load(&eds, input_file.path, NODE_ID, err, sizeof err);
    eds_result_t result_again =
        eds_load(&again, input_file.path, NODE_ID, err_again, sizeof err_again);
    rig_check(result == result_again && (result != EDS_OK || same_eds(&eds, &again)) &&
                  (result == EDS_OK || strcmp(err, err_again) == 0),
              "the same file read twice with two results");
    eds_free(&again);
    rig_check(result == EDS_OK || result == EDS_MALFORMED, "a file in memory that cannot be read");
    text_t text;
    read_text(&text, data, size);
    if (result == EDS_OK)
        check_accepted(&eds, &text);
    else
        check_refused(&eds, &text, err);
    free_text(&text);
    eds_free(&eds);
    return 0;
}
