/* SPDX-License-Identifier: Apache-2.0 */
/* systemd's service notification (sd_notify(3)) without libsystemd: the daemon tells a service
 * manager that it is ready, what it is doing and that it is stopping. docs/atv312d.md, "systemd".
 */
#ifndef ATV312D_NOTIFY_H
#define ATV312D_NOTIFY_H

#include <stdbool.h>

/* Sends `state` (newline-separated KEY=VALUE assignments, "READY=1\nSTATUS=...") as one datagram
 * to the AF_UNIX socket $NOTIFY_SOCKET names: a path, or an abstract name when it starts with '@'.
 * Without $NOTIFY_SOCKET (not under a service manager) nothing is sent and the result is true;
 * false, with errno set, when the socket cannot be reached. */
bool atv312d_notify(const char *state);

#endif
