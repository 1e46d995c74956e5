/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's status surface: what every emulated drive is doing at a glance. The CAN controller
 * state and the loop's frame counters, then one line per drive, its view (view.h) as the control
 * surface's `state` gives it; written to a file once a second (--status FILE, replaced atomically:
 * a reader never sees half a file) and to the log on SIGUSR1. Both are descriptors in the daemon's
 * loop (a timerfd, a signalfd), so the loop stays tickless without --status. docs/atv312d.md. */
#ifndef ATV312D_STATUS_H
#define ATV312D_STATUS_H

#include "atv312d/view.h"
#include "co_linux/loop.h"

#include <signal.h>
#include <stddef.h>

typedef struct atv312d_status {
    co_linux_loop_t *loop;
    const atv312d_control_node_t *nodes;
    size_t count;
    const char *path; /* NULL: no file, SIGUSR1 only */
    int timer_fd, signal_fd;
    sigset_t old_mask;
} atv312d_status_t;

/* Writes the status text (one line each, newline-terminated) into buf; returns its length. */
size_t atv312d_status_format(const atv312d_status_t *status, char *buf, size_t len);

/* Watches SIGUSR1 and, with a path, a one-second timer that rewrites the file (written once at
 * once, so it exists when this returns). 0, or an exit status after logging why. */
int atv312d_status_open(atv312d_status_t *status, co_linux_loop_t *loop, const char *path,
                        const atv312d_control_node_t *nodes, size_t count);
/* Stops both, restores the signal mask; the file stays (a last picture). Does nothing when
 * not open. */
void atv312d_status_close(atv312d_status_t *status);

#endif
