/* SPDX-License-Identifier: Apache-2.0 */
/* The serial-line CAN protocol (slcan, the Lawicel CAN232/CANUSB ASCII protocol) that Linux's
 * `slcan` line discipline and can-utils' `slcand` speak: CAN frames as text lines over a UART,
 * so that a board without a CAN controller, or an emulated one, is an ordinary SocketCAN
 * interface on the host (docs/porting.md, "The firmware on an emulated board").
 *
 * Lines end in CR (0x0D). Frames: `tIIILDD..` (11-bit), `TIIIIIIIILDD..` (29-bit), `rIIIL` and
 * `RIIIIIIIIL` (remote), identifier and data in hexadecimal, L the DLC 0..8. Commands: `O`
 * (open the channel), `C` (close it), `Sn` (bit rate n, 0..8 = 10 kbit/s..1 Mbit/s). A device
 * answers a command with CR (done) or BEL (0x07, refused), and a line it cannot read with BEL.
 *
 * Portable like the core: no OS headers, no globals, no allocation; it uses only the core's frame
 * type (co/co_types.h). */
#ifndef SLCAN_H
#define SLCAN_H

#include "co/co_types.h"

#include <stddef.h>
#include <stdint.h>

/* The longest line, CR included: 'T', 8 identifier digits, the DLC, 16 data digits, CR. */
#define SLCAN_LINE_MAX 27u

#define SLCAN_CR '\r'
#define SLCAN_BEL '\a'

/* The highest bit rate index of `Sn`: S0..S8 are 10, 20, 50, 100, 125, 250, 500, 800 and 1000
 * kbit/s. */
#define SLCAN_BITRATE_MAX 8u

/* Writes frame as one line, CR included, into line (SLCAN_LINE_MAX bytes, not NUL-terminated);
 * returns its length, or 0 for a frame the protocol cannot carry (DLC over 8, an 11-bit
 * identifier over 7FFh, a 29-bit one over 1FFFFFFFh), of which nothing is written. */
size_t slcan_encode(const co_frame_t *frame, char *line);

/* What a complete line asks for. */
typedef enum slcan_kind {
    SLCAN_NOTHING, /* no complete line yet, or an empty one (a host flushing the line: no answer) */
    SLCAN_FRAME,   /* a frame, in slcan_message_t.frame */
    SLCAN_OPEN,    /* O */
    SLCAN_CLOSE,   /* C */
    SLCAN_BITRATE, /* Sn, the index in slcan_message_t.bitrate */
    SLCAN_INVALID  /* a malformed, overlong or unknown line: answer SLCAN_BEL */
} slcan_kind_t;

typedef struct slcan_message {
    slcan_kind_t kind;
    co_frame_t frame;
    uint8_t bitrate;
} slcan_message_t;

/* Reads one line (without its CR). A line that is not exactly one of the forms above is
 * SLCAN_INVALID, and message then holds nothing else: no half-decoded frame is left behind. */
slcan_message_t slcan_decode(const char *line, size_t len);

/* Gathers a line from the bytes of the serial link, one at a time (an interrupt handler's
 * work). A line longer than SLCAN_LINE_MAX is dropped up to its CR and reported SLCAN_INVALID. */
typedef struct slcan_reader {
    char line[SLCAN_LINE_MAX - 1u];
    uint8_t len;
    bool overlong;
} slcan_reader_t;

void slcan_reader_init(slcan_reader_t *reader);

/* Takes one byte; at a CR, decodes the line gathered and starts the next one. The kind is
 * SLCAN_NOTHING until a line is complete. */
slcan_message_t slcan_read(slcan_reader_t *reader, uint8_t byte);

/* The answer of a device to a decoded line: SLCAN_CR for a command done, SLCAN_BEL for a line
 * refused, 0 for none (a frame, which this device does not acknowledge with z/Z: the kernel's
 * driver needs no acknowledgement, and the link's capacity is left to the frames). */
char slcan_answer(slcan_kind_t kind);

#endif
