/* SPDX-License-Identifier: Apache-2.0 */
/* The JSON writer (json.h). */
#include "cli/json.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

size_t cli_json_escape(unsigned char c, char out[CLI_JSON_ESCAPE_MAX])
{
    if (c == '"' || c == '\\') {
        out[0] = '\\';
        out[1] = (char)c;
        return 2;
    }
    if (c < 0x20) {
        static const char hex[] = "0123456789abcdef";
        memcpy(out, "\\u00", 4);
        out[4] = hex[c >> 4];
        out[5] = hex[c & 0xF];
        return 6;
    }
    out[0] = (char)c;
    return 1;
}

void cli_json_init(cli_json_t *json, char *buf, size_t cap)
{
    *json = (cli_json_t){.buf = buf, .cap = cap, .overflow = cap == 0};
    if (cap)
        buf[0] = '\0';
}

static void overflow(cli_json_t *json)
{
    json->overflow = true;
    json->len = 0;
    if (json->cap)
        json->buf[0] = '\0';
}

static void append(cli_json_t *json, const char *bytes, size_t n)
{
    if (json->overflow)
        return;
    if (n >= json->cap - json->len) {
        overflow(json);
        return;
    }
    memcpy(json->buf + json->len, bytes, n);
    json->len += n;
    json->buf[json->len] = '\0';
}

static void append_string(cli_json_t *json, const char *text)
{
    append(json, "\"", 1);
    for (const unsigned char *c = (const unsigned char *)text; *c && !json->overflow; c++) {
        char escaped[CLI_JSON_ESCAPE_MAX];
        append(json, escaped, cli_json_escape(*c, escaped));
    }
    append(json, "\"", 1);
}

/* What comes before a value: the comma after the container's previous member, then its key. */
static void begin_value(cli_json_t *json, const char *key)
{
    uint32_t bit = UINT32_C(1) << json->depth;
    if (json->has_member & bit)
        append(json, ",", 1);
    json->has_member |= bit;
    if (key) {
        append_string(json, key);
        append(json, ":", 1);
    }
}

static void begin(cli_json_t *json, const char *key, const char *bracket)
{
    begin_value(json, key);
    if (json->depth + 1 >= CLI_JSON_DEPTH_MAX) {
        overflow(json);
        return;
    }
    append(json, bracket, 1);
    json->has_member &= ~(UINT32_C(1) << ++json->depth);
}

static void end(cli_json_t *json, const char *bracket)
{
    if (json->depth == 0) {
        overflow(json);
        return;
    }
    json->depth--;
    append(json, bracket, 1);
}

void cli_json_begin_object(cli_json_t *json, const char *key)
{
    begin(json, key, "{");
}

void cli_json_end_object(cli_json_t *json)
{
    end(json, "}");
}

void cli_json_begin_array(cli_json_t *json, const char *key)
{
    begin(json, key, "[");
}

void cli_json_end_array(cli_json_t *json)
{
    end(json, "]");
}

void cli_json_str(cli_json_t *json, const char *key, const char *text)
{
    begin_value(json, key);
    append_string(json, text);
}

void cli_json_int(cli_json_t *json, const char *key, long long value)
{
    cli_json_number(json, key, "%lld", value);
}

void cli_json_uint(cli_json_t *json, const char *key, unsigned long long value)
{
    cli_json_number(json, key, "%llu", value);
}

void cli_json_bool(cli_json_t *json, const char *key, bool value)
{
    begin_value(json, key);
    append(json, value ? "true" : "false", value ? 4 : 5);
}

void cli_json_null(cli_json_t *json, const char *key)
{
    begin_value(json, key);
    append(json, "null", 4);
}

void cli_json_number(cli_json_t *json, const char *key, const char *format, ...)
{
    begin_value(json, key);
    char number[64];
    va_list args;
    va_start(args, format);
    int n = vsnprintf(number, sizeof number, format, args);
    va_end(args);
    if (n < 0 || (size_t)n >= sizeof number)
        overflow(json);
    else
        append(json, number, (size_t)n);
}

size_t cli_json_finish(cli_json_t *json)
{
    if (json->depth != 0)
        overflow(json);
    return json->overflow ? 0 : json->len;
}

bool cli_json_quote(const char *text, char *out, size_t cap)
{
    cli_json_t json;
    cli_json_init(&json, out, cap);
    cli_json_str(&json, NULL, text);
    return cli_json_finish(&json) > 0;
}
