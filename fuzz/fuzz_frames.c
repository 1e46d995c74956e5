/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the frame path: an ATV312 drive (node 4, with in-memory storage behind
 * 1010h / 1011h) fed a sequence of frames and time steps decoded from the input (steps.h has the
 * format), then reset by NMT and compared with a fresh drive (rig.h has the invariants). */
#include "memory_storage.h"
#include "rig.h"
#include "steps.h"

#include <string.h>

#define NODE_ID 4

static rig_t rig, fresh;
static memory_storage_t memory, fresh_memory;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    co_storage_t storage, fresh_storage;
    memory_storage_init(&memory, &storage);
    rig_start(&rig, NODE_ID, &storage, 0);
    fuzz_input_t input = {data, size};
    fuzz_step_t step;
    while (fuzz_next_step(&input, false, &step)) {
        if (step.kind == FUZZ_STEP_TIME)
            rig_advance(&rig, step.us);
        else
            rig_receive(&rig, &step.frame);
    }
    /* The fresh drive boots on what the fuzzed one saved, as a real one would after a restart. */
    memory_storage_init(&fresh_memory, &fresh_storage);
    memcpy(fresh_memory.image, memory.image, sizeof memory.image);
    memcpy(fresh_memory.size, memory.size, sizeof memory.size);
    rig_check_reset(&rig, &fresh, &fresh_storage);
    return 0;
}
