/* SPDX-License-Identifier: Apache-2.0 */
/* The control socket (control_socket.h): its session on the runtime's line socket in the
 * daemon's loop, each line answered by the command interpreter, and the `atv312d ctl` client. */
#include "atv312d/control_socket.h"

#include "cli/co_cli.h"
#include "co_linux/log.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sysexits.h>

static size_t answer(void *ctx, const char *line, bool cut, char *reply, size_t cap)
{
    const atv312d_control_socket_t *control_socket = ctx;
    if (cut)
        snprintf(reply, cap, "error: command longer than %d characters",
                 ATV312D_CONTROL_LINE_MAX - 1);
    else
        atv312d_control_execute(control_socket->control, line, reply, cap - 1);
    size_t len = strlen(reply);
    reply[len++] = '\n';
    return len;
}

int atv312d_control_open(atv312d_control_socket_t *control_socket, co_linux_loop_t *loop,
                         const char *path, const atv312d_control_t *control)
{
    static char reply[ATV312D_CONTROL_REPLY_MAX];
    control_socket->control = control;
    co_line_server_config_t config = {.mode = CO_LINE_SESSION,
                                      .answer = answer,
                                      .ctx = control_socket,
                                      .reply = reply,
                                      .reply_cap = sizeof reply};
    const char *call = NULL;
    co_line_result_t result =
        co_line_server_open(&control_socket->server, loop, path, &config, &call);
    if (result == CO_LINE_TOO_LONG)
        return cli_fail(NULL, EX_USAGE,
                        "--control %s: the path is longer than %zu characters: give a shorter one",
                        path, CO_LINE_PATH_MAX - 1);
    if (result != CO_LINE_OK) {
        /* Another daemon answers there, or the path is a file of another kind. */
        if (errno == EADDRINUSE)
            call = "bind (the path exists: another daemon's socket or a file)";
        co_log(CO_LOG_ERROR, "control socket %s: %s: %s", path, call, strerror(errno));
        return EX_CANTCREAT;
    }
    co_log(CO_LOG_INFO, "control socket %s: listening (atv312d ctl %s state)", path, path);
    return 0;
}

void atv312d_control_close(atv312d_control_socket_t *control_socket)
{
    co_line_server_close(&control_socket->server);
}

/* ---- the client ---- */

static int client_usage(void)
{
    return cli_fail(NULL, EX_USAGE,
                    "ctl: give the daemon's socket and a command: atv312d ctl PATH [--json] "
                    "COMMAND..., e.g. atv312d ctl /tmp/atv312d.sock fault 4 OHF");
}

int atv312d_control_client(int argc, char *const argv[])
{
    if (argc < 2)
        return client_usage();
    const char *path = argv[0];
    char line[ATV312D_CONTROL_LINE_MAX + sizeof ATV312D_CONTROL_JSON_PREFIX];
    size_t used = 0;
    int first = 1;
    if (strcmp(argv[1], "--json") == 0) {
        used = (size_t)snprintf(line, sizeof line, "%s", ATV312D_CONTROL_JSON_PREFIX);
        first = 2;
    }
    if (first >= argc)
        return client_usage();
    for (int i = first; i < argc && used < sizeof line; i++)
        used += (size_t)snprintf(line + used, sizeof line - used, "%s%s", i > first ? " " : "",
                                 argv[i]);
    if (used + 1 >= sizeof line || strchr(line, '\n'))
        return cli_fail(NULL, EX_USAGE,
                        "ctl: the command has a newline or is longer than %d characters: give "
                        "one command of one line",
                        ATV312D_CONTROL_LINE_MAX - 1);
    static char reply[ATV312D_CONTROL_REPLY_MAX];
    switch (co_line_request(path, CO_LINE_SESSION, line, reply, sizeof reply)) {
    case CO_LINE_OK:
        break;
    case CO_LINE_TOO_LONG:
        return cli_fail(NULL, EX_USAGE,
                        "ctl: the path %s is longer than %zu characters: give a shorter one", path,
                        CO_LINE_PATH_MAX - 1);
    case CO_LINE_NO_SERVER:
        return cli_fail(NULL, EX_UNAVAILABLE,
                        "ctl: cannot connect to %s: %s: is atv312d running with --control %s?",
                        path, strerror(errno), path);
    default:
        return cli_fail(NULL, EX_PROTOCOL,
                        "ctl: no reply from %s: the daemon closed the connection", path);
    }
    bool json = first == 2;
    bool ok = strncmp(reply, "ok", 2) == 0 || strncmp(reply, "{\"ok\":true", 10) == 0;
    if (ok || json) {
        fputs(reply, stdout);
        return ok ? 0 : CLI_EXIT_REFUSED;
    }
    /* The daemon refused: "error: WHY" is the program's error. */
    const char *why = strncmp(reply, "error: ", 7) == 0 ? reply + 7 : reply;
    return cli_fail(NULL, CLI_EXIT_REFUSED, "%.*s", (int)strcspn(why, "\n"), why);
}
