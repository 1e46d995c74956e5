/* SPDX-License-Identifier: Apache-2.0 */
/* The input of the harnesses fed frames and time (fuzz_frames, fuzz_sdo_client, fuzz_net_master):
 * a sequence of steps, each a tag byte and what follows it, to the input's end:
 *
 *     tag < F0h:  a frame: CAN-ID (tag & 07h) << 8 | next byte, RTR if tag & 08h, length
 *                 (tag >> 4) mod 9, then that many data bytes (fewer if the input ends)
 *     tag >= F0h: a time step of (u16 LE) << (tag & 0Fh) microseconds (up to 35 minutes)
 *
 * so that "604#2F00620001" reads 56 04 2F 00 62 00 01 (fuzz/seeds.py writes the seeds). Tags
 * E0h..EFh give the same frames as 50h..5Fh (the length is taken mod 9), so a harness may take
 * them as commands of its own, whose arguments follow the tag. */
#ifndef FUZZ_STEPS_H
#define FUZZ_STEPS_H

#include "co/co_types.h"

#define FUZZ_TIME_STEP_TAG 0xF0u
#define FUZZ_COMMAND_TAG 0xE0u

typedef enum fuzz_step_kind {
    FUZZ_STEP_FRAME,
    FUZZ_STEP_TIME,
    FUZZ_STEP_COMMAND /* only when the harness takes commands */
} fuzz_step_kind_t;

typedef struct fuzz_step {
    fuzz_step_kind_t kind;
    co_frame_t frame; /* FUZZ_STEP_FRAME */
    co_time_t us;     /* FUZZ_STEP_TIME */
    uint8_t command;  /* FUZZ_STEP_COMMAND: tag & 0Fh; its arguments come from fuzz_take */
} fuzz_step_t;

/* What is left of the input. */
typedef struct fuzz_input {
    const uint8_t *data;
    size_t size;
} fuzz_input_t;

/* Takes the next step; false at the end of the input. `commands`: tags E0h..EFh are commands. */
bool fuzz_next_step(fuzz_input_t *in, bool commands, fuzz_step_t *step);

/* Takes `n` bytes (a header, a command's arguments); NULL when fewer are left, and the input is
 * then at its end. */
const uint8_t *fuzz_take(fuzz_input_t *in, size_t n);

#endif
