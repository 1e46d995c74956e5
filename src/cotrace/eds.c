#include "eds.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define EDS_LINE_MAX 1024

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return s;
}

/* "1A05" -> index, "1A05sub1" -> index and sub-index; false for other sections ([FileInfo]). */
static bool parse_section(const char *name, uint16_t *index, uint16_t *sub)
{
    char *end;
    if (strlen(name) < 4 || !isxdigit((unsigned char)name[0]))
        return false;
    unsigned long idx = strtoul(name, &end, 16);
    if (end != name + 4 || idx > 0xFFFF)
        return false;
    *index = (uint16_t)idx;
    if (*end == '\0') {
        *sub = COTRACE_EDS_OBJECT;
        return true;
    }
    if (strncasecmp(end, "sub", 3) != 0 || !isxdigit((unsigned char)end[3]))
        return false;
    unsigned long s = strtoul(end + 3, &end, 16);
    if (*end != '\0' || s > 0xFF)
        return false;
    *sub = (uint16_t)s;
    return true;
}

/* CiA 306 values: decimal, 0x hexadecimal, octal with a leading 0, and "$NODEID+x" / "x+$NODEID".
 */
static bool parse_value(const char *text, uint8_t node_id, uint64_t *value)
{
    *value = 0;
    const char *p = text;
    if (*p == '\0')
        return false;
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (strncasecmp(p, "$NODEID", 7) == 0) {
            *value += node_id;
            p += 7;
        } else {
            char *end;
            errno = 0;
            unsigned long long term = strtoull(p, &end, 0);
            if (end == p || errno != 0 || *p == '-')
                return false;
            *value += term;
            p = end;
        }
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '\0')
            return true;
        if (*p++ != '+')
            return false;
    }
}

static cotrace_eds_entry_t *add_entry(cotrace_eds_t *eds, uint16_t index, uint16_t sub)
{
    if (eds->count == eds->capacity) {
        size_t capacity = eds->capacity ? 2 * eds->capacity : 256;
        cotrace_eds_entry_t *grown = realloc(eds->entries, capacity * sizeof *grown);
        if (!grown)
            return NULL;
        eds->entries = grown;
        eds->capacity = capacity;
    }
    cotrace_eds_entry_t *e = &eds->entries[eds->count++];
    memset(e, 0, sizeof *e);
    e->index = index;
    e->sub = sub;
    return e;
}

typedef struct parse_state {
    cotrace_eds_entry_t *entry; /* the section being read, NULL outside object sections */
    bool value_is_parameter;    /* a DCF ParameterValue was read: it wins over DefaultValue */
    const char *path;
    unsigned line;
    uint8_t node_id;
} parse_state_t;

static bool set_key(parse_state_t *st, const char *key, const char *value, char *err,
                    size_t err_len)
{
    cotrace_eds_entry_t *e = st->entry;
    if (strcasecmp(key, "ParameterName") == 0) {
        free(e->name);
        e->name = strdup(value);
        if (!e->name) {
            snprintf(err, err_len, "%s: out of memory", st->path);
            return false;
        }
    } else if (strcasecmp(key, "DataType") == 0) {
        uint64_t type;
        if (!parse_value(value, st->node_id, &type) || type > 0xFFFF) {
            snprintf(err, err_len, "%s:%u: DataType '%s' is not a number such as 0x0006", st->path,
                     st->line, value);
            return false;
        }
        e->data_type = (uint16_t)type;
    } else if (strcasecmp(key, "ParameterValue") == 0 ||
               (strcasecmp(key, "DefaultValue") == 0 && !st->value_is_parameter)) {
        /* Strings and domains have values that are not numbers: they are only not decoded. */
        e->has_value = parse_value(value, st->node_id, &e->value);
        st->value_is_parameter = st->value_is_parameter || strcasecmp(key, "ParameterValue") == 0;
    }
    return true;
}

static bool read_line(parse_state_t *st, cotrace_eds_t *eds, char *line, char *err, size_t err_len)
{
    char *s = trim(line);
    if (*s == '\0' || *s == ';' || *s == '#')
        return true;
    if (*s == '[') {
        char *close = strchr(s, ']');
        if (!close) {
            snprintf(err, err_len, "%s:%u: section header '%s' has no ']'", st->path, st->line, s);
            return false;
        }
        *close = '\0';
        uint16_t index, sub;
        st->entry = NULL;
        st->value_is_parameter = false;
        if (parse_section(trim(s + 1), &index, &sub)) {
            st->entry = add_entry(eds, index, sub);
            if (!st->entry) {
                snprintf(err, err_len, "%s: out of memory", st->path);
                return false;
            }
        }
        return true;
    }
    char *eq = strchr(s, '=');
    if (!eq) {
        snprintf(err, err_len, "%s:%u: '%s' is neither a [section] nor a key=value line", st->path,
                 st->line, s);
        return false;
    }
    *eq = '\0';
    if (!st->entry)
        return true;
    return set_key(st, trim(s), trim(eq + 1), err, err_len);
}

cotrace_eds_result_t cotrace_eds_load(cotrace_eds_t *eds, const char *path, uint8_t node_id,
                                      char *err, size_t err_len)
{
    memset(eds, 0, sizeof *eds);
    FILE *f = fopen(path, "re");
    if (!f) {
        snprintf(err, err_len, "cannot read the EDS '%s': %s", path, strerror(errno));
        return COTRACE_EDS_CANNOT_READ;
    }
    parse_state_t st = {.path = path, .node_id = node_id};
    char line[EDS_LINE_MAX];
    bool ok = true;
    while (ok && fgets(line, sizeof line, f)) {
        st.line++;
        ok = read_line(&st, eds, line, err, err_len);
    }
    fclose(f);
    if (ok && eds->count == 0) {
        snprintf(err, err_len, "%s: no object sections such as [1000]: not an EDS or DCF", path);
        ok = false;
    }
    if (ok)
        return COTRACE_EDS_OK;
    cotrace_eds_free(eds);
    return COTRACE_EDS_MALFORMED;
}

void cotrace_eds_free(cotrace_eds_t *eds)
{
    for (size_t i = 0; i < eds->count; i++)
        free(eds->entries[i].name);
    free(eds->entries);
    memset(eds, 0, sizeof *eds);
}

static const cotrace_eds_entry_t *find_exact(const cotrace_eds_t *eds, uint16_t index, uint16_t sub)
{
    for (size_t i = 0; i < eds->count; i++) {
        if (eds->entries[i].index == index && eds->entries[i].sub == sub)
            return &eds->entries[i];
    }
    return NULL;
}

const cotrace_eds_entry_t *cotrace_eds_find(const cotrace_eds_t *eds, uint16_t index, uint8_t sub)
{
    const cotrace_eds_entry_t *e = find_exact(eds, index, sub);
    if (!e && sub == 0)
        e = find_exact(eds, index, COTRACE_EDS_OBJECT);
    return e;
}

const char *cotrace_eds_name(const cotrace_eds_t *eds, uint16_t index, uint8_t sub)
{
    const cotrace_eds_entry_t *e = cotrace_eds_find(eds, index, sub);
    if (!e || !e->name)
        e = find_exact(eds, index, COTRACE_EDS_OBJECT);
    return e ? e->name : NULL;
}
