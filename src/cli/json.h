/* SPDX-License-Identifier: Apache-2.0 */
/* The project's one JSON writer: compact JSON ({"a":1,"b":[true,null]}, no spaces) into a buffer
 * the caller owns, the commas between members and elements written by the writer. A value that
 * does not fit empties the buffer and marks the writer overflowed: a cut object is never mistaken
 * for a whole one (cli_json_finish says which). Strings are escaped as every JSON the programs
 * write is (cli_json_escape): '"' and '\' after a backslash, control characters as \u00XX, every
 * other byte as it is. */
#ifndef CLI_JSON_H
#define CLI_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Objects and arrays open at once, at most. */
#define CLI_JSON_DEPTH_MAX 16
/* The longest escape of one byte: "\u001f". */
#define CLI_JSON_ESCAPE_MAX 6
/* The room a text of n bytes needs as one JSON string: every byte escaped, two quotes, the NUL.
 * A buffer of this size always takes cli_json_quote's result. */
#define CLI_JSON_QUOTED_MAX(n) ((n)*CLI_JSON_ESCAPE_MAX + 3)

typedef struct cli_json {
    char *buf;
    size_t cap, len;
    bool overflow; /* a value did not fit, or the nesting went wrong: buf is "" */
    unsigned depth;
    uint32_t has_member; /* bit d: the object or array at depth d has one already */
} cli_json_t;

/* The text of one byte inside a JSON string, its escape or itself, in out; returns its length. */
size_t cli_json_escape(unsigned char c, char out[CLI_JSON_ESCAPE_MAX]);

/* Starts writing into buf (cap bytes, NUL-terminated as it goes). */
void cli_json_init(cli_json_t *json, char *buf, size_t cap);

/* Each value below is an object's member when key is given, else an element of the array open
 * (or the document itself). */
void cli_json_begin_object(cli_json_t *json, const char *key);
void cli_json_end_object(cli_json_t *json);
void cli_json_begin_array(cli_json_t *json, const char *key);
void cli_json_end_array(cli_json_t *json);
void cli_json_str(cli_json_t *json, const char *key, const char *text);
void cli_json_int(cli_json_t *json, const char *key, long long value);
void cli_json_uint(cli_json_t *json, const char *key, unsigned long long value);
void cli_json_bool(cli_json_t *json, const char *key, bool value);
void cli_json_null(cli_json_t *json, const char *key);
/* A number as printf writes it, for decimals: ("%.1f", rate), ("%u.%u", amps, tenths). */
void cli_json_number(cli_json_t *json, const char *key, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/* The document's length; 0, with buf "", when it overflowed or is not closed. */
size_t cli_json_finish(cli_json_t *json);

/* `text` as one JSON string into out ("\"a \\\"b\\\"\""); false, with out "", when it does not
 * fit in cap bytes (never when cap is CLI_JSON_QUOTED_MAX of its length). */
bool cli_json_quote(const char *text, char *out, size_t cap);

#endif
