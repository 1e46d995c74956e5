/* SPDX-License-Identifier: Apache-2.0 */
/* The control socket of comaster run: a UNIX stream socket on which another comaster (set, get,
 * status) sends one request line and reads the reply until the run closes the connection. The
 * requests and their replies are in docs/comaster.md "run and its control socket". */
#ifndef COMASTER_RUN_CONTROL_H
#define COMASTER_RUN_CONTROL_H

#include "co_linux/line_socket.h"
#include "co_linux/loop.h"
#include "comaster/comaster.h"
#include "comaster/network.h" /* COMASTER_CONTROL_PATH_MAX, the callers' path buffers */

#include <stdbool.h>
#include <stddef.h>

#define COMASTER_CONTROL_LINE_MAX CO_LINE_MAX

/* What a process image address is (D-IMAGE-ADDRESS), for the client's usage error and the run's
 * refusal alike; a printf argument, not a format. */
#define COMASTER_MARKER_SYNTAX                                                                     \
    "%IB/%IW/%ID (inputs) or %QB/%QW/%QD (outputs), bytes 2000..2511, words even, double words "   \
    "multiples of 4"
#define COMASTER_CONTROL_REPLY_MAX                                                                 \
    65536u /* status --json of 127 slaves, 64-byte names, every field at its longest */

/* Answers one request line (without its newline) into `reply` (cap bytes, newline-terminated
 * lines; an error is one line "error: ...", an SDO abort "abort: ...", no answer in time
 * "timeout: ..."), or takes a ticket (comaster_control_defer) and returns true: the reply then
 * comes by comaster_control_reply. */
typedef bool (*comaster_control_fn)(void *ctx, const char *request, char *reply, size_t cap);

typedef struct comaster_control {
    co_line_server_t server;
    comaster_control_fn handle;
    void *ctx;
} comaster_control_t;

/* The default path: $XDG_RUNTIME_DIR (else /tmp) /comaster-IFACE.sock. */
void comaster_control_default_path(const char *iface, char *path, size_t len);

/* Listens on `path` (a stale socket file of a run that ended is replaced; one a run still
 * answers on is not) and serves requests on the loop. Returns 0, or the exit status after a
 * one-line message in err. */
int comaster_control_open(comaster_control_t *control, co_linux_loop_t *loop, const char *path,
                          comaster_control_fn handle, void *ctx, char *err, size_t err_len);
/* Within the answer function: a ticket for the connection of the request, answered later. */
uint32_t comaster_control_defer(comaster_control_t *control);
/* The reply to the request of `ticket`, which ends its connection; nothing when it is gone. */
void comaster_control_reply(comaster_control_t *control, uint32_t ticket, const char *reply);

/* Stops serving, closes and removes the socket. */
void comaster_control_close(comaster_control_t *control);

/* The client: sends `request` to the run listening on `path` and reads its reply (at most cap - 1
 * bytes, NUL-terminated). Returns 0, or the exit status after a one-line message in err. */
int comaster_control_request(const char *path, const char *request, char *reply, size_t cap,
                             char *err, size_t err_len);

/* The longest a request through a run may ask the run to wait (below the client's own wait for
 * the reply, CO_LINE_REPLY_TIMEOUT_S). */
#define COMASTER_CONTROL_WAIT_MAX_MS 4000u

/* Sends the request of `count` fields (joined by tabs, "json" first with --json) to the run on
 * `path` (NULL: the default path of the interface) and prints its reply: 0; a reply
 * "error: ..." (the run refused) or "abort: ..." (the SDO abort) exits 1, "timeout: ..." 2, each
 * with the message as comaster's error. */
int comaster_control_forward(comaster_options_t *opts, const char *path, const char *const *fields,
                             size_t count);

/* Takes "--run" (the run on the interface, at its default socket) or "--control PATH" out of the
 * argv of nmt, read and write: *via_run tells that either was given (the command then goes
 * through the run rather than on the bus itself), *path the socket (NULL: the default). False
 * when --control has no value. */
bool comaster_run_option(int *argc, char **argv, bool *via_run, const char **path);

/* Takes "--control PATH" out of a command's argv (the common parser does not know it) into *path
 * (left as it is when absent). False when the option has no value. */
bool comaster_control_take_option(int *argc, char **argv, const char **path);

#endif
