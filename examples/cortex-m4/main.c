/* A bare-metal CANopen node on a Cortex-M4: the integration a porter writes (docs/porting.md,
 * "The bare-metal example"). One node on the dictionary of blinky.eds, its SDO transfer buffer
 * given by the application (the core is built with CO_CONFIG_SDO_BUFFER=0 and tables sized to the
 * dictionary: CMakeLists.txt), parameters saved by 1010h into flash pages, frames in from the CAN
 * receive interrupt's queue and out through the transmit stub, and the main loop sleeping until
 * the next frame or deadline. */
#include "blinky_od.h"
#include "board.h"
#include "co/co_node.h"
#include "flash_storage.h"

/* Largest segmented or block transfer: 1008h-like strings and a whole PDO mapping fit. Nodes of
 * one firmware could share it (co_sdo_buffer_t). */
#define SDO_BUFFER_SIZE 64u
#define NODE_ID 0x10u

static co_node_t node;
static uint8_t od_data[BLINKY_OD_DATA_SIZE];
static uint8_t sdo_data[SDO_BUFFER_SIZE];
static co_sdo_buffer_t sdo_buffer = {.data = sdo_data, .size = SDO_BUFFER_SIZE};
static flash_storage_t flash;
static co_storage_t storage;

/* The core never waits for a frame to leave: a full controller is a lost frame, reported once
 * as the CiA 301 "CAN overrun" error (cleared when the application decides, here never). */
static void send(void *user, const co_frame_t *frame)
{
    co_node_t *self = user;
    if (!can_transmit(frame))
        co_emcy_raise(self, CO_EMCY_CAN_OVERRUN, CO_ERR_REG_COMMUNICATION, NULL);
}

/* The application's work: count blinks at the period of 2000h; 2001h is mapped into TPDO1, and
 * co_node_process sends it when it changes. */
static co_time_t blink(co_time_t now, co_time_t due)
{
    if (now < due)
        return due;
    uint32_t count = (uint32_t)co_od_value(&node, 0x2001, 0);
    co_od_set_value(&node, 0x2001, 0, count + 1);
    return now + (co_time_t)co_od_value(&node, 0x2000, 0) * 1000u;
}

int main(void)
{
    board_init();
    flash_storage_init(&storage, &flash);
    co_node_config_t config = {
        .node_id = NODE_ID,
        .od = &blinky_od,
        .od_data = od_data,
        .send = send,
        .user = &node,
        .storage = &storage,
        .sdo_buffer = &sdo_buffer,
    };
    if (co_node_init(&node, &config) != 0)
        for (;;) /* a dictionary the core refuses is a build error: stop here under a debugger */
            ;
    co_node_start(&node, clock_us());
    co_time_t blink_due = clock_us();
    for (;;) {
        co_frame_t frame;
        while (can_receive(&frame))
            co_node_receive(&node, &frame, clock_us());
        co_time_t now = clock_us();
        blink_due = blink(now, blink_due);
        co_time_t next = co_time_min(co_node_process(&node, now), blink_due);
        /* Sleep only when nothing is due. The SysTick wakes the loop every millisecond, so a
         * frame queued since the receive loop above waits at most 1 ms. */
        if (next > clock_us())
            board_idle();
    }
}
