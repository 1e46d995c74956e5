/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's control commands, the one interpreter behind the control socket (`atv312d ctl`,
 * control_socket.h) and the web's POST /api/command (http.h): one command line in, one reply out,
 * "ok ..." or "error: ..." (or a JSON object when the line starts with "json "). They inject a
 * fault and remove its cause, set a mains undervoltage, press the keypad's STOP and RUN keys,
 * switch forced local control, load the motor, set the logic and analogue inputs, set an I/O
 * node's terminals and read or write a PLC300's markers (the plain nodes' commands), and read
 * the state of the nodes (view.h). Commands: docs/atv312d.md, "Control surface". */
#ifndef ATV312D_CONTROL_COMMANDS_H
#define ATV312D_CONTROL_COMMANDS_H

#include "atv312d/view.h"
#include "co_linux/line_socket.h"

#include <stdbool.h>
#include <stddef.h>

/* Longest command line; a longer one is refused. */
#define ATV312D_CONTROL_LINE_MAX CO_LINE_MAX
/* What starts a command line whose reply is JSON. */
#define ATV312D_CONTROL_JSON_PREFIX "json "
/* Longest reply line: `state` of 127 drives in JSON, about 450 bytes each, fits. */
#define ATV312D_CONTROL_REPLY_MAX 65536

/* The drives the commands act on. */
typedef struct atv312d_control {
    const atv312d_control_node_t *nodes; /* ascending node-ids */
    size_t count;
} atv312d_control_t;

/* Executes one command line (without its newline) on the nodes; writes the reply line without
 * its newline. Returns true for "ok". */
bool atv312d_control_execute(const atv312d_control_t *control, const char *line, char *reply,
                             size_t reply_len);

#endif
