/* SPDX-License-Identifier: Apache-2.0 */
/* The `candump -L` log format, one frame per line:
 *   (1700000000.123456) vcan0 604#4000100000000000
 * 3 hex digits for an 11-bit identifier, 8 for a 29-bit one (error frames: 8 digits including
 * CAN_ERR_FLAG, as candump prints them), upper-case data bytes, `R` for a remote frame followed by
 * its DLC when non-zero (`704#R`, `704#R1`). Written with 6 fraction digits; read with any number
 * of digits on either side of the point, as canplayer and log2asc read them. */
#ifndef CO_LINUX_CANDUMP_H
#define CO_LINUX_CANDUMP_H

#include <linux/can.h>
#include <net/if.h>
#include <stdbool.h>
#include <stddef.h>
#include <time.h>

/* Longest line including the newline and the terminating NUL: '(', the seconds (any long long
 * co_candump_parse reads: up to 19 digits), '.', 6 fraction digits, ") ", the interface's name (up
 * to IFNAMSIZ - 1 characters), ' ', 8 identifier digits, '#', the data. */
#define CO_CANDUMP_LINE_MAX (1 + 19 + 1 + 6 + 2 + (IFNAMSIZ - 1) + 1 + 8 + 1 + 2 * CAN_MAX_DLEN + 2)

/* Writes one line ending in '\n' into buf (cap >= CO_CANDUMP_LINE_MAX) and returns its length. */
size_t co_candump_format(char *buf, size_t cap, const struct timespec *wall, const char *iface,
                         const struct can_frame *frame);

/* Parses one line (trailing newline allowed). iface gets IFNAMSIZ bytes. Returns false for
 * anything that is not a valid line; the outputs are then unspecified. */
bool co_candump_parse(const char *line, struct timespec *wall, char iface[IFNAMSIZ],
                      struct can_frame *frame);

#endif
