/* SPDX-License-Identifier: Apache-2.0 */
/* The requests of comaster run's control socket that act on the bus through the network master
 * (docs/comaster.md "run and its control socket"): an NMT command confirmed by the state the
 * nodes report, an SDO read or write queued on the master's own client behind the boot of its
 * slaves, disable and enable communication (the PLC300's DisableComm), and the CAN controller's
 * state and counters. NMT and SDO replies come when the master has the answer (a deferred reply
 * of the line socket); the others at once. Each reply is one line, or one JSON object. */
#include "comaster/runner.h"

#include "cli/json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool parse_node(const char *text, bool allow_all, uint8_t *node)
{
    if (allow_all && strcmp(text, "all") == 0) {
        *node = CO_NMT_MASTER_ALL_NODES;
        return true;
    }
    char *end;
    unsigned long n = strtoul(text, &end, 10);
    if (end == text || *end != '\0' || n < 1 || n > CO_NMT_MASTER_NODE_ID_MAX)
        return false;
    *node = (uint8_t)n;
    return true;
}

static const char *disabled_error =
    "error: the communication of the run is disabled: comaster enable\n";

/* ---- nmt COMMAND NODE|all MS ---------------------------------------------------------------- */

static const char *state_text(uint8_t state)
{
    return state == CO_NMT_INITIALISING ? "boot-up" : co_nmt_state_name(state);
}

/* " 4 5 6": the node-ids addressed by the command that are (not) awaited any more. */
static void node_list(const runner_t *r, bool awaited, bool json, char *out, size_t cap)
{
    const co_net_nmt_request_t *n = &r->master.nmt_request;
    size_t used = 0;
    out[0] = '\0';
    for (unsigned id = 1; id <= CO_NMT_MASTER_NODE_ID_MAX && used < cap; id++) {
        bool addressed = n->node_id == id || (n->node_id == CO_NMT_MASTER_ALL_NODES &&
                                              co_net_master_slave(&r->master, (uint8_t)id) != NULL);
        if (addressed && co_net_master_nmt_awaited(&r->master, (uint8_t)id) == awaited)
            used += (size_t)snprintf(out + used, cap - used, "%s%u", used && json ? ", " : " ", id);
    }
}

void run_nmt_done(runner_t *r)
{
    if (r->nmt_ticket == 0)
        return;
    const co_net_nmt_request_t *n = &r->master.nmt_request;
    char target[16], json_node[8], confirmed[512], missing[512], reply[1280];
    if (n->node_id == CO_NMT_MASTER_ALL_NODES) {
        snprintf(target, sizeof target, "all");
        snprintf(json_node, sizeof json_node, "\"all\"");
    } else {
        snprintf(target, sizeof target, "node %u", n->node_id);
        snprintf(json_node, sizeof json_node, "%u", n->node_id);
    }
    const char *command = comaster_nmt_name(n->command);
    const char *state = state_text(n->expected);
    node_list(r, false, r->nmt_json, confirmed, sizeof confirmed);
    node_list(r, true, false, missing, sizeof missing);
    if (r->master.disabled && missing[0] != '\0')
        snprintf(reply, sizeof reply, "error: %s: communication disabled before%s confirmed %s\n",
                 target, missing, command);
    else if (missing[0] != '\0' && n->node_id != CO_NMT_MASTER_ALL_NODES)
        snprintf(reply, sizeof reply,
                 "timeout: %s: no %s reported within %u ms after %s: is the node on %s?\n", target,
                 state, r->nmt_timeout_ms, command, r->bus.opts->iface);
    else if (missing[0] != '\0')
        snprintf(reply, sizeof reply,
                 "timeout: all: no %s reported by node%s within %u ms after %s (confirmed:%s)\n",
                 state, missing, r->nmt_timeout_ms, command, confirmed[0] ? confirmed : " none");
    else if (r->nmt_json)
        snprintf(reply, sizeof reply,
                 "{\"node\": %s, \"command\": \"%s\", \"state\": \"%s\", \"confirmed\": [%s]}\n",
                 json_node, command, state, confirmed + 1);
    else if (n->node_id == CO_NMT_MASTER_ALL_NODES)
        snprintf(reply, sizeof reply, "all: %s (nodes%s)\n", state, confirmed);
    else
        snprintf(reply, sizeof reply, "%s: %s\n", target, state);
    comaster_control_reply(&r->control, r->nmt_ticket, reply);
    r->nmt_ticket = 0;
}

static bool request_nmt(runner_t *r, char **field, size_t count, bool json, char *reply, size_t cap)
{
    uint8_t command, node;
    char *end = NULL;
    unsigned long ms = count == 4 ? strtoul(field[3], &end, 10) : 0;
    bool valid = count == 4 && *end == '\0' && ms >= 1 && ms <= COMASTER_CONTROL_WAIT_MAX_MS;
    if (!valid || !comaster_nmt_command(field[1], &command) || !parse_node(field[2], true, &node)) {
        snprintf(reply, cap,
                 "error: nmt start|stop|preop|reset-node|reset-comm NODE|all MS (1..%u)\n",
                 COMASTER_CONTROL_WAIT_MAX_MS);
        return false;
    }
    if (r->master.disabled) {
        snprintf(reply, cap, "%s", disabled_error);
        return false;
    }
    if (r->nmt_ticket != 0) {
        snprintf(reply, cap, "error: an NMT command awaits its confirmation: try again\n");
        return false;
    }
    r->nmt_json = json;
    r->nmt_timeout_ms = (uint32_t)ms;
    r->nmt_ticket = comaster_control_defer(&r->control);
    co_net_master_nmt(&r->master, command, node, (uint32_t)ms, co_linux_now());
    return true;
}

/* ---- read NODE OBJECT [TYPE], write NODE OBJECT [TYPE] VALUE ------------------------------- */

/* The DCF of a slave of the network names its objects; another node's are INDEX:SUB. */
static const eds_t *node_eds(const runner_t *r, uint8_t node)
{
    for (size_t i = 0; i < r->net->slave_count; i++) {
        if (r->net->slave_config[i].node_id == node)
            return &r->net->slave[i].dcf;
    }
    return NULL;
}

/* A read without a type, of an object no DCF types: unsigned by its size, else bytes (as
 * comaster read). */
static const comaster_type_t *type_by_size(uint32_t size)
{
    switch (size) {
    case 1:
        return comaster_type_by_name("u8");
    case 2:
        return comaster_type_by_name("u16");
    case 4:
        return comaster_type_by_name("u32");
    case 8:
        return comaster_type_by_name("u64");
    default:
        return comaster_type_by_name("octets");
    }
}

/* {"node": 4, "index": "0x203C", "subindex": 2, "name": ..., "type": ...: as comaster read. */
static size_t json_head(const run_sdo_t *s, const comaster_type_t *type, char *out, size_t cap)
{
    char name[256];
    cli_json_quote(s->object.name ? s->object.name : "", name, sizeof name);
    return (size_t)snprintf(out, cap,
                            "{\"node\": %u, \"index\": \"0x%04X\", \"subindex\": %u, \"name\": "
                            "%s, \"type\": \"%s\"",
                            s->node, s->object.index, s->object.sub, s->object.name ? name : "null",
                            type->name);
}

static void format_sdo_reply(const runner_t *r, run_sdo_t *s, const co_net_request_t *request,
                             const co_sdo_client_result_t *result, char *reply, size_t cap)
{
    char where[32];
    snprintf(where, sizeof where, "node %u, %04X:%02X", s->node, s->object.index, s->object.sub);
    if (result->status == CO_SDO_CLIENT_CLIENT_ABORT && r->master.disabled) {
        snprintf(reply, cap, "error: %s: communication disabled before the transfer ended\n",
                 where);
        return;
    }
    if (result->status == CO_SDO_CLIENT_CLIENT_ABORT &&
        result->abort_code == CO_SDO_ABORT_TIMEOUT) {
        snprintf(reply, cap, "timeout: %s: no answer within %u ms (the run's sdo_timeout)\n", where,
                 r->master.config.sdo_timeout_ms);
        return;
    }
    if (result->status != CO_SDO_CLIENT_OK) {
        snprintf(reply, cap, "abort: %s: %s abort 0x%08X: %s\n", where,
                 result->status == CO_SDO_CLIENT_SERVER_ABORT ? "SDO" : "client",
                 result->abort_code, co_sdo_abort_text(result->abort_code));
        return;
    }
    const comaster_type_t *type = s->type ? s->type : type_by_size(result->size);
    if (request->write) {
        size_t used = s->json ? json_head(s, type, reply, cap) : 0;
        snprintf(reply + used, cap - used, s->json ? ", \"written\": %u}\n" : "ok\n", s->len);
        return;
    }
    char text[RUN_SDO_VALUE_MAX * 3 + 1];
    bool is_text;
    if (!comaster_value_format(type, s->data, result->size, COMASTER_VALUE_DECIMAL, text,
                               sizeof text, &is_text)) {
        snprintf(reply, cap, "error: %s: %s\n", where, text);
        return;
    }
    if (!s->json) {
        snprintf(reply, cap, "%s\n", text);
        return;
    }
    size_t used = json_head(s, type, reply, cap);
    char value[CLI_JSON_QUOTED_MAX(sizeof text)];
    if (is_text)
        cli_json_quote(text, value, sizeof value);
    snprintf(reply + used, cap - used, ", \"value\": %s}\n", is_text ? value : text);
}

static void sdo_done(void *user, const co_net_request_t *request,
                     const co_sdo_client_result_t *result)
{
    run_sdo_t *s = user;
    runner_t *r = s->runner;
    char reply[4096];
    format_sdo_reply(r, s, request, result, reply, sizeof reply);
    comaster_control_reply(&r->control, s->ticket, reply);
    s->used = false;
}

static run_sdo_t *free_slot(runner_t *r)
{
    for (size_t i = 0; i < CO_NET_REQUEST_MAX; i++) {
        if (!r->sdo[i].used)
            return &r->sdo[i];
    }
    return NULL;
}

/* Node, object and type of the request into s; false with the reply written. */
static bool resolve(runner_t *r, run_sdo_t *s, const char *node, const char *object,
                    const char *type, char *reply, size_t cap)
{
    char err[512];
    if (!parse_node(node, false, &s->node)) {
        snprintf(reply, cap, "error: '%s' is not a node-id 1..127\n", node);
        return false;
    }
    if (!comaster_object_parse(object, node_eds(r, s->node), &s->object, err, sizeof err)) {
        snprintf(reply, cap, "error: %s\n", err);
        return false;
    }
    s->type = type ? comaster_type_by_name(type) : comaster_type_by_code(s->object.data_type);
    if (type && !s->type) {
        snprintf(reply, cap, "error: '%s' is not a data type: give one of %s\n", type,
                 comaster_type_names());
        return false;
    }
    return true;
}

static bool request_sdo(runner_t *r, char **field, size_t count, bool json, char *reply, size_t cap)
{
    bool write = strcmp(field[0], "write") == 0;
    size_t min = write ? 4 : 3;
    if (count < min || count > min + 1) {
        snprintf(reply, cap, "error: %s\n",
                 write ? "write NODE OBJECT [TYPE] VALUE" : "read NODE OBJECT [TYPE]");
        return false;
    }
    run_sdo_t *s = free_slot(r);
    if (!s) {
        snprintf(reply, cap,
                 "error: %u SDO requests wait for the run's client already: try again\n",
                 CO_NET_REQUEST_MAX);
        return false;
    }
    *s = (run_sdo_t){.json = json, .runner = r};
    if (!resolve(r, s, field[1], field[2], count == min + 1 ? field[3] : NULL, reply, cap))
        return false;
    co_net_request_t request = {.node_id = s->node,
                                .index = s->object.index,
                                .subindex = s->object.sub,
                                .write = write,
                                .data = s->data,
                                .len = sizeof s->data,
                                .done = sdo_done,
                                .user = s};
    if (write) {
        size_t len;
        char err[256];
        if (!s->type) {
            snprintf(reply, cap,
                     "error: write %s %s: give the TYPE of the value (no DCF names its data type): "
                     "one of %s\n",
                     field[1], field[2], comaster_type_names());
            return false;
        }
        if (!comaster_value_parse(s->type, field[count - 1], s->data, sizeof s->data, &len, err,
                                  sizeof err)) {
            snprintf(reply, cap, "error: node %u, %04X:%02X: %s\n", s->node, s->object.index,
                     s->object.sub, err);
            return false;
        }
        request.len = s->len = (uint32_t)len;
    }
    if (r->master.disabled) {
        snprintf(reply, cap, "%s", disabled_error);
        return false;
    }
    s->used = true;
    s->ticket = comaster_control_defer(&r->control);
    co_net_master_sdo(&r->master, &request, co_linux_now());
    return true;
}

/* ---- disable, enable, can ------------------------------------------------------------------- */

static void reply_master_status(runner_t *r, bool json, char *reply, size_t cap)
{
    co_net_master_set_bus(&r->master, run_bus_bits(r));
    uint16_t status = co_net_master_status(&r->master);
    char text[256];
    run_master_status_text(status, text, sizeof text);
    if (json)
        snprintf(reply, cap, "{\"status\": \"0x%04X\", \"disabled\": %s}\n", status,
                 r->master.disabled ? "true" : "false");
    else
        snprintf(reply, cap, "%s\n", text);
}

/* The controller's state in the PLC300's words: an interface that is down has no bus power. */
static const char *controller_state(const runner_t *r)
{
    static const char *const names[] = {
        [CO_LINUX_CAN_DOWN] = "no bus power",           [CO_LINUX_CAN_BUS_OFF] = "bus-off",
        [CO_LINUX_CAN_ERROR_PASSIVE] = "error-passive", [CO_LINUX_CAN_ERROR_WARNING] = "warning",
        [CO_LINUX_CAN_ERROR_ACTIVE] = "error-active",
    };
    return names[co_linux_bus_can_state(&r->bus.loop.bus)];
}

/* The interface's configuration markers the network description gives, the PLC300's %CB3052
 * (node-id) and %CB3055 (bit rate code): ", node-id 1, bit-rate 2 (500 kbit/s)", or the JSON
 * fields, null when not given (D-NET-MASTER-MARKERS). */
static void format_markers(const runner_t *r, bool json, char *out, size_t cap)
{
    uint8_t node_id = r->net->config.node_id;
    uint8_t code = r->net->bit_rate;
    char id[8] = "null", rate[64] = "null";
    if (node_id != 0)
        snprintf(id, sizeof id, "%u", node_id);
    if (code != COMASTER_BIT_RATE_NONE && json)
        snprintf(rate, sizeof rate, "{\"code\": %u, \"bit_s\": %lu}", code,
                 (unsigned long)co_net_bit_rate(code));
    else if (code != COMASTER_BIT_RATE_NONE)
        snprintf(rate, sizeof rate, "%u (%lu kbit/s)", code,
                 (unsigned long)co_net_bit_rate(code) / 1000ul);
    if (json)
        snprintf(out, cap, ", \"node_id\": %s, \"bit_rate\": %s", id, rate);
    else
        snprintf(out, cap, "%s%s%s%s", node_id != 0 ? ", node-id " : "", node_id != 0 ? id : "",
                 code != COMASTER_BIT_RATE_NONE ? ", bit-rate " : "",
                 code != COMASTER_BIT_RATE_NONE ? rate : "");
}

static void reply_can(const runner_t *r, bool json, char *reply, size_t cap)
{
    const co_linux_stats_t *st = &r->bus.loop.stats;
    const char *iface = r->bus.opts->iface;
    unsigned long long dropped = st->tx_dropped + st->down_dropped;
    char markers[128];
    format_markers(r, json, markers, sizeof markers);
    if (json)
        snprintf(reply, cap,
                 "{\"interface\": \"%s\", \"state\": \"%s\", \"bus_power\": %s, \"rx\": %llu, "
                 "\"tx\": %llu, \"tx_dropped\": %llu, \"error_frames\": %llu, \"bus_off\": "
                 "%llu%s}\n",
                 iface, controller_state(r), r->bus.loop.bus.link_up ? "true" : "false", st->rx,
                 st->tx, dropped, st->error_frames, r->bus.loop.bus.conditions.bus_offs, markers);
    else
        snprintf(reply, cap,
                 "can %s: %s, rx %llu, tx %llu, tx-dropped %llu, error-frames %llu, bus-off "
                 "%llu%s\n",
                 iface, controller_state(r), st->rx, st->tx, dropped, st->error_frames,
                 r->bus.loop.bus.conditions.bus_offs, markers);
}

/* CiA 302-2's configuration request 1F25h: "conf" to the node's sub-index, or 128 for all. */
static void request_configure(runner_t *r, const char *target, bool json, char *reply, size_t cap)
{
    bool all = strcmp(target, "all") == 0;
    char *end;
    unsigned long node = all ? CO_NET_1F25_ALL : strtoul(target, &end, 0);
    if (!all && (*end != '\0' || node == 0 || node > CO_NMT_MASTER_NODE_ID_MAX))
        snprintf(reply, cap, "error: configure: '%s' is not a node-id 1..127 or all\n", target);
    else if (r->master.disabled)
        snprintf(reply, cap, "%s", disabled_error);
    else if (!co_net_master_request_configuration(&r->master, (uint8_t)node, CO_NET_1F25_SIGNATURE,
                                                  co_linux_now()))
        snprintf(reply, cap, "error: configure: node %s is not a slave of the run\n", target);
    else if (json && all)
        snprintf(reply, cap, "{\"node\": \"all\", \"configuration_request\": \"0x%08X\"}\n",
                 CO_NET_1F25_SIGNATURE);
    else if (json) /* the number read, not the text given: 0x05 is no JSON */
        snprintf(reply, cap, "{\"node\": %lu, \"configuration_request\": \"0x%08X\"}\n", node,
                 CO_NET_1F25_SIGNATURE);
    else
        snprintf(reply, cap, "ok\n");
}

bool run_request(runner_t *r, char **field, size_t count, bool json, char *reply, size_t cap,
                 bool *deferred)
{
    const char *name = field[0];
    if (strcmp(name, "nmt") == 0)
        *deferred = request_nmt(r, field, count, json, reply, cap);
    else if (strcmp(name, "read") == 0 || strcmp(name, "write") == 0)
        *deferred = request_sdo(r, field, count, json, reply, cap);
    else if (count == 1 && strcmp(name, "disable") == 0) {
        co_net_master_disable(&r->master, co_linux_now());
        reply_master_status(r, json, reply, cap);
    } else if (count == 1 && strcmp(name, "enable") == 0) {
        co_net_master_enable(&r->master, co_linux_now());
        reply_master_status(r, json, reply, cap);
    } else if (count == 1 && strcmp(name, "can") == 0)
        reply_can(r, json, reply, cap);
    else if (count == 2 && strcmp(name, "configure") == 0)
        request_configure(r, field[1], json, reply, cap);
    else
        return false;
    return true;
}
