/* SPDX-License-Identifier: Apache-2.0 */
/* A drive of your own on the installed package's generic CiA 402 velocity drive (canopen::drive):
 * the conveyor of conveyor.eds, its table generated at build time by co-edstool with the drive
 * layer's hooks (conveyor.hooks), and a drive_profile_t saying where its parameters are. It runs
 * in-process with injected time the way the Linux runtime runs a drive: a master's SDO requests
 * take it through the CiA 402 state machine to Operation enabled at 1200 rpm. Every frame is
 * printed in candump -L format (canopen::linux); each answer and state is checked. Exits 0 when
 * all is right, 1 otherwise. */
#include "co/co_emcy.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "conveyor_od.h"
#include "drive/drive.h"

#include <stdio.h>
#include <string.h>

#define NODE_ID 4
#define SDO_REQUEST (0x600 + NODE_ID)
#define SDO_RESPONSE (0x580 + NODE_ID)

/* The conveyor's faults: the communication loss the drive raises itself (heartbeat or life
 * guarding), which cuts the output, and an overheating a test could inject, which stops the belt
 * on the deceleration ramp first (drive/faults.h). */
static const drive_fault_def_t conveyor_fault_defs[] = {
    {"CnF", "communication loss", 0x8130, CO_ERR_REG_COMMUNICATION, DRIVE_FAULT_RESET_COMMAND,
     DRIVE_FAULT_FREEWHEEL},
    {"OHF", "overheating", 0x4210, CO_ERR_REG_TEMPERATURE, DRIVE_FAULT_RESET_COMMAND,
     DRIVE_FAULT_RAMP_STOP},
};
static const drive_fault_table_t conveyor_faults = {
    .faults = conveyor_fault_defs,
    .count = sizeof conveyor_fault_defs / sizeof conveyor_fault_defs[0],
    .communication_loss = 0,
};

/* Where the conveyor's parameters are (conveyor.eds, 3000h and 3001h), and its faults. */
static const drive_profile_t conveyor_profile = {
    .od = &conveyor_od,
    .faults = &conveyor_faults,
    .acceleration = DRIVE_PARAM(0x3000, 1),
    .deceleration = DRIVE_PARAM(0x3000, 2),
    .high_speed = DRIVE_PARAM(0x3000, 3),
    .nominal_frequency = DRIVE_PARAM(0x3000, 4),
    .nominal_speed = DRIVE_PARAM(0x3000, 5),
    .nominal_current = DRIVE_PARAM(0x3000, 6),
    .motor_current = DRIVE_PARAM(0x3001, 1),
    .motor_torque = DRIVE_PARAM(0x3001, 2),
};

typedef struct bench {
    drive_t drive;
    uint8_t od_data[CONVEYOR_OD_DATA_SIZE];
    co_time_t now;
    co_time_t deadline;
    co_frame_t answer; /* the last frame the drive sent */
    unsigned sent;
} bench_t;

static void print_frame(co_time_t now, const char *direction, const co_frame_t *frame)
{
    struct timespec at = {.tv_sec = (time_t)(now / 1000000u),
                          .tv_nsec = (long)(now % 1000000u) * 1000};
    struct can_frame can;
    char line[CO_CANDUMP_LINE_MAX];
    co_linux_frame_to_can(frame, &can);
    co_candump_format(line, sizeof line, &at, direction, &can);
    fputs(line, stdout);
}

static void send_frame(void *user, const co_frame_t *frame)
{
    bench_t *b = user;
    b->answer = *frame;
    b->sent++;
    print_frame(b->now, "TX", frame);
}

/* Lets time pass to `until`, running the drive at each deadline on the way (the ramp). */
static void advance(bench_t *b, co_time_t until)
{
    while (b->deadline <= until) {
        b->now = b->deadline;
        b->deadline = drive_process(&b->drive, b->now);
    }
    b->now = until;
    b->deadline = drive_process(&b->drive, b->now);
}

static void deliver(bench_t *b, const co_frame_t *frame)
{
    print_frame(b->now, "RX", frame);
    drive_receive(&b->drive, frame, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

/* An expedited SDO request; returns the value of the answer (upload) or -1 when the answer is not
 * the CiA 301 confirmation of this request. */
static long sdo(bench_t *b, uint8_t command, uint16_t index, uint8_t sub, uint32_t value)
{
    co_frame_t request = {.id = SDO_REQUEST,
                          .len = 8,
                          .data = {command, (uint8_t)index, (uint8_t)(index >> 8), sub,
                                   (uint8_t)value, (uint8_t)(value >> 8), (uint8_t)(value >> 16),
                                   (uint8_t)(value >> 24)}};
    unsigned before = b->sent;
    deliver(b, &request);
    const co_frame_t *a = &b->answer;
    bool same_object =
        a->data[1] == request.data[1] && a->data[2] == request.data[2] && a->data[3] == sub;
    if (b->sent != before + 1 || a->id != SDO_RESPONSE || a->len != 8 || !same_object)
        return -1;
    bool upload = command == 0x40;
    if (!upload)
        return a->data[0] == 0x60 ? 0 : -1;
    if ((a->data[0] & 0xE3) != 0x43) /* expedited, size indicated */
        return -1;
    return (long)(a->data[4] | a->data[5] << 8 | (uint32_t)a->data[6] << 16 |
                  (uint32_t)a->data[7] << 24);
}

static long write16(bench_t *b, uint16_t index, uint16_t value)
{
    return sdo(b, 0x2B, index, 0, value);
}

static long read_object(bench_t *b, uint16_t index)
{
    return sdo(b, 0x40, index, 0, 0);
}

static int failures;

static void check(bool ok, const char *what)
{
    printf("%s: %s\n", ok ? "ok" : "FAILED", what);
    if (!ok)
        failures++;
}

/* CiA 402 status word bits 0-3, 5 and 6 give the power state. */
static bool in_state(bench_t *b, uint16_t pattern)
{
    long status = read_object(b, 0x6041);
    return status >= 0 && ((uint16_t)status & 0x6F) == pattern;
}

int main(void)
{
    static bench_t b;
    drive_config_t config = {.profile = &conveyor_profile,
                             .od_data = b.od_data,
                             .node_id = NODE_ID,
                             .send = send_frame,
                             .send_user = &b};
    if (drive_init(&b.drive, &config) != 0) {
        fprintf(stderr, "drive: the conveyor's dictionary does not initialise\n");
        return 1;
    }
    drive_start(&b.drive, 0);
    b.deadline = drive_process(&b.drive, 0);
    check(b.sent == 1 && b.answer.id == 0x700 + NODE_ID && b.answer.data[0] == 0x00,
          "boot-up 704#00");

    co_frame_t start = {.id = 0x000, .len = 2, .data = {0x01, NODE_ID}};
    deliver(&b, &start);
    check(in_state(&b, 0x40), "Switch on disabled after boot");
    check(write16(&b, 0x6042, 1200) == 0, "6042h = 1200 rpm");
    check(write16(&b, 0x6040, 0x0006) == 0 && in_state(&b, 0x21), "shutdown: Ready to switch on");
    check(write16(&b, 0x6040, 0x0007) == 0 && in_state(&b, 0x23), "switch on: Switched on");
    check(write16(&b, 0x6040, 0x000F) == 0 && in_state(&b, 0x27),
          "enable operation: Operation enabled");

    /* 2.0 s from 0 to the nominal 1500 rpm: 1200 rpm within 1.6 s. */
    advance(&b, b.now + 2000000);
    check(read_object(&b, 0x6044) == 1200, "6044h: 1200 rpm after the ramp");
    check((read_object(&b, 0x6041) & 0x0400) != 0, "6041h bit 10: target reached");

    check(write16(&b, 0x6040, 0x0002) == 0 && in_state(&b, 0x07), "quick stop: Quick stop active");
    advance(&b, b.now + 2000000);
    check(read_object(&b, 0x6044) == 0 && in_state(&b, 0x07),
          "quick stop done: 0 rpm, locked in Quick stop active");
    check(write16(&b, 0x6040, 0x0000) == 0 && in_state(&b, 0x40),
          "disable voltage: Switch on disabled");
    printf("%s\n", failures ? "drive: FAILED" : "drive: all checks passed");
    return failures ? 1 : 0;
}
