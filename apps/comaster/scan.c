/* SPDX-License-Identifier: Apache-2.0 */
/* comaster scan: the nodes present. Every node-id 1..127 is asked for its device type (1000h) at
 * once, one SDO client each; the nodes that answer (even with an abort) are then asked for
 * their identity (1018h:01..03) and name (1008h), and their NMT state is taken from their
 * heartbeat (the NMT master follows them while the scan runs) or asked by a node guarding
 * request. */
#include "cli/co_cli.h"
#include "co/co_nmt.h"
#include "co/co_nmt_master.h"
#include "comaster/comaster.h"

#include <stdio.h>
#include <string.h>

static const char scan_help[] =
    "usage: comaster scan\n"
    "\n"
    "Lists the nodes that answer an SDO upload of 1000h (device type) within\n"
    "--timeout, all node-ids asked at once, with vendor-ID, product code and revision\n"
    "(1018h:01..03), name (1008h) and NMT state (heartbeat, else a node guarding\n"
    "request); '-' for what a node does not have. Exit status 2 when no node answers.\n"
    "\n"
    "Example: comaster -i vcan0 scan\n";

#define NODE_COUNT CO_NMT_MASTER_NODE_ID_MAX

typedef struct probe {
    struct scan *scan;
    co_sdo_client_t client;
    uint8_t value[4];
    bool done;
    bool present;
    bool has_device_type;
} probe_t;

typedef struct scan {
    comaster_bus_t *bus;
    co_nmt_master_t master;
    probe_t probes[NODE_COUNT];
    size_t pending;
    co_time_t deadline;
    uint8_t state[NODE_COUNT]; /* NMT state, CO_NMT_MASTER_STATE_UNKNOWN until heard */
} scan_t;

static void probe_send(void *user, const co_frame_t *frame)
{
    probe_t *p = user;
    comaster_bus_send(p->scan->bus, frame);
}

static void probe_done(void *user, const co_sdo_client_result_t *result)
{
    probe_t *p = user;
    p->done = true;
    p->has_device_type = result->status == CO_SDO_CLIENT_OK && result->size == 4;
    /* An abort from the server is an answer; the client's own (its timeout) is silence. */
    p->present = result->status != CO_SDO_CLIENT_CLIENT_ABORT;
    if (--p->scan->pending == 0)
        comaster_bus_finish(p->scan->bus, 0);
}

static void master_send(void *user, const co_frame_t *frame)
{
    scan_t *s = user;
    comaster_bus_send(s->bus, frame);
}

static void probes_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    scan_t *s = ctx;
    co_nmt_master_receive(&s->master, frame, now);
    for (size_t i = 0; i < NODE_COUNT; i++) {
        if (co_sdo_client_receive(&s->probes[i].client, frame, now))
            break;
    }
}

static co_time_t probes_process(void *ctx, co_time_t now)
{
    scan_t *s = ctx;
    co_time_t next = CO_TIME_NEVER;
    for (size_t i = 0; i < NODE_COUNT; i++) {
        co_time_t d = co_sdo_client_process(&s->probes[i].client, now);
        next = d < next ? d : next;
    }
    return next;
}

/* Phase 1: every node-id asked for 1000h at once. */
static int probe_all(scan_t *s, uint32_t timeout_ms)
{
    co_time_t now = co_linux_now();
    for (uint8_t node = 1; node <= NODE_COUNT; node++) {
        probe_t *p = &s->probes[node - 1];
        p->scan = s;
        co_sdo_client_config_t config = {
            .server_node_id = node, .send = probe_send, .user = p, .done = probe_done};
        co_sdo_client_init(&p->client, &config);
        if (co_sdo_client_upload(&p->client, 0x1000, 0, p->value, sizeof p->value,
                                 CO_SDO_CLIENT_AUTO, timeout_ms, now) == 0)
            s->pending++;
    }
    comaster_job_t job = {.receive = probes_receive, .process = probes_process, .ctx = s};
    return comaster_bus_run(s->bus, &job);
}

/* ---- phase 3: the NMT states not heard yet, by node guarding -------------------------------- */

static bool states_known(const scan_t *s)
{
    for (size_t i = 0; i < NODE_COUNT; i++) {
        if (s->probes[i].present && s->state[i] == CO_NMT_MASTER_STATE_UNKNOWN)
            return false;
    }
    return true;
}

/* A guarding reply (or a heartbeat) gives the state; the toggle bit is whatever the node's last
 * guarding left it at, so a one-off request takes either. A device of the older profile pads the
 * reply to 8 bytes. */
static void guard_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    scan_t *s = ctx;
    (void)now;
    uint32_t node = frame->id - CO_CAN_ID_ERROR_CONTROL;
    if ((frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF)) || frame->len < 1 || node < 1 ||
        node > NODE_COUNT)
        return;
    uint8_t state = frame->data[0] & (uint8_t)~CO_GUARD_TOGGLE;
    s->state[node - 1] = state == CO_NMT_INITIALISING ? CO_NMT_PRE_OPERATIONAL : state;
    if (states_known(s))
        comaster_bus_finish(s->bus, 0);
}

static co_time_t guard_process(void *ctx, co_time_t now)
{
    scan_t *s = ctx;
    if (now >= s->deadline || states_known(s)) {
        comaster_bus_finish(s->bus, 0);
        return CO_TIME_NEVER;
    }
    return s->deadline;
}

static int ask_states(scan_t *s, uint32_t timeout_ms)
{
    for (uint8_t node = 1; node <= NODE_COUNT; node++) {
        s->state[node - 1] = co_nmt_master_state(&s->master, node);
        if (s->probes[node - 1].present && s->state[node - 1] == CO_NMT_MASTER_STATE_UNKNOWN) {
            co_frame_t request = {
                .id = CO_CAN_ID_ERROR_CONTROL + node, .len = 1, .flags = CO_FRAME_RTR};
            comaster_bus_send(s->bus, &request);
        }
    }
    s->deadline = co_linux_now() + (co_time_t)timeout_ms * 1000u;
    comaster_job_t job = {.receive = guard_receive, .process = guard_process, .ctx = s};
    return comaster_bus_run(s->bus, &job);
}

/* ---- phase 2 and the output ---------------------------------------------------------------- */

typedef struct identity {
    bool has[3];
    uint32_t value[3]; /* 1018h:01..03 */
    char name[64];     /* 1008h, "" when absent */
} identity_t;

/* Reads one object; an abort (the node has no such object) is not an error. */
static int read_optional(comaster_bus_t *bus, const comaster_options_t *opts, uint8_t node,
                         uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap, uint32_t *size)
{
    co_sdo_client_result_t result;
    *size = 0;
    int rc = comaster_sdo_upload(bus, node, index, sub, buf, cap, CO_SDO_CLIENT_AUTO,
                                 opts->timeout_ms, &result);
    if (rc == 0 && result.status == CO_SDO_CLIENT_OK)
        *size = result.size;
    return rc;
}

static int read_identity(comaster_bus_t *bus, const comaster_options_t *opts, uint8_t node,
                         identity_t *id)
{
    memset(id, 0, sizeof *id);
    uint32_t size;
    for (uint8_t sub = CO_IDENTITY_VENDOR; sub <= CO_IDENTITY_REVISION; sub++) {
        uint8_t buf[4];
        int rc = read_optional(bus, opts, node, CO_IDX_IDENTITY, sub, buf, sizeof buf, &size);
        if (rc != 0)
            return rc;
        id->has[sub - 1] = size == 4;
        id->value[sub - 1] = size == 4 ? co_get_u32(buf) : 0;
    }
    int rc = read_optional(bus, opts, node, CO_IDX_DEVICE_NAME, 0, (uint8_t *)id->name,
                           sizeof id->name - 1, &size);
    id->name[size] = '\0';
    return rc;
}

/* A state's name, "-" when the node's state was not heard. */
static const char *nmt_state_name(uint8_t state)
{
    const char *name = state == CO_NMT_INITIALISING ? NULL : co_nmt_state_name(state);
    return name ? name : "-";
}

static void print_hex_or_dash(bool has, uint32_t value, bool json)
{
    if (!has)
        printf(json ? "null" : "%-12s", "-");
    else
        printf(json ? "\"0x%08X\"" : "0x%08X  ", value);
}

static void print_node(const comaster_options_t *opts, uint8_t node, const probe_t *p,
                       const identity_t *id, uint8_t state)
{
    bool json = opts->json;
    if (json)
        printf("{\"node\": %u, \"device_type\": ", node);
    else
        printf("%4u  ", node);
    print_hex_or_dash(p->has_device_type, co_get_u32(p->value), json);
    const char *keys[] = {"vendor", "product", "revision"};
    for (int i = 0; i < 3; i++) {
        if (json)
            printf(", \"%s\": ", keys[i]);
        print_hex_or_dash(id->has[i], id->value[i], json);
    }
    if (json) {
        printf(", \"name\": ");
        if (id->name[0])
            cli_json_string(stdout, id->name);
        else
            printf("null");
        printf(", \"state\": ");
        if (state == CO_NMT_MASTER_STATE_UNKNOWN)
            printf("null}\n");
        else
            printf("\"%s\"}\n", nmt_state_name(state));
        return;
    }
    printf("%-16s  %s\n", id->name[0] ? id->name : "-", nmt_state_name(state));
}

static int report(scan_t *s, const comaster_options_t *opts)
{
    size_t found = 0;
    for (uint8_t node = 1; node <= NODE_COUNT; node++) {
        const probe_t *p = &s->probes[node - 1];
        if (!p->present)
            continue;
        identity_t id;
        int rc = read_identity(s->bus, opts, node, &id);
        if (rc != 0)
            return rc;
        if (found++ == 0 && !opts->json)
            printf("node  device type vendor      product     revision    name              "
                   "state\n");
        print_node(opts, node, p, &id, s->state[node - 1]);
    }
    if (found == 0)
        return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                             "no node answered on %s within %u ms (--timeout MS waits longer)",
                             opts->iface, opts->timeout_ms);
    return 0;
}

int comaster_scan_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, scan_help, "", 0, 0);
    if (rc >= 0)
        return rc;
    static comaster_bus_t bus;
    static scan_t scan;
    memset(&scan, 0, sizeof scan);
    scan.bus = &bus;
    co_nmt_master_config_t config = {.send = master_send, .user = &scan};
    co_nmt_master_init(&scan.master, &config);
    rc = comaster_bus_open(&bus, opts);
    if (rc == 0)
        rc = probe_all(&scan, opts->timeout_ms);
    if (rc == 0)
        rc = ask_states(&scan, opts->timeout_ms);
    if (rc == 0)
        rc = report(&scan, opts);
    comaster_bus_close(&bus);
    return rc;
}
