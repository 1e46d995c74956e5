/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the drive on DeviceNet (src/drive/devicenet behind src/devicenet): an
 * ATV312 behind its card at MAC ID 25, fed frames, time steps and the runtime's events decoded
 * from the input (steps.h), and held after every step, and at every deadline on the way, to the
 * rule of docs/decisions.md, D-DEVICENET-CONNECTION-END: the drive never runs on the network's
 * command without a live connection carrying it (the polled connection or the explicit one
 * Established), unless COL says to ignore the loss. Commands:
 *
 *     E0h:  the controller goes bus off (drive_dn_bus_off)
 *     E1h:  the interface comes back after an outage (drive_dn_restart)
 *     E2h..EFh: nothing
 *
 * fuzz/seeds.py writes the seeds from readable frames, time steps and these commands. */
#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "dn/dn_link.h"
#include "rig.h"
#include "steps.h"

#include <string.h>

#define MAC_ID 25u
#define COMMAND_BUS_OFF 0u
#define COMMAND_INTERFACE_BACK 1u
#define DEADLINES_PER_STEP 100000u

static drive_t drive;
static uint8_t od_data[ATV312_OD_DATA_SIZE];
static drive_dn_t dn;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The card speaks only as itself: 11-bit data frames of its own MAC ID, in group 1 or 2. */
static void drop(void *user, const co_frame_t *frame)
{
    (void)user;
    dn_can_id_t id = dn_can_id_decode(frame->id);
    rig_check(!(frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF)), "a remote or 29-bit frame");
    rig_check((id.group == 1 || id.group == 2) && id.mac_id == MAC_ID,
              "a frame on another MAC ID's identifiers");
    rig_check(frame->len <= CO_FRAME_DLC_MAX, "a frame longer than 8 bytes");
}

static bool keep(void *user, const dn_stored_t *stored)
{
    (void)user;
    (void)stored;
    return true;
}

static bool established(uint8_t instance)
{
    return dn_node_connection_state(&dn.node, instance) == DN_CONN_ESTABLISHED;
}

static void check_carried(void)
{
    bool runs_on_network = drive_dn_state(&dn) == DRIVE_DN_ENABLED && !drive_local_control(&drive);
    drive_param_t col = drive.profile->communication_loss_mode;
    bool loss_ignored =
        co_od_value(&drive.node, col.index, col.subindex) == DRIVE_COMMUNICATION_LOSS_IGNORE;
    rig_check(!runs_on_network || loss_ignored || established(DN_CONN_POLL) ||
                  established(DN_CONN_EXPLICIT),
              "the drive runs on the network's command with no connection carrying it");
}

/* Time goes on to `target` through every deadline on the way, the rule checked at each. */
static co_time_t advance(co_time_t now, co_time_t deadline, co_time_t target)
{
    for (unsigned i = 0; deadline <= target && i < DEADLINES_PER_STEP; i++) {
        if (deadline > now)
            now = deadline;
        co_time_t next = drive_dn_process(&dn, now);
        rig_check(next > now, "a deadline that does not advance");
        deadline = next;
        check_carried();
    }
    return deadline;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    drive_config_t dc = {.profile = atv312_devicenet_profile.drive,
                         .od_data = od_data,
                         .node_id = 1,
                         .send = drive_dn_drop_frame};
    rig_check(drive_init(&drive, &dc) == 0, "drive_init");
    drive_dn_config_t c = {.drive = &drive,
                           .profile = &atv312_devicenet_profile,
                           .mac_id = MAC_ID,
                           .baud_rate = 2,
                           .serial_number = 0x31200019,
                           .send = drop,
                           .store = keep};
    rig_check(drive_dn_init(&dn, &c) == 0, "drive_dn_init");
    co_time_t now = 0;
    drive_dn_start(&dn, now);
    co_time_t deadline = drive_dn_process(&dn, now);
    fuzz_input_t input = {data, size};
    fuzz_step_t step;
    while (fuzz_next_step(&input, true, &step)) {
        switch (step.kind) {
        case FUZZ_STEP_TIME:
            deadline = advance(now, deadline, now + step.us);
            now += step.us;
            break;
        case FUZZ_STEP_FRAME:
            drive_dn_receive(&dn, &step.frame, now);
            deadline = drive_dn_process(&dn, now);
            break;
        case FUZZ_STEP_COMMAND:
            if (step.command == COMMAND_BUS_OFF)
                drive_dn_bus_off(&dn, now);
            else if (step.command == COMMAND_INTERFACE_BACK)
                drive_dn_restart(&dn, now);
            deadline = drive_dn_process(&dn, now);
            break;
        }
        check_carried();
    }
    return 0;
}
