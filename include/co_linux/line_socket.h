/* SPDX-License-Identifier: Apache-2.0 */
/* A line-socket server and client for the programs' control sockets: a UNIX stream socket on a
 * path, requests one line each, replies written as the program formats them. The server runs in
 * a co_linux loop and never waits for a client; the programs keep only their commands and their
 * replies. Two ways to talk: a session (many requests per connection, one reply line each, as
 * `atv312d ctl`) or one request (the reply lines until the server closes, as `comaster set`). */
#ifndef CO_LINUX_LINE_SOCKET_H
#define CO_LINUX_LINE_SOCKET_H

#include "co_linux/loop.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/un.h>

/* Longest request line with its terminating NUL; a longer line is cut (co_line_answer_fn). */
#define CO_LINE_MAX 256
/* Connections served at once; one more is accepted, told "error: too many control connections"
 * and closed. */
#define CO_LINE_CLIENTS 8
/* How long a client waits for a reply. */
#define CO_LINE_REPLY_TIMEOUT_S 5
/* Longest path with its terminating NUL (sockaddr_un.sun_path). */
#define CO_LINE_PATH_MAX sizeof(((struct sockaddr_un *)0)->sun_path)

typedef enum co_line_mode {
    CO_LINE_SESSION,    /* requests until the client closes; a reply ends with its newline */
    CO_LINE_ONE_REQUEST /* one request; the reply ends when the server closes the connection,
                         * and a last line without newline is a request too */
} co_line_mode_t;

typedef enum co_line_result {
    CO_LINE_OK,
    CO_LINE_TOO_LONG,  /* the path does not fit in CO_LINE_PATH_MAX */
    CO_LINE_ANSWERED,  /* server: another server answers on the path (errno EADDRINUSE) */
    CO_LINE_FAILED,    /* server: a system call failed (errno set; see its name) */
    CO_LINE_NO_SERVER, /* client: nobody accepts on the path (errno set) */
    CO_LINE_NO_REPLY   /* client: the connection ended or timed out before a whole reply */
} co_line_result_t;

/* Returned by an answer function that replies later (co_line_server_defer). */
#define CO_LINE_DEFERRED SIZE_MAX

/* Writes the reply to one request line (without its newline) into reply (cap bytes) and returns
 * its length; cut: the line was longer than CO_LINE_MAX - 1 and holds its beginning only. Or,
 * in CO_LINE_ONE_REQUEST mode, takes a ticket from co_line_server_defer and returns
 * CO_LINE_DEFERRED: the connection then waits for co_line_server_reply. */
typedef size_t (*co_line_answer_fn)(void *ctx, const char *line, bool cut, char *reply, size_t cap);

typedef struct co_line_server_config {
    co_line_mode_t mode;
    bool owner_only; /* the socket file gets mode 0600 */
    co_line_answer_fn answer;
    void *ctx;
    char *reply; /* the buffer replies are written into */
    size_t reply_cap;
} co_line_server_config_t;

typedef struct co_line_client {
    int fd; /* -1: free */
    char line[CO_LINE_MAX];
    size_t len;
    bool cut;        /* the current line passed CO_LINE_MAX - 1 characters */
    uint32_t ticket; /* not 0: its reply was deferred under this ticket */
} co_line_client_t;

typedef struct co_line_server {
    co_linux_loop_t *loop;
    co_line_server_config_t config;
    int listen_fd;
    char path[CO_LINE_PATH_MAX];
    co_line_client_t clients[CO_LINE_CLIENTS];
    co_line_client_t *answering; /* the client whose line the answer function has */
    uint32_t last_ticket;
} co_line_server_t;

/* Listens on path in the loop: a socket file nobody accepts on (left by a program that died) is
 * replaced, one a server answers on is not (CO_LINE_ANSWERED). On CO_LINE_FAILED *call names the
 * system call. */
co_line_result_t co_line_server_open(co_line_server_t *server, co_linux_loop_t *loop,
                                     const char *path, const co_line_server_config_t *config,
                                     const char **call);
/* Called by the answer function of a CO_LINE_ONE_REQUEST server: a ticket (never 0) for the
 * connection of the line being answered, which stays open for co_line_server_reply. 0 outside an
 * answer or in a session. */
uint32_t co_line_server_defer(co_line_server_t *server);
/* Sends the reply deferred under `ticket` and closes its connection. False when the client has
 * gone (its ticket with it). */
bool co_line_server_reply(co_line_server_t *server, uint32_t ticket, const char *reply, size_t len);

/* Closes the connections and the socket and removes the path. */
void co_line_server_close(co_line_server_t *server);

/* Sends one request line (without newline) to the server on path and reads its reply into reply
 * (at most cap - 1 bytes, NUL-terminated): up to its newline in a session, until the server
 * closes for one request. */
co_line_result_t co_line_request(const char *path, co_line_mode_t mode, const char *line,
                                 char *reply, size_t cap);

#endif
