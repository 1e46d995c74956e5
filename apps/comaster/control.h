/* The control socket of comaster run: a UNIX stream socket on which another comaster (set, get,
 * status) sends one request line and reads the reply until the run closes the connection. The
 * requests and their replies are in docs/comaster.md "run and its control socket". */
#ifndef COMASTER_CONTROL_H
#define COMASTER_CONTROL_H

#include "co_linux/line_socket.h"
#include "co_linux/loop.h"
#include "network.h" /* COMASTER_CONTROL_PATH_MAX, the callers' path buffers */

#include <stdbool.h>
#include <stddef.h>

#define COMASTER_CONTROL_LINE_MAX CO_LINE_MAX
#define COMASTER_CONTROL_REPLY_MAX 8192u

/* Answers one request line (without its newline) into `reply` (cap bytes, newline-terminated
 * lines; an error is one line "error: ..."). */
typedef void (*comaster_control_fn)(void *ctx, const char *request, char *reply, size_t cap);

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
/* Stops serving, closes and removes the socket. */
void comaster_control_close(comaster_control_t *control);

/* The client: sends `request` to the run listening on `path` and reads its reply (at most cap - 1
 * bytes, NUL-terminated). Returns 0, or the exit status after a one-line message in err. */
int comaster_control_request(const char *path, const char *request, char *reply, size_t cap,
                             char *err, size_t err_len);

/* Takes "--control PATH" out of a command's argv (the common parser does not know it) into *path
 * (left as it is when absent). False when the option has no value. */
bool comaster_control_take_option(int *argc, char **argv, const char **path);

#endif
