/* libFuzzer harness of the frame path: an ATV312 drive (node 4, with in-memory storage behind
 * 1010h / 1011h) fed a sequence of frames and time steps decoded from the input, then reset by
 * NMT and compared with a fresh drive (rig.h has the invariants). Input, repeated to its end:
 *
 *     tag < F0h:  a frame: CAN-ID (tag & 07h) << 8 | next byte, RTR if tag & 08h, length
 *                 (tag >> 4) mod 9, then that many data bytes (fewer if the input ends)
 *     tag >= F0h: a time step of (u16 LE) << (tag & 0Fh) microseconds (up to 35 minutes)
 *
 * so that "604#2F00620001" reads 56 04 2F 00 62 00 01 in a corpus file (fuzz/seeds.py). */
#include "memory_storage.h"
#include "rig.h"

#include <string.h>

#define NODE_ID 4
#define TIME_STEP_TAG 0xF0u

static rig_t rig, fresh;
static memory_storage_t memory, fresh_memory;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    co_storage_t storage, fresh_storage;
    memory_storage_init(&memory, &storage);
    rig_start(&rig, NODE_ID, &storage, 0);
    while (size >= 2) {
        uint8_t tag = data[0];
        if (tag >= TIME_STEP_TAG) {
            if (size < 3)
                break;
            rig_advance(&rig, (co_time_t)co_get_u16(data + 1) << (tag & 0x0Fu));
            data += 3;
            size -= 3;
            continue;
        }
        co_frame_t frame = {
            .id = (uint32_t)(tag & 0x07u) << 8 | data[1],
            .flags = (tag & 0x08u) ? CO_FRAME_RTR : 0,
        };
        data += 2;
        size -= 2;
        size_t len = (size_t)(tag >> 4) % 9;
        frame.len = (uint8_t)(len < size ? len : size);
        memcpy(frame.data, data, frame.len);
        data += frame.len;
        size -= frame.len;
        rig_receive(&rig, &frame);
    }
    /* The fresh drive boots on what the fuzzed one saved, as a real one would after a restart. */
    memory_storage_init(&fresh_memory, &fresh_storage);
    memcpy(fresh_memory.image, memory.image, sizeof memory.image);
    memcpy(fresh_memory.size, memory.size, sizeof memory.size);
    rig_check_reset(&rig, &fresh, &fresh_storage);
    return 0;
}
