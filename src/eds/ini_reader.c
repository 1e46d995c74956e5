#include "ini_reader.h"

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

/* Whether `buf`, as fgets filled it, holds a whole line: a longer one comes in pieces, and each
 * piece read as a line would make a "[1001]" at the end of a long name a section of the file. A
 * full buffer without its newline is whole only at the end of the file. */
static bool whole_line(FILE *file, const char *buf)
{
    size_t len = strlen(buf);
    if (len < INI_LINE_MAX - 1 || buf[len - 1] == '\n')
        return true;
    int next = getc(file);
    if (next == EOF)
        return true;
    ungetc(next, file);
    return false;
}

bool ini_read(FILE *file, const char *path, const ini_reader_t *reader, void *ctx, char *err,
              size_t err_len)
{
    char section[INI_LINE_MAX] = "";
    char buf[INI_LINE_MAX];
    ini_line_t line = {.path = path, .section = section};
    bool ok = true;
    while (ok && fgets(buf, sizeof buf, file)) {
        line.number++;
        if (!whole_line(file, buf)) {
            snprintf(err, err_len, "%s:%u: line longer than %d characters", path, line.number,
                     INI_LINE_MAX - 2);
            return false;
        }
        ok = read_line(reader, &line, section, buf, ctx, err, err_len);
    }
    return ok;
}
