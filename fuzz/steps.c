/* SPDX-License-Identifier: Apache-2.0 */
#include "steps.h"

#include <string.h>

const uint8_t *fuzz_take(fuzz_input_t *in, size_t n)
{
    if (in->size < n) {
        in->size = 0;
        return NULL;
    }
    const uint8_t *taken = in->data;
    in->data += n;
    in->size -= n;
    return taken;
}

bool fuzz_next_step(fuzz_input_t *in, bool commands, fuzz_step_t *step)
{
    /* A step is at least a tag and one byte. */
    if (in->size < 2)
        return false;
    uint8_t tag = in->data[0];
    if (tag >= FUZZ_TIME_STEP_TAG) {
        const uint8_t *p = fuzz_take(in, 3);
        if (p == NULL)
            return false;
        step->kind = FUZZ_STEP_TIME;
        step->us = (co_time_t)co_get_u16(p + 1) << (tag & 0x0Fu);
        return true;
    }
    if (commands && (tag & 0xF0u) == FUZZ_COMMAND_TAG) {
        fuzz_take(in, 1);
        step->kind = FUZZ_STEP_COMMAND;
        step->command = tag & 0x0Fu;
        return true;
    }
    const uint8_t *head = fuzz_take(in, 2);
    step->kind = FUZZ_STEP_FRAME;
    step->frame = (co_frame_t){
        .id = (uint32_t)(tag & 0x07u) << 8 | head[1],
        .flags = (tag & 0x08u) ? CO_FRAME_RTR : 0,
    };
    size_t len = (size_t)(tag >> 4) % 9;
    step->frame.len = (uint8_t)(len < in->size ? len : in->size);
    memcpy(step->frame.data, fuzz_take(in, step->frame.len), step->frame.len);
    return true;
}
