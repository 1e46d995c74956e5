/* SPDX-License-Identifier: Apache-2.0 */
/* The status surface (status.h). */
#include "atv312d/status.h"

#include "co_linux/log.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <time.h>
#include <unistd.h>

#define STATUS_PERIOD_S 1
#define STATUS_TEXT_MAX 65536

static bool condition(const co_linux_loop_t *loop, uint16_t emcy_code)
{
    return co_linux_conditions_active(&loop->bus.conditions, emcy_code);
}

size_t atv312d_status_format(const atv312d_status_t *status, char *buf, size_t len)
{
    const co_linux_loop_t *loop = status->loop;
    const co_linux_stats_t *stats = &loop->stats;
    size_t used = (size_t)snprintf(
        buf, len,
        "%s: CAN %s%s; frames received %llu, sent %llu, dropped %llu, lost while down %llu, "
        "error frames %llu, bus-offs %llu; wake-ups %llu, sendmmsg calls %llu\n",
        loop->iface, atv312d_can_state(loop),
        condition(loop, CO_LINUX_EMCY_CAN_OVERRUN) ? ", overrun" : "", stats->rx, stats->tx,
        stats->tx_dropped, stats->down_dropped, stats->error_frames, loop->bus.conditions.bus_offs,
        stats->wakeups, stats->tx_calls);
    for (size_t i = 0; i < status->count && used < len; i++) {
        char line[1024];
        atv312d_format_state(&status->nodes[i], false, line, sizeof line);
        used += (size_t)snprintf(buf + used, len - used, "%s\n", line);
    }
    return used < len ? used : len - 1;
}

/* temp file + rename: a reader sees the old text or the new one, never a mixture. No fsync:
 * the file is a view for people, rewritten every second, not data to keep across a crash. */
static void write_file(const atv312d_status_t *status)
{
    static char text[STATUS_TEXT_MAX];
    size_t len = atv312d_status_format(status, text, sizeof text);
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", status->path);
    FILE *f = fopen(tmp, "we");
    bool ok = f && fwrite(text, 1, len, f) == len;
    if (f && fclose(f) != 0)
        ok = false;
    if (ok && rename(tmp, status->path) == 0)
        return;
    co_log(CO_LOG_WARN, "status %s: cannot be written: %s", status->path, strerror(errno));
    unlink(tmp);
}

static void on_timer(void *ctx, int fd)
{
    uint64_t expirations;
    if (read(fd, &expirations, sizeof expirations) > 0)
        write_file(ctx);
}

/* The status in the log, line by line. */
static void on_signal(void *ctx, int fd)
{
    struct signalfd_siginfo info;
    while (read(fd, &info, sizeof info) == (ssize_t)sizeof info) {
        static char text[STATUS_TEXT_MAX];
        atv312d_status_format(ctx, text, sizeof text);
        char *save;
        for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save))
            co_log(CO_LOG_INFO, "status: %s", line);
    }
}

static int open_failed(atv312d_status_t *status, const char *what)
{
    co_log(CO_LOG_ERROR, "status: %s: %s", what, strerror(errno));
    atv312d_status_close(status);
    return EX_OSERR;
}

static int open_timer(atv312d_status_t *status)
{
    status->timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    struct itimerspec period = {.it_interval.tv_sec = STATUS_PERIOD_S,
                                .it_value.tv_sec = STATUS_PERIOD_S};
    if (status->timer_fd < 0 || timerfd_settime(status->timer_fd, 0, &period, NULL) != 0 ||
        co_linux_loop_watch(status->loop, status->timer_fd, on_timer, status) != 0)
        return open_failed(status, "timer");
    write_file(status);
    return 0;
}

int atv312d_status_open(atv312d_status_t *status, co_linux_loop_t *loop, const char *path,
                        const atv312d_control_node_t *nodes, size_t count)
{
    *status = (atv312d_status_t){.loop = loop,
                                 .nodes = nodes,
                                 .count = count,
                                 .path = path,
                                 .timer_fd = -1,
                                 .signal_fd = -1};
    sigprocmask(SIG_SETMASK, NULL, &status->old_mask);
    sigset_t usr1;
    sigemptyset(&usr1);
    sigaddset(&usr1, SIGUSR1);
    if (sigprocmask(SIG_BLOCK, &usr1, &status->old_mask) != 0)
        return open_failed(status, "sigprocmask");
    status->signal_fd = signalfd(-1, &usr1, SFD_NONBLOCK | SFD_CLOEXEC);
    if (status->signal_fd < 0 ||
        co_linux_loop_watch(loop, status->signal_fd, on_signal, status) != 0)
        return open_failed(status, "signalfd (SIGUSR1)");
    return path ? open_timer(status) : 0;
}

void atv312d_status_close(atv312d_status_t *status)
{
    if (!status->loop)
        return;
    int *fds[] = {&status->timer_fd, &status->signal_fd};
    for (size_t i = 0; i < 2; i++) {
        if (*fds[i] < 0)
            continue;
        co_linux_loop_unwatch(status->loop, *fds[i]);
        close(*fds[i]);
        *fds[i] = -1;
    }
    sigprocmask(SIG_SETMASK, &status->old_mask, NULL);
    status->loop = NULL;
}
