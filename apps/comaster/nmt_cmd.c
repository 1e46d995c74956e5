/* SPDX-License-Identifier: Apache-2.0 */
/* comaster nmt: an NMT command to one node or to all; after a reset of one node, its boot-up is
 * awaited. */
#include "co/co_nmt_master.h"
#include "comaster/comaster.h"
#include "comaster/run_control.h"

#include <stdio.h>
#include <string.h>

static const char nmt_help[] =
    "usage: comaster nmt start|stop|preop|reset-node|reset-comm NODE|all\n"
    "\n"
    "Sends an NMT command (000h) to node NODE (1..127) or to all nodes. After\n"
    "reset-node or reset-comm of one node, waits up to --timeout for its boot-up\n"
    "(700h + NODE) and prints 'node NODE: boot-up'.\n"
    "\n"
    "  start        Start remote node: Operational\n"
    "  stop         Stop remote node: Stopped\n"
    "  preop        Enter pre-operational\n"
    "  reset-node   Reset node: the application and communication\n"
    "  reset-comm   Reset communication\n"
    "  --run        send it through the comaster run on the interface (its control\n"
    "               socket): the run's master sends it and confirms the state each\n"
    "               node reports next (all: each slave of its network) within --timeout\n"
    "  --control PATH  the same through the run listening on PATH\n"
    "\n"
    "Example: comaster -i vcan0 nmt start all\n";

typedef struct nmt_name {
    const char *name;
    uint8_t command;
} nmt_name_t;

static const nmt_name_t nmt_names[] = {
    {"start", CO_NMT_CS_START},
    {"stop", CO_NMT_CS_STOP},
    {"preop", CO_NMT_CS_ENTER_PRE_OPERATIONAL},
    {"reset-node", CO_NMT_CS_RESET_NODE},
    {"reset-comm", CO_NMT_CS_RESET_COMMUNICATION},
};

/* Waits for the boot-up of one node: the NMT master reports it. */
typedef struct boot_wait {
    comaster_bus_t *bus;
    co_nmt_master_t master;
    uint8_t node;
    co_time_t deadline;
} boot_wait_t;

static void boot_event(void *user, const co_nmt_master_event_t *event)
{
    boot_wait_t *w = user;
    if (event->kind == CO_NMT_MASTER_BOOT_UP && event->node_id == w->node)
        comaster_bus_finish(w->bus, CLI_EXIT_OK);
}

static void boot_send(void *user, const co_frame_t *frame)
{
    boot_wait_t *w = user;
    comaster_bus_send(w->bus, frame);
}

static void boot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    boot_wait_t *w = ctx;
    co_nmt_master_receive(&w->master, frame, now);
}

static co_time_t boot_process(void *ctx, co_time_t now)
{
    boot_wait_t *w = ctx;
    if (now >= w->deadline) {
        comaster_bus_finish(w->bus, CLI_EXIT_TIMEOUT);
        return CO_TIME_NEVER;
    }
    return w->deadline;
}

static int send_command(comaster_bus_t *bus, const comaster_options_t *opts, const nmt_name_t *cmd,
                        uint8_t node)
{
    static boot_wait_t wait;
    memset(&wait, 0, sizeof wait);
    wait.bus = bus;
    wait.node = node;
    co_nmt_master_config_t config = {.send = boot_send, .user = &wait, .event = boot_event};
    co_nmt_master_init(&wait.master, &config);
    co_nmt_master_command(&wait.master, cmd->command, node);
    bool await_boot =
        node != CO_NMT_MASTER_ALL_NODES &&
        (cmd->command == CO_NMT_CS_RESET_NODE || cmd->command == CO_NMT_CS_RESET_COMMUNICATION);
    if (!await_boot) {
        int rc = comaster_bus_pause(bus, 0); /* sends what is queued */
        if (rc == 0 && opts->json && node == CO_NMT_MASTER_ALL_NODES)
            printf("{\"node\": \"all\", \"command\": \"%s\"}\n", cmd->name);
        else if (rc == 0 && opts->json)
            printf("{\"node\": %u, \"command\": \"%s\"}\n", node, cmd->name);
        return rc;
    }
    wait.deadline = co_linux_now() + (co_time_t)opts->timeout_ms * 1000u;
    comaster_job_t job = {.receive = boot_receive, .process = boot_process, .ctx = &wait};
    int rc = comaster_bus_run(bus, &job);
    if (rc == CLI_EXIT_TIMEOUT)
        return comaster_fail(opts, rc,
                             "node %u: no boot-up within %u ms after %s: is the node on %s? "
                             "(--timeout MS waits longer)",
                             node, opts->timeout_ms, cmd->name, opts->iface);
    if (rc == 0 && opts->json)
        printf("{\"node\": %u, \"command\": \"%s\", \"boot_up\": true}\n", node, cmd->name);
    else if (rc == 0)
        printf("node %u: boot-up\n", node);
    return rc;
}

static const nmt_name_t *nmt_by_name(const char *name)
{
    for (size_t i = 0; i < sizeof nmt_names / sizeof nmt_names[0]; i++) {
        if (strcmp(nmt_names[i].name, name) == 0)
            return &nmt_names[i];
    }
    return NULL;
}

bool comaster_nmt_command(const char *name, uint8_t *command)
{
    const nmt_name_t *cmd = nmt_by_name(name);
    if (cmd)
        *command = cmd->command;
    return cmd != NULL;
}

const char *comaster_nmt_name(uint8_t command)
{
    for (size_t i = 0; i < sizeof nmt_names / sizeof nmt_names[0]; i++) {
        if (nmt_names[i].command == command)
            return nmt_names[i].name;
    }
    return "?";
}

/* Through a run: the request "nmt COMMAND NODE|all MS"; the run replies when confirmed. */
static int through_run(comaster_options_t *opts, const char *control, const comaster_args_t *args)
{
    if (opts->timeout_ms > COMASTER_CONTROL_WAIT_MAX_MS)
        return comaster_fail(opts, EX_USAGE,
                             "nmt through a run: --timeout is at most %u ms (the run's reply "
                             "must come within the control socket's wait)",
                             COMASTER_CONTROL_WAIT_MAX_MS);
    char timeout[16];
    snprintf(timeout, sizeof timeout, "%u", opts->timeout_ms);
    const char *fields[] = {"nmt", args->positional[0], args->positional[1], timeout};
    return comaster_control_forward(opts, control, fields, 4);
}

int comaster_nmt_main(comaster_options_t *opts, int argc, char **argv)
{
    const char *control = NULL;
    bool via_run = false;
    if (!comaster_run_option(&argc, argv, &via_run, &control))
        return comaster_missing_value(opts, "--control");
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, nmt_help, "", 2, 2);
    if (rc >= 0)
        return rc;
    const nmt_name_t *cmd = nmt_by_name(args.positional[0]);
    if (!cmd)
        return comaster_fail(opts, EX_USAGE,
                             "nmt: '%s' is not an NMT command: give start, stop, preop, "
                             "reset-node or reset-comm",
                             args.positional[0]);
    uint8_t node;
    if (!comaster_parse_node(opts, args.positional[1], true, &node))
        return EX_USAGE;
    if (via_run)
        return through_run(opts, control, &args);
    static comaster_bus_t bus;
    rc = comaster_bus_open(&bus, opts);
    if (rc == 0)
        rc = send_command(&bus, opts, cmd, node);
    comaster_bus_close(&bus);
    return rc;
}
