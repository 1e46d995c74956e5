/* SPDX-License-Identifier: Apache-2.0 */
/* comaster monitor: what happens on the bus, as it arrives: NMT state changes told by boot-ups
 * and heartbeats, emergencies decoded, SYNC, and PDOs decoded by name through each watched node's
 * mapping, read over SDO (with the names of its EDS). Runs until SIGINT or SIGTERM. */
#include "cli/co_cli.h"
#include "co/co_emcy_consumer.h"
#include "co/co_nmt.h"
#include "co/co_nmt_master.h"
#include "comaster/comaster.h"
#include "trace/decoder.h"

#include "co_linux/can_frame.h"

#include <stdio.h>
#include <string.h>

static const char monitor_help[] =
    "usage: comaster monitor [NODE...] [--heartbeat MS]\n"
    "\n"
    "Prints, as they arrive, one line each: NMT states told by boot-ups and\n"
    "heartbeats (only their changes), emergencies with the meaning of their code,\n"
    "SYNC, and PDOs. The PDOs of each NODE given are decoded by name: its PDO\n"
    "COB-IDs and mappings (1400h-1407h, 1600h-1607h, 1800h-1807h, 1A00h-1A07h) are\n"
    "read over SDO at the start, and named from its EDS (--eds FILE, or the one of\n"
    "its identity); other PDOs show their bytes. Each line starts with the seconds\n"
    "since the start. SIGINT (Ctrl-C) or SIGTERM ends it, exit status 0.\n"
    "\n"
    "  --heartbeat MS  consume the heartbeats of the NODEs given: 'heartbeat lost'\n"
    "                  when none came for MS ms (1..65535), 'heard again' when\n"
    "                  one comes back\n"
    "\n"
    "Example: comaster -i vcan0 monitor 4 5 --heartbeat 300\n";

/* The PDOs of a node read over SDO: the first eight of each direction (the predefined set has
 * four; the ATV312 uses PDO1 and PDO6). */
#define PDO_READ_COUNT 8u
#define PDO_MAPPED_MAX 64u

typedef struct watched {
    uint8_t node;
    eds_t eds;
    cotrace_decoder_t decoder;
} watched_t;

typedef struct monitor {
    comaster_bus_t *bus;
    const comaster_options_t *opts;
    co_nmt_master_t master;
    watched_t watched[COMASTER_MAX_ARGS];
    size_t watched_count;
    cotrace_decoder_t plain; /* PDOs of the nodes not watched */
    co_time_t start;
    co_time_t now;
} monitor_t;

/* The start of a line: seconds since the start, or the JSON object's first fields. */
static void line_start(const monitor_t *m, const char *event)
{
    double t = (double)(m->now - m->start) / 1e6;
    if (m->opts->json)
        printf("{\"time\": %.3f, \"event\": \"%s\", ", t, event);
    else
        printf("%9.3f  ", t);
}

/* A state's name, "unknown" before the node was heard. */
static const char *state_name(uint8_t state)
{
    const char *name = state == CO_NMT_INITIALISING ? NULL : co_nmt_state_name(state);
    return name ? name : "unknown";
}

static void nmt_event(void *user, const co_nmt_master_event_t *event)
{
    monitor_t *m = user;
    if (event->kind == CO_NMT_MASTER_BOOT_UP) {
        line_start(m, "boot-up");
        printf(m->opts->json ? "\"node\": %u}\n" : "node %u: boot-up\n", event->node_id);
    } else if (event->kind == CO_NMT_MASTER_HEARTBEAT_LOST ||
               event->kind == CO_NMT_MASTER_RESUMED) {
        bool lost = event->kind == CO_NMT_MASTER_HEARTBEAT_LOST;
        line_start(m, lost ? "heartbeat-lost" : "heard-again");
        printf(m->opts->json ? "\"node\": %u}\n"
                             : (lost ? "node %u: heartbeat lost\n" : "node %u: heard again\n"),
               event->node_id);
    } else if (event->kind == CO_NMT_MASTER_STATE_CHANGED) {
        line_start(m, "state");
        bool first = event->old_state == CO_NMT_MASTER_STATE_UNKNOWN;
        if (m->opts->json)
            printf("\"node\": %u, \"state\": \"%s\", \"old_state\": \"%s\"}\n", event->node_id,
                   state_name(event->state), state_name(event->old_state));
        else if (first) /* the first heartbeat heard tells the state, not a change */
            printf("node %u: %s\n", event->node_id, state_name(event->state));
        else
            printf("node %u: %s -> %s\n", event->node_id, state_name(event->old_state),
                   state_name(event->state));
    }
}

static void nmt_send(void *user, const co_frame_t *frame)
{
    monitor_t *m = user;
    comaster_bus_send(m->bus, frame);
}

static void print_emcy(monitor_t *m, const co_emcy_message_t *msg)
{
    line_start(m, "emcy");
    const char *text = co_emcy_code_text(msg->code);
    if (m->opts->json) {
        printf("\"node\": %u, \"code\": \"0x%04X\", \"register\": \"0x%02X\", \"text\": ",
               msg->node_id, msg->code, msg->reg);
        cli_json_string(stdout, text);
        printf("}\n");
    } else {
        printf("node %u: EMCY 0x%04X %s, error register 0x%02X\n", msg->node_id, msg->code, text,
               msg->reg);
    }
}

static void print_sync(monitor_t *m, const co_frame_t *frame)
{
    line_start(m, "sync");
    if (frame->len >= 1)
        printf(m->opts->json ? "\"counter\": %u}\n" : "SYNC counter %u\n", frame->data[0]);
    else
        printf(m->opts->json ? "\"counter\": null}\n" : "SYNC\n");
}

static cotrace_decoder_t *decoder_of(monitor_t *m, uint32_t cob_id)
{
    for (size_t i = 0; i < m->watched_count; i++) {
        cotrace_decoder_t *dec = &m->watched[i].decoder;
        for (size_t p = 0; p < dec->pdo_count; p++) {
            if (dec->pdos[p].cob_id == cob_id)
                return dec;
        }
    }
    return &m->plain;
}

static void print_pdo(monitor_t *m, const co_frame_t *frame)
{
    struct can_frame cf;
    char text[1024];
    co_linux_frame_to_can(frame, &cf);
    cotrace_decode(decoder_of(m, frame->id), &cf, text, sizeof text);
    line_start(m, "pdo");
    if (m->opts->json) {
        printf("\"cob_id\": \"0x%03X\", \"text\": ", frame->id);
        cli_json_string(stdout, text);
        printf("}\n");
    } else {
        printf("%s\n", text);
    }
}

static void monitor_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    monitor_t *m = ctx;
    m->now = now;
    if (frame->flags & CO_FRAME_EFF)
        return;
    co_emcy_message_t msg;
    if (co_nmt_master_receive(&m->master, frame, now))
        return;
    if (co_emcy_decode(frame, &msg) == CO_EMCY_DECODE_OK)
        print_emcy(m, &msg);
    else if (frame->id == CO_CAN_ID_SYNC && !(frame->flags & CO_FRAME_RTR))
        print_sync(m, frame);
    else if (frame->id >= CO_CAN_ID_TPDO1 && frame->id < CO_CAN_ID_SDO_TX &&
             !(frame->flags & CO_FRAME_RTR))
        print_pdo(m, frame);
}

static co_time_t monitor_process(void *ctx, co_time_t now)
{
    monitor_t *m = ctx;
    m->now = now;
    return co_nmt_master_process(&m->master, now);
}

/* ---- the mapping of a watched node, read over SDO ------------------------------------------ */

/* Reads an UNSIGNED8 or UNSIGNED32 object into the node's dictionary; false when the node does
 * not have it. Returns the transfer's exit status in *rc when it could not run (no answer). */
static bool read_into(monitor_t *m, watched_t *w, uint16_t index, uint8_t sub, int *rc)
{
    uint8_t buf[4] = {0};
    co_sdo_client_result_t result;
    *rc = comaster_sdo_upload(m->bus, w->node, index, sub, buf, sizeof buf, CO_SDO_CLIENT_AUTO,
                              m->opts->timeout_ms, &result);
    if (*rc == 0 && result.status == CO_SDO_CLIENT_CLIENT_ABORT &&
        result.abort_code == CO_SDO_ABORT_TIMEOUT)
        *rc = comaster_sdo_status(m->opts, w->node, &result);
    if (*rc != 0 || result.status != CO_SDO_CLIENT_OK)
        return false;
    if (!eds_set_value(&w->eds, index, sub, co_get_u32(buf))) {
        *rc = comaster_fail(m->opts, EX_OSERR, "out of memory");
        return false;
    }
    return true;
}

static int read_pdo(monitor_t *m, watched_t *w, uint16_t comm)
{
    int rc;
    if (!read_into(m, w, comm, 1, &rc))
        return rc;
    uint16_t mapping = (uint16_t)(comm + CO_PDO_INDEX_SPAN);
    if (!read_into(m, w, mapping, 0, &rc))
        return rc;
    const eds_entry_t *count = eds_find(&w->eds, mapping, 0);
    for (uint8_t sub = 1; rc == 0 && sub <= count->value && sub <= PDO_MAPPED_MAX; sub++)
        read_into(m, w, mapping, sub, &rc);
    return rc;
}

static int watch_node(monitor_t *m, watched_t *w)
{
    int rc = comaster_load_eds(m->bus, m->opts, w->node, &w->eds);
    if (rc > 0)
        return rc;
    rc = 0; /* without an EDS (-1) the mapping comes without names */
    for (uint16_t i = 0; rc == 0 && i < PDO_READ_COUNT; i++) {
        rc = read_pdo(m, w, (uint16_t)(CO_PDO_TPDO_COMM + i));
        if (rc == 0)
            rc = read_pdo(m, w, (uint16_t)(CO_PDO_RPDO_COMM + i));
    }
    if (rc > 0)
        return rc;
    cotrace_decoder_init(&w->decoder, &w->eds, w->node, NULL);
    return 0;
}

static void free_watched(monitor_t *m)
{
    for (size_t i = 0; i < m->watched_count; i++)
        eds_free(&m->watched[i].eds);
}

static int run_monitor(monitor_t *m)
{
    for (size_t i = 0; i < m->watched_count; i++) {
        int rc = watch_node(m, &m->watched[i]);
        if (rc != 0)
            return rc;
    }
    fprintf(stderr, "comaster: monitoring %s (Ctrl-C ends)\n", m->opts->iface);
    setvbuf(stdout, NULL, _IOLBF, 0);
    m->start = m->now = co_linux_now();
    m->bus->signal_is_the_end = true;
    comaster_job_t job = {.receive = monitor_receive, .process = monitor_process, .ctx = m};
    int rc = comaster_bus_run(m->bus, &job);
    return rc == CLI_EXIT_INTERRUPTED ? 0 : rc;
}

int comaster_monitor_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, monitor_help, "--heartbeat", 0,
                                 COMASTER_MAX_ARGS);
    if (rc >= 0)
        return rc;
    static monitor_t m;
    static comaster_bus_t bus;
    memset(&m, 0, sizeof m);
    m.bus = &bus;
    m.opts = opts;
    for (int i = 0; i < args.count; i++) {
        if (!comaster_parse_node(opts, args.positional[i], false, &m.watched[i].node))
            return EX_USAGE;
        m.watched_count++;
    }
    co_nmt_master_config_t config = {.send = nmt_send, .user = &m, .event = nmt_event};
    co_nmt_master_init(&m.master, &config);
    for (size_t i = 0; i < m.watched_count && args.heartbeat_ms; i++)
        co_nmt_master_heartbeat(&m.master, m.watched[i].node, args.heartbeat_ms);
    cotrace_decoder_init(&m.plain, NULL, 0, NULL);
    rc = comaster_bus_open(&bus, opts);
    if (rc == 0)
        rc = run_monitor(&m);
    comaster_bus_close(&bus);
    free_watched(&m);
    return rc;
}
