/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/line_socket.h"
#include "co_linux/log.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

static bool socket_address(const char *path, struct sockaddr_un *addr)
{
    memset(addr, 0, sizeof *addr);
    addr->sun_family = AF_UNIX;
    if (strlen(path) >= sizeof addr->sun_path)
        return false;
    memcpy(addr->sun_path, path, strlen(path) + 1);
    return true;
}

/* A connected stream socket, or -1 with errno of the call that failed. */
static int connect_to(const struct sockaddr_un *addr)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || connect(fd, (const struct sockaddr *)addr, sizeof *addr) == 0)
        return fd;
    int err = errno;
    close(fd);
    errno = err;
    return -1;
}

/* ---- the server ---- */

static void drop_client(co_line_server_t *server, co_line_client_t *client)
{
    co_linux_loop_unwatch(server->loop, client->fd);
    close(client->fd);
    client->fd = -1;
}

static co_line_client_t *client_of(co_line_server_t *server, int fd)
{
    for (size_t i = 0; i < CO_LINE_CLIENTS; i++) {
        if (server->clients[i].fd == fd)
            return &server->clients[i];
    }
    return NULL;
}

/* The reply in one non-blocking send: a client that does not read it in time loses it (the loop
 * never waits for a client). */
static void send_reply(co_line_client_t *client, const char *reply, size_t len)
{
    if (send(client->fd, reply, len, MSG_NOSIGNAL | MSG_DONTWAIT) != (ssize_t)len)
        co_log(CO_LOG_WARN, "control: a reply could not be sent whole: %s", strerror(errno));
}

static void answer(co_line_server_t *server, co_line_client_t *client)
{
    const co_line_server_config_t *config = &server->config;
    client->line[client->len] = '\0';
    server->answering = client;
    size_t len =
        config->answer(config->ctx, client->line, client->cut, config->reply, config->reply_cap);
    server->answering = NULL;
    if (len != CO_LINE_DEFERRED)
        send_reply(client, config->reply, len);
    client->len = 0;
    client->cut = false;
}

/* Answers the complete lines in buf; false when the connection is done (one request answered
 * now). A connection whose reply was deferred takes no more requests: what it sends is dropped. */
static bool take_bytes(co_line_server_t *server, co_line_client_t *client, const char *buf,
                       size_t n)
{
    for (size_t i = 0; i < n && client->ticket == 0; i++) {
        if (buf[i] != '\n') {
            if (client->len + 1 < sizeof client->line)
                client->line[client->len++] = buf[i];
            else
                client->cut = true;
            continue;
        }
        answer(server, client);
        if (server->config.mode == CO_LINE_ONE_REQUEST)
            return client->ticket != 0;
    }
    return true;
}

static void on_client(void *ctx, int fd)
{
    co_line_server_t *server = ctx;
    co_line_client_t *client = client_of(server, fd);
    char buf[512];
    ssize_t n = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n < 0 && (errno == EAGAIN || errno == EINTR))
        return;
    bool unterminated = (client->len > 0 || client->cut) && client->ticket == 0;
    if (n == 0 && unterminated && server->config.mode == CO_LINE_ONE_REQUEST)
        answer(server, client); /* a reply deferred now is lost: the client is gone */
    if (n <= 0 || !take_bytes(server, client, buf, (size_t)n))
        drop_client(server, client);
}

static void on_listen(void *ctx, int fd)
{
    co_line_server_t *server = ctx;
    int conn = accept4(fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (conn < 0)
        return;
    co_line_client_t *client = client_of(server, -1);
    if (!client || co_linux_loop_watch(server->loop, conn, on_client, server) != 0) {
        const char *busy = "error: too many control connections\n";
        send(conn, busy, strlen(busy), MSG_NOSIGNAL | MSG_DONTWAIT);
        close(conn);
        return;
    }
    *client = (co_line_client_t){.fd = conn};
}

/* A socket file nobody accepts on is a leftover of a server that died: it is removed. */
static co_line_result_t claim_path(const struct sockaddr_un *addr)
{
    struct stat st;
    if (lstat(addr->sun_path, &st) != 0 || !S_ISSOCK(st.st_mode))
        return CO_LINE_OK;
    int fd = connect_to(addr);
    if (fd >= 0) {
        close(fd);
        errno = EADDRINUSE;
        return CO_LINE_ANSWERED;
    }
    if (errno == ECONNREFUSED)
        unlink(addr->sun_path);
    return CO_LINE_OK;
}

static co_line_result_t listen_on(co_line_server_t *server, const struct sockaddr_un *addr,
                                  const char **call)
{
    server->listen_fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (server->listen_fd < 0) {
        *call = "socket";
        return CO_LINE_FAILED;
    }
    /* The file's mode comes from the umask at bind: 0777 less 0177 is 0600, read and write (the
     * right to connect) for the owner alone. */
    mode_t old_mask = server->config.owner_only ? umask(0177) : 0;
    int bound = bind(server->listen_fd, (const struct sockaddr *)addr, sizeof *addr);
    if (server->config.owner_only)
        umask(old_mask);
    if (bound != 0) {
        *call = "bind";
        return CO_LINE_FAILED;
    }
    if (listen(server->listen_fd, CO_LINE_CLIENTS) != 0 ||
        co_linux_loop_watch(server->loop, server->listen_fd, on_listen, server) != 0) {
        unlink(addr->sun_path);
        *call = "listen";
        return CO_LINE_FAILED;
    }
    return CO_LINE_OK;
}

co_line_result_t co_line_server_open(co_line_server_t *server, co_linux_loop_t *loop,
                                     const char *path, const co_line_server_config_t *config,
                                     const char **call)
{
    memset(server, 0, sizeof *server);
    server->loop = loop;
    server->config = *config;
    server->listen_fd = -1;
    for (size_t i = 0; i < CO_LINE_CLIENTS; i++)
        server->clients[i].fd = -1;
    struct sockaddr_un addr;
    if (!socket_address(path, &addr))
        return CO_LINE_TOO_LONG;
    co_line_result_t result = claim_path(&addr);
    if (result == CO_LINE_OK)
        result = listen_on(server, &addr, call);
    if (result != CO_LINE_OK) {
        int err = errno;
        if (server->listen_fd >= 0)
            close(server->listen_fd);
        server->listen_fd = -1;
        errno = err;
        return result;
    }
    snprintf(server->path, sizeof server->path, "%s", path);
    return CO_LINE_OK;
}

uint32_t co_line_server_defer(co_line_server_t *server)
{
    co_line_client_t *client = server->answering;
    if (client == NULL || server->config.mode != CO_LINE_ONE_REQUEST)
        return 0;
    if (++server->last_ticket == 0)
        server->last_ticket = 1;
    client->ticket = server->last_ticket;
    return client->ticket;
}

bool co_line_server_reply(co_line_server_t *server, uint32_t ticket, const char *reply, size_t len)
{
    for (size_t i = 0; ticket != 0 && i < CO_LINE_CLIENTS; i++) {
        co_line_client_t *client = &server->clients[i];
        if (client->fd < 0 || client->ticket != ticket)
            continue;
        send_reply(client, reply, len);
        drop_client(server, client);
        return true;
    }
    return false;
}

void co_line_server_close(co_line_server_t *server)
{
    if (server->listen_fd < 0)
        return;
    for (size_t i = 0; i < CO_LINE_CLIENTS; i++) {
        if (server->clients[i].fd >= 0)
            drop_client(server, &server->clients[i]);
    }
    co_linux_loop_unwatch(server->loop, server->listen_fd);
    close(server->listen_fd);
    server->listen_fd = -1;
    unlink(server->path);
}

/* ---- the client ---- */

static bool send_all(int fd, const char *text, size_t len)
{
    while (len > 0) {
        ssize_t n = send(fd, text, len, MSG_NOSIGNAL);
        if (n <= 0)
            return false;
        text += n;
        len -= (size_t)n;
    }
    return true;
}

/* Reads until the reply is whole: its newline in a session, the server's close for one request. */
static bool read_reply(int fd, co_line_mode_t mode, char *reply, size_t cap)
{
    size_t got = 0;
    bool whole = false;
    ssize_t n;
    while (!whole && got + 1 < cap && (n = recv(fd, reply + got, cap - 1 - got, 0)) > 0) {
        got += (size_t)n;
        whole = mode == CO_LINE_SESSION && memchr(reply, '\n', got) != NULL;
    }
    reply[got] = '\0';
    return mode == CO_LINE_SESSION ? whole : got > 0;
}

co_line_result_t co_line_request(const char *path, co_line_mode_t mode, const char *line,
                                 char *reply, size_t cap)
{
    struct sockaddr_un addr;
    if (!socket_address(path, &addr))
        return CO_LINE_TOO_LONG;
    int fd = connect_to(&addr);
    if (fd < 0)
        return CO_LINE_NO_SERVER;
    struct timeval timeout = {.tv_sec = CO_LINE_REPLY_TIMEOUT_S};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    bool whole = send_all(fd, line, strlen(line)) && send_all(fd, "\n", 1) &&
                 read_reply(fd, mode, reply, cap);
    close(fd);
    return whole ? CO_LINE_OK : CO_LINE_NO_REPLY;
}
