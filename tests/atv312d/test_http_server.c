/* SPDX-License-Identifier: Apache-2.0 */
/* The web surface's server on a loopback TCP port, in the runtime's loop as the daemon runs it:
 * one ATV312 at node 4 on a bus that is a socketpair (co_linux_loop_open_fd), the server on
 * 127.0.0.1 at a free port, and a client in a child process that makes its requests, writes what
 * it saw to a pipe and exits, which hangs up the bus and ends the loop. Checked here what the
 * handler's tests (test_http.c) cannot see: keep-alive, the event stream's first event and its
 * period, the limit of connections per address, the budget of event streams apart from the
 * requests, the deadline of a request that trickles in or never comes, 414 and 431 as JSON before
 * the library's own, the wrong method of a POST answered before its body; and the lines the
 * server logs at warn for each refusal. */
#include "atv312/atv312.h"
#include "atv312d/http.h"
#include "atv312d/options.h"
#include "check_main.h"
#include "co_linux/log.h"

#include <arpa/inet.h>
#include <check.h>
#include <ctype.h>
#include <errno.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/timerfd.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define NODE 4

static co_linux_loop_t loop;
static uint8_t od_data[ATV312_OD_DATA_SIZE];
static drive_t drive;
static co_linux_device_t device;
static atv312d_counters_t counters;
static atv312d_control_node_t node;
static atv312d_control_t control;
static atv312d_http_t http;

static void slot_start(void *ctx, co_time_t now)
{
    drive_start(ctx, now);
}

static void slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    drive_receive(ctx, frame, now);
}

static co_time_t slot_process(void *ctx, co_time_t now)
{
    return drive_process(ctx, now);
}

static const co_node_t *slot_node(void *ctx)
{
    return &((drive_t *)ctx)->node;
}

static const co_linux_device_ops_t ops = {
    .start = slot_start, .receive = slot_receive, .process = slot_process, .node = slot_node};

/* ---- the client, in the child ---- */

static FILE *report;
static uint16_t port;
static bool ipv6; /* the server listens on [::1] */

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec / 1e9;
}

/* A connection from 127.0.0.<host> (every 127/8 address is this machine's). */
static int connect_from(unsigned host)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in from = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(0x7F000000 | host)};
    struct sockaddr_in to = {.sin_family = AF_INET, .sin_port = htons(port)};
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || bind(fd, (struct sockaddr *)&from, sizeof from) != 0 ||
        connect(fd, (struct sockaddr *)&to, sizeof to) != 0)
        exit(2);
    struct timeval timeout = {.tv_sec = 8};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    return fd;
}

static int connect_server(void)
{
    int fd = socket(ipv6 ? AF_INET6 : AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_port = htons(port)};
    struct sockaddr_in6 addr6 = {.sin6_family = AF_INET6, .sin6_port = htons(port)};
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr6.sin6_addr = in6addr_loopback;
    int rc = ipv6 ? connect(fd, (struct sockaddr *)&addr6, sizeof addr6)
                  : connect(fd, (struct sockaddr *)&addr, sizeof addr);
    if (fd < 0 || rc != 0)
        exit(2);
    struct timeval timeout = {.tv_sec = 5};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    return fd;
}

static void send_text(int fd, const char *text)
{
    if (write(fd, text, strlen(text)) != (ssize_t)strlen(text))
        exit(3);
}

/* Reads into buf until `until` is in it, the peer closes, or 5 s pass; the bytes read. */
static size_t read_until(int fd, char *buf, size_t cap, const char *until)
{
    size_t used = 0;
    buf[0] = '\0';
    while (used + 1 < cap && !(until && strstr(buf, until))) {
        ssize_t n = read(fd, buf + used, cap - 1 - used);
        if (n <= 0)
            break;
        used += (size_t)n;
        buf[used] = '\0';
    }
    return used;
}

/* One answer of known length on a kept connection: its status line. */
static void get_status(int fd, const char *path, char *status, size_t len)
{
    char request[256], answer[8192];
    snprintf(request, sizeof request, "GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n", path);
    send_text(fd, request);
    read_until(fd, answer, sizeof answer, "\r\n\r\n");
    const char *length = strstr(answer, "Content-Length: ");
    const char *body = strstr(answer, "\r\n\r\n");
    if (length && body) {
        size_t want = (size_t)(body + 4 - answer) + strtoul(length + 16, NULL, 10);
        size_t have = strlen(answer);
        while (have < want) {
            ssize_t n = read(fd, answer + have, sizeof answer - 1 - have);
            if (n <= 0)
                break;
            have += (size_t)n;
        }
    }
    snprintf(status, len, "%.*s", (int)strcspn(answer, "\r"), answer);
}

static void client_keep_alive(void)
{
    int fd = connect_server();
    char first[64], second[64];
    get_status(fd, "/api/bench", first, sizeof first);
    get_status(fd, "/api/state", second, sizeof second);
    fprintf(report, "keep-alive: %s; %s\n", first, second);
    close(fd);
}

static void client_events(void)
{
    int fd = connect_server();
    static char text[256 * 1024];
    double start = seconds();
    send_text(fd, "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    read_until(fd, text, sizeof text, "\n\n");
    double first = seconds() - start;
    bool stream = strstr(text, "Content-Type: text/event-stream") != NULL;
    bool event = strstr(text, "event: state\ndata: {\"ok\":true,\"time_ms\":") != NULL;
    read_until(fd, text, sizeof text, "\n\n");
    double second = seconds() - start;
    fprintf(report, "events: %s, first %s, second after %s\n",
            stream && event ? "a state stream" : "no stream", first < 0.15 ? "at once" : "late",
            second > 0.2 && second < 1.0 ? "a period" : "?");
    close(fd);
}

/* An answer read to the server's close: "<status line>; <body>". */
static void report_answer(const char *what, int fd)
{
    static char answer[16384];
    read_until(fd, answer, sizeof answer, NULL);
    const char *body = strstr(answer, "\r\n\r\n");
    fprintf(report, "%s: %.*s; %s\n", what, (int)strcspn(answer, "\r"), answer,
            body ? body + 4 : "no body");
}

/* Whether the server closed the connection without a byte. */
static const char *closed_unanswered(int fd)
{
    char c;
    return read(fd, &c, 1) == 0 ? "closed unanswered" : "answered or still open";
}

/* 16 connections from 127.0.0.1 are served; a 17th from it is closed at once, one from
 * 127.0.0.2 is served. */
static void client_per_address(void)
{
    int held[ATV312D_HTTP_PER_ADDRESS_MAX];
    char status[64];
    for (int i = 0; i < ATV312D_HTTP_PER_ADDRESS_MAX; i++) {
        held[i] = connect_from(1);
        get_status(held[i], "/api/bench", status, sizeof status);
    }
    fprintf(report, "16th from 127.0.0.1: %s\n", status);
    int refused = connect_from(1);
    fprintf(report, "17th from 127.0.0.1: %s\n", closed_unanswered(refused));
    close(refused);
    int other = connect_from(2);
    get_status(other, "/api/bench", status, sizeof status);
    fprintf(report, "1st from 127.0.0.2: %s\n", status);
    close(other);
    for (int i = 0; i < ATV312D_HTTP_PER_ADDRESS_MAX; i++)
        close(held[i]);
}

/* 16 streams from 127.0.0.1; a 17th from 127.0.0.2 is refused while its page loads. */
static void client_streams(void)
{
    int streams[ATV312D_HTTP_STREAMS_MAX];
    char text[16384], status[64];
    for (int i = 0; i < ATV312D_HTTP_STREAMS_MAX; i++) {
        streams[i] = connect_from(1);
        send_text(streams[i], "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
        read_until(streams[i], text, sizeof text, "\n\n");
    }
    int refused = connect_from(2);
    send_text(refused, "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    report_answer("17th stream", refused);
    close(refused);
    int page = connect_from(2);
    get_status(page, "/", status, sizeof status);
    fprintf(report, "the page meanwhile: %s\n", status);
    close(page);
    for (int i = 0; i < ATV312D_HTTP_STREAMS_MAX; i++)
        close(streams[i]);
}

/* A request trickling in a byte every 250 ms and a connection that sends nothing: both closed
 * by the deadline (5 s), before the silence limit (10 s) would close the idle one, which the
 * trickle never reaches. */
static void client_deadline(void)
{
    int trickler = connect_from(1), idle = connect_from(2);
    double start = seconds();
    send_text(trickler, "GET /api/bench HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ");
    double trickler_closed = 0, idle_closed = 0;
    while ((!trickler_closed || !idle_closed) && seconds() - start < 8.0) {
        struct pollfd fds[2] = {{.fd = trickler, .events = POLLIN}, {.fd = idle, .events = POLLIN}};
        poll(fds, 2, 250);
        char c;
        if (!trickler_closed && fds[0].revents && read(trickler, &c, 1) <= 0)
            trickler_closed = seconds() - start;
        else if (!trickler_closed && write(trickler, "x", 1) != 1)
            trickler_closed = seconds() - start;
        if (!idle_closed && fds[1].revents && read(idle, &c, 1) <= 0)
            idle_closed = seconds() - start;
    }
    fprintf(report, "trickler: %s; idle: %s\n",
            trickler_closed > 4.8 && trickler_closed < 6.0 ? "closed at the deadline" : "?",
            idle_closed > 4.8 && idle_closed < 6.0 ? "closed at the deadline" : "?");
    close(trickler);
    close(idle);
}

/* A target and a head too long for the server, well inside the library's pool: JSON. */
static void client_too_long(void)
{
    static char request[16384];
    char target[3001];
    memset(target, 'a', sizeof target - 1);
    target[0] = '/';
    target[sizeof target - 1] = '\0';
    snprintf(request, sizeof request, "GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n", target);
    int fd = connect_from(1);
    send_text(fd, request);
    report_answer("long target", fd);
    close(fd);
    char cookie[9001];
    memset(cookie, 'c', sizeof cookie - 1);
    cookie[sizeof cookie - 1] = '\0';
    snprintf(request, sizeof request,
             "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nCookie: %s\r\nConnection: close\r\n\r\n",
             cookie);
    fd = connect_from(1);
    send_text(fd, request);
    report_answer("long head", fd);
    close(fd);
}

/* A POST refused on its headers is answered before its body is sent. */
static void client_refused_post(void)
{
    int fd = connect_server();
    char answer[4096];
    send_text(fd, "POST /api/command HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: "
                  "application/json\r\nContent-Length: 25\r\n\r\n");
    read_until(fd, answer, sizeof answer, "}");
    const char *body = strstr(answer, "\r\n\r\n");
    fprintf(report, "refused post: %.*s; %s\n", (int)strcspn(answer, "\r"), answer,
            body ? body + 4 : "no body");
    close(fd);
}

/* On [::1], with its name as Host. */
static void client_ipv6(void)
{
    int fd = connect_server();
    char answer[8192];
    send_text(fd, "GET /api/bench HTTP/1.1\r\nHost: [::1]\r\nConnection: close\r\n\r\n");
    read_until(fd, answer, sizeof answer, NULL);
    fprintf(report, "ipv6: %.*s\n", (int)strcspn(answer, "\r"), answer);
    close(fd);
}

/* ---- the server, in the parent ---- */

/* What the web server logged at warn during the last serve, each client's port as PORT (the
 * bus's hang-up at the end is not the server's). */
static char logged[8192];

/* "... http 127.0.0.1:40422: ..." as "... http 127.0.0.1:PORT: ...", the server's lines only. */
static void keep_server_lines(char *text)
{
    char *out = text;
    for (const char *in = text; *in;) {
        const char *end = strchr(in, '\n');
        size_t n = end ? (size_t)(end + 1 - in) : strlen(in);
        const char *peer = strstr(in, "http ");
        if (!peer || peer >= in + n) {
            in += n;
            continue;
        }
        const char *colon = strstr(peer, ": ");
        const char *digits = colon;
        while (digits && digits > peer && isdigit((unsigned char)digits[-1]))
            digits--;
        if (colon && colon < in + n && digits != colon && digits[-1] == ':') {
            size_t head = (size_t)(digits - in);
            memmove(out, in, head);
            memcpy(out + head, "PORT", 4);
            out += head + 4;
            n -= (size_t)(colon - in);
            in = colon;
        }
        memmove(out, in, n);
        out += n;
        in += n;
    }
    *out = '\0';
}

/* Runs the loop with the server until the child, running `client`, exits; returns its report.
 * The server's log at warn goes to `logged`. */
static const char *serve_at(const char *address, void (*client)(void))
{

    int bus[2], pipe_fds[2];
    ck_assert_int_eq(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, bus), 0);
    ck_assert_int_eq(pipe(pipe_fds), 0);
    co_linux_loop_config_t config = {.iface = "pair"};
    ck_assert_int_eq(co_linux_loop_open_fd(&loop, &config, bus[0]), CO_LINUX_OPEN_OK);
    drive_config_t drive_config = {.profile = &atv312_profile,
                                   .od_data = od_data,
                                   .node_id = NODE,
                                   .send = co_linux_device_send,
                                   .send_user = &device};
    ck_assert_int_eq(drive_init(&drive, &drive_config), 0);
    co_linux_loop_add(&loop, &device, &ops, &drive);
    node = (atv312d_control_node_t){
        .id = NODE, .model = "atv312", .drive = &drive, .device = &device, .counters = &counters};
    control = (atv312d_control_t){.nodes = &node, .count = 1};
    atv312d_http_settings_t settings = {0};
    char err[256];
    ck_assert_int_eq(atv312d_parse_http_address(address, &settings.address, err, sizeof err), 0);
    ipv6 = settings.address.addr.ss_family == AF_INET6;
    ck_assert_int_eq(atv312d_http_open(&http, &loop, &settings, &control), 0);
    port = http.port;
    ck_assert_uint_ne(port, 0);
    /* No client yet: nothing armed. */
    struct itimerspec armed;
    ck_assert_int_eq(timerfd_gettime(http.timer_fd, &armed), 0);
    ck_assert(armed.it_value.tv_sec == 0 && armed.it_value.tv_nsec == 0);
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        close(bus[0]);
        close(pipe_fds[0]);
        report = fdopen(pipe_fds[1], "w");
        client();
        fclose(report);
        _exit(0);
    }
    close(bus[1]);
    close(pipe_fds[1]);
    FILE *log = tmpfile();
    ck_assert_ptr_nonnull(log);
    int saved_err = dup(STDERR_FILENO);
    dup2(fileno(log), STDERR_FILENO);
    co_log_setup("atv312d", CO_LOG_WARN);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    dup2(saved_err, STDERR_FILENO);
    close(saved_err);
    rewind(log);
    size_t logged_len = fread(logged, 1, sizeof logged - 1, log);
    logged[logged_len] = '\0';
    fclose(log);
    keep_server_lines(logged);
    static char text[4096];
    size_t used = 0;
    ssize_t n;
    while ((n = read(pipe_fds[0], text + used, sizeof text - 1 - used)) > 0)
        used += (size_t)n;
    text[used] = '\0';
    close(pipe_fds[0]);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the client failed: %d", status);
    atv312d_http_close(&http);
    co_linux_loop_close(&loop);
    return text;
}

static const char *serve(void (*client)(void))
{
    return serve_at("127.0.0.1:0", client);
}

START_TEST(connections_are_kept)
{
    ck_assert_str_eq(serve(client_keep_alive), "keep-alive: HTTP/1.1 200 OK; HTTP/1.1 200 OK\n");
}
END_TEST

START_TEST(events_first_at_once_then_each_period)
{
    ck_assert_str_eq(serve(client_events),
                     "events: a state stream, first at once, second after a period\n");
}
END_TEST

START_TEST(sixteen_connections_per_address)
{
    ck_assert_str_eq(serve(client_per_address), "16th from 127.0.0.1: HTTP/1.1 200 OK\n"
                                                "17th from 127.0.0.1: closed unanswered\n"
                                                "1st from 127.0.0.2: HTTP/1.1 200 OK\n");
    ck_assert_str_eq(logged, "atv312d: warn: http 127.0.0.1:PORT: refused, closed: 16 "
                             "connections from its address, the most for one\n");
}
END_TEST

START_TEST(streams_apart_from_requests)
{
    ck_assert_str_eq(serve(client_streams),
                     "17th stream: HTTP/1.1 503 Service Unavailable; {\"ok\":false,\"error\":"
                     "\"busy: 16 event streams are open, the most at once; try again in a few "
                     "seconds (the page and the API still answer)\"}\n"
                     "the page meanwhile: HTTP/1.1 200 OK\n");
    ck_assert_str_eq(logged, "atv312d: warn: http 127.0.0.2:PORT: GET /api/events: refused, 503: "
                             "busy: 16 event streams are open, the most at once; try again in a "
                             "few seconds (the page and the API still answer)\n");
}
END_TEST

START_TEST(request_deadline_whatever_the_trickle)
{
    ck_assert_str_eq(serve(client_deadline),
                     "trickler: closed at the deadline; idle: closed at the deadline\n");
    /* Each once. They expire at one timer wake-up or at two a few milliseconds apart, so in
     * either order. */
    static const char trickler[] = "atv312d: warn: http 127.0.0.1:PORT: refused, closed: its "
                                   "request did not arrive whole within 5 s\n";
    static const char idle[] = "atv312d: warn: http 127.0.0.2:PORT: refused, closed: no request "
                               "came within 5 s\n";
    ck_assert_ptr_nonnull(strstr(logged, trickler));
    ck_assert_ptr_nonnull(strstr(logged, idle));
    ck_assert_uint_eq(strlen(logged), strlen(trickler) + strlen(idle));
}
END_TEST

START_TEST(too_long_answered_as_json)
{
    ck_assert_str_eq(serve(client_too_long),
                     "long target: HTTP/1.1 414 URI Too Long; {\"ok\":false,\"error\":\"the "
                     "request target is 3000 bytes, longer than 2048: no path of this server "
                     "is\"}\n"
                     "long head: HTTP/1.1 431 Request Header Fields Too Large; {\"ok\":false,"
                     "\"error\":\"the request head is 9064 bytes, longer than 8192: send fewer "
                     "or shorter headers (cookies?)\"}\n");
    ck_assert_str_eq(logged, "atv312d: warn: http 127.0.0.1:PORT: GET (too long): refused, 414: "
                             "the request target is 3000 bytes, longer than 2048: no path of this "
                             "server is\n"
                             "atv312d: warn: http 127.0.0.1:PORT: GET /: refused, 431: the "
                             "request head is 9064 bytes, longer than 8192: send fewer or shorter "
                             "headers (cookies?)\n");
}
END_TEST

START_TEST(refused_post_answered_before_its_body)
{
    ck_assert_str_eq(serve(client_refused_post),
                     "refused post: HTTP/1.1 403 Forbidden; {\"ok\":false,\"error\":\"actions are "
                     "off: start atv312d with --http-actions to allow them\"}\n");
}
END_TEST

START_TEST(listens_on_ipv6)
{
    ck_assert_str_eq(serve_at("[::1]:0", client_ipv6), "ipv6: HTTP/1.1 200 OK\n");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312d_http_server");
    TCase *tc = tcase_create("server");
    tcase_set_timeout(tc, 30);
    tcase_add_test(tc, connections_are_kept);
    tcase_add_test(tc, events_first_at_once_then_each_period);
    tcase_add_test(tc, sixteen_connections_per_address);
    tcase_add_test(tc, streams_apart_from_requests);
    tcase_add_test(tc, request_deadline_whatever_the_trickle);
    tcase_add_test(tc, too_long_answered_as_json);
    tcase_add_test(tc, refused_post_answered_before_its_body);
    tcase_add_test(tc, listens_on_ipv6);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
