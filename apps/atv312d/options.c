/* SPDX-License-Identifier: Apache-2.0 */
/* The daemon's command-line parser and its --help (options.h). */
#include "atv312d/options.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <net/if.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

static int usage_error(char *err, size_t err_len, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static int usage_error(char *err, size_t err_len, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(err, err_len, format, args);
    va_end(args);
    return EX_USAGE;
}

/* --http's host when it names only a port: loopback, so that nothing but this machine connects. */
#define HTTP_DEFAULT_HOST "127.0.0.1"

static bool parse_port(const char *text, uint16_t *port)
{
    if (!isdigit((unsigned char)text[0]))
        return false;
    char *end;
    errno = 0;
    unsigned long value = strtoul(text, &end, 10);
    if (errno != 0 || *end != '\0' || value > 65535)
        return false;
    *port = (uint16_t)value;
    return true;
}

/* The host part, an IPv4 or IPv6 literal ("localhost" is 127.0.0.1: names are not resolved). */
static bool parse_host(const char *host, uint16_t port, atv312d_http_address_t *address)
{
    struct sockaddr_in *v4 = (struct sockaddr_in *)&address->addr;
    struct sockaddr_in6 *v6 = (struct sockaddr_in6 *)&address->addr;
    if (strcmp(host, "localhost") == 0)
        host = HTTP_DEFAULT_HOST;
    if (inet_pton(AF_INET, host, &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons(port);
        address->len = sizeof *v4;
        address->loopback = (ntohl(v4->sin_addr.s_addr) >> 24) == 127;
        snprintf(address->text, sizeof address->text, "%s:%u", host, port);
        return true;
    }
    if (inet_pton(AF_INET6, host, &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons(port);
        address->len = sizeof *v6;
        address->loopback = IN6_IS_ADDR_LOOPBACK(&v6->sin6_addr);
        snprintf(address->text, sizeof address->text, "[%s]:%u", host, port);
        return true;
    }
    return false;
}

int atv312d_parse_http_address(const char *text, atv312d_http_address_t *address, char *err,
                               size_t err_len)
{
    memset(address, 0, sizeof *address);
    char host[INET6_ADDRSTRLEN + 16];
    const char *port_text;
    if (text[0] == '[') {
        const char *close = strchr(text, ']');
        if (!close || close[1] != ':' || (size_t)(close - text - 1) >= sizeof host)
            return usage_error(err, err_len,
                               "--http %s: write an IPv6 address in brackets with its port, "
                               "e.g. [::1]:8080",
                               text);
        snprintf(host, sizeof host, "%.*s", (int)(close - text - 1), text + 1);
        port_text = close + 2;
    } else {
        const char *colon = strrchr(text, ':');
        if (colon && (size_t)(colon - text) >= sizeof host)
            colon = NULL;
        snprintf(host, sizeof host, "%.*s", colon ? (int)(colon - text) : 0, text);
        if (!colon)
            snprintf(host, sizeof host, HTTP_DEFAULT_HOST);
        port_text = colon ? colon + 1 : text;
        if (strchr(host, ':'))
            return usage_error(err, err_len,
                               "--http %s: write an IPv6 address in brackets with its port, "
                               "e.g. [::1]:8080",
                               text);
    }
    uint16_t port;
    if (!parse_port(port_text, &port))
        return usage_error(err, err_len,
                           "--http %s: '%s' is not a port: give [ADDRESS:]PORT with PORT 0..65535, "
                           "e.g. --http 8080 (127.0.0.1) or --http 0.0.0.0:8080",
                           text, port_text);
    if (!parse_host(host, port, address))
        return usage_error(err, err_len,
                           "--http %s: '%s' is not an IPv4 or IPv6 address: give one such as "
                           "127.0.0.1, 0.0.0.0, [::1] or [::] (names are not resolved)",
                           text, host);
    return 0;
}

/* Decimal, or hexadecimal with 0x (CANopen people write both); no sign, no trailing text. */
static bool parse_number(const char *text, size_t len, unsigned long *value)
{
    char buf[16];
    if (len == 0 || len >= sizeof buf || !isdigit((unsigned char)text[0]))
        return false;
    memcpy(buf, text, len);
    buf[len] = '\0';
    int base = (len > 2 && buf[0] == '0' && (buf[1] == 'x' || buf[1] == 'X')) ? 16 : 10;
    char *end;
    errno = 0;
    *value = strtoul(buf, &end, base);
    return errno == 0 && *end == '\0' && end != buf + (base == 16 ? 2 : 0);
}

/* What a drive's address is on each bus: CANopen node-ids (--node-id) or DeviceNet MAC IDs
 * (--mac-id), written the same ways. */
typedef struct id_kind {
    const char *option; /* "--node-id" */
    const char *noun;   /* "node-id" */
    int min, max;
} id_kind_t;

static const id_kind_t node_id_kind = {"--node-id", "node-id", ATV312D_NODE_ID_MIN,
                                       ATV312D_NODE_ID_MAX};
static const id_kind_t mac_id_kind = {"--mac-id", "MAC ID", ATV312D_MAC_ID_MIN, ATV312D_MAC_ID_MAX};

static int parse_id(const id_kind_t *kind, const char *text, size_t len, unsigned long *id,
                    char *err, size_t err_len)
{
    if (!parse_number(text, len, id))
        return usage_error(err, err_len,
                           "%s: '%.*s' is not a %s: use a number %d..%d, a range like 4-9 or a "
                           "list like 4,6",
                           kind->option, (int)len, text, kind->noun, kind->min, kind->max);
    if (*id < (unsigned long)kind->min || *id > (unsigned long)kind->max)
        return usage_error(err, err_len, "%s: %.*s is out of range: %ss are %d..%d", kind->option,
                           (int)len, text, kind->noun, kind->min, kind->max);
    return 0;
}

/* The drives given so far: each --node-id (or --mac-id) option is a group, and a --model after it
 * names the model of that group. Every group adds at least one id, so there are at most 127. */
typedef struct node_groups {
    uint8_t group_of[ATV312D_NODE_ID_MAX + 1]; /* 0: not given; n: given by the n-th group */
    atv312d_model_t model_of[ATV312D_NODE_ID_MAX + 1]; /* per group; name NULL: default */
    bool can_off_of[ATV312D_NODE_ID_MAX + 1];          /* per group: --canopen-off */
    uint8_t count;                                     /* groups so far */
    const char *first_node_id;                         /* the first --node-id's value, NULL: none */
    const char *first_mac_id;                          /* the first --mac-id's value, NULL: none */
    /* --unconfigured N: a group of N nodes without node-id; 0 for a group of ids. */
    uint8_t unconfigured_of[ATV312D_NODE_ID_MAX + 1];
    const char *first_unconfigured; /* the first --unconfigured's value, NULL: none */
    /* A --model with no group of its own before it, for the --unconfigured after it
     * (`--model io --unconfigured 20`); name NULL: none. */
    atv312d_model_t pending_model;
    const char *pending_after; /* the model of the group before the pending one, NULL: none */
} node_groups_t;

/* A --model before a group other than --unconfigured's belongs to none. */
static int refuse_pending_model(const node_groups_t *groups, char *err, size_t err_len)
{
    const char *name = groups->pending_model.name;
    if (groups->pending_after)
        return usage_error(err, err_len,
                           "--model %s: the nodes of the --node-id before it are already %s: "
                           "give one --model after each --node-id",
                           name, groups->pending_after);
    return usage_error(err, err_len,
                       "--model %s: no --node-id before it: a model follows the node-ids of its "
                       "drives, e.g. --node-id 4 --model %s (--mac-id 25 --model %s on DeviceNet), "
                       "or comes just before --unconfigured: --model io --unconfigured 20",
                       name, name, name);
}

/* One --node-id or --mac-id value: "N", "A-B" or a comma-separated list of those, a new group. */
static int parse_ids(const id_kind_t *kind, const char *value, node_groups_t *groups, char *err,
                     size_t err_len)
{
    if (groups->pending_model.name)
        return refuse_pending_model(groups, err, err_len);
    const char **first = kind == &mac_id_kind ? &groups->first_mac_id : &groups->first_node_id;
    if (!*first)
        *first = value;
    groups->count++;
    const char *item = value;
    for (;;) {
        size_t len = strcspn(item, ",");
        const char *dash = memchr(item, '-', len);
        unsigned long first_id = 0, last_id = 0;
        int rc;
        if (dash) {
            rc = parse_id(kind, item, (size_t)(dash - item), &first_id, err, err_len);
            if (rc == 0)
                rc = parse_id(kind, dash + 1, len - (size_t)(dash - item) - 1, &last_id, err,
                              err_len);
            if (rc == 0 && first_id > last_id)
                rc = usage_error(err, err_len, "%s: range %.*s is backwards: write it as %lu-%lu",
                                 kind->option, (int)len, item, last_id, first_id);
        } else {
            rc = parse_id(kind, item, len, &first_id, err, err_len);
            last_id = first_id;
        }
        if (rc)
            return rc;
        for (unsigned long id = first_id; id <= last_id; id++) {
            if (groups->group_of[id])
                return usage_error(err, err_len,
                                   "%s: %s %lu is given twice: each drive needs its own %s in "
                                   "%d..%d",
                                   kind->option, kind->noun, id, kind->noun, kind->min, kind->max);
            groups->group_of[id] = groups->count;
        }
        if (item[len] == '\0')
            return 0;
        item += len + 1;
    }
}

/* "atv312, atv31, ..., plc300, io": the names --model takes. */
static void list_models(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < atv312d_model_count() && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                                 atv312d_model_at(i).name);
}

/* --unconfigured N: N nodes without node-id (FFh) for an LSS master to number (docs/lss.md), a
 * group of its own whose model is the --model just before or after it. */
static int parse_unconfigured(const char *value, node_groups_t *groups, char *err, size_t err_len)
{
    char *end;
    long count = strtol(value, &end, 10);
    if (*value < '0' || *value > '9' || *end != '\0' || count < 1 || count > ATV312D_NODE_ID_MAX)
        return usage_error(err, err_len,
                           "--unconfigured %s: give the number of nodes without node-id, 1..%d, "
                           "e.g. --model io --unconfigured 20",
                           value, ATV312D_NODE_ID_MAX);
    if (!groups->first_unconfigured)
        groups->first_unconfigured = value;
    groups->count++;
    groups->unconfigured_of[groups->count] = (uint8_t)count;
    groups->model_of[groups->count] = groups->pending_model;
    groups->pending_model.name = NULL;
    return 0;
}

/* --model names the model of the drives of the --node-id just before it, or of the
 * --unconfigured just after it. */
static int parse_model(const char *name, node_groups_t *groups, char *err, size_t err_len)
{
    atv312d_model_t model;
    if (!atv312d_model_find(name, &model)) {
        char names[128];
        list_models(names, sizeof names);
        return usage_error(err, err_len, "--model: unknown model '%s': the models are %s", name,
                           names);
    }
    if (groups->pending_model.name)
        return refuse_pending_model(groups, err, err_len);
    if (groups->count == 0 || groups->model_of[groups->count].name) {
        groups->pending_model = model;
        groups->pending_after = groups->count ? groups->model_of[groups->count].name : NULL;
        return 0;
    }
    groups->model_of[groups->count] = model;
    return 0;
}

/* --canopen-off: the drives of the --node-id just before it have AdCO = 0 (D-ADCO-BDCO). */
static int parse_canopen_off(node_groups_t *groups, char *err, size_t err_len)
{
    if (groups->count == 0)
        return usage_error(err, err_len,
                           "--canopen-off: no --node-id before it: it follows the node-ids of its "
                           "drives, e.g. --node-id 4 --canopen-off");
    groups->can_off_of[groups->count] = true;
    return 0;
}

typedef enum {
    OPT_NODE_ID,
    OPT_MAC_ID,
    OPT_DEVICENET,
    OPT_BAUD,
    OPT_MODEL,
    OPT_CANOPEN_OFF,
    OPT_UNCONFIGURED,
    OPT_STORE,
    OPT_TRACE,
    OPT_CONTROL,
    OPT_STATUS,
    OPT_HTTP,
    OPT_HTTP_ACTIONS,
    OPT_HTTP_TOKEN,
    OPT_LOG_LEVEL,
    OPT_HELP,
    OPT_VERSION
} opt_t;

/* Each option, and the name of its value in --help (NULL: it takes none). */
static const struct {
    const char *name;
    opt_t opt;
    const char *value;
} options[] = {
    {"--node-id", OPT_NODE_ID, "N"},
    {"--mac-id", OPT_MAC_ID, "N"},
    {"--devicenet", OPT_DEVICENET, NULL},
    {"--baud", OPT_BAUD, "RATE"},
    {"--model", OPT_MODEL, "M"},
    {"--canopen-off", OPT_CANOPEN_OFF, NULL},
    {"--unconfigured", OPT_UNCONFIGURED, "N"},
    {"--store", OPT_STORE, "FILE"},
    {"--trace", OPT_TRACE, "FILE"},
    {"--control", OPT_CONTROL, "PATH"},
    {"--status", OPT_STATUS, "FILE"},
    {"--http-actions", OPT_HTTP_ACTIONS, NULL},
    {"--http-token", OPT_HTTP_TOKEN, "FILE"},
    {"--http", OPT_HTTP, "[ADDRESS:]PORT"},
    {"--log-level", OPT_LOG_LEVEL, "LEVEL"},
    {"--help", OPT_HELP, NULL},
    {"-h", OPT_HELP, NULL},
    {"--version", OPT_VERSION, NULL},
    {"-V", OPT_VERSION, NULL},
};

/* Finds the option of "--name" or "--name=value"; *inline_value points after '='. */
static int find_option(const char *arg, const char **inline_value)
{
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        size_t n = strlen(options[i].name);
        if (strncmp(arg, options[i].name, n) != 0)
            continue;
        if (arg[n] == '\0') {
            *inline_value = NULL;
            return (int)i;
        }
        if (arg[n] == '=' && options[i].value) {
            *inline_value = arg + n + 1;
            return (int)i;
        }
    }
    return -1;
}

/* The DeviceNet data rates, as --baud takes them and as the DeviceNet object reports them. */
static const struct {
    const char *name;
    atv312d_baud_t baud;
} baud_rates[] = {
    {"125k", ATV312D_BAUD_125K},
    {"250k", ATV312D_BAUD_250K},
    {"500k", ATV312D_BAUD_500K},
};

static int parse_baud(const char *value, atv312d_options_t *opts, char *err, size_t err_len)
{
    for (size_t i = 0; i < sizeof baud_rates / sizeof baud_rates[0]; i++) {
        if (strcmp(value, baud_rates[i].name) == 0) {
            opts->baud = baud_rates[i].baud;
            opts->baud_given = true;
            return 0;
        }
    }
    return usage_error(err, err_len,
                       "--baud: unknown data rate '%s': DeviceNet runs at 125k, 250k or 500k",
                       value);
}

static int apply_option(opt_t opt, const char *value, atv312d_options_t *opts,
                        node_groups_t *groups, char *err, size_t err_len)
{
    switch (opt) {
    case OPT_NODE_ID:
        return parse_ids(&node_id_kind, value, groups, err, err_len);
    case OPT_MAC_ID:
        return parse_ids(&mac_id_kind, value, groups, err, err_len);
    case OPT_DEVICENET:
        opts->devicenet = true;
        return 0;
    case OPT_BAUD:
        return parse_baud(value, opts, err, err_len);
    case OPT_MODEL:
        return parse_model(value, groups, err, err_len);
    case OPT_CANOPEN_OFF:
        return parse_canopen_off(groups, err, err_len);
    case OPT_UNCONFIGURED:
        return parse_unconfigured(value, groups, err, err_len);
    case OPT_STORE:
        opts->store_path = value;
        return 0;
    case OPT_TRACE:
        opts->trace_path = value;
        return 0;
    case OPT_CONTROL:
        opts->control_path = value;
        return 0;
    case OPT_STATUS:
        opts->status_path = value;
        return 0;
    case OPT_HTTP:
        opts->http = value;
        return atv312d_parse_http_address(value, &opts->http_address, err, err_len);
    case OPT_HTTP_ACTIONS:
        opts->http_actions = true;
        return 0;
    case OPT_HTTP_TOKEN:
        opts->http_token_path = value;
        return 0;
    case OPT_LOG_LEVEL:
        if (!co_log_level_parse(value, &opts->log_level))
            return usage_error(err, err_len,
                               "--log-level: unknown level '%s': use error, warn, info or debug",
                               value);
        return 0;
    case OPT_HELP:
        opts->help = true;
        return 0;
    case OPT_VERSION:
        opts->version = true;
        return 0;
    }
    return 0;
}

/* "atv312": the models with DeviceNet data. */
static void list_devicenet_models(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < drive_model_count && used < len; i++) {
        if (drive_models[i].devicenet)
            used += (size_t)snprintf(buf + used, len - used, "%s%s", used ? ", " : "",
                                     drive_models[i].name);
    }
}

/* One interface is one bus: CANopen (node-ids) or DeviceNet (--devicenet, MAC IDs), never both;
 * a DeviceNet bus takes only the models with a DeviceNet card. */
static int check_bus(atv312d_options_t *opts, node_groups_t *groups, char *err, size_t err_len)
{
    if (!opts->devicenet) {
        if (groups->first_mac_id)
            return usage_error(err, err_len,
                               "--mac-id %s: MAC IDs are DeviceNet's and this interface is "
                               "CANopen: add --devicenet to put the drives on DeviceNet",
                               groups->first_mac_id);
        if (opts->baud_given)
            return usage_error(err, err_len,
                               "--baud: the data rate is DeviceNet's (its DeviceNet object "
                               "reports it): add --devicenet; a CANopen interface's bitrate is "
                               "set with ip link");
        return 0;
    }
    for (uint8_t g = 1; g <= groups->count; g++)
        if (groups->can_off_of[g])
            return usage_error(err, err_len,
                               "--canopen-off: AdCO is the CANopen port's address; a DeviceNet "
                               "drive is on the bus by its card's MAC ID: leave --canopen-off out");
    if (groups->first_unconfigured)
        return usage_error(err, err_len,
                           "--unconfigured %s: nodes without node-id wait for a CANopen LSS "
                           "master (CiA 305); --devicenet makes %s a DeviceNet bus, which has no "
                           "LSS: leave --devicenet out, or give the drives --mac-id 0..63",
                           groups->first_unconfigured, opts->iface);
    if (groups->first_node_id)
        return usage_error(err, err_len,
                           "--node-id %s: --devicenet makes %s a DeviceNet bus, whose drives have "
                           "MAC IDs: give --mac-id 0..63 instead (one interface is either CANopen "
                           "or DeviceNet: run one atv312d per bus)",
                           groups->first_node_id, opts->iface);
    if (!groups->first_mac_id)
        groups->group_of[ATV312D_MAC_ID_DEFAULT] = ++groups->count;
    for (uint8_t g = 1; g <= groups->count; g++) {
        const atv312d_model_t *model = &groups->model_of[g];
        if (model->name && (!model->drive || !model->drive->devicenet)) {
            char names[128];
            list_devicenet_models(names, sizeof names);
            return usage_error(err, err_len,
                               "--model %s: the %s has no DeviceNet card here: on DeviceNet give "
                               "--model %s, or leave --model out",
                               model->name, model->name, names);
        }
    }
    return 0;
}

/* The nodes of each --unconfigured, after those with node-ids: only a model with LSS starts
 * without node-id (the drives' manuals list no LSS), and a bus numbers at most 127 nodes. */
static int add_unconfigured(atv312d_options_t *opts, const node_groups_t *groups, char *err,
                            size_t err_len)
{
    for (uint8_t g = 1; g <= groups->count; g++) {
        uint8_t count = groups->unconfigured_of[g];
        if (count == 0)
            continue;
        atv312d_model_t model =
            groups->model_of[g].name ? groups->model_of[g] : atv312d_model_at(0);
        if (!model.node || !model.node->lss)
            return usage_error(err, err_len,
                               "--unconfigured %u: the %s has no LSS (CiA 305), so it cannot start "
                               "without node-id: give --model io --unconfigured %u, or give the %s "
                               "--node-id",
                               count, model.name, count, model.name);
        if (opts->node_count + count > (size_t)ATV312D_NODE_ID_MAX)
            return usage_error(err, err_len,
                               "--unconfigured %u: with the other nodes that is %zu nodes, and a "
                               "CANopen bus numbers at most %d",
                               count, opts->node_count + count, ATV312D_NODE_ID_MAX);
        for (uint8_t k = 0; k < count; k++) {
            opts->models[opts->node_count] = model;
            opts->node_ids[opts->node_count++] = CO_LSS_NODE_ID_UNCONFIGURED;
        }
    }
    return 0;
}

/* The web surface's options go with --http; its actions, when anything but this machine can
 * connect, with a token (docs/web.md). */
static int check_http(const atv312d_options_t *opts, char *err, size_t err_len)
{
    if (!opts->http && (opts->http_actions || opts->http_token_path))
        return usage_error(err, err_len,
                           "%s: no --http: the web surface's options need it, e.g. --http 8080",
                           opts->http_actions ? "--http-actions" : "--http-token");
    if (opts->http_token_path && !opts->http_actions)
        return usage_error(err, err_len,
                           "--http-token %s: the token guards the actions: give --http-actions "
                           "too",
                           opts->http_token_path);
    if (opts->http_actions && !opts->http_address.loopback && !opts->http_token_path)
        return usage_error(err, err_len,
                           "--http %s --http-actions: anyone who reaches %s could drive the "
                           "drives: give --http-token FILE (a secret) or listen on loopback "
                           "(--http 127.0.0.1:PORT)",
                           opts->http, opts->http_address.text);
    return 0;
}

/* --canopen-off is the Altivars' AdCO = 0 (D-ADCO-BDCO): refused for a model without AdCO, a
 * plain node or a drive whose node-id is set on its card. */
static int check_canopen_off(const atv312d_model_t *model, bool can_off, char *err, size_t err_len)
{
    if (!can_off)
        return 0;
    if (model->kind == ATV312D_KIND_NODE)
        return usage_error(err, err_len,
                           "--canopen-off: the %s is a plain node, not a drive: it has no AdCO, "
                           "CANopen off is the atv312's and the atv31's AdCO = 0; leave "
                           "--canopen-off out",
                           model->name);
    if (model->drive->profile->can_address.index == 0)
        return usage_error(err, err_len,
                           "--canopen-off: the %s has no AdCO (its node-id is set on its card): "
                           "CANopen off is the atv312's and the atv31's AdCO = 0",
                           model->name);
    return 0;
}

static int check_complete(atv312d_options_t *opts, node_groups_t *groups, char *err, size_t err_len)
{
    if (!opts->iface)
        return usage_error(err, err_len,
                           "missing interface: run atv312d IFACE --node-id N, e.g. atv312d vcan0 "
                           "--node-id 4");
    if (strlen(opts->iface) >= IFNAMSIZ)
        return usage_error(err, err_len,
                           "interface name '%s' is too long: Linux allows at most %d characters",
                           opts->iface, IFNAMSIZ - 1);
    if (groups->pending_model.name)
        return refuse_pending_model(groups, err, err_len);
    int rc = check_bus(opts, groups, err, err_len);
    if (rc == 0)
        rc = check_http(opts, err, err_len);
    if (rc)
        return rc;
    for (int id = 0; id <= ATV312D_NODE_ID_MAX; id++) {
        uint8_t group = groups->group_of[id];
        if (!group)
            continue;
        const atv312d_model_t *model = &groups->model_of[group];
        if (model->name && !opts->devicenet && id > model->node_id_max)
            return usage_error(err, err_len,
                               "--node-id %d: the %s takes node-ids %d..%d, give it one of those",
                               id, model->name, ATV312D_NODE_ID_MIN, model->node_id_max);
        opts->models[opts->node_count] = model->name ? *model : atv312d_model_at(0);
        opts->can_off[opts->node_count] = groups->can_off_of[group];
        rc = check_canopen_off(&opts->models[opts->node_count], opts->can_off[opts->node_count],
                               err, err_len);
        if (rc)
            return rc;
        opts->node_ids[opts->node_count++] = (uint8_t)id;
    }
    rc = add_unconfigured(opts, groups, err, err_len);
    if (rc)
        return rc;
    if (opts->node_count == 0)
        return usage_error(err, err_len,
                           "missing --node-id: give the drive's node-id (%d..%d), e.g. --node-id 4",
                           ATV312D_NODE_ID_MIN, ATV312D_NODE_ID_MAX);
    return 0;
}

int atv312d_parse_args(int argc, char *const argv[], atv312d_options_t *opts, char *err,
                       size_t err_len)
{
    memset(opts, 0, sizeof *opts);
    opts->log_level = CO_LOG_INFO;
    node_groups_t groups = {0};
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || strcmp(arg, "-") == 0) {
            if (opts->iface)
                return usage_error(err, err_len,
                                   "unexpected argument '%s': give one interface (it is '%s')", arg,
                                   opts->iface);
            opts->iface = arg;
            continue;
        }
        const char *value;
        int k = find_option(arg, &value);
        if (k < 0)
            return usage_error(err, err_len, "unknown option '%s'", arg);
        if (options[k].value && !value && i + 1 < argc)
            value = argv[++i];
        if (options[k].value && (!value || value[0] == '\0'))
            return usage_error(err, err_len, "option %s needs a value: give %s %s", options[k].name,
                               options[k].name, options[k].value);
        int rc = apply_option(options[k].opt, value, opts, &groups, err, err_len);
        if (rc)
            return rc;
        if (opts->help || opts->version)
            return 0;
    }
    return check_complete(opts, &groups, err, err_len);
}

void atv312d_print_usage(FILE *out)
{
    fputs("usage: atv312d IFACE --node-id N [--model M] [--node-id N [--model M]...] [options]\n"
          "       atv312d IFACE --devicenet [--mac-id N [--model M]...] [--baud RATE] [options]\n"
          "       atv312d ctl PATH [--json] COMMAND...\n"
          "\n"
          "Puts emulated Schneider Altivar drives (CANopen, CiA 402), WEG PLC300 slaves\n"
          "and CiA 401 I/O nodes on a SocketCAN interface, or Altivar 312 drives with\n"
          "their DeviceNet card on a DeviceNet bus.\n"
          "\n"
          "  IFACE               SocketCAN interface, e.g. can0 or vcan0\n"
          "  --node-id N         node-id 1..127 of a drive or node; a range 4-9 or a list\n"
          "                      4,6 puts several on one socket; may be repeated\n"
          "  --model M           model of the nodes of the --node-id just before it, or of\n"
          "                      the --unconfigured just after it\n",
          out);
    fprintf(out, "                      (default %s), a drive or a node, one of:\n",
            atv312d_model_at(0).name);
    /* The names in a column as wide as the longest: two spaces or more before each description,
     * which is how a reader (and tools/man-from-help.py) tells a term from its description. */
    int width = 0;
    for (size_t i = 0; i < atv312d_model_count(); i++)
        if ((int)strlen(atv312d_model_at(i).name) > width)
            width = (int)strlen(atv312d_model_at(i).name);
    for (size_t i = 0; i < atv312d_model_count(); i++) {
        atv312d_model_t model = atv312d_model_at(i);
        fprintf(out, "                        %-*s  %s\n", width, model.name, model.description);
    }
    fputs("  --canopen-off       the drives of the --node-id just before it have CANopen\n"
          "                      off (AdCO = 0): present, controlled and shown by their\n"
          "                      node-id, silent on the bus (no boot-up, no answer)\n"
          "  --unconfigured N    N nodes without node-id (FFh) for an LSS master to find and\n"
          "                      number (CiA 305), each with its own serial number; only\n"
          "                      a model with LSS (io)\n"
          "  --devicenet         the interface is a DeviceNet bus: the drives are DeviceNet\n"
          "                      slaves (predefined set and UCMM) instead of CANopen nodes\n"
          "  --mac-id N          MAC ID 0..63 of a DeviceNet drive (default 63); ranges,\n"
          "                      lists, repeats and --model after it as for --node-id\n"
          "  --baud RATE         125k (default), 250k or 500k: the data rate the DeviceNet\n"
          "                      object reports (the interface's bitrate is ip link's)\n"
          "  --store FILE        keep parameters saved with 1010h in FILE (all drives share\n"
          "                      it, one record per node-id); on DeviceNet the assembly\n"
          "                      selection and Quick Connect; without it 1010h aborts\n"
          "  --trace FILE        write every frame in and out to FILE in candump -L format\n"
          "                      ('-' = standard output)\n"
          "  --control PATH      take control commands on a UNIX socket at PATH (see below)\n"
          "  --status FILE       rewrite FILE once a second with the CAN controller state,\n"
          "                      the frame counters and the state of every drive; SIGUSR1\n"
          "                      writes the same to the log (also without --status)\n"
          "  --http [ADDRESS:]PORT\n"
          "                      serve a live view of the bench to a browser and its JSON\n"
          "                      API at ADDRESS (default 127.0.0.1; 0.0.0.0, [::1]); read\n"
          "                      only unless --http-actions\n"
          "  --http-actions      let the page (POST /api/command) run the control commands\n"
          "  --http-token FILE   the secret (FILE's first line) a request must send in the\n"
          "                      header X-Atv312d-Token to run a command; required with\n"
          "                      --http-actions when ADDRESS is not loopback\n"
          "  --log-level LEVEL   error, warn, info (default) or debug, on standard error\n"
          "  -h, --help          show this help\n"
          "  -V, --version       show the version\n"
          "\n",
          out);
    fputs("Example: atv312d vcan0 --node-id 4-5 --model atv312 --node-id 6\n"
          "         atv312d vcan0 --node-id 1 --model plc300 --node-id 10-12 --model io\n"
          "         atv312d vcan0 --model io --unconfigured 20\n"
          "         atv312d vcan1 --devicenet --mac-id 25,63\n"
          "\n"
          "Control commands, for testing a master: atv312d ctl PATH COMMAND sends one to\n"
          "the daemon started with --control PATH and prints its one-line reply, 'ok ...'\n"
          "(exit 0), or its refusal as an error (exit 1); with --json the reply is a JSON\n"
          "object. On DeviceNet NODE is the MAC ID.\n"
          "\n"
          "Control commands:\n"
          "  fault NODE CODE     the fault CODE (OHF, OCF, USF, COF, ...) happens: EMCY, 603Fh,\n"
          "                      state Fault (on DeviceNet: Faulted); its cause stays until\n"
          "                      cleared\n"
          "  clear NODE CODE|all\n"
          "                      the cause of the fault is gone (a fault reset is then\n"
          "                      accepted; USF, CFF and CFI end by themselves)\n"
          "  mains NODE undervoltage|normal\n"
          "                      mains undervoltage (the fault USF) or back\n"
          "  stop-key NODE       the keypad's STOP key: status word bit 14; a freewheel stop\n"
          "                      under network control, a ramp stop under local control; on\n"
          "                      an ATV31 (STOP/RESET) also a fault reset once the cause is\n"
          "                      gone\n"
          "  run-key NODE        the keypad's RUN key, under local control: runs to 6042h\n"
          "  local NODE on|off   forced local control (status word bit 9 = 0): the network's\n"
          "                      control word is ignored; either way a freewheel stop\n"
          "  load NODE PERCENT   extra load torque, 0..150 % of nominal: torque and current\n"
          "  input NODE LIn|DIn on|off\n"
          "                      a logic input (LI1..LI3 on an ATV312): a switch assigned\n"
          "                      to it (rFC, CCS, rPS) acts at once; on an I/O node a\n"
          "                      digital input DI1..DI8 (6000h:01, TPDO1)\n"
          "  analog NODE AIn VALUE\n"
          "                      an analogue input (ATV312 AI2 -10..10 V, AI3 0..20 mA;\n"
          "                      ATV31 also AI1 0..10 V): a reference channel Fr1/Fr2\n"
          "                      assigned to it follows, LSP..HSP over its range; on an\n"
          "                      I/O node AI1..AI2, the raw value of 6401h (TPDO2)\n"
          "  pot NODE PERCENT    the front panel's reference potentiometer (ATV31 AIP,\n"
          "                      0..100 %)\n"
          "  marker NODE MARKER [VALUE]\n"
          "                      a PLC300's network marker (%IB2000, %QW2004, %QD2508)\n"
          "                      read, or written as its PLC program would: outputs go\n"
          "                      out in TPDOs, inputs are what the master wrote\n",
          out);
    fputs("  state [NODE]        NMT and CiA 402 state, status word, speed, current, torque,\n"
          "                      front panel display, RUN and ERR LEDs, latched fault, frame\n"
          "                      counters, inputs (on DeviceNet the MS and NS LEDs and the\n"
          "                      Control supervisor state replace the NMT state and the RUN\n"
          "                      and ERR LEDs, the card's counters the CANopen services');\n"
          "                      of a PLC300 or I/O node its NMT state, RUN and ERR LEDs,\n"
          "                      error control event, counters, markers or terminals; a\n"
          "                      node without node-id by its serial number until LSS gives\n"
          "                      it one\n"
          "\n"
          "Example: atv312d ctl /tmp/atv312d.sock fault 4 OHF\n"
          "\n"
          "An error is one line on stderr, 'atv312d: error: ' then what is wrong and what\n"
          "would be right, as the daemon logs (its levels error, warn, info, debug); after\n"
          "wrong arguments a second line names the --help to read. See docs/atv312d.md and\n"
          "docs/web.md.\n"
          "\n"
          "Exit status:\n"
          "  0   stopped by SIGINT or SIGTERM; ctl: the daemon answered ok\n"
          "  1   ctl: the daemon refused the command\n"
          "  64  wrong arguments: an unknown option or model, a bad node-id, MAC ID or\n"
          "      address, options that do not go together\n"
          "  65  bad data: the --http-token file has no secret on its first line\n"
          "  66  the store file or the --http-token file cannot be read\n"
          "  69  no such interface or no SocketCAN, or (--http) no GNU libmicrohttpd;\n"
          "      ctl: no daemon answers at PATH\n"
          "  70  internal error (a drive could not be initialised)\n"
          "  71  system error\n"
          "  73  the trace file, the store's directory or the control socket cannot be\n"
          "      created, or the --http address cannot be listened at\n"
          "  76  ctl: the daemon closed the connection without a reply\n",
          out);
}
