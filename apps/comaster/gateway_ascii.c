/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 309-3's command lines and replies for comaster gateway: tokens split at blanks (a quoted
 * string is one token, "" in it a quote, '#' begins a comment), "[sequence] [[net] node]
 * command ...", and the reply lines "[sequence] OK", "[sequence] value", "[sequence] ERROR:code"
 * ended by CR LF as the standard asks and canopend writes them (D-GATEWAY-REPLIES). */
#include "comaster/gateway_ascii.h"

#include "co/co_nmt.h"
#include "co/co_types.h"
#include "comaster/value.h"

#include <ctype.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#define MAX_TOKENS 16

static const gw_type_t types[] = {
    {"b", 1, 'u', CO_DT_BOOLEAN},        {"i8", 1, 'i', CO_DT_INTEGER8},
    {"i16", 2, 'i', CO_DT_INTEGER16},    {"i32", 4, 'i', CO_DT_INTEGER32},
    {"i64", 8, 'i', CO_DT_INTEGER64},    {"u8", 1, 'u', CO_DT_UNSIGNED8},
    {"u16", 2, 'u', CO_DT_UNSIGNED16},   {"u32", 4, 'u', CO_DT_UNSIGNED32},
    {"u64", 8, 'u', CO_DT_UNSIGNED64},   {"x8", 1, 'x', CO_DT_UNSIGNED8},
    {"x16", 2, 'x', CO_DT_UNSIGNED16},   {"x32", 4, 'x', CO_DT_UNSIGNED32},
    {"x64", 8, 'x', CO_DT_UNSIGNED64},   {"r32", 4, 'r', CO_DT_REAL32},
    {"r64", 8, 'r', CO_DT_REAL64},       {"vs", 0, 's', CO_DT_VISIBLE_STRING},
    {"hex", 0, 'h', CO_DT_OCTET_STRING},
};

/* The data types CiA 309-3 names that comaster does not handle yet: their requests answer
 * "request not supported", not "syntax error". */
static const char *const unsupported_types[] = {"os", "us", "d", "t", "td"};

/* The LSS commands: their name, service and how many numbers they take (min..max), each within
 * its bound. */
typedef struct lss_command {
    const char *name;
    gw_lss_t lss;
    int min, max;
    uint32_t bound[4];
} lss_command_t;

static const lss_command_t lss_commands[] = {
    {"lss_switch_glob", GW_LSS_SWITCH_GLOBAL, 1, 1, {1, 0, 0, 0}},
    {"lss_switch_sel",
     GW_LSS_SWITCH_SELECTIVE,
     4,
     4,
     {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX}},
    {"lss_set_node", GW_LSS_SET_NODE, 1, 1, {255, 0, 0, 0}},
    {"lss_conf_bitrate", GW_LSS_CONF_BITRATE, 2, 2, {0, 9, 0, 0}},
    {"lss_activate_bitrate", GW_LSS_ACTIVATE_BITRATE, 1, 1, {UINT16_MAX, 0, 0, 0}},
    {"lss_store", GW_LSS_STORE, 0, 0, {0, 0, 0, 0}},
    {"lss_inquire_addr", GW_LSS_INQUIRE, 0, 1, {3, 0, 0, 0}},
    {"lss_get_node", GW_LSS_GET_NODE, 0, 0, {0, 0, 0, 0}},
    {"_lss_fastscan", GW_LSS_FASTSCAN, 0, 1, {UINT16_MAX, 0, 0, 0}},
};

static const char help_text[] =
    "comaster gateway: CiA 309-3 ASCII commands, one a line:\n"
    "[<sequence>] [[<net>] <node>] r[ead] <index> <subindex> [<datatype>]\n"
    "[<sequence>] [[<net>] <node>] w[rite] <index> <subindex> <datatype> <value>\n"
    "[<sequence>] [[<net>] <node>] start | stop | preop[erational]\n"
    "[<sequence>] [[<net>] <node>] reset node | reset comm[unication]\n"
    "[<sequence>] [<net>] set network 1 | set node <1..127>\n"
    "[<sequence>] [<net>] set sdo_timeout <ms> | set sdo_block <0|1>\n"
    "[<sequence>] [<net>] lss_switch_glob <0|1>\n"
    "[<sequence>] [<net>] lss_switch_sel <vendor> <product> <revision> <serial>\n"
    "[<sequence>] [<net>] lss_set_node <1..127|255> | lss_store | lss_get_node\n"
    "[<sequence>] [<net>] lss_conf_bitrate 0 <index> | lss_activate_bitrate <ms>\n"
    "[<sequence>] [<net>] lss_inquire_addr [<0..3>] | _lss_fastscan [<ms>]\n"
    "[<sequence>] help\n"
    "Node 0 sends an NMT command to all nodes. Data types: b i8 i16 i32 i64 u8 u16\n"
    "u32 u64 x8 x16 x32 x64 (hexadecimal) r32 r64 vs (quoted when it has blanks)\n"
    "hex (bytes); without one a read prints hex. Replies: [<sequence>] OK, a value,\n"
    "ERROR:0x<SDO abort code> or ERROR:<code>: 100 not supported, 101 syntax,\n"
    "102 busy, 103 time-out, 105 no default node, 106 unsupported net, 107\n"
    "unsupported node, 501..504 the LSS slave's error.\r\n";

void gw_session_init(gw_session_t *session)
{
    session->node = -1;
    session->sdo_timeout_ms = GW_DEFAULT_SDO_TIMEOUT_MS;
    session->sdo_block = false;
}

/* The line cut into tokens, in place in a copy: quoted tokens lose their quotes. Returns the
 * count, -1 for an unterminated quote. */
static int tokenize(char *text, char **tokens)
{
    int count = 0;
    char *p = text;
    for (;;) {
        while (*p && isspace((unsigned char)*p))
            p++;
        if (*p == '\0' || *p == '#')
            return count;
        if (count == MAX_TOKENS)
            return -1;
        if (*p == '"') {
            char *out = ++p;
            tokens[count++] = out;
            for (;;) {
                if (*p == '\0')
                    return -1;
                if (*p == '"' && p[1] == '"') {
                    *out++ = '"';
                    p += 2;
                } else if (*p == '"') {
                    p++;
                    break;
                } else {
                    *out++ = *p++;
                }
            }
            if (*p && !isspace((unsigned char)*p))
                return -1;
            *out = '\0';
            if (*p)
                p++;
        } else {
            tokens[count++] = p;
            while (*p && !isspace((unsigned char)*p))
                p++;
            if (*p)
                *p++ = '\0';
        }
    }
}

static bool is_any(const char *token, const char *const *names, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (strcasecmp(token, names[i]) == 0)
            return true;
    return false;
}

static const gw_type_t *type_by_name(const char *name)
{
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcasecmp(types[i].name, name) == 0)
            return &types[i];
    return NULL;
}

static void reply_error(gw_request_t *req, unsigned code)
{
    req->action = GW_REPLY;
    gw_reply_error(req->reply, sizeof req->reply, req->sequence, code);
}

static void reply_ok(gw_request_t *req)
{
    req->action = GW_REPLY;
    gw_reply_ok(req->reply, sizeof req->reply, req->sequence);
}

/* The node of a command: the line's, else the session's. NMT takes 0 (all nodes). */
static bool take_node(gw_request_t *req, int node, int min)
{
    if (node < 0) {
        reply_error(req, GW_ERROR_NO_DEFAULT_NODE);
        return false;
    }
    if (node < min || node > 127) {
        reply_error(req, GW_ERROR_UNSUPPORTED_NODE);
        return false;
    }
    req->node = (uint8_t)node;
    return true;
}

static void parse_set(gw_session_t *session, gw_request_t *req, char **arg, int count)
{
    if (count != 2) {
        reply_error(req, count == 1 && !is_any(arg[0],
                                               (const char *const[]){"network", "node",
                                                                     "sdo_timeout", "sdo_block"},
                                               4)
                             ? GW_ERROR_NOT_SUPPORTED
                             : GW_ERROR_SYNTAX);
        return;
    }
    uint32_t value;
    if (strcasecmp(arg[0], "network") == 0) {
        if (!comaster_parse_number(arg[1], UINT16_MAX, &value))
            reply_error(req, GW_ERROR_SYNTAX);
        else if (value != GW_NET)
            reply_error(req, GW_ERROR_UNSUPPORTED_NET);
        else
            reply_ok(req);
    } else if (strcasecmp(arg[0], "node") == 0) {
        if (!comaster_parse_number(arg[1], 127, &value) || value == 0) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
        session->node = (int16_t)value;
        reply_ok(req);
    } else if (strcasecmp(arg[0], "sdo_timeout") == 0) {
        if (!comaster_parse_number(arg[1], UINT16_MAX, &value) || value == 0) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
        session->sdo_timeout_ms = (uint16_t)value;
        reply_ok(req);
    } else if (strcasecmp(arg[0], "sdo_block") == 0) {
        if (!comaster_parse_number(arg[1], 1, &value)) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
        session->sdo_block = value == 1;
        reply_ok(req);
    } else {
        reply_error(req, GW_ERROR_NOT_SUPPORTED);
    }
}

/* index and sub-index of r[ead] and w[rite]. */
static bool parse_object(gw_request_t *req, char **arg)
{
    uint32_t index, sub;
    if (!comaster_parse_number(arg[0], UINT16_MAX, &index) ||
        !comaster_parse_number(arg[1], UINT8_MAX, &sub)) {
        reply_error(req, GW_ERROR_SYNTAX);
        return false;
    }
    req->index = (uint16_t)index;
    req->sub = (uint8_t)sub;
    return true;
}

static bool parse_type(gw_request_t *req, const char *name)
{
    req->type = type_by_name(name);
    if (!req->type)
        reply_error(req, is_any(name, unsupported_types,
                                sizeof unsupported_types / sizeof unsupported_types[0])
                             ? GW_ERROR_NOT_SUPPORTED
                             : GW_ERROR_SYNTAX);
    return req->type != NULL;
}

static void parse_read(gw_request_t *req, char **arg, int count)
{
    if (count < 2 || count > 3) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    if (!parse_object(req, arg) || !parse_type(req, count == 3 ? arg[2] : "hex"))
        return;
    req->action = GW_READ;
}

/* The value of w[rite]: one token (a quoted string for blanks), or for hex the bytes of the
 * remaining tokens. */
static void parse_write(gw_request_t *req, char **arg, int count)
{
    if (count < 4) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    if (!parse_object(req, arg) || !parse_type(req, arg[2]))
        return;
    char text[GW_LINE_MAX];
    text[0] = '\0';
    if (req->type->kind == 'h') {
        for (int i = 3; i < count; i++)
            strncat(text, arg[i], sizeof text - strlen(text) - 1);
    } else if (count == 4) {
        snprintf(text, sizeof text, "%s", arg[3]);
    } else {
        {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
    }
    char err[128];
    const comaster_type_t *type = comaster_type_by_code(req->type->code);
    if (!comaster_value_parse(type, text, req->data, sizeof req->data, &req->len, err,
                              sizeof err) ||
        req->len == 0) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    req->action = GW_WRITE;
}

static void parse_nmt(gw_request_t *req, const char *command, char **arg, int count)
{
    if (strcasecmp(command, "reset") == 0) {
        if (count != 1) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
        if (strcasecmp(arg[0], "node") == 0)
            req->nmt_command = CO_NMT_CS_RESET_NODE;
        else if (strcasecmp(arg[0], "comm") == 0 || strcasecmp(arg[0], "communication") == 0)
            req->nmt_command = CO_NMT_CS_RESET_COMMUNICATION;
        else {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
    } else {
        if (count != 0) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
        if (strcasecmp(command, "start") == 0)
            req->nmt_command = CO_NMT_CS_START;
        else if (strcasecmp(command, "stop") == 0)
            req->nmt_command = CO_NMT_CS_STOP;
        else
            req->nmt_command = CO_NMT_CS_ENTER_PRE_OPERATIONAL;
    }
    req->action = GW_NMT;
}

static void parse_lss(gw_request_t *req, const lss_command_t *cmd, char **arg, int count)
{
    if (count < cmd->min || count > cmd->max) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    for (int i = 0; i < count; i++) {
        if (!comaster_parse_number(arg[i], cmd->bound[i], &req->args[i])) {
            reply_error(req, GW_ERROR_SYNTAX);
            return;
        }
    }
    req->lss = cmd->lss;
    if (cmd->lss == GW_LSS_INQUIRE && count == 0)
        req->lss = GW_LSS_INQUIRE_ALL;
    if (cmd->lss == GW_LSS_FASTSCAN && count == 0)
        req->args[0] = GW_DEFAULT_FASTSCAN_MS;
    /* Node-id 0 is none, as index 5 of the bit timing table (reserved) and a fastscan without
     * time. */
    bool invalid = (cmd->lss == GW_LSS_SET_NODE &&
                    (req->args[0] == 0 || (req->args[0] > 127 && req->args[0] < 255))) ||
                   (cmd->lss == GW_LSS_CONF_BITRATE && req->args[1] == 5) ||
                   (cmd->lss == GW_LSS_FASTSCAN && req->args[0] == 0);
    if (invalid) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    req->action = GW_LSS;
}

static const lss_command_t *lss_by_name(const char *name)
{
    for (size_t i = 0; i < sizeof lss_commands / sizeof lss_commands[0]; i++)
        if (strcasecmp(lss_commands[i].name, name) == 0)
            return &lss_commands[i];
    return NULL;
}

/* The sequence "[N]", then up to two numbers before the command: [[net] node]. Returns 0, a
 * CiA 309-3 error code, or -1 when the line has no sequence. */
static int parse_head(gw_request_t *req, char **tokens, int count, int *at, int *node)
{
    const char *seq = tokens[0];
    size_t len = strlen(seq);
    char digits[16];
    uint32_t sequence;
    if (len < 3 || len - 2 >= sizeof digits || seq[0] != '[' || seq[len - 1] != ']')
        return -1;
    memcpy(digits, seq + 1, len - 2);
    digits[len - 2] = '\0';
    if (!comaster_parse_number(digits, UINT32_MAX, &sequence))
        return -1;
    req->sequence = sequence;
    uint32_t numbers[2];
    int n = 0;
    *at = 1;
    while (*at < count && isdigit((unsigned char)tokens[*at][0])) {
        if (n == 2 || !comaster_parse_number(tokens[*at], UINT32_MAX, &numbers[n]))
            return GW_ERROR_SYNTAX;
        n++;
        (*at)++;
    }
    if (*at == count)
        return GW_ERROR_SYNTAX;
    /* set and the LSS commands take a net alone: [<net>] set ... */
    const char *command = tokens[*at];
    bool net_only = strcasecmp(command, "set") == 0 || lss_by_name(command) != NULL ||
                    strcasecmp(command, "lss_allnodes") == 0;
    if (net_only && n == 2)
        return GW_ERROR_SYNTAX;
    if ((n == 2 || net_only) && n > 0 && numbers[0] != GW_NET)
        return GW_ERROR_UNSUPPORTED_NET;
    if (!net_only && n > 0 && numbers[n - 1] > 127)
        return GW_ERROR_UNSUPPORTED_NODE;
    if (!net_only && n > 0)
        *node = (int)numbers[n - 1];
    return 0;
}

void gw_parse(gw_session_t *session, uint32_t *last_sequence, const char *line, gw_request_t *req)
{
    char copy[GW_LINE_MAX];
    char *tokens[MAX_TOKENS];
    req->action = GW_REPLY;
    req->help = NULL;
    req->reply[0] = '\0';
    req->sequence = *last_sequence;
    snprintf(copy, sizeof copy, "%s", line);
    int count = tokenize(copy, tokens);
    if (count == 0) {
        snprintf(req->reply, sizeof req->reply, "\r\n"); /* an empty line or a comment */
        return;
    }
    int at = 0;
    int node = session->node;
    /* A line without its sequence: the error reply repeats the one before. */
    int head = count < 0 ? -1 : parse_head(req, tokens, count, &at, &node);
    if (head < 0) {
        reply_error(req, GW_ERROR_SYNTAX);
        return;
    }
    *last_sequence = req->sequence;
    if (head > 0) {
        reply_error(req, (unsigned)head);
        return;
    }
    const char *command = tokens[at];
    char **arg = tokens + at + 1;
    int args = count - at - 1;
    if (strcasecmp(command, "set") == 0) {
        parse_set(session, req, arg, args);
    } else if (strcasecmp(command, "r") == 0 || strcasecmp(command, "read") == 0) {
        if (take_node(req, node, 1))
            parse_read(req, arg, args);
    } else if (strcasecmp(command, "w") == 0 || strcasecmp(command, "write") == 0) {
        if (take_node(req, node, 1))
            parse_write(req, arg, args);
    } else if (is_any(command,
                      (const char *const[]){"start", "stop", "preop", "preoperational", "reset"},
                      5)) {
        if (take_node(req, node, 0))
            parse_nmt(req, command, arg, args);
    } else if (lss_by_name(command)) {
        parse_lss(req, lss_by_name(command), arg, args);
    } else if (strcasecmp(command, "help") == 0) {
        req->help = help_text;
        snprintf(req->reply, sizeof req->reply, "[%" PRIu32 "] ", req->sequence);
    } else {
        reply_error(req, GW_ERROR_NOT_SUPPORTED);
    }
}

size_t gw_reply_ok(char *out, size_t cap, uint32_t sequence)
{
    return (size_t)snprintf(out, cap, "[%" PRIu32 "] OK\r\n", sequence);
}

size_t gw_reply_error(char *out, size_t cap, uint32_t sequence, unsigned code)
{
    return (size_t)snprintf(out, cap, "[%" PRIu32 "] ERROR:%u\r\n", sequence, code);
}

size_t gw_reply_abort(char *out, size_t cap, uint32_t sequence, uint32_t abort_code)
{
    return (size_t)snprintf(out, cap, "[%" PRIu32 "] ERROR:0x%08" PRIX32 "\r\n", sequence,
                            abort_code);
}

size_t gw_reply_words(char *out, size_t cap, uint32_t sequence, const uint32_t *words,
                      unsigned count, unsigned digits)
{
    size_t used = (size_t)snprintf(out, cap, "[%" PRIu32 "]", sequence);
    for (unsigned i = 0; i < count && used < cap; i++)
        used += (size_t)snprintf(out + used, cap - used, " 0x%0*" PRIX32, (int)digits, words[i]);
    if (used < cap)
        used += (size_t)snprintf(out + used, cap - used, "\r\n");
    return used;
}

static uint64_t get_le(const uint8_t *data, size_t len)
{
    uint64_t v = 0;
    for (size_t i = len; i > 0; i--)
        v = v << 8 | data[i - 1];
    return v;
}

/* A string in quotes, a quote in it doubled, NULs left out (canopend's vs). */
static void format_string(const uint8_t *data, size_t len, char *out, size_t cap)
{
    size_t used = 0;
    out[used++] = '"';
    for (size_t i = 0; i < len && used + 3 < cap; i++) {
        if (data[i] == '\0' || data[i] == '\r')
            continue;
        out[used++] = (char)data[i];
        if (data[i] == '"')
            out[used++] = '"';
    }
    out[used++] = '"';
    out[used] = '\0';
}

bool gw_reply_value(char *out, size_t cap, uint32_t sequence, const gw_type_t *type,
                    const uint8_t *data, size_t len)
{
    if (type->size != 0 && len != type->size)
        return false;
    int head = snprintf(out, cap, "[%" PRIu32 "] ", sequence);
    char *text = out + head;
    size_t room = cap - (size_t)head - 2; /* CR LF */
    bool is_text;
    if (type->kind == 'x') {
        snprintf(text, room, "0x%0*" PRIX64, 2 * type->size, get_le(data, len));
    } else if (type->kind == 'r' && type->size == 4) {
        uint32_t bits = (uint32_t)get_le(data, len);
        float f;
        memcpy(&f, &bits, sizeof f);
        snprintf(text, room, "%g", (double)f);
    } else if (type->kind == 'r') {
        uint64_t bits = get_le(data, len);
        double d;
        memcpy(&d, &bits, sizeof d);
        snprintf(text, room, "%g", d);
    } else if (type->kind == 's') {
        format_string(data, len, text, room);
    } else {
        comaster_value_format(comaster_type_by_code(type->code), data, len, COMASTER_VALUE_DECIMAL,
                              text, room, &is_text);
    }
    strcat(text, "\r\n");
    return true;
}
