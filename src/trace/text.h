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

#endif
