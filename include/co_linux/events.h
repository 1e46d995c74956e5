/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime's event loop, after Redis's ae.c: one epoll instance, the descriptors it watches
 * with a function each to run when one is ready, a timerfd armed to one absolute deadline on
 * CLOCK_MONOTONIC, and a signalfd that stops the loop on SIGINT or SIGTERM. It knows nothing of
 * CAN: the bus, its link monitor and the application's descriptors are handlers like any other.
 */
#ifndef CO_LINUX_EVENTS_H
#define CO_LINUX_EVENTS_H

#include "co/co_types.h"

#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <sys/epoll.h>

/* Descriptors watched at once: the timer, the signals, the CAN socket, the link monitor and the
 * application's CO_LINUX_WATCH_MAX (co_linux/loop.h). */
#define CO_LINUX_EVENTS_MAX 20

/* Runs when a watched descriptor is ready; events are the epoll events it reported. */
typedef void (*co_linux_ready_fn)(void *ctx, uint32_t events);

typedef struct co_linux_handler {
    int fd; /* -1: free */
    co_linux_ready_fn fn;
    void *ctx;
} co_linux_handler_t;

typedef struct co_linux_events {
    int epoll_fd, timer_fd, signal_fd;
    sigset_t old_mask;     /* the signal mask before co_linux_events_open blocked SIGINT, SIGTERM */
    co_time_t timer_armed; /* the deadline the timerfd holds; CO_TIME_NEVER: disarmed */
    bool running;
    int exit_status;
    co_linux_handler_t handlers[CO_LINUX_EVENTS_MAX]; /* epoll_event.data.u32 is the slot */
} co_linux_events_t;

/* Nothing open, the signal mask saved: co_linux_events_close is safe from here on. */
void co_linux_events_init(co_linux_events_t *ev);

/* Creates the epoll instance, the timer (on_timer runs when its deadline passes) and the signalfd;
 * SIGINT and SIGTERM are blocked from here on. NULL, or the system call that failed (errno set). */
const char *co_linux_events_open(co_linux_events_t *ev, co_linux_ready_fn on_timer, void *ctx);

/* Watches fd for `events`; 0, or -1 with errno set (ENOSPC: CO_LINUX_EVENTS_MAX are watched). */
int co_linux_events_add(co_linux_events_t *ev, int fd, uint32_t events, co_linux_ready_fn fn,
                        void *ctx);
/* Changes the events a watched fd waits for; 0, or -1 with errno set. */
int co_linux_events_modify(co_linux_events_t *ev, int fd, uint32_t events);
/* Stops watching fd (before its owner closes it); may be called from its handler. */
void co_linux_events_remove(co_linux_events_t *ev, int fd);

/* Arms the timer to `deadline` (CO_TIME_NEVER disarms it) unless it holds it already, or holds
 * an earlier one that is still ahead of `now` (it fires early, and is armed then); a failure is
 * logged and stops the loop with EX_OSERR. */
void co_linux_events_arm(co_linux_events_t *ev, co_time_t deadline, co_time_t now);

/* Sleeps until a descriptor is ready (no timeout); the number of ready ones in fired (at most
 * max), or -1 after logging why epoll_wait failed. */
int co_linux_events_wait(co_linux_events_t *ev, struct epoll_event *fired, int max);
/* Runs the handlers of the descriptors co_linux_events_wait found ready, skipping one removed
 * since. */
void co_linux_events_dispatch(co_linux_events_t *ev, const struct epoll_event *fired, int count);

/* Ends the loop with `status` after the current wake-up. */
void co_linux_events_stop(co_linux_events_t *ev, int status);

/* Closes the epoll instance, the timer and the signalfd, and restores the signal mask. */
void co_linux_events_close(co_linux_events_t *ev);

#endif
