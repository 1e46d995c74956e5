/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's control surface for people testing masters: a UNIX stream socket (--control PATH)
 * in the daemon's epoll loop that takes one command per line and answers each with one line, the
 * reply of the command interpreter (control_commands.h). `atv312d ctl PATH COMMAND...` is its
 * client. docs/atv312d.md, "Control surface". */
#ifndef ATV312D_CONTROL_SOCKET_H
#define ATV312D_CONTROL_SOCKET_H

#include "atv312d/control_commands.h"
#include "co_linux/line_socket.h"
#include "co_linux/loop.h"

typedef struct atv312d_control_socket {
    co_line_server_t server;
    const atv312d_control_t *control; /* the drives its commands act on */
} atv312d_control_socket_t;

/* Binds PATH (a stale socket left by a dead daemon is replaced, any other file is not) and
 * watches it in the loop. 0, or an exit status after logging why. */
int atv312d_control_open(atv312d_control_socket_t *control_socket, co_linux_loop_t *loop,
                         const char *path, const atv312d_control_t *control);
/* Closes the connections and the socket and removes PATH. */
void atv312d_control_close(atv312d_control_socket_t *control_socket);

/* `atv312d ctl PATH [--json] COMMAND...`: sends the command and prints the reply: "ok ..." on
 * stdout, exit 0; "error: ..." as the program's error line on stderr (with --json the reply on
 * stdout), exit CLI_EXIT_REFUSED; EX_USAGE, EX_UNAVAILABLE when no daemon listens, EX_PROTOCOL
 * when it closed without a reply (cli/co_cli.h). */
int atv312d_control_client(int argc, char *const argv[]);

#endif
