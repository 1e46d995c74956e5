/* SPDX-License-Identifier: Apache-2.0 */
/* The control socket of comaster run: its requests on the runtime's line socket, one per
 * connection, and the client side. */
#include "comaster/run_control.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

void comaster_control_default_path(const char *iface, char *path, size_t len)
{
    const char *dir = getenv("XDG_RUNTIME_DIR");
    snprintf(path, len, "%s/comaster-%s.sock", dir && dir[0] ? dir : "/tmp", iface);
}

/* A request longer than the line is answered from its beginning, as the run always did. */
static size_t answer(void *ctx, const char *line, bool cut, char *reply, size_t cap)
{
    const comaster_control_t *c = ctx;
    (void)cut;
    reply[0] = '\0';
    if (c->handle(c->ctx, line, reply, cap))
        return CO_LINE_DEFERRED;
    return strlen(reply);
}

uint32_t comaster_control_defer(comaster_control_t *control)
{
    return co_line_server_defer(&control->server);
}

void comaster_control_reply(comaster_control_t *control, uint32_t ticket, const char *reply)
{
    co_line_server_reply(&control->server, ticket, reply, strlen(reply));
}

int comaster_control_open(comaster_control_t *control, co_linux_loop_t *loop, const char *path,
                          comaster_control_fn handle, void *ctx, char *err, size_t err_len)
{
    static char reply[COMASTER_CONTROL_REPLY_MAX];
    control->handle = handle;
    control->ctx = ctx;
    co_line_server_config_t config = {.mode = CO_LINE_ONE_REQUEST,
                                      .owner_only = true, /* the process image is the user's */
                                      .answer = answer,
                                      .ctx = control,
                                      .reply = reply,
                                      .reply_cap = sizeof reply};
    const char *call;
    switch (co_line_server_open(&control->server, loop, path, &config, &call)) {
    case CO_LINE_OK:
        return 0;
    case CO_LINE_TOO_LONG:
        snprintf(err, err_len, "control socket path '%s' is longer than %zu characters", path,
                 CO_LINE_PATH_MAX - 1);
        return EX_USAGE;
    case CO_LINE_ANSWERED:
        snprintf(err, err_len,
                 "another comaster run answers on %s: stop it, or give --control PATH", path);
        return EX_CANTCREAT;
    default:
        snprintf(err, err_len, "cannot listen on %s: %s", path, strerror(errno));
        return EX_CANTCREAT;
    }
}

void comaster_control_close(comaster_control_t *control)
{
    co_line_server_close(&control->server);
}

int comaster_control_request(const char *path, const char *request, char *reply, size_t cap,
                             char *err, size_t err_len)
{
    switch (co_line_request(path, CO_LINE_ONE_REQUEST, request, reply, cap)) {
    case CO_LINE_OK:
        return 0;
    case CO_LINE_TOO_LONG:
        snprintf(err, err_len, "control socket path '%s' is too long", path);
        return EX_USAGE;
    case CO_LINE_NO_SERVER:
        snprintf(err, err_len,
                 "no comaster run answers on %s (%s): start one with comaster run NETWORK, or "
                 "give its --control PATH",
                 path, strerror(errno));
        return EX_UNAVAILABLE;
    default:
        snprintf(err, err_len, "the comaster run on %s closed without a reply", path);
        return EX_PROTOCOL;
    }
}

bool comaster_control_take_option(int *argc, char **argv, const char **path)
{
    for (int i = 1; i < *argc; i++) {
        if (strcmp(argv[i], "--control") != 0)
            continue;
        if (i + 1 >= *argc || argv[i + 1][0] == '\0')
            return false;
        *path = argv[i + 1];
        memmove(&argv[i], &argv[i + 2], (size_t)(*argc - i - 2) * sizeof *argv);
        *argc -= 2;
        return true;
    }
    return true;
}
