/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's control surface for people testing masters: a UNIX stream socket (--control PATH)
 * in the daemon's epoll loop that takes one command per line and answers one line, "ok ..." or
 * "error: ..." (or a JSON object when the line starts with "json "): inject a fault and remove
 * its cause, set a mains undervoltage, press the keypad's STOP and RUN keys, switch forced local
 * control, load the motor, read the state of a drive (NMT and CiA 402 states, speed, current, the
 * front panel's display and LEDs). `atv312d ctl PATH COMMAND...` is its client.
 * Commands: docs/atv312d.md, "Control surface". */
#ifndef ATV312D_CONTROL_H
#define ATV312D_CONTROL_H

#include "co_linux/line_socket.h"
#include "co_linux/loop.h"
#include "counters.h"
#include "drive/drive.h"
#include "drive/drive_devicenet.h"

#include <stdbool.h>
#include <stddef.h>

/* Longest command line; a longer one is refused. */
#define ATV312D_CONTROL_LINE_MAX CO_LINE_MAX
/* Longest reply line: `state` of 127 drives in JSON, about 450 bytes each, fits. */
#define ATV312D_CONTROL_REPLY_MAX 65536

typedef struct atv312d_control_node {
    uint8_t id;        /* what NODE names: the node-id on CANopen, the MAC ID on DeviceNet */
    const char *model; /* its --model name, "atv312" */
    drive_t *drive;
    const drive_dn_t *devicenet; /* its DeviceNet card; NULL on CANopen */
    co_linux_device_t *device;   /* processed after a command changed the drive; its frame counts */
    const atv312d_counters_t *counters;
} atv312d_control_node_t;

typedef struct atv312d_control {
    co_line_server_t server;
    const atv312d_control_node_t *nodes; /* ascending node-ids */
    size_t count;
} atv312d_control_t;

/* One node's state as `state` reports it: "node 4: nmt ..., fault none" (on DeviceNet "node 25:
 * ms ..., ns ..., supervisor ..., cia402 ...") or its JSON object. */
void atv312d_format_state(const atv312d_control_node_t *node, bool json, char *buf, size_t len);

/* Executes one command line (without its newline) on the nodes; writes the reply line without
 * its newline. Returns true for "ok". */
bool atv312d_control_execute(const atv312d_control_t *control, const char *line, char *reply,
                             size_t reply_len);

/* Binds PATH (a stale socket left by a dead daemon is replaced, any other file is not) and
 * watches it in the loop. 0, or an exit status after logging why. */
int atv312d_control_open(atv312d_control_t *control, co_linux_loop_t *loop, const char *path,
                         const atv312d_control_node_t *nodes, size_t count);
/* Closes the connections and the socket and removes PATH. */
void atv312d_control_close(atv312d_control_t *control);

/* `atv312d ctl PATH [--json] COMMAND...`: sends the command and prints the reply: "ok ..." on
 * stdout, exit 0; "error: ..." as the program's error line on stderr (with --json the reply on
 * stdout), exit CLI_EXIT_REFUSED; EX_USAGE, EX_UNAVAILABLE when no daemon listens, EX_PROTOCOL
 * when it closed without a reply (co_cli.h). */
int atv312d_control_client(int argc, char *const argv[]);

#endif
