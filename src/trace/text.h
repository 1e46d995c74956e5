/* SPDX-License-Identifier: Apache-2.0 */
/* The line a decoder writes: a bounded text buffer and the ways of putting bytes and values in
 * it that the CANopen and DeviceNet decoders share, and the meaning of a CAN error frame. */
#ifndef COTRACE_TEXT_H
#define COTRACE_TEXT_H

#include <linux/can.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct text {
    char *buf;
    size_t cap, len;
} text_t;

/* Appends to the line; what does not fit is cut (the buffer stays NUL-terminated). */
void say(text_t *t, const char *format, ...) __attribute__((format(printf, 2, 3)));
/* "01 02 03": upper-case hex, one space apart. */
void say_bytes(text_t *t, const uint8_t *data, size_t len);
/* A value: in quotes when every byte is printable, else its bytes with the little-endian number
 * in parentheses for 1..4 bytes; " ..." when only len of total bytes are shown. */
void say_value(text_t *t, const uint8_t *data, size_t len, size_t total);
/* "CAN error frame: <classes>" with the controller's problems. */
void say_error_frame(text_t *t, const struct can_frame *f);
/* Starts the line of frame f in out (cap bytes), in *t. An error frame, or a 29-bit frame that
 * `protocol` (CANopen, DeviceNet) does not have, is said whole: false then, and for cap 0; true
 * for a standard frame, which the decoder goes on with. */
bool say_start(text_t *t, char *out, size_t cap, const struct can_frame *f, const char *protocol);

#endif
