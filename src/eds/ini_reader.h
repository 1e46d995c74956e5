/* SPDX-License-Identifier: Apache-2.0 */
/* The INI line reader of the installed tools' files: the CiA 306 EDS and DCF (eds_reader.c), the
 * CiA 306-3 nodelist and comaster's option file (apps/comaster/network.c). It owns the syntax:
 * [section] headers, key = value lines, comments, blanks, line numbers and the errors of a line
 * that is none of these; what the sections and keys mean is the caller's, told line by line. */
#ifndef INI_READER_H
#define INI_READER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* The longest line read, its newline and the terminating NUL included: a longer line (more than
 * INI_LINE_MAX - 2 characters, the last line of the file too), or one with a NUL byte, is
 * refused with its number. */
#define INI_LINE_MAX 1024

/* A section header (key and value NULL) or a key = value line, blanks trimmed. */
typedef struct ini_line {
    const char *path;    /* the file, for the caller's errors */
    unsigned number;     /* from 1, comment and blank lines counted */
    const char *section; /* the name between the brackets; "" before the first header */
    const char *key;
    const char *value;
} ini_line_t;

/* Takes one line; false after writing a one-line error to err, which stops the reading. */
typedef bool (*ini_line_fn)(void *ctx, const ini_line_t *line, char *err, size_t err_len);

/* The dialect of a kind of file and the callbacks its lines go to. */
typedef struct ini_reader {
    /* ';' or '#' after a blank also starts a comment (an option file). CiA 306 has comment lines
     * only, and a name or value of an EDS may hold either character. */
    bool trailing_comments;
    /* A key line as the file's documentation writes it ("key=value"), for the error on a line
     * that is neither a header nor a key line. */
    const char *key_line;
    ini_line_fn on_section; /* NULL: headers only name the section of the keys that follow */
    ini_line_fn on_key;
} ini_reader_t;

/* Reads `file` (`path` in errors) to its end or its first error. False with a one-line error in
 * err ("path:line: ..." for a line longer than INI_LINE_MAX - 2 characters or with a NUL byte, a
 * header without ']' or a line of neither kind, else a callback's). */
bool ini_read(FILE *file, const char *path, const ini_reader_t *reader, void *ctx, char *err,
              size_t err_len);

#endif
