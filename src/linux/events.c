/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/events.h"
#include "co_linux/log.h"

#include <errno.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <unistd.h>

void co_linux_events_init(co_linux_events_t *ev)
{
    memset(ev, 0, sizeof *ev);
    ev->epoll_fd = ev->timer_fd = ev->signal_fd = -1;
    for (int slot = 0; slot < CO_LINUX_EVENTS_MAX; slot++)
        ev->handlers[slot].fd = -1;
    sigprocmask(SIG_SETMASK, NULL, &ev->old_mask);
    ev->timer_armed = CO_TIME_NEVER;
}

static int find_slot(const co_linux_events_t *ev, int fd)
{
    for (int slot = 0; slot < CO_LINUX_EVENTS_MAX; slot++) {
        if (ev->handlers[slot].fd == fd)
            return slot;
    }
    return -1;
}

int co_linux_events_add(co_linux_events_t *ev, int fd, uint32_t events, co_linux_ready_fn fn,
                        void *ctx)
{
    int slot = find_slot(ev, -1);
    if (slot < 0) {
        errno = ENOSPC;
        return -1;
    }
    struct epoll_event event = {.events = events, .data.u32 = (uint32_t)slot};
    if (epoll_ctl(ev->epoll_fd, EPOLL_CTL_ADD, fd, &event) != 0)
        return -1;
    ev->handlers[slot] = (co_linux_handler_t){.fd = fd, .fn = fn, .ctx = ctx};
    return 0;
}

int co_linux_events_modify(co_linux_events_t *ev, int fd, uint32_t events)
{
    struct epoll_event event = {.events = events, .data.u32 = (uint32_t)find_slot(ev, fd)};
    return epoll_ctl(ev->epoll_fd, EPOLL_CTL_MOD, fd, &event);
}

void co_linux_events_remove(co_linux_events_t *ev, int fd)
{
    int slot = find_slot(ev, fd);
    if (slot < 0)
        return;
    epoll_ctl(ev->epoll_fd, EPOLL_CTL_DEL, fd, NULL);
    ev->handlers[slot].fd = -1;
}

static void read_signals(void *ctx, uint32_t events)
{
    co_linux_events_t *ev = ctx;
    (void)events;
    struct signalfd_siginfo info;
    while (read(ev->signal_fd, &info, sizeof info) == (ssize_t)sizeof info) {
        co_log(CO_LOG_INFO, "received %s: stopping", strsignal((int)info.ssi_signo));
        co_linux_events_stop(ev, 0);
    }
}

static int open_signals(co_linux_events_t *ev)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    if (sigprocmask(SIG_BLOCK, &set, &ev->old_mask) != 0)
        return -1;
    ev->signal_fd = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
    if (ev->signal_fd < 0)
        return -1;
    return co_linux_events_add(ev, ev->signal_fd, EPOLLIN, read_signals, ev);
}

const char *co_linux_events_open(co_linux_events_t *ev, co_linux_ready_fn on_timer, void *ctx)
{
    ev->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
    if (ev->epoll_fd < 0)
        return "epoll_create1";
    ev->timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    if (ev->timer_fd < 0 || co_linux_events_add(ev, ev->timer_fd, EPOLLIN, on_timer, ctx) != 0)
        return "timerfd_create";
    if (open_signals(ev) != 0)
        return "signalfd";
    return NULL;
}

/* The timerfd is not read: the timerfd_settime here resets its expiration count, and it always
 * runs after a firing, since the armed deadline has then passed. Were a deadline still due at
 * the armed time, the timer is left as it is and, still readable, brings the loop straight back
 * for it.
 *
 * A deadline that only moved later while the armed one is still ahead is not armed: the timer
 * fires at the earlier time, finds nothing due and is armed then. A watchdog that every frame
 * pushes on (a DeviceNet I/O connection's, at each poll) would otherwise cost a timerfd_settime
 * per frame; this way it costs one early wake-up per armed period. No deadline at all disarms at
 * once, so that an idle loop does not wake up. */
void co_linux_events_arm(co_linux_events_t *ev, co_time_t deadline, co_time_t now)
{
    bool later = deadline != CO_TIME_NEVER && deadline > ev->timer_armed && ev->timer_armed > now;
    if (deadline == ev->timer_armed || later)
        return;
    struct itimerspec its;
    memset(&its, 0, sizeof its);
    if (deadline != CO_TIME_NEVER) {
        its.it_value.tv_sec = (time_t)(deadline / 1000000u);
        its.it_value.tv_nsec = (long)(deadline % 1000000u) * 1000;
        if (its.it_value.tv_sec == 0 && its.it_value.tv_nsec == 0)
            its.it_value.tv_nsec = 1; /* all zero would disarm */
    }
    if (timerfd_settime(ev->timer_fd, TFD_TIMER_ABSTIME, &its, NULL) != 0) {
        co_log(CO_LOG_ERROR, "timerfd_settime: %s", strerror(errno));
        co_linux_events_stop(ev, EX_OSERR);
        return;
    }
    ev->timer_armed = deadline;
}

int co_linux_events_wait(co_linux_events_t *ev, struct epoll_event *fired, int max)
{
    for (;;) {
        int n = epoll_wait(ev->epoll_fd, fired, max, -1);
        if (n >= 0)
            return n;
        if (errno != EINTR) {
            co_log(CO_LOG_ERROR, "epoll_wait: %s", strerror(errno));
            return -1;
        }
    }
}

void co_linux_events_dispatch(co_linux_events_t *ev, const struct epoll_event *fired, int count)
{
    for (int i = 0; i < count; i++) {
        const co_linux_handler_t *handler = &ev->handlers[fired[i].data.u32];
        if (handler->fd >= 0)
            handler->fn(handler->ctx, fired[i].events);
    }
}

void co_linux_events_stop(co_linux_events_t *ev, int status)
{
    ev->running = false;
    ev->exit_status = status;
}

void co_linux_events_close(co_linux_events_t *ev)
{
    int *fds[] = {&ev->timer_fd, &ev->signal_fd, &ev->epoll_fd};
    for (size_t i = 0; i < sizeof fds / sizeof fds[0]; i++) {
        if (*fds[i] >= 0)
            close(*fds[i]);
        *fds[i] = -1;
    }
    sigprocmask(SIG_SETMASK, &ev->old_mask, NULL);
}
