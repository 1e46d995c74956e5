/* The control socket of comaster run: listening, one request per connection, the client side. */
#include "control.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sysexits.h>
#include <unistd.h>

/* How long a client waits for the reply of a run. */
#define REPLY_TIMEOUT_S 5

/* How long the run waits for the request line of a client that connected: a client that
 * connects and says nothing holds the loop at most this long. */
#define REQUEST_TIMEOUT_MS 200

void comaster_control_default_path(const char *iface, char *path, size_t len)
{
    const char *dir = getenv("XDG_RUNTIME_DIR");
    snprintf(path, len, "%s/comaster-%s.sock", dir && dir[0] ? dir : "/tmp", iface);
}

static bool socket_address(const char *path, struct sockaddr_un *addr)
{
    memset(addr, 0, sizeof *addr);
    addr->sun_family = AF_UNIX;
    if (strlen(path) >= sizeof addr->sun_path)
        return false;
    memcpy(addr->sun_path, path, strlen(path) + 1);
    return true;
}

static bool someone_answers(const struct sockaddr_un *addr)
{
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return false;
    bool answers = connect(fd, (const struct sockaddr *)addr, sizeof *addr) == 0;
    close(fd);
    return answers;
}

/* Reads one line (up to its newline, or the end of the connection) within the timeout. */
static bool read_request(int fd, char *line, size_t cap)
{
    struct timeval tv = {.tv_sec = 0, .tv_usec = REQUEST_TIMEOUT_MS * 1000};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    size_t used = 0;
    while (used + 1 < cap) {
        ssize_t n = read(fd, line + used, cap - 1 - used);
        if (n <= 0)
            break;
        used += (size_t)n;
        if (memchr(line, '\n', used))
            break;
    }
    line[used] = '\0';
    char *newline = strchr(line, '\n');
    if (newline)
        *newline = '\0';
    return newline != NULL || used > 0;
}

static void write_all(int fd, const char *text)
{
    size_t len = strlen(text);
    while (len > 0) {
        ssize_t n = send(fd, text, len, MSG_NOSIGNAL);
        if (n <= 0)
            return;
        text += n;
        len -= (size_t)n;
    }
}

static void serve(void *ctx, int listen_fd)
{
    comaster_control_t *c = ctx;
    int fd = accept4(listen_fd, NULL, NULL, SOCK_CLOEXEC);
    if (fd < 0)
        return;
    char request[COMASTER_CONTROL_LINE_MAX];
    static char reply[COMASTER_CONTROL_REPLY_MAX];
    if (read_request(fd, request, sizeof request)) {
        reply[0] = '\0';
        c->handle(c->ctx, request, reply, sizeof reply);
        write_all(fd, reply);
    }
    close(fd);
}

int comaster_control_open(comaster_control_t *control, co_linux_loop_t *loop, const char *path,
                          comaster_control_fn handle, void *ctx, char *err, size_t err_len)
{
    memset(control, 0, sizeof *control);
    control->fd = -1;
    struct sockaddr_un addr;
    if (!socket_address(path, &addr)) {
        snprintf(err, err_len, "control socket path '%s' is longer than %zu characters", path,
                 sizeof addr.sun_path - 1);
        return EX_USAGE;
    }
    if (someone_answers(&addr)) {
        snprintf(err, err_len,
                 "another comaster run answers on %s: stop it, or give --control PATH", path);
        return EX_UNAVAILABLE;
    }
    unlink(path); /* the socket file of a run that ended */
    control->fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    mode_t old = umask(0077); /* the process image is the user's: no one else may set it */
    bool bound = control->fd >= 0 &&
                 bind(control->fd, (const struct sockaddr *)&addr, sizeof addr) == 0 &&
                 listen(control->fd, 8) == 0;
    umask(old);
    if (!bound || co_linux_loop_watch(loop, control->fd, serve, control) != 0) {
        snprintf(err, err_len, "cannot listen on %s: %s", path, strerror(errno));
        if (control->fd >= 0)
            close(control->fd);
        control->fd = -1;
        return EX_CANTCREAT;
    }
    snprintf(control->path, sizeof control->path, "%s", path);
    control->loop = loop;
    control->handle = handle;
    control->ctx = ctx;
    return 0;
}

void comaster_control_close(comaster_control_t *control)
{
    if (control->fd < 0)
        return;
    co_linux_loop_unwatch(control->loop, control->fd);
    close(control->fd);
    unlink(control->path);
    control->fd = -1;
}

int comaster_control_request(const char *path, const char *request, char *reply, size_t cap,
                             char *err, size_t err_len)
{
    struct sockaddr_un addr;
    if (!socket_address(path, &addr)) {
        snprintf(err, err_len, "control socket path '%s' is too long", path);
        return EX_USAGE;
    }
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || connect(fd, (const struct sockaddr *)&addr, sizeof addr) != 0) {
        snprintf(err, err_len,
                 "no comaster run answers on %s (%s): start one with comaster run NETWORK, or "
                 "give its --control PATH",
                 path, strerror(errno));
        if (fd >= 0)
            close(fd);
        return EX_UNAVAILABLE;
    }
    struct timeval tv = {.tv_sec = REPLY_TIMEOUT_S};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    write_all(fd, request);
    write_all(fd, "\n");
    size_t used = 0;
    ssize_t n;
    while (used + 1 < cap && (n = read(fd, reply + used, cap - 1 - used)) > 0)
        used += (size_t)n;
    reply[used] = '\0';
    close(fd);
    if (used == 0) {
        snprintf(err, err_len, "the comaster run on %s closed without a reply", path);
        return EX_PROTOCOL;
    }
    return 0;
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
