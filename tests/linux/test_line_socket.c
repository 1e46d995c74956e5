/* SPDX-License-Identifier: Apache-2.0 */
/* The line socket of the programs' control sockets (co_linux/line_socket.h): a session answers
 * each line on one connection, one request is answered (also without its newline) and closed, an
 * overlong line reaches the program cut and flagged, a stale socket file is replaced while a
 * socket a server answers on and a file of another kind are not, silent clients hold up no one
 * and the one too many is told so, a deferred reply comes by its ticket, and the client tells a
 * missing server and a path too long. The server runs in a loop on a socketpair that carries no
 * frame. */
#include "check_main.h"
#include "co_linux/line_socket.h"

#include <check.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

/* Longest a test may take: a loop that never sees its stop never returns. */
#define TEST_ALARM_S 10

static co_linux_loop_t loop;
static int bus_peer;
static char dir[32], path[64];

/* What the program's answer function saw. */
static struct {
    size_t lines;
    size_t stop_after;
    bool cut;
    size_t longest;
} seen;

static size_t echo(void *ctx, const char *line, bool cut, char *reply, size_t cap)
{
    (void)ctx;
    seen.lines++;
    seen.cut = seen.cut || cut;
    if (strlen(line) > seen.longest)
        seen.longest = strlen(line);
    if (seen.lines == seen.stop_after)
        co_linux_loop_stop(&loop, 0);
    return (size_t)snprintf(reply, cap, "got %s\n", line);
}

static char reply_buf[512];

static void setup(void)
{
    int pair[2];
    ck_assert_int_eq(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, pair), 0);
    bus_peer = pair[1];
    co_linux_loop_config_t config = {.iface = "pair"};
    ck_assert_int_eq(co_linux_loop_open_fd(&loop, &config, pair[0]), CO_LINUX_OPEN_OK);
    snprintf(dir, sizeof dir, "/tmp/line_socket.XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/control.sock", dir);
    memset(&seen, 0, sizeof seen);
    alarm(TEST_ALARM_S);
}

static void teardown(void)
{
    alarm(0);
    co_linux_loop_close(&loop);
    close(bus_peer);
    unlink(path);
    rmdir(dir);
}

static void open_server(co_line_server_t *server, co_line_mode_t mode)
{
    co_line_server_config_t config = {
        .mode = mode, .answer = echo, .reply = reply_buf, .reply_cap = sizeof reply_buf};
    const char *call = NULL;
    ck_assert_int_eq(co_line_server_open(server, &loop, path, &config, &call), CO_LINE_OK);
}

static int connect_client(void)
{
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    ck_assert_int_eq(connect(fd, (struct sockaddr *)&addr, sizeof addr), 0);
    return fd;
}

/* Everything the server wrote until it closed or paused. */
static void read_all(int fd, char *buf, size_t cap)
{
    size_t got = 0;
    ssize_t n;
    while (got + 1 < cap && (n = recv(fd, buf + got, cap - 1 - got, MSG_DONTWAIT)) > 0)
        got += (size_t)n;
    buf[got] = '\0';
}

START_TEST(a_session_answers_each_line_and_stays_open)
{
    co_line_server_t server;
    open_server(&server, CO_LINE_SESSION);
    int fd = connect_client();
    const char *lines = "one\ntwo\n";
    ck_assert_int_eq(send(fd, lines, strlen(lines), 0), (ssize_t)strlen(lines));
    seen.stop_after = 2;
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    char buf[128];
    read_all(fd, buf, sizeof buf);
    ck_assert_str_eq(buf, "got one\ngot two\n");
    ck_assert_int_eq(recv(fd, buf, sizeof buf, MSG_DONTWAIT), -1);
    ck_assert_int_eq(errno, EAGAIN);
    close(fd);
    co_line_server_close(&server);
    ck_assert_int_ne(access(path, F_OK), 0);
}
END_TEST

START_TEST(one_request_without_newline_is_answered_and_closed)
{
    co_line_server_t server;
    open_server(&server, CO_LINE_ONE_REQUEST);
    int fd = connect_client();
    ck_assert_int_eq(send(fd, "status", 6, 0), 6);
    shutdown(fd, SHUT_WR);
    seen.stop_after = 1;
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    char buf[128];
    read_all(fd, buf, sizeof buf);
    ck_assert_str_eq(buf, "got status\n");
    ck_assert_int_eq(recv(fd, buf, sizeof buf, MSG_DONTWAIT), 0);
    close(fd);
    co_line_server_close(&server);
}
END_TEST

/* An answer deferred by its ticket: the connection waits, a reply under a ticket no connection
 * has is refused, the reply comes when the program sends it and ends the connection. */
static co_line_server_t *deferring_server;
static uint32_t deferred_ticket;

static size_t defer(void *ctx, const char *line, bool cut, char *reply, size_t cap)
{
    (void)ctx;
    (void)line;
    (void)cut;
    (void)reply;
    (void)cap;
    deferred_ticket = co_line_server_defer(deferring_server);
    co_linux_loop_stop(&loop, 0);
    return CO_LINE_DEFERRED;
}

START_TEST(a_deferred_reply_comes_by_its_ticket)
{
    co_line_server_t server;
    co_line_server_config_t config = {.mode = CO_LINE_ONE_REQUEST,
                                      .answer = defer,
                                      .reply = reply_buf,
                                      .reply_cap = sizeof reply_buf};
    const char *call = NULL;
    ck_assert_int_eq(co_line_server_open(&server, &loop, path, &config, &call), CO_LINE_OK);
    deferring_server = &server;
    ck_assert_uint_eq(co_line_server_defer(&server), 0); /* outside an answer */
    int fd = connect_client();
    ck_assert_int_eq(send(fd, "nmt\tstart\t4\n", 13, 0), 13);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_ne(deferred_ticket, 0);
    char buf[128];
    ck_assert_int_eq(recv(fd, buf, sizeof buf, MSG_DONTWAIT), -1);
    ck_assert_int_eq(errno, EAGAIN); /* open, no reply yet */
    ck_assert(!co_line_server_reply(&server, deferred_ticket + 1, "x\n", 2));
    ck_assert(co_line_server_reply(&server, deferred_ticket, "node 4: Operational\n", 20));
    read_all(fd, buf, sizeof buf);
    ck_assert_str_eq(buf, "node 4: Operational\n");
    ck_assert_int_eq(recv(fd, buf, sizeof buf, MSG_DONTWAIT), 0); /* closed */
    ck_assert(!co_line_server_reply(&server, deferred_ticket, "x\n", 2));
    close(fd);
    co_line_server_close(&server);
}
END_TEST

START_TEST(an_overlong_line_is_cut_and_flagged)
{
    co_line_server_t server;
    open_server(&server, CO_LINE_SESSION);
    int fd = connect_client();
    char line[300 + 1];
    memset(line, 'x', 300);
    line[300] = '\n';
    ck_assert_int_eq(send(fd, line, sizeof line, 0), (ssize_t)sizeof line);
    seen.stop_after = 1;
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert(seen.cut);
    ck_assert_uint_eq(seen.longest, CO_LINE_MAX - 1);
    close(fd);
    co_line_server_close(&server);
}
END_TEST

START_TEST(a_stale_socket_is_replaced_a_live_one_and_a_file_are_not)
{
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path);
    int stale = socket(AF_UNIX, SOCK_STREAM, 0);
    ck_assert_int_eq(bind(stale, (struct sockaddr *)&addr, sizeof addr), 0);
    close(stale); /* the file stays, nobody accepts on it */
    co_line_server_t server, second;
    open_server(&server, CO_LINE_SESSION);
    co_line_server_config_t config = {.answer = echo, .reply = reply_buf, .reply_cap = 8};
    const char *call = NULL;
    ck_assert_int_eq(co_line_server_open(&second, &loop, path, &config, &call), CO_LINE_ANSWERED);
    ck_assert_int_eq(errno, EADDRINUSE);
    co_line_server_close(&server);
    int file = open(path, O_CREAT | O_WRONLY, 0600);
    close(file);
    ck_assert_int_eq(co_line_server_open(&second, &loop, path, &config, &call), CO_LINE_FAILED);
    ck_assert_str_eq(call, "bind");
    ck_assert_int_eq(errno, EADDRINUSE);
    struct stat st;
    ck_assert_int_eq(stat(path, &st), 0);
    ck_assert(S_ISREG(st.st_mode));
}
END_TEST

/* Clients that connect and say nothing hold a connection each but hold up no one: a request on
 * another connection is answered meanwhile. The one beyond CO_LINE_CLIENTS is told so and closed.
 * An owner-only socket file has mode 0600. */
START_TEST(silent_clients_block_no_one_and_the_one_too_many_is_told)
{
    co_line_server_t server;
    co_line_server_config_t config = {.mode = CO_LINE_SESSION,
                                      .owner_only = true,
                                      .answer = echo,
                                      .reply = reply_buf,
                                      .reply_cap = sizeof reply_buf};
    const char *call = NULL;
    ck_assert_int_eq(co_line_server_open(&server, &loop, path, &config, &call), CO_LINE_OK);
    struct stat st;
    ck_assert_int_eq(stat(path, &st), 0);
    ck_assert_uint_eq(st.st_mode & 0777u, 0600u);
    int silent[CO_LINE_CLIENTS - 1];
    for (size_t i = 0; i < CO_LINE_CLIENTS - 1; i++)
        silent[i] = connect_client();
    int talker = connect_client();
    ck_assert_int_eq(send(talker, "one\n", 4, 0), 4);
    seen.stop_after = 1;
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    char buf[128];
    read_all(talker, buf, sizeof buf);
    ck_assert_str_eq(buf, "got one\n");
    int extra = connect_client();
    ck_assert_int_eq(send(talker, "two\n", 4, 0), 4);
    seen.stop_after = 2;
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    read_all(talker, buf, sizeof buf);
    ck_assert_str_eq(buf, "got two\n");
    read_all(extra, buf, sizeof buf);
    ck_assert_str_eq(buf, "error: too many control connections\n");
    ck_assert_int_eq(recv(extra, buf, sizeof buf, MSG_DONTWAIT), 0);
    close(extra);
    close(talker);
    for (size_t i = 0; i < CO_LINE_CLIENTS - 1; i++)
        close(silent[i]);
    co_line_server_close(&server);
}
END_TEST

START_TEST(the_client_tells_no_server_and_a_path_too_long)
{
    char reply[64];
    ck_assert_int_eq(co_line_request(path, CO_LINE_SESSION, "state", reply, sizeof reply),
                     CO_LINE_NO_SERVER);
    ck_assert_int_eq(errno, ENOENT);
    char long_path[CO_LINE_PATH_MAX + 8];
    memset(long_path, 'p', sizeof long_path - 1);
    long_path[sizeof long_path - 1] = '\0';
    ck_assert_int_eq(co_line_request(long_path, CO_LINE_ONE_REQUEST, "status", reply, sizeof reply),
                     CO_LINE_TOO_LONG);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("line_socket");
    TCase *tc = tcase_create("server and client");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, a_session_answers_each_line_and_stays_open);
    tcase_add_test(tc, one_request_without_newline_is_answered_and_closed);
    tcase_add_test(tc, a_deferred_reply_comes_by_its_ticket);
    tcase_add_test(tc, an_overlong_line_is_cut_and_flagged);
    tcase_add_test(tc, a_stale_socket_is_replaced_a_live_one_and_a_file_are_not);
    tcase_add_test(tc, silent_clients_block_no_one_and_the_one_too_many_is_told);
    tcase_add_test(tc, the_client_tells_no_server_and_a_path_too_long);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
