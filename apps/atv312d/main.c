/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d: emulated Schneider Altivar drives on a SocketCAN interface, one process, one epoll
 * loop, one socket for all of them. main() parses the options, opens the trace, the store and the
 * loop, builds the drives (drives.h), opens the surfaces on them, runs until a signal and gives
 * the exit status. Usage and behaviour: docs/atv312d.md. */
#include "atv312d/control_socket.h"
#include "atv312d/drives.h"
#include "atv312d/http.h"
#include "atv312d/notify.h"
#include "atv312d/options.h"
#include "atv312d/status.h"
#include "atv312d/storage.h"
#include "cli/co_cli.h"
#include "co_linux/log.h"
#include "co_linux/loop.h"

#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

static int report_open_error(const co_linux_loop_t *loop, co_linux_open_result_t result)
{
    const char *iface = loop->iface;
    const char *why = strerror(loop->open_errno);
    switch (result) {
    case CO_LINUX_OPEN_NO_CAN:
        co_log(CO_LOG_ERROR,
               "this kernel has no SocketCAN support (%s: %s): load it with modprobe can-raw "
               "vcan, or run inside the sandbox: tools/vcan-run atv312d vcan0 --node-id 4",
               loop->open_call, why);
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NO_IFACE:
        co_log(CO_LOG_ERROR,
               "no network interface '%s': create a virtual CAN bus with: ip link add dev %s "
               "type vcan && ip link set up %s (as root), or list the CAN interfaces with: ip "
               "link show type can",
               iface, strncmp(iface, "vcan", 4) == 0 ? iface : "vcan0",
               strncmp(iface, "vcan", 4) == 0 ? iface : "vcan0");
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NOT_CAN:
        co_log(CO_LOG_ERROR,
               "'%s' is not a CAN interface (%s: %s): give a SocketCAN interface such as can0 or "
               "vcan0",
               iface, loop->open_call, why);
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_OS_ERROR:
    case CO_LINUX_OPEN_OK:
        break;
    }
    co_log(CO_LOG_ERROR, "%s on %s failed: %s", loop->open_call, iface, why);
    return EX_OSERR;
}

static int open_trace(const char *path, FILE **trace)
{
    *trace = NULL;
    if (!path)
        return 0;
    if (strcmp(path, "-") == 0) {
        *trace = stdout;
        return 0;
    }
    *trace = fopen(path, "we");
    if (*trace)
        return 0;
    co_log(CO_LOG_ERROR, "cannot create the trace file '%s': %s", path, strerror(errno));
    return EX_CANTCREAT;
}

static const char *baud_text(atv312d_baud_t baud)
{
    switch (baud) {
    case ATV312D_BAUD_125K:
        return "125 kbit/s";
    case ATV312D_BAUD_250K:
        return "250 kbit/s";
    case ATV312D_BAUD_500K:
        return "500 kbit/s";
    }
    return "?";
}

/* "4,5 (atv312)" or, on a mixed bench, "4,5 (atv312), 6 (atv31)": node-ids ascending, each run
 * of one model followed by its name. */
static void format_node_ids(const atv312d_options_t *opts, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < opts->node_count && used < len; i++) {
        const char *separator = i == 0                                             ? ""
                                : opts->models[i].name == opts->models[i - 1].name ? ","
                                                                                   : ", ";
        used += (size_t)snprintf(buf + used, len - used, "%s%u", separator, opts->node_ids[i]);
        bool run_ends =
            i + 1 == opts->node_count || opts->models[i + 1].name != opts->models[i].name;
        if (run_ends && used < len)
            used += (size_t)snprintf(buf + used, len - used, " (%s)", opts->models[i].name);
    }
}

/* What the bench is made of, for the log and the service manager: "drive(s)" when every node
 * is a drive, "node(s)" when some are not (a PLC300, an I/O node). */
static const char *nodes_noun(const atv312d_options_t *opts)
{
    for (size_t i = 0; i < opts->node_count; i++) {
        if (opts->models[i].kind != ATV312D_KIND_DRIVE)
            return "node(s)";
    }
    return "drive(s)";
}

/* The web surface's settings: --http's address, --http-actions and the secret of --http-token. */
static int http_settings(const atv312d_options_t *opts, atv312d_http_settings_t *settings)
{
    *settings =
        (atv312d_http_settings_t){.address = opts->http_address, .actions = opts->http_actions};
    if (!opts->http_token_path)
        return 0;
    char err[512];
    int rc = atv312d_http_read_token(opts->http_token_path, settings->token, sizeof settings->token,
                                     err, sizeof err);
    if (rc != 0)
        co_log(CO_LOG_ERROR, "%s", err);
    return rc;
}

/* The surfaces on the drives' views (nodes): the control socket (--control) and the web (--http),
 * whose commands act on `control`, and the status (--status, SIGUSR1). */
static int open_surfaces(atv312d_control_socket_t *control_socket, atv312d_control_t *control,
                         atv312d_status_t *status, atv312d_http_t *http, co_linux_loop_t *loop,
                         const atv312d_options_t *opts, atv312d_drive_t *drives,
                         atv312d_control_node_t *nodes)
{
    for (size_t i = 0; i < opts->node_count; i++)
        nodes[i] = (atv312d_control_node_t){.id = drives[i].id,
                                            .model = opts->models[i].name,
                                            .plain = drives[i].plain,
                                            .drive = drives[i].plain ? NULL : &drives[i].drive,
                                            .devicenet = drives[i].dn,
                                            .device = &drives[i].device,
                                            .counters = &drives[i].counters};
    control->nodes = nodes;
    control->count = opts->node_count;
    int rc = atv312d_status_open(status, loop, opts->status_path, nodes, opts->node_count);
    if (rc == 0 && opts->control_path)
        rc = atv312d_control_open(control_socket, loop, opts->control_path, control);
    atv312d_http_settings_t settings;
    if (rc == 0 && opts->http && (rc = http_settings(opts, &settings)) == 0)
        rc = atv312d_http_open(http, loop, &settings, control);
    return rc;
}

/* What systemd's Type=notify waits for (docs/atv312d.md, "systemd"). */
typedef struct readiness {
    const atv312d_options_t *opts;
    const atv312d_drive_t *drives;
} readiness_t;

static void notify(const char *state)
{
    if (atv312d_notify(state))
        return;
    co_log(CO_LOG_WARN, "NOTIFY_SOCKET %s: %s: the service manager was not told",
           getenv("NOTIFY_SOCKET"), strerror(errno));
}

/* READY=1 once every drive's start has reached the bus: on CANopen its boot-up written to the
 * socket (an interface down at start: after it came up and the boot-ups left); on DeviceNet, in
 * addition, every card's duplicate MAC ID check over, online or faulted. Told once. */
static void tell_when_ready(void *ctx, co_linux_loop_t *loop)
{
    const readiness_t *ready = ctx;
    if (!co_linux_loop_sent_all(loop))
        return;
    size_t faulted = 0;
    for (size_t i = 0; i < ready->opts->node_count; i++) {
        const drive_dn_t *dn = ready->drives[i].dn;
        if (dn && dn->node.link != DN_LINK_ONLINE && dn->node.link != DN_LINK_FAULTED)
            return;
        faulted += dn && dn->node.link == DN_LINK_FAULTED;
    }
    co_linux_loop_on_settled(loop, NULL, NULL);
    char state[256];
    size_t count = ready->opts->node_count;
    if (ready->opts->devicenet)
        snprintf(state, sizeof state,
                 "READY=1\nSTATUS=%zu drive(s) on DeviceNet on %s: %zu online, %zu faulted", count,
                 loop->iface, count - faulted, faulted);
    else
        snprintf(state, sizeof state, "READY=1\nSTATUS=%zu %s booted on %s", count,
                 nodes_noun(ready->opts), loop->iface);
    co_log(CO_LOG_DEBUG, "service manager told: %s", strchr(state, '\n') + 1);
    notify(state);
}

static int run(const atv312d_options_t *opts, FILE *trace, co_file_store_t *store)
{
    static atv312d_control_socket_t control_socket = {.server.listen_fd = -1};
    static atv312d_control_t control;
    static atv312d_status_t status = {.timer_fd = -1, .signal_fd = -1};
    static atv312d_http_t http = {.mhd_fd = -1, .timer_fd = -1};
    static atv312d_control_node_t control_nodes[ATV312D_NODE_ID_MAX];
    static co_linux_loop_t loop;
    co_linux_loop_config_t config = {.iface = opts->iface, .trace = trace};
    co_linux_open_result_t opened = co_linux_loop_open(&loop, &config);
    if (opened != CO_LINUX_OPEN_OK)
        return report_open_error(&loop, opened);
    atv312d_drive_t *drives = calloc(opts->node_count, sizeof *drives);
    int rc = drives ? atv312d_drives_init(drives, opts, store, &loop) : EX_OSERR;
    if (rc == 0)
        rc = open_surfaces(&control_socket, &control, &status, &http, &loop, opts, drives,
                           control_nodes);
    if (rc == 0) {
        char ids[2048];
        format_node_ids(opts, ids, sizeof ids);
        if (opts->devicenet)
            co_log(CO_LOG_INFO,
                   "atv312d %s started on %s: %zu drive(s) on DeviceNet at %s, MAC ID %s",
                   ATV312D_VERSION, opts->iface, opts->node_count, baud_text(opts->baud), ids);
        else
            co_log(CO_LOG_INFO, "atv312d %s started on %s: %zu %s, node-id %s", ATV312D_VERSION,
                   opts->iface, opts->node_count, nodes_noun(opts), ids);
        readiness_t readiness = {.opts = opts, .drives = drives};
        co_linux_loop_on_settled(&loop, tell_when_ready, &readiness);
        rc = co_linux_loop_run(&loop);
        notify("STOPPING=1");
        co_log(CO_LOG_INFO,
               "stopped: %llu wake-ups, %llu frames received, %llu sent, %llu dropped, %llu lost "
               "while the interface was down, %llu error frames, %llu received for no drive, "
               "%llu sendmmsg calls, %llu receive filters set",
               loop.stats.wakeups, loop.stats.rx, loop.stats.tx, loop.stats.tx_dropped,
               loop.stats.down_dropped, loop.stats.error_frames, loop.stats.unrouted,
               loop.stats.tx_calls, loop.stats.filters);
    }
    atv312d_http_close(&http);
    atv312d_control_close(&control_socket);
    atv312d_status_close(&status);
    co_linux_loop_close(&loop);
    atv312d_drives_free(drives, opts->node_count);
    return rc;
}

int main(int argc, char *argv[])
{
    atv312d_options_t opts;
    char err[256];
    co_log_setup("atv312d", CO_LOG_INFO);
    if (argc >= 2 && strcmp(argv[1], "ctl") == 0)
        return atv312d_control_client(argc - 2, argv + 2);
    int rc = atv312d_parse_args(argc, argv, &opts, err, sizeof err);
    if (rc != 0)
        return cli_fail(NULL, rc, "%s", err);
    if (opts.help) {
        atv312d_print_usage(stdout);
        return 0;
    }
    if (opts.version) {
        printf("atv312d %s\n", ATV312D_VERSION);
        return 0;
    }
    co_log_setup("atv312d", opts.log_level);
    /* A closed trace pipe must not kill the daemon: the write fails and tracing stops. */
    signal(SIGPIPE, SIG_IGN);

    FILE *trace;
    rc = open_trace(opts.trace_path, &trace);
    if (rc != 0)
        return rc;
    co_file_store_t store;
    if (opts.store_path)
        rc = atv312d_storage_open(opts.store_path, &store);
    if (rc == 0) {
        rc = run(&opts, trace, opts.store_path ? &store : NULL);
        if (opts.store_path)
            co_file_store_close(&store);
    }
    if (trace && trace != stdout)
        fclose(trace);
    return rc;
}
