/* SPDX-License-Identifier: Apache-2.0 */
/* A bare-metal CANopen node on a Cortex-M4: the integration a porter writes (docs/porting.md,
 * "The bare-metal example"). One node on the dictionary of blinky.eds, its SDO transfer buffer
 * given by the application (the core is built with CO_CONFIG_SDO_BUFFER=0 and tables sized to the
 * dictionary: CMakeLists.txt), parameters saved by 1010h into flash pages, frames in from the
 * receive interrupt's queue and out through the board's transmitter, the RUN and ERR LEDs of
 * CiA 303-3, and the main loop sleeping until the next frame or deadline. The node has CiA 305
 * LSS: a master may give it another node-id, or none, and store that in flash (docs/lss.md). The
 * same file runs on both boards of board.h. */
#include "blinky_od.h"
#include "board.h"
#include "co/co_emcy.h"
#include "co/co_indicators.h"
#include "co/co_node.h"
#include "flash_storage.h"

/* Largest segmented or block transfer: 1008h-like strings and a whole PDO mapping fit. Nodes of
 * one firmware could share it (co_sdo_buffer_t). */
#define SDO_BUFFER_SIZE 64u
#define NODE_ID 0x10u /* until LSS stores another */
/* The bit timing index (CiA 305 table 0) LSS stores beside the node-id: 125 kbit/s, what the
 * host's slcand is told. The board has no CAN controller to retime (its frames cross a UART), so
 * the node offers no other: configure bit timing answers "not supported". */
#define BIT_TIMING_125K 4u
#define BLINK_PERIOD 0x2000u
#define BLINK_COUNT 0x2001u
#define SIMULATED_ERROR 0x2002u

static co_node_t node;
static uint8_t od_data[BLINKY_OD_DATA_SIZE];
static uint8_t sdo_data[SDO_BUFFER_SIZE];
static co_sdo_buffer_t sdo_buffer = {.data = sdo_data, .size = SDO_BUFFER_SIZE};
static flash_storage_t flash;
static co_storage_t storage;
static co_lss_slave_t lss;
/* The EMCY code raised through 2002h, 0 for none. */
static uint16_t simulated_error;
/* Guarding or a monitored heartbeat lost and not back: the ERR LED's double flash. */
static bool error_control_event;

/* The core never waits for a frame to leave: a transmitter without room is a lost frame,
 * reported as the CiA 301 "CAN overrun" error (cleared when the application decides, here
 * never). */
static void send(void *user, const co_frame_t *frame)
{
    co_node_t *self = user;
    if (!can_transmit(frame))
        co_emcy_raise(self, CO_EMCY_CAN_OVERRUN, CO_ERR_REG_COMMUNICATION, NULL);
}

/* A write of 2002h raises the EMCY of its value (0 raises none) and clears the one before. */
static void od_written(co_node_t *self, const co_od_entry_t *entry, co_od_origin_t origin)
{
    (void)origin;
    if (entry->index != SIMULATED_ERROR)
        return;
    uint16_t code = (uint16_t)co_od_value(self, SIMULATED_ERROR, 0);
    if (simulated_error != 0)
        co_emcy_clear(self, simulated_error);
    simulated_error = code;
    if (code != 0)
        co_emcy_raise(self, code, CO_ERR_REG_MANUFACTURER, NULL);
}

/* Reset node restores 2002h to 0, and the EMCY producer forgets what it raised. */
static void reset(co_node_t *self, co_nmt_reset_t scope)
{
    (void)self;
    if (scope == CO_NMT_RESET_NODE)
        simulated_error = 0;
    error_control_event = false; /* every reset restarts error control */
}

/* Error control: the master stopped guarding this node, or a monitored heartbeat stopped: the
 * CiA 301 "life guard or heartbeat error", cleared when it resumes. */
static void guarding(co_node_t *self, bool lost)
{
    error_control_event = lost;
    if (lost)
        co_emcy_raise(self, CO_EMCY_HEARTBEAT, CO_ERR_REG_COMMUNICATION, NULL);
    else
        co_emcy_clear(self, CO_EMCY_HEARTBEAT);
}

static void heartbeat(co_node_t *self, uint8_t producer, bool lost)
{
    (void)producer;
    guarding(self, lost);
}

static const co_app_hooks_t hooks = {
    .od_written = od_written, .reset = reset, .guarding = guarding, .heartbeat = heartbeat};

/* LSS store configuration: the node-id and bit timing in their own flash area, a 2-byte image. */
static uint8_t lss_store(co_node_t *self, uint8_t node_id, uint8_t bit_timing, uint8_t *specific)
{
    (void)self;
    (void)specific;
    const uint8_t image[2] = {node_id, bit_timing};
    bool saved = storage.save_begin(storage.ctx, FLASH_STORAGE_AREA_LSS) == 0 &&
                 storage.save_write(storage.ctx, image, sizeof(image)) == 0;
    if (storage.save_end(storage.ctx, saved) != 0 || !saved)
        return CO_LSS_STORE_MEDIA_ERROR;
    return CO_LSS_OK;
}

static const co_lss_slave_hooks_t lss_hooks = {.store = lss_store};

/* The node-id LSS stored (FFh: none, the node waits for LSS), else NODE_ID. */
static uint8_t stored_node_id(void)
{
    uint8_t image[2];
    if (storage.load_size(storage.ctx, FLASH_STORAGE_AREA_LSS) != (long)sizeof(image) ||
        storage.load_read(storage.ctx, FLASH_STORAGE_AREA_LSS, 0, image, sizeof(image)) != 0)
        return NODE_ID;
    bool valid =
        (image[0] >= 1 && image[0] <= CO_NODE_ID_MAX) || image[0] == CO_LSS_NODE_ID_UNCONFIGURED;
    return valid ? image[0] : NODE_ID;
}

/* The application's work: count blinks at the period of 2000h; 2001h is mapped into TPDO1, and
 * co_node_process sends it when it changes. */
static co_time_t blink(co_time_t now, co_time_t due)
{
    if (now < due)
        return due;
    uint32_t count = (uint32_t)co_od_value(&node, BLINK_COUNT, 0);
    co_od_set_value(&node, BLINK_COUNT, 0, count + 1);
    return now + (co_time_t)co_od_value(&node, BLINK_PERIOD, 0) * 1000u;
}

/* The LEDs as CiA 303-3 has them for the node's state at `now`; returns when they change next. */
static co_time_t show_leds(co_time_t now)
{
    co_indicator_state_t state = {.nmt_state = node.nmt_state,
                                  .error_control = error_control_event};
    co_led_t run = co_indicator_run(&state);
    co_led_t err = co_indicator_err(&state);
    board_leds(co_led_lit(run, false, now), co_led_lit(err, true, now));
    return co_time_min(co_led_next_change(run, now), co_led_next_change(err, now));
}

int main(void)
{
    board_init();
    flash_storage_init(&storage, &flash);
    co_lss_slave_init(&lss, &lss_hooks, BIT_TIMING_125K);
    co_node_config_t config = {
        .node_id = stored_node_id(),
        .od = &blinky_od,
        .od_data = od_data,
        .send = send,
        .user = &node,
        .hooks = &hooks,
        .storage = &storage,
        .sdo_buffer = &sdo_buffer,
        .lss = &lss,
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
        if (can_receive_overruns() != 0)
            co_emcy_raise(&node, CO_EMCY_CAN_OVERRUN, CO_ERR_REG_COMMUNICATION, NULL);
        co_time_t now = clock_us();
        blink_due = blink(now, blink_due);
        co_time_t due = co_time_min(co_node_process(&node, now), blink_due);
        /* Sleep until the earliest of the core's deadline, the application's and the LEDs', or a
         * frame. */
        board_wait(co_time_min(due, show_leds(now)));
    }
}
