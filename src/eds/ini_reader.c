/* SPDX-License-Identifier: Apache-2.0 */
#include "eds/ini_reader.h"

#include <ctype.h>
#include <string.h>

/* `s` without its leading and trailing blanks (the trailing ones cut in place). */
static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return s;
}

static bool starts_comment(char c)
{
    return c == ';' || c == '#';
}

/* A trailing comment starts at the beginning of a line or after a blank, so that "vcan1#2" keeps
 * its '#'. */
static void strip_trailing_comment(char *s)
{
    for (char *p = s; *p; p++) {
        if (starts_comment(*p) && (p == s || isspace((unsigned char)p[-1]))) {
            *p = '\0';
            return;
        }
    }
}

/* One line of `buf`; `section` (INI_LINE_MAX bytes) keeps the current section's name. */
static bool read_line(const ini_reader_t *reader, ini_line_t *line, char *section, char *buf,
                      void *ctx, char *err, size_t err_len)
{
    if (reader->trailing_comments)
        strip_trailing_comment(buf);
    char *s = trim(buf);
    if (*s == '\0' || starts_comment(*s))
        return true;
    if (*s == '[') {
        char *close = strchr(s, ']');
        if (!close) {
            snprintf(err, err_len, "%s:%u: section header '%s' has no ']'", line->path,
                     line->number, s);
            return false;
        }
        *close = '\0';
        snprintf(section, INI_LINE_MAX, "%s", trim(s + 1));
        line->key = NULL;
        line->value = NULL;
        return !reader->on_section || reader->on_section(ctx, line, err, err_len);
    }
    char *eq = strchr(s, '=');
    if (!eq) {
        snprintf(err, err_len, "%s:%u: '%s' is neither a [section] nor a %s line", line->path,
                 line->number, s, reader->key_line);
        return false;
    }
    *eq = '\0';
    line->key = trim(s);
    line->value = trim(eq + 1);
    return reader->on_key(ctx, line, err, err_len);
}

typedef enum raw_line {
    RAW_LINE,          /* a line in buf, its newline (if any) and a NUL after it */
    RAW_END,           /* the end of the file, nothing read */
    RAW_LINE_TOO_LONG, /* more than INI_LINE_MAX - 2 characters before the newline */
    RAW_LINE_NUL       /* a NUL byte before the newline */
} raw_line_t;

/* Reads one line into buf (INI_LINE_MAX bytes) to its newline or the end of the file. A line
 * that does not fit, or holds a NUL byte, is refused rather than cut: fgets would hand over its
 * pieces, and each piece read as a line makes a "[1001]" at the end of a long name a section of
 * the file. The rest of a refused line is left unread (the reading stops there). */
static raw_line_t read_raw_line(FILE *file, char *buf)
{
    size_t len = 0;
    int c;
    while ((c = getc(file)) != EOF) {
        if (c == '\0')
            return RAW_LINE_NUL;
        if (len == INI_LINE_MAX - 2 && c != '\n')
            return RAW_LINE_TOO_LONG;
        buf[len++] = (char)c;
        if (c == '\n')
            break;
    }
    buf[len] = '\0';
    return len == 0 ? RAW_END : RAW_LINE;
}

bool ini_read(FILE *file, const char *path, const ini_reader_t *reader, void *ctx, char *err,
              size_t err_len)
{
    char section[INI_LINE_MAX] = "";
    char buf[INI_LINE_MAX];
    ini_line_t line = {.path = path, .section = section};
    bool ok = true;
    raw_line_t raw;
    while (ok && (raw = read_raw_line(file, buf)) != RAW_END) {
        line.number++;
        if (raw == RAW_LINE_TOO_LONG) {
            snprintf(err, err_len, "%s:%u: line longer than %d characters", path, line.number,
                     INI_LINE_MAX - 2);
            return false;
        }
        if (raw == RAW_LINE_NUL) {
            snprintf(err, err_len, "%s:%u: a NUL byte in the line", path, line.number);
            return false;
        }
        ok = read_line(reader, &line, section, buf, ctx, err, err_len);
    }
    return ok;
}
