/* SPDX-License-Identifier: Apache-2.0 */
/* comaster boot and run: the network master of the core (co_net_master_t, docs/net-master.md) on
 * the bus, printing each step and status change; run also serves its process image and status on
 * the control socket (run_control.c) to comaster set, get and status, and the requests of
 * run_requests.c. */
#include "cli/json.h"
#include "co/co_image_address.h"
#include "comaster/runner.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char run_help[] =
    "usage: comaster run NETWORK [--control PATH]\n"
    "\n"
    "Runs the network master in the foreground: reset communication to all, then per\n"
    "slave identify (1000h, 1018h), download the DCF's configuration, start error\n"
    "control, NMT start; a failed slave is retried after the others, a slave whose\n"
    "error control fails is reset and booted again. Prints each step and status change\n"
    "until SIGINT or SIGTERM.\n"
    "\n"
    "  NETWORK         the option file ([Master] cpj = the CiA 306-3 nodelist, whose\n"
    "                  DCFs configure the slaves; docs/comaster.md \"Network description\")\n"
    "  --control PATH  the control socket for comaster set, get, status, disable,\n"
    "                  enable, can, configure, and nmt, read and write with --run;\n"
    "                  default [Master] control, else\n"
    "                  $XDG_RUNTIME_DIR/comaster-IFACE.sock\n"
    "\n"
    "Example: comaster -i vcan0 run examples/netmaster/bench.ini\n";

static const char boot_help[] =
    "usage: comaster boot NODE DCF\n"
    "\n"
    "Boots one slave as comaster run would: reset communication, identify (1000h and\n"
    "1018h against the DCF), download the DCF's ParameterValue entries, NMT start.\n"
    "\n"
    "Exit status: boot exits 0 once the slave is operational, 1 when it aborted an SDO\n"
    "transfer, 2 when it did not answer in time, 65 when it is not the device the DCF\n"
    "describes.\n"
    "\n"
    "Example: comaster -i vcan0 boot 4 examples/netmaster/drive4.dcf\n";

/* The master's status word and its protocol state (the PLC300's %SB3180, which tells a node
 * guarding error from a heartbeat error), each printed when it changed. */
static void print_master_status(runner_t *r)
{
    uint16_t status = co_net_master_status(&r->master);
    if (status != r->master_status) {
        r->master_status = status;
        char text[256];
        run_master_status_text(status, text, sizeof text);
        printf("master: status %s\n", text + strlen("master "));
    }
    uint8_t protocol = co_net_master_protocol_state(&r->master);
    if (protocol != r->protocol_state) {
        r->protocol_state = protocol;
        printf("master: protocol %u %s\n", protocol, co_net_protocol_state_text(protocol));
    }
}

/* " (heartbeat error)" after a slave's status whose bit 5 is set, "" otherwise. */
static const char *ec_error_note(const co_net_slave_t *s, char *out, size_t cap)
{
    out[0] = '\0';
    if (s->ec_error != CO_NET_EC_ERROR_NONE)
        snprintf(out, cap, " (%s)", co_net_ec_error_text(s->ec_error));
    return out;
}

static const char *slave_name(const runner_t *r, uint8_t node_id)
{
    for (size_t i = 0; i < r->net->slave_count; i++) {
        if (r->net->slave_config[i].node_id == node_id)
            return r->net->slave[i].name;
    }
    return "";
}

/* "identity mismatch (read 0x00000312), CiA 302 error M: product code differs from 1F86h". */
static void format_failure(const co_net_slave_t *s, char *out, size_t cap)
{
    int n;
    if (s->failure == CO_NET_FAIL_DEVICE_TYPE || s->failure == CO_NET_FAIL_IDENTITY)
        n = snprintf(out, cap, "%s (read 0x%08X)", co_net_failure_text(s->failure), s->read_value);
    else
        n = snprintf(out, cap, "%s", co_net_failure_text(s->failure));
    if (s->boot_error != CO_NET_BOOT_ERROR_NONE && n > 0 && (size_t)n < cap)
        snprintf(out + n, cap - (size_t)n, ", CiA 302 error %c: %s", s->boot_error,
                 co_net_boot_error_text(s->boot_error));
}

static void format_sdo_error(const co_net_sdo_error_t *e, char *out, size_t cap)
{
    if (e->node_id == 0) {
        snprintf(out, cap, "none");
        return;
    }
    snprintf(out, cap, "node %u %s %04Xh:%02X abort 0x%08X (%s)", e->node_id,
             e->access == CO_NET_ACCESS_WRITE ? "write" : "read", e->index, e->subindex,
             e->abort_code, co_sdo_abort_text(e->abort_code));
}

static void format_emcy(const co_emcy_message_t *m, char *out, size_t cap)
{
    if (m->node_id == 0) {
        snprintf(out, cap, "none");
        return;
    }
    snprintf(out, cap, "node %u 0x%04X register 0x%02X data %02X %02X %02X %02X %02X (%s)",
             m->node_id, m->code, m->reg, m->msef[0], m->msef[1], m->msef[2], m->msef[3],
             m->msef[4], co_emcy_code_text(m->code));
}

/* The boot of `comaster boot` ends with its slave operational or failed. */
static void finish_boot(runner_t *r, const co_net_slave_t *s)
{
    if (s->step == CO_NET_STEP_OPERATIONAL) {
        comaster_bus_finish(&r->bus, CLI_EXIT_OK);
    } else if (s->step == CO_NET_STEP_FAILED) {
        int status = EX_DATAERR;
        if (s->failure == CO_NET_FAIL_SDO)
            status = r->master.last_sdo_error.abort_code == CO_SDO_ABORT_TIMEOUT ? CLI_EXIT_TIMEOUT
                                                                                 : CLI_EXIT_REFUSED;
        comaster_bus_finish(&r->bus, status);
    }
}

static void print_slave_event(runner_t *r, const co_net_event_t *event)
{
    const co_net_slave_t *s = co_net_master_slave(&r->master, event->node_id);
    const char *name = slave_name(r, event->node_id);
    char text[256];
    if (event->kind == CO_NET_EVENT_STEP) {
        if (s->step == CO_NET_STEP_FAILED) {
            format_failure(s, text, sizeof text);
            printf("node %u %s: init error: %s\n", event->node_id, name, text);
        } else {
            printf("node %u %s: %s\n", event->node_id, name, co_net_step_text(s->step));
        }
        if (r->boot_only)
            finish_boot(r, s);
    } else {
        char note[64];
        run_slave_status_text(s->status, text, sizeof text);
        printf("node %u %s: status 0x%04X%s%s\n", event->node_id, name, s->status, text,
               ec_error_note(s, note, sizeof note));
    }
}

static void on_event(void *user, const co_net_event_t *event)
{
    runner_t *r = user;
    char text[256];
    switch (event->kind) {
    case CO_NET_EVENT_STEP:
    case CO_NET_EVENT_STATUS:
        print_slave_event(r, event);
        break;
    case CO_NET_EVENT_SDO_ERROR:
        format_sdo_error(&r->master.last_sdo_error, text, sizeof text);
        printf("SDO error: %s\n", text);
        break;
    case CO_NET_EVENT_EMCY:
        format_emcy(&r->master.last_emcy, text, sizeof text);
        printf("EMCY: %s\n", text);
        break;
    case CO_NET_EVENT_STARTED:
        printf("network: NMT start all\n");
        break;
    case CO_NET_EVENT_BOOT_TIME:
        printf("network: boot time 1F89h (%lu ms) over, a mandatory slave not configured\n",
               (unsigned long)r->master.config.boot_limit_ms);
        break;
    case CO_NET_EVENT_NMT_DONE:
        run_nmt_done(r);
        break;
    case CO_NET_EVENT_INPUT:
        break;
    }
    print_master_status(r);
}

static void run_send(void *user, const co_frame_t *frame)
{
    runner_t *r = user;
    comaster_bus_send(&r->bus, frame);
}

static void job_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    runner_t *r = ctx;
    co_net_master_receive(&r->master, frame, now);
}

static co_time_t job_process(void *ctx, co_time_t now)
{
    runner_t *r = ctx;
    if (!r->started) {
        r->started = true;
        co_net_master_start(&r->master, now);
    }
    co_net_master_set_bus(&r->master, run_bus_bits(r));
    co_time_t next = co_net_master_process(&r->master, now);
    print_master_status(r);
    return next;
}

/* ---- the control requests: status, get, set (tab-separated fields) --------------------------- */

/* Appends to out (cap bytes, `used` of them written) what the format says; the new length, at
 * most cap - 1 when it did not fit. */
static size_t append(char *out, size_t cap, size_t used, const char *format, ...)
    __attribute__((format(printf, 4, 5)));
static size_t append(char *out, size_t cap, size_t used, const char *format, ...)
{
    if (used + 1 >= cap)
        return used;
    va_list ap;
    va_start(ap, format);
    int n = vsnprintf(out + used, cap - used, format, ap);
    va_end(ap);
    size_t end = used + (n < 0 ? 0u : (size_t)n);
    return end < cap ? end : cap - 1;
}

/* A slave's expected identity, CiA 302-2's 1F84h..1F88h: {"1F84h": "0x00020192", ...}, the
 * values checked only (a check of 0, which a DCF may imply, shown too). */
static size_t append_expected(char *reply, size_t cap, size_t used, const co_net_slave_config_t *c)
{
    const char *separator = "";
    used = append(reply, cap, used, "{");
    for (unsigned k = 0; k <= CO_NET_IDENTITY_SUBS; k++) {
        if ((c->check & (CO_NET_CHECK_DEVICE_TYPE << k)) == 0)
            continue;
        uint32_t value = k == 0 ? c->device_type : c->identity[k - 1];
        used = append(reply, cap, used, "%s\"%04Xh\": \"0x%08lX\"", separator,
                      CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION + k, (unsigned long)value);
        separator = ", ";
    }
    return append(reply, cap, used, "}");
}

/* status --json: one object, the records of the PLC300's 5.6.3-5.6.5, and CiA 302-2's boot time
 * 1F89h, expected identity and error status of each slave. */
static void reply_status_json(runner_t *r, uint16_t status, char *reply, size_t cap)
{
    char name[CLI_JSON_QUOTED_MAX(COMASTER_NAME_MAX)], text[256];
    char failure[CLI_JSON_QUOTED_MAX(sizeof text)], ec_error[32], boot_error[96];
    uint8_t protocol = co_net_master_protocol_state(&r->master);
    size_t used = append(reply, cap, 0,
                         "{\"status\": \"0x%04X\", \"protocol_state\": {\"code\": %u, \"text\": "
                         "\"%s\"}, \"boot_time\": {\"ms\": %lu, \"over\": %s}, \"slaves\": [",
                         status, protocol, co_net_protocol_state_text(protocol),
                         (unsigned long)r->master.config.boot_limit_ms,
                         r->master.boot_time_over ? "true" : "false");
    for (size_t i = 0; i < r->net->slave_count; i++) {
        const co_net_slave_t *s = &r->net->slave_state[i];
        cli_json_quote(r->net->slave[i].name, name, sizeof name);
        snprintf(failure, sizeof failure, "null");
        if (s->step == CO_NET_STEP_FAILED) {
            format_failure(s, text, sizeof text);
            cli_json_quote(text, failure, sizeof failure);
        }
        snprintf(ec_error, sizeof ec_error, "null");
        if (s->ec_error != CO_NET_EC_ERROR_NONE)
            snprintf(ec_error, sizeof ec_error, "\"%s\"", co_net_ec_error_text(s->ec_error));
        snprintf(boot_error, sizeof boot_error, "null");
        if (s->boot_error != CO_NET_BOOT_ERROR_NONE)
            snprintf(boot_error, sizeof boot_error, "{\"code\": \"%c\", \"text\": \"%s\"}",
                     s->boot_error, co_net_boot_error_text(s->boot_error));
        used = append(reply, cap, used,
                      "%s{\"node\": %u, \"name\": %s, \"assignment\": \"0x%08lX\", \"expected\": ",
                      i ? ", " : "", r->net->slave_config[i].node_id, name,
                      (unsigned long)co_net_slave_1f81(&r->net->slave_config[i]));
        used = append_expected(reply, cap, used, &r->net->slave_config[i]);
        used = append(reply, cap, used,
                      ", \"status\": \"0x%04X\", \"step\": \"%s\", \"failure\": %s, "
                      "\"boot_error\": %s, \"error_control_error\": %s}",
                      s->status, co_net_step_text(s->step), failure, boot_error, ec_error);
    }
    const co_net_sdo_error_t *e = &r->master.last_sdo_error;
    if (e->node_id == 0)
        used = append(reply, cap, used, "], \"last_sdo_error\": null");
    else
        used = append(reply, cap, used,
                      "], \"last_sdo_error\": {\"node\": %u, \"access\": \"%s\", \"index\": "
                      "\"0x%04X\", \"subindex\": %u, \"value\": %u, \"abort_code\": \"0x%08X\"}",
                      e->node_id, e->access == CO_NET_ACCESS_WRITE ? "write" : "read", e->index,
                      e->subindex, e->value, e->abort_code);
    const co_emcy_message_t *m = &r->master.last_emcy;
    if (m->node_id == 0)
        append(reply, cap, used, ", \"last_emcy\": null}\n");
    else
        append(reply, cap, used,
               ", \"last_emcy\": {\"node\": %u, \"code\": \"0x%04X\", \"register\": \"0x%02X\", "
               "\"data\": \"%02X %02X %02X %02X %02X\"}}\n",
               m->node_id, m->code, m->reg, m->msef[0], m->msef[1], m->msef[2], m->msef[3],
               m->msef[4]);
}

static void reply_status(runner_t *r, bool json, char *reply, size_t cap)
{
    char text[256];
    co_net_master_set_bus(&r->master, run_bus_bits(r));
    uint16_t status = co_net_master_status(&r->master);
    if (json) {
        reply_status_json(r, status, reply, cap);
        return;
    }
    run_master_status_text(status, text, sizeof text);
    uint8_t protocol = co_net_master_protocol_state(&r->master);
    size_t used = (size_t)snprintf(reply, cap, "%s\nprotocol %u %s\n", text, protocol,
                                   co_net_protocol_state_text(protocol));
    for (size_t i = 0; i < r->net->slave_count && used < cap; i++) {
        const co_net_slave_t *s = &r->net->slave_state[i];
        char note[64];
        if (s->step == CO_NET_STEP_FAILED)
            format_failure(s, text, sizeof text);
        used += (size_t)snprintf(
            reply + used, cap - used, "node %u %s 0x%04X %s%s%s%s\n",
            r->net->slave_config[i].node_id, r->net->slave[i].name, s->status,
            co_net_step_text(s->step), s->step == CO_NET_STEP_FAILED ? ": " : "",
            s->step == CO_NET_STEP_FAILED ? text : "", ec_error_note(s, note, sizeof note));
    }
    format_sdo_error(&r->master.last_sdo_error, text, sizeof text);
    if (used < cap)
        used += (size_t)snprintf(reply + used, cap - used, "last SDO error: %s\n", text);
    format_emcy(&r->master.last_emcy, text, sizeof text);
    if (used < cap)
        snprintf(reply + used, cap - used, "last EMCY: %s\n", text);
}

static const comaster_type_t *variable_type(const comaster_variable_t *v, char *reply, size_t cap)
{
    const comaster_type_t *type = comaster_type_by_code(v->data_type);
    if (!type || type->size != v->size) {
        snprintf(reply, cap, "error: %s has DataType 0x%04X, which is not a number of %u bytes\n",
                 v->name, v->data_type, v->size);
        return NULL;
    }
    return type;
}

/* get and set --json: {"node": 4, "name": "speed", "value": 1200}. */
static void variable_json(const comaster_variable_t *v, const char *value, bool is_text,
                          char *reply, size_t cap)
{
    char name[256], text[256];
    cli_json_quote(v->name, name, sizeof name);
    if (is_text)
        cli_json_quote(value, text, sizeof text);
    snprintf(reply, cap, "{\"node\": %u, \"name\": %s, \"value\": %s}\n", v->node_id, name,
             is_text ? text : value);
}

static void reply_get(runner_t *r, uint8_t node, const char *name, bool json, char *reply,
                      size_t cap)
{
    const comaster_variable_t *v;
    char err[256];
    if (comaster_network_find(r->net, node, name, &v, err, sizeof err) == 0) {
        snprintf(reply, cap, "error: %s\n", err);
        return;
    }
    const comaster_type_t *type = variable_type(v, reply, cap);
    if (!type)
        return;
    const uint8_t *image = v->output ? r->net->output_image : r->net->input_image;
    char text[128];
    bool is_text;
    comaster_value_format(type, image + v->offset, v->size, COMASTER_VALUE_DECIMAL, text,
                          sizeof text, &is_text);
    if (json)
        variable_json(v, text, is_text, reply, cap);
    else
        snprintf(reply, cap, "%s\n", text);
}

/* The value set, as its type prints it (0x10 given is 16). */
static void set_json(const comaster_variable_t *v, const comaster_type_t *type,
                     const uint8_t *bytes, size_t len, char *reply, size_t cap)
{
    char text[128];
    bool is_text;
    comaster_value_format(type, bytes, len, COMASTER_VALUE_DECIMAL, text, sizeof text, &is_text);
    variable_json(v, text, is_text, reply, cap);
}

static void reply_set(runner_t *r, uint8_t node, const char *name, const char *value, bool json,
                      char *reply, size_t cap)
{
    const comaster_variable_t *first;
    char err[256];
    if (comaster_network_find(r->net, node, name, &first, err, sizeof err) == 0) {
        snprintf(reply, cap, "error: %s\n", err);
        return;
    }
    const comaster_type_t *type = variable_type(first, reply, cap);
    if (!type)
        return;
    uint8_t bytes[8];
    size_t len;
    if (!comaster_value_parse(type, value, bytes, sizeof bytes, &len, err, sizeof err)) {
        snprintf(reply, cap, "error: %s: %s\n", first->name, err);
        return;
    }
    /* Every output of the object: one mapped by two RPDOs gets the value in both. */
    size_t written = 0;
    for (size_t i = 0; i < r->net->variable_count; i++) {
        const comaster_variable_t *v = &r->net->variable[i];
        if (v->node_id == node && v->index == first->index && v->sub == first->sub && v->output) {
            co_net_master_write_output(&r->master, v->offset, bytes, len);
            written++;
        }
    }
    if (written == 0)
        snprintf(reply, cap, "error: %s of node %u is an input (a TPDO of the slave): get it\n",
                 first->name, node);
    else if (json)
        set_json(first, type, bytes, len, reply, cap);
    else
        snprintf(reply, cap, "ok\n");
}

/* ---- the process image by the PLC300's markers (co_image_address.h) ------------------------ */

/* The marker, or false after the refusal in reply. */
static bool marker_parse(const char *marker, co_image_address_t *a, char *reply, size_t cap)
{
    if (co_image_address_parse(marker, a))
        return true;
    snprintf(reply, cap, "error: '%s' is not a process image address: %s\n", marker,
             COMASTER_MARKER_SYNTAX);
    return false;
}

/* The marker's data type: the manual's objects 3000h-49FCh are UNSIGNED8, 16 or 32. */
static const comaster_type_t *marker_type(const co_image_address_t *a)
{
    return comaster_type_by_code(a->size == 1   ? CO_DT_UNSIGNED8
                                 : a->size == 2 ? CO_DT_UNSIGNED16
                                                : CO_DT_UNSIGNED32);
}

static void marker_reply(const char *marker, uint32_t value, bool json, char *reply, size_t cap)
{
    char quoted[64];
    cli_json_quote(marker, quoted, sizeof quoted);
    if (json)
        snprintf(reply, cap, "{\"address\": %s, \"value\": %lu}\n", quoted, (unsigned long)value);
    else
        snprintf(reply, cap, "%lu\n", (unsigned long)value);
}

static void reply_get_marker(runner_t *r, const char *marker, bool json, char *reply, size_t cap)
{
    co_image_address_t a;
    if (!marker_parse(marker, &a, reply, cap))
        return;
    const uint8_t *image = a.area == CO_IMAGE_OUTPUT ? r->net->output_image : r->net->input_image;
    marker_reply(marker, co_image_address_get(image, &a), json, reply, cap);
}

static void reply_set_marker(runner_t *r, const char *marker, const char *value, bool json,
                             char *reply, size_t cap)
{
    co_image_address_t a;
    if (!marker_parse(marker, &a, reply, cap))
        return;
    if (a.area == CO_IMAGE_INPUT) {
        snprintf(reply, cap, "error: %s is an input (the slaves' TPDOs write it): get it\n",
                 marker);
        return;
    }
    uint8_t bytes[4];
    size_t len;
    char err[256];
    if (!comaster_value_parse(marker_type(&a), value, bytes, sizeof bytes, &len, err, sizeof err)) {
        snprintf(reply, cap, "error: %s: %s\n", marker, err);
        return;
    }
    /* UNSIGNEDn's bytes, least significant first, are the marker's bytes (D-IMAGE-ADDRESS). */
    co_net_master_write_output(&r->master, a.offset, bytes, len);
    if (json)
        marker_reply(marker, co_image_address_get(r->net->output_image, &a), json, reply, cap);
    else
        snprintf(reply, cap, "ok\n");
}

static bool parse_node_field(const char *text, uint8_t *node)
{
    char *end;
    unsigned long n = strtoul(text, &end, 10);
    if (end == text || *end != '\0' || n < 1 || n > CO_NMT_MASTER_NODE_ID_MAX)
        return false;
    *node = (uint8_t)n;
    return true;
}

#define REQUEST_FIELDS 6

static bool handle_request(void *ctx, const char *request, char *reply, size_t cap)
{
    runner_t *r = ctx;
    char copy[COMASTER_CONTROL_LINE_MAX];
    snprintf(copy, sizeof copy, "%s", request);
    char *field[REQUEST_FIELDS + 1] = {0};
    size_t count = 0;
    for (char *save, *f = strtok_r(copy, "\t", &save); f && count < REQUEST_FIELDS + 1;
         f = strtok_r(NULL, "\t", &save))
        field[count++] = f;
    /* "json" first: the client asks for JSON (the requests of run_requests.c answer in it). */
    bool json = count > 0 && strcmp(field[0], "json") == 0;
    char **fields = json ? field + 1 : field;
    count -= json ? 1u : 0u;
    uint8_t node = 0;
    bool deferred = false;
    if (count == 0)
        snprintf(reply, cap, "error: empty request\n");
    else if (run_request(r, fields, count, json, reply, cap, &deferred))
        ;
    else if (count == 1 && strcmp(fields[0], "status") == 0)
        reply_status(r, json, reply, cap);
    else if (count == 2 && strcmp(fields[0], "get") == 0 && fields[1][0] == '%')
        reply_get_marker(r, fields[1], json, reply, cap);
    else if (count == 3 && strcmp(fields[0], "set") == 0 && fields[1][0] == '%')
        reply_set_marker(r, fields[1], fields[2], json, reply, cap);
    else if (count >= 3 && !parse_node_field(fields[1], &node))
        snprintf(reply, cap, "error: '%s' is not a node-id 1..127\n", fields[1]);
    else if (count == 3 && strcmp(fields[0], "get") == 0)
        reply_get(r, node, fields[2], json, reply, cap);
    else if (count == 4 && strcmp(fields[0], "set") == 0)
        reply_set(r, node, fields[2], fields[3], json, reply, cap);
    else
        snprintf(
            reply, cap,
            "error: unknown request (status, get NODE NAME, get %%IW2002, set NODE NAME VALUE, "
            "set %%QW2000 VALUE, nmt "
            "COMMAND NODE|all MS, read NODE OBJECT [TYPE], write NODE OBJECT [TYPE] VALUE, "
            "disable, enable, can, configure NODE|all)\n");
    /* A set, an NMT command, an SDO request or enable change what the master sends outside a
     * frame or a deadline: it sends it now. */
    co_linux_device_process(&r->bus.device);
    return deferred;
}

/* ---- the commands ---------------------------------------------------------------------------- */

static int run_master(runner_t *r, comaster_options_t *opts, const char *control_path)
{
    co_net_master_config_t config = r->net->config;
    config.send = run_send;
    config.user = r;
    config.event = on_event;
    if (!co_net_master_init(&r->master, &config))
        return comaster_fail(opts, EX_DATAERR,
                             "the network master refuses this network (a PDO outside its image "
                             "or twice the same node-id)");
    r->protocol_state = co_net_master_protocol_state(&r->master);
    int rc = comaster_bus_open(&r->bus, opts);
    if (rc != 0)
        return rc;
    r->bus.signal_is_the_end = !r->boot_only; /* a run ends with SIGINT or SIGTERM */
    char err[512];
    if (control_path) {
        rc = comaster_control_open(&r->control, &r->bus.loop, control_path, handle_request, r, err,
                                   sizeof err);
        if (rc != 0) {
            comaster_bus_close(&r->bus);
            return comaster_fail(opts, rc, "%s", err);
        }
        printf("comaster: network %s: %zu slaves on %s, NMT start-up 1F80h = 0x%08lX, control "
               "socket %s\n",
               r->net->net_name, r->net->slave_count, opts->iface,
               (unsigned long)co_net_master_1f80(&r->master.config), control_path);
    }
    comaster_job_t job = {.receive = job_receive, .process = job_process, .ctx = r};
    rc = comaster_bus_run(&r->bus, &job);
    if (control_path)
        comaster_control_close(&r->control);
    comaster_bus_close(&r->bus);
    return rc;
}

int comaster_run_main(comaster_options_t *opts, int argc, char **argv)
{
    const char *control = NULL;
    if (!comaster_control_take_option(&argc, argv, &control))
        return comaster_missing_value(opts, "--control");
    comaster_args_t args;
    const char *iface = opts->iface;
    int rc = comaster_parse_args(opts, &args, argc, argv, run_help, "", 1, 1);
    if (rc >= 0)
        return rc;
    static comaster_network_t net;
    static runner_t runner;
    char err[512];
    rc = comaster_network_load(&net, args.positional[0], err, sizeof err);
    if (rc != 0)
        return comaster_fail(opts, rc, "%s", err);
    if (opts->iface == iface && net.iface[0] != '\0')
        opts->iface = net.iface; /* -i on the command line wins over [Master] interface */
    char path[COMASTER_CONTROL_PATH_MAX];
    if (!control && net.control[0] != '\0')
        control = net.control;
    if (!control) {
        comaster_control_default_path(opts->iface, path, sizeof path);
        control = path;
    }
    setvbuf(stdout, NULL, _IOLBF, 0); /* each step as it happens, also through a pipe */
    runner = (runner_t){.net = &net};
    rc = run_master(&runner, opts, control);
    comaster_network_free(&net);
    return rc == CLI_EXIT_INTERRUPTED ? CLI_EXIT_OK : rc;
}

int comaster_boot_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, boot_help, "", 2, 2);
    if (rc >= 0)
        return rc;
    uint8_t node;
    if (!comaster_parse_node(opts, args.positional[0], false, &node))
        return EX_USAGE;
    static comaster_network_t net;
    static runner_t runner;
    char err[512];
    rc = comaster_network_single(&net, node, args.positional[1], err, sizeof err);
    if (rc != 0)
        return comaster_fail(opts, rc, "%s", err);
    setvbuf(stdout, NULL, _IOLBF, 0);
    runner = (runner_t){.net = &net, .boot_only = true};
    rc = run_master(&runner, opts, NULL);
    comaster_network_free(&net);
    return rc;
}
