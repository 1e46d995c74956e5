/* SPDX-License-Identifier: Apache-2.0 */
/* comaster gateway: a CiA 309-3 ASCII gateway on standard input and output, or on a TCP port and
 * a UNIX socket. Every connection's lines run one at a time in their order, all of them in the
 * bus's epoll loop: an SDO transfer runs on the gateway's one SDO client while the loop goes on
 * reading the other connections, whose lines wait their turn (docs/comaster.md). */
#include "co/co_lss_master.h"
#include "co/co_nmt_master.h"
#include "co/co_sdo_client.h"
#include "co_linux/log.h"
#include "comaster/comaster.h"
#include "comaster/gateway_ascii.h"
#include "comaster/value.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* Connections at once (standard input or the clients of the listeners); the loop watches each
 * and the two listeners (CO_LINUX_WATCH_MAX). */
#define GW_CONNECTIONS 8
/* The shortest wait of a fastscan frame after the reset, as comaster lss fastscan's. */
#define FASTSCAN_MIN_WAIT_US 5000u
/* Input a connection may have waiting: lines beyond it stay in the socket until their turn. */
#define GW_INPUT_MAX (4u * GW_LINE_MAX)

static const char gateway_help[] =
    "usage: comaster gateway [--listen [ADDR:]PORT] [--socket PATH]\n"
    "\n"
    "A CiA 309-3 ASCII gateway to the bus: one command a line, such as\n"
    "'[1] 4 read 0x1017 0 u16', answered '[1] 1000', '[1] OK' or '[1] ERROR:...'\n"
    "(CR LF ended, as CANopenNode's canopend answers). Lines are read from standard\n"
    "input and answered on standard output until the end of the input, or with\n"
    "--listen or --socket from the clients of a TCP port or a UNIX socket until\n"
    "SIGINT or SIGTERM. '[1] help' lists the commands (SDO, NMT, LSS, set);\n"
    "docs/comaster.md tells the syntax, the error codes and what is not supported\n"
    "(lss_allnodes, the base64 types).\n"
    "\n"
    "  --listen [ADDR:]PORT  accept TCP clients on PORT of ADDR (default 127.0.0.1)\n"
    "  --socket PATH         accept clients on the UNIX socket PATH\n"
    "  --timeout MS          how long an LSS service waits for its answer (an SDO\n"
    "                        transfer: 'set sdo_timeout', 500 ms before)\n"
    "\n"
    "Example: comaster -i vcan0 gateway --listen 6000\n";

typedef struct gw_conn {
    int in_fd; /* -1: free */
    int out_fd;
    char input[GW_INPUT_MAX];
    size_t len;
    bool watching;   /* false while input is full, or after the end of the input */
    bool ended;      /* the end of its input was read */
    bool discarding; /* the line being read is too long: its rest is dropped */
    gw_session_t session;
    uint32_t last_sequence;
} gw_conn_t;

typedef struct gateway {
    comaster_bus_t *bus;
    gw_conn_t conns[GW_CONNECTIONS];
    int listeners[2];
    bool stdio;
    size_t next;       /* the connection whose line goes first, round robin */
    gw_conn_t *active; /* the one whose SDO transfer or LSS service runs, NULL when none */
    bool orphan;       /* ... which closed: the transfer runs to its end, unanswered */
    co_sdo_client_t client;
    co_sdo_client_result_t result;
    bool done;
    co_nmt_master_t nmt;
    co_lss_master_t lss;
    co_lss_master_result_t lss_result;
    uint32_t address[4]; /* lss_inquire_addr without LSSSUB: the parts inquired so far */
    unsigned part;
    bool rescanning; /* _lss_fastscan lost its slave: scanning again, every frame its whole time */
    co_time_t lss_timeout_us; /* --timeout */
    gw_request_t req;
    uint8_t upload[GW_VALUE_MAX];
    char reply[3 * GW_VALUE_MAX + 64];
} gateway_t;

static gateway_t gateway;

static void conn_close(gateway_t *gw, gw_conn_t *c)
{
    if (c->watching)
        co_linux_loop_unwatch(&gw->bus->loop, c->in_fd);
    if (c->in_fd > STDERR_FILENO)
        close(c->in_fd);
    if (gw->active == c)
        gw->orphan = true; /* its transfer runs to its end, which frees the client */
    c->in_fd = -1;
    c->watching = false;
}

/* A reply, written whole: a client that does not read its replies is closed rather than let
 * the loop wait for it. */
static void conn_write(gateway_t *gw, gw_conn_t *c, const char *text, size_t len)
{
    if (c->in_fd < 0)
        return;
    while (len > 0) {
        ssize_t n = c->out_fd == STDOUT_FILENO
                        ? write(c->out_fd, text, len)
                        : send(c->out_fd, text, len, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            co_log(CO_LOG_WARN, "gateway: a client does not take its replies: closed");
            conn_close(gw, c);
            return;
        }
        text += n;
        len -= (size_t)n;
    }
}

static void input_ready(void *ctx, int fd);

static void conn_watch(gateway_t *gw, gw_conn_t *c)
{
    if (!c->watching && !c->ended && c->len < sizeof c->input &&
        co_linux_loop_watch(&gw->bus->loop, c->in_fd, input_ready, c) == 0)
        c->watching = true;
}

/* Takes the first whole line of c (the last one without its newline once the input ended);
 * false when there is none. *too_long: it has GW_LINE_MAX characters or more (only its beginning
 * is in line). */
static bool take_line(gw_conn_t *c, char *line, bool *too_long)
{
    char *nl = memchr(c->input, '\n', c->len);
    size_t n = nl ? (size_t)(nl - c->input) : c->len;
    if (!nl && (!c->ended || c->len == 0))
        return false;
    *too_long = n >= GW_LINE_MAX;
    size_t keep = *too_long ? GW_LINE_MAX - 1 : n;
    memcpy(line, c->input, keep);
    line[keep] = '\0';
    if (keep > 0 && line[keep - 1] == '\r')
        line[keep - 1] = '\0';
    size_t used = nl ? n + 1 : n;
    memmove(c->input, c->input + used, c->len - used);
    c->len -= used;
    return true;
}

/* The syntax error of a line longer than CiA 309-3's buffer (1024 characters, D-GATEWAY-REPLIES):
 * no sequence of its own is read from it. */
static void reply_too_long(gateway_t *gw, gw_conn_t *c)
{
    size_t n = gw_reply_error(gw->reply, sizeof gw->reply, c->last_sequence, GW_ERROR_SYNTAX);
    conn_write(gw, c, gw->reply, n);
}

static void bus_send(void *user, const co_frame_t *frame)
{
    gateway_t *gw = user;
    comaster_bus_send(gw->bus, frame);
}

static void sdo_done(void *user, const co_sdo_client_result_t *result)
{
    gateway_t *gw = user;
    gw->result = *result;
    gw->done = true;
}

static void lss_done(void *user, const co_lss_master_result_t *result)
{
    gateway_t *gw = user;
    gw->lss_result = *result;
    gw->done = true;
}

/* Starts an LSS service: the unconfirmed ones are answered at once, the others when their
 * answer or timeout comes (finish_lss). */
static int start_lss(gateway_t *gw, const gw_request_t *req, bool *confirmed)
{
    co_lss_master_t *m = &gw->lss;
    co_time_t now = co_linux_now();
    co_time_t t = gw->lss_timeout_us;
    *confirmed = true;
    switch (req->lss) {
    case GW_LSS_SWITCH_GLOBAL:
        *confirmed = false;
        return co_lss_master_switch_global(m, req->args[0] ? CO_LSS_CONFIGURATION : CO_LSS_WAITING);
    case GW_LSS_ACTIVATE_BITRATE:
        *confirmed = false;
        return co_lss_master_activate_bit_timing(m, (uint16_t)req->args[0]);
    case GW_LSS_SWITCH_SELECTIVE: {
        co_lss_address_t address;
        memcpy(address.part, req->args, sizeof address.part);
        return co_lss_master_switch_selective(m, &address, t, now);
    }
    case GW_LSS_SET_NODE:
        return co_lss_master_configure_node_id(m, (uint8_t)req->args[0], t, now);
    case GW_LSS_CONF_BITRATE:
        return co_lss_master_configure_bit_timing(m, (uint8_t)req->args[0], (uint8_t)req->args[1],
                                                  t, now);
    case GW_LSS_STORE:
        return co_lss_master_store(m, t, now);
    case GW_LSS_INQUIRE:
        return co_lss_master_inquire(m, (uint8_t)(CO_LSS_CS_INQUIRE_VENDOR + req->args[0]), t, now);
    case GW_LSS_INQUIRE_ALL:
        gw->part = 0;
        return co_lss_master_inquire(m, CO_LSS_CS_INQUIRE_VENDOR, t, now);
    case GW_LSS_GET_NODE:
        return co_lss_master_inquire(m, CO_LSS_CS_INQUIRE_NODE_ID, t, now);
    case GW_LSS_FASTSCAN: {
        /* The timeout is the reset frame's wait and the longest of the others, which wait twice
         * the slowest answer, at least FASTSCAN_MIN_WAIT_US (D-LSS-FASTSCAN-WAIT). */
        co_time_t wait = (co_time_t)req->args[0] * 1000u;
        return co_lss_master_fastscan(
            m, NULL, wait, wait < FASTSCAN_MIN_WAIT_US ? wait : FASTSCAN_MIN_WAIT_US, now);
    }
    }
    return CO_LSS_MASTER_ERR_ARG;
}

/* The reply of a confirmed LSS service; false when it goes on (the next part of an address). */
static bool finish_lss(gateway_t *gw, char *out, size_t cap)
{
    const gw_request_t *req = &gw->req;
    const co_lss_master_result_t *r = &gw->lss_result;
    if (req->lss == GW_LSS_FASTSCAN && r->status != CO_LSS_MASTER_OK && r->answers > 0 &&
        !gw->rescanning) {
        /* A slave answered, then an answer came later than the shortened wait: once more with
         * every frame waiting the whole time, as comaster lss fastscan does. */
        co_time_t wait = (co_time_t)req->args[0] * 1000u;
        gw->rescanning = true;
        co_lss_master_switch_global(&gw->lss, CO_LSS_WAITING);
        if (co_lss_master_fastscan(&gw->lss, NULL, wait, wait, co_linux_now()) == 0)
            return false;
    }
    if (r->status != CO_LSS_MASTER_OK) {
        gw_reply_error(out, cap, req->sequence, GW_ERROR_TIMEOUT);
        return true;
    }
    /* The slave's error (CiA 305: 1 not supported, 255 its own), in 309-3's LSS codes. */
    unsigned refused = req->lss == GW_LSS_SET_NODE       ? GW_ERROR_LSS_NODE_ID
                       : req->lss == GW_LSS_CONF_BITRATE ? GW_ERROR_LSS_BIT_RATE
                                                         : GW_ERROR_LSS_STORE;
    switch (req->lss) {
    case GW_LSS_SET_NODE:
    case GW_LSS_CONF_BITRATE:
    case GW_LSS_STORE:
        if (r->error == CO_LSS_SPECIFIC_ERROR)
            gw_reply_error(out, cap, req->sequence, GW_ERROR_LSS_MANUFACTURER);
        else if (r->error != CO_LSS_OK)
            gw_reply_error(out, cap, req->sequence, refused);
        else
            gw_reply_ok(out, cap, req->sequence);
        return true;
    case GW_LSS_INQUIRE:
        gw_reply_words(out, cap, req->sequence, &r->value, 1, 8);
        return true;
    case GW_LSS_GET_NODE:
        gw_reply_words(out, cap, req->sequence, &r->value, 1, 2);
        return true;
    case GW_LSS_INQUIRE_ALL:
        gw->address[gw->part++] = r->value;
        if (gw->part < 4 &&
            co_lss_master_inquire(&gw->lss, (uint8_t)(CO_LSS_CS_INQUIRE_VENDOR + gw->part),
                                  gw->lss_timeout_us, co_linux_now()) == 0)
            return false;
        gw_reply_words(out, cap, req->sequence, gw->address, 4, 8);
        return true;
    case GW_LSS_FASTSCAN:
        gw_reply_words(out, cap, req->sequence, r->address.part, 4, 8);
        return true;
    default:
        gw_reply_ok(out, cap, req->sequence);
        return true;
    }
}

/* Runs a parsed line: replies at once, or starts its SDO transfer. */
static void start_request(gateway_t *gw, gw_conn_t *c)
{
    gw_request_t *req = &gw->req;
    if (req->action == GW_REPLY) {
        conn_write(gw, c, req->reply, strlen(req->reply));
        if (req->help)
            conn_write(gw, c, req->help, strlen(req->help));
        return;
    }
    if (req->action == GW_NMT) {
        co_nmt_master_command(&gw->nmt, req->nmt_command, req->node);
        size_t n = gw_reply_ok(gw->reply, sizeof gw->reply, req->sequence);
        conn_write(gw, c, gw->reply, n);
        return;
    }
    if (req->action == GW_LSS) {
        bool confirmed;
        int rc = start_lss(gw, req, &confirmed);
        if (rc == 0 && confirmed) {
            gw->done = false;
            gw->active = c;
            return;
        }
        size_t n = rc == 0 ? gw_reply_ok(gw->reply, sizeof gw->reply, req->sequence)
                           : gw_reply_error(gw->reply, sizeof gw->reply, req->sequence,
                                            GW_ERROR_INTERNAL_STATE);
        conn_write(gw, c, gw->reply, n);
        return;
    }
    co_sdo_client_config_t config = {
        .server_node_id = req->node, .send = bus_send, .user = gw, .done = sdo_done};
    co_sdo_client_init(&gw->client, &config);
    co_sdo_client_mode_t mode = c->session.sdo_block ? CO_SDO_CLIENT_BLOCK : CO_SDO_CLIENT_AUTO;
    co_time_t now = co_linux_now();
    gw->done = false;
    gw->active = c;
    int started =
        req->action == GW_READ
            ? co_sdo_client_upload(&gw->client, req->index, req->sub, gw->upload, sizeof gw->upload,
                                   mode, c->session.sdo_timeout_ms, now)
            : co_sdo_client_download(&gw->client, req->index, req->sub, req->data,
                                     (uint32_t)req->len, mode, c->session.sdo_timeout_ms, now);
    if (started != 0) {
        gw->active = NULL;
        size_t n =
            gw_reply_error(gw->reply, sizeof gw->reply, req->sequence, GW_ERROR_INTERNAL_STATE);
        conn_write(gw, c, gw->reply, n);
    }
}

/* The reply of the transfer that ended. An SDO timeout is the client's abort 0x05040000, as
 * canopend answers it. */
static void finish_transfer(gateway_t *gw)
{
    gw_conn_t *c = gw->active;
    gw->active = NULL;
    gw->done = false;
    if (gw->orphan) {
        gw->orphan = false;
        return;
    }
    const gw_request_t *req = &gw->req;
    const co_sdo_client_result_t *r = &gw->result;
    if (req->action == GW_LSS) {
        if (!finish_lss(gw, gw->reply, sizeof gw->reply)) {
            gw->active = c; /* the next part of the address is inquired */
            return;
        }
    } else if (r->status != CO_SDO_CLIENT_OK)
        gw_reply_abort(gw->reply, sizeof gw->reply, req->sequence, r->abort_code);
    else if (req->action == GW_WRITE)
        gw_reply_ok(gw->reply, sizeof gw->reply, req->sequence);
    else if (!gw_reply_value(gw->reply, sizeof gw->reply, req->sequence, req->type, gw->upload,
                             r->size))
        gw_reply_abort(gw->reply, sizeof gw->reply, req->sequence, CO_SDO_ABORT_TYPE_LENGTH);
    conn_write(gw, c, gw->reply, strlen(gw->reply));
}

/* Runs the waiting lines, one connection after the other, until a transfer starts. */
static void pump(gateway_t *gw)
{
    char line[GW_LINE_MAX];
    bool ran = true;
    while (!gw->active && ran) {
        ran = false;
        for (size_t k = 0; k < GW_CONNECTIONS && !gw->active; k++) {
            gw_conn_t *c = &gw->conns[(gw->next + k) % GW_CONNECTIONS];
            if (c->in_fd < 0)
                continue;
            bool too_long;
            if (take_line(c, line, &too_long)) {
                if (too_long) {
                    reply_too_long(gw, c);
                } else {
                    gw_parse(&c->session, &c->last_sequence, line, &gw->req);
                    start_request(gw, c);
                }
                conn_watch(gw, c);
                gw->next = (gw->next + k + 1) % GW_CONNECTIONS;
                ran = true;
                break;
            }
            if (c->ended && c->len == 0 && c->in_fd >= 0)
                conn_close(gw, c);
        }
    }
    if (!gw->active && gw->stdio && gw->conns[0].in_fd < 0)
        comaster_bus_finish(gw->bus, CLI_EXIT_OK); /* standard input ended, every line answered */
}

/* Drops what is read of a line longer than CiA 309-3's buffer whose end has not come, answering it
 * a syntax error once: the lines after it stay whole. */
static void drop_long_lines(gateway_t *gw, gw_conn_t *c)
{
    if (!c->discarding) {
        if (memchr(c->input, '\n', c->len) || c->len < GW_LINE_MAX)
            return; /* a whole line, which take_line checks, or one not yet too long */
        reply_too_long(gw, c);
        c->discarding = true;
    }
    char *nl = memchr(c->input, '\n', c->len);
    size_t drop = nl ? (size_t)(nl - c->input) + 1 : c->len;
    memmove(c->input, c->input + drop, c->len - drop);
    c->len -= drop;
    c->discarding = !nl;
}

static void input_ready(void *ctx, int fd)
{
    gw_conn_t *c = ctx;
    gateway_t *gw = &gateway;
    ssize_t n = read(fd, c->input + c->len, sizeof c->input - c->len);
    if (n < 0 && (errno == EINTR || errno == EAGAIN))
        return;
    if (n <= 0) {
        c->ended = true;
    } else {
        c->len += (size_t)n;
        drop_long_lines(gw, c);
    }
    if (c->watching && (c->ended || c->len == sizeof c->input)) {
        co_linux_loop_unwatch(&gw->bus->loop, fd);
        c->watching = false;
    }
    co_linux_device_process(&gw->bus->device);
}

static void accept_ready(void *ctx, int fd)
{
    gateway_t *gw = ctx;
    int client = accept4(fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (client < 0)
        return;
    for (size_t i = 0; i < GW_CONNECTIONS; i++) {
        gw_conn_t *c = &gw->conns[i];
        if (c->in_fd >= 0)
            continue;
        memset(c, 0, sizeof *c);
        c->in_fd = client;
        c->out_fd = client;
        gw_session_init(&c->session);
        conn_watch(gw, c);
        if (c->watching)
            return;
        c->in_fd = -1;
        break;
    }
    static const char busy[] = "ERROR:102 too many gateway connections\r\n";
    (void)send(client, busy, sizeof busy - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
    close(client);
}

static void gw_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    gateway_t *gw = ctx;
    if (gw->active && gw->req.action == GW_LSS)
        co_lss_master_receive(&gw->lss, frame, now);
    else if (gw->active)
        co_sdo_client_receive(&gw->client, frame, now);
}

/* The deadline of the transfer or LSS service under way. */
static co_time_t active_process(gateway_t *gw, co_time_t now)
{
    if (!gw->active)
        return CO_TIME_NEVER;
    return gw->req.action == GW_LSS ? co_lss_master_process(&gw->lss, now)
                                    : co_sdo_client_process(&gw->client, now);
}

static co_time_t gw_process(void *ctx, co_time_t now)
{
    gateway_t *gw = ctx;
    co_time_t deadline = active_process(gw, now);
    if (gw->done) {
        finish_transfer(gw);
        deadline = active_process(gw, now);
    }
    if (!gw->active) {
        pump(gw);
        deadline = active_process(gw, now);
    }
    return deadline;
}

/* "[ADDR:]PORT" into a TCP listener; -1 after a one-line error. */
static int open_tcp(const comaster_options_t *opts, const char *text)
{
    char addr[64] = "127.0.0.1";
    const char *port_text = text;
    const char *colon = strrchr(text, ':');
    if (colon) {
        if ((size_t)(colon - text) >= sizeof addr)
            return -comaster_fail(opts, EX_USAGE, "gateway: --listen '%s': no such address", text);
        memcpy(addr, text, (size_t)(colon - text));
        addr[colon - text] = '\0';
        port_text = colon + 1;
    }
    uint32_t port;
    struct sockaddr_in sa = {.sin_family = AF_INET};
    if (!comaster_parse_number(port_text, UINT16_MAX, &port) || port == 0 ||
        inet_pton(AF_INET, addr, &sa.sin_addr) != 1)
        return -comaster_fail(opts, EX_USAGE,
                              "gateway: --listen '%s' is not [ADDR:]PORT: give a port 1..65535 "
                              "and an IPv4 address",
                              text);
    sa.sin_port = htons((uint16_t)port);
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    int one = 1;
    if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(fd, (struct sockaddr *)&sa, sizeof sa) != 0 || listen(fd, GW_CONNECTIONS) != 0) {
        int err = errno;
        if (fd >= 0)
            close(fd);
        return -comaster_fail(opts, EX_CANTCREAT, "gateway: cannot listen on %s:%u: %s", addr, port,
                              strerror(err));
    }
    return fd;
}

static int open_unix(const comaster_options_t *opts, const char *path)
{
    struct sockaddr_un sa = {.sun_family = AF_UNIX};
    if (strlen(path) >= sizeof sa.sun_path)
        return -comaster_fail(opts, EX_USAGE, "gateway: --socket '%s' is too long a path", path);
    strcpy(sa.sun_path, path);
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd >= 0)
        unlink(path); /* a socket file left behind by a gateway that died */
    if (fd < 0 || bind(fd, (struct sockaddr *)&sa, sizeof sa) != 0 ||
        listen(fd, GW_CONNECTIONS) != 0) {
        int err = errno;
        if (fd >= 0)
            close(fd);
        return -comaster_fail(opts, EX_CANTCREAT, "gateway: cannot listen on %s: %s", path,
                              strerror(err));
    }
    return fd;
}

static int watch_listener(gateway_t *gw, int fd, size_t slot)
{
    gw->listeners[slot] = fd;
    if (co_linux_loop_watch(&gw->bus->loop, fd, accept_ready, gw) == 0)
        return 0;
    return comaster_fail(gw->bus->opts, EX_OSERR, "gateway: cannot watch a listener: %s",
                         strerror(errno));
}

static int open_inputs(gateway_t *gw, const comaster_options_t *opts, const comaster_args_t *args)
{
    if (!args->listen && !args->socket) {
        gw_conn_t *c = &gw->conns[0];
        c->in_fd = STDIN_FILENO;
        c->out_fd = STDOUT_FILENO;
        gw_session_init(&c->session);
        gw->stdio = true;
        conn_watch(gw, c);
        if (!c->watching)
            return comaster_fail(opts, EX_USAGE,
                                 "gateway: standard input cannot be watched (%s): give a pipe, a "
                                 "terminal or a socket, not a file",
                                 strerror(errno));
        return 0;
    }
    if (args->listen) {
        int fd = open_tcp(opts, args->listen);
        if (fd < 0)
            return -fd;
        int rc = watch_listener(gw, fd, 0);
        if (rc != 0)
            return rc;
    }
    if (args->socket) {
        int fd = open_unix(opts, args->socket);
        if (fd < 0)
            return -fd;
        return watch_listener(gw, fd, 1);
    }
    return 0;
}

static void close_all(gateway_t *gw, const comaster_args_t *args)
{
    for (size_t i = 0; i < GW_CONNECTIONS; i++)
        if (gw->conns[i].in_fd >= 0)
            conn_close(gw, &gw->conns[i]);
    for (size_t i = 0; i < 2; i++) {
        if (gw->listeners[i] >= 0) {
            co_linux_loop_unwatch(&gw->bus->loop, gw->listeners[i]);
            close(gw->listeners[i]);
        }
    }
    if (gw->listeners[1] >= 0)
        unlink(args->socket);
}

int comaster_gateway_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, gateway_help, "--listen --socket", 0, 0);
    if (rc >= 0)
        return rc;
    signal(SIGPIPE, SIG_IGN); /* a client gone: its write fails, the gateway goes on */
    static comaster_bus_t bus;
    rc = comaster_bus_open(&bus, opts);
    if (rc != 0)
        return rc;
    gateway_t *gw = &gateway;
    memset(gw, 0, sizeof *gw);
    gw->bus = &bus;
    gw->listeners[0] = gw->listeners[1] = -1;
    for (size_t i = 0; i < GW_CONNECTIONS; i++)
        gw->conns[i].in_fd = -1;
    co_nmt_master_config_t nmt = {.send = comaster_bus_send, .user = &bus};
    co_nmt_master_init(&gw->nmt, &nmt);
    co_lss_master_config_t lss = {.send = bus_send, .user = gw, .done = lss_done};
    co_lss_master_init(&gw->lss, &lss);
    gw->lss_timeout_us = (co_time_t)opts->timeout_ms * 1000u;
    bus.signal_is_the_end = !!(args.listen || args.socket);
    rc = open_inputs(gw, opts, &args);
    if (rc == 0) {
        comaster_job_t job = {.receive = gw_receive, .process = gw_process, .ctx = gw};
        rc = comaster_bus_run(&bus, &job);
        if (bus.signal_is_the_end && rc == CLI_EXIT_INTERRUPTED)
            rc = CLI_EXIT_OK; /* how a listening gateway ends */
    }
    close_all(gw, &args);
    comaster_bus_close(&bus);
    return rc;
}
