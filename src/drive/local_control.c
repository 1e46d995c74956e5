/* SPDX-License-Identifier: Apache-2.0 */
/* What happens at the drive rather than on the network (include/drive/drive.h, "At the drive"):
 * the keypad's STOP and RUN keys, forced local control, the load on the motor, the logic inputs,
 * and whether local control holds. Each event brings the motor to its time and changes the state;
 * the composition root (drive.c) settles the drive on it. */
#include "drive/drive_floors.h"

bool drive_local_control(const drive_t *drive)
{
    return drive->local || !drive->command_from_network;
}

/* A change of command channel (forced local on or off, a switch) is a freewheel stop to Switch
 * on disabled, as the drive's power-up under bus control: the new channel starts from there. A
 * fault stays latched. */
void drive_local_channel_changed(drive_t *drive)
{
    if (!cia402_faulted(&drive->cia402))
        cia402_reset(&drive->cia402);
    drive->local_run = false;
}

void drive_local_force(drive_t *drive, bool local, co_time_t now)
{
    drive_motor_advance(&drive->motor, now);
    drive->local = local;
    drive_local_channel_changed(drive);
}

void drive_local_stop_key(drive_t *drive, co_time_t now)
{
    drive_motor_advance(&drive->motor, now);
    drive->stop_key = true;
    if (drive_local_control(drive))
        drive->local_run = false;
    else
        cia402_configuration_changed(&drive->cia402);
}

/* A local run command (the RUN key, a terminal's run input): Operation enabled. */
static void local_run(drive_t *drive, bool reverse)
{
    drive->stop_key = false;
    drive->local_run = true;
    drive->terminal_reverse = reverse;
    drive->cia402.state = CIA402_OPERATION_ENABLED;
}

bool drive_local_run_key(drive_t *drive, co_time_t now)
{
    if (!drive_local_control(drive) || cia402_faulted(&drive->cia402))
        return false;
    drive_motor_advance(&drive->motor, now);
    local_run(drive, false);
    return true;
}

/* Logic input `input` of the model is not as it was in `before`. */
static bool input_changed(const drive_t *drive, uint8_t before, uint8_t input)
{
    return input != 0 && input <= drive->profile->logic_inputs &&
           (((unsigned)(before ^ drive->inputs) >> (input - 1u)) & 1u) != 0;
}

/* 2-wire control: a run input switched on alone starts the drive in its direction, and it runs
 * while that input alone stays on; a run input's other changes stop it (on the deceleration
 * ramp). Other inputs leave the run as it is. `before` holds the inputs before this change. */
void drive_local_terminals(drive_t *drive, uint8_t before)
{
    const drive_profile_t *profile = drive->profile;
    bool forward_changed = input_changed(drive, before, profile->run_forward);
    bool reverse_changed = input_changed(drive, before, profile->run_reverse);
    if (!drive->command_from_terminals || drive->local || !(forward_changed || reverse_changed))
        return;
    bool forward = drive_input(drive, profile->run_forward);
    bool reverse = drive_input(drive, profile->run_reverse);
    if (forward == reverse || (drive->local_run && drive->terminal_reverse != reverse)) {
        drive->local_run = false;
        return;
    }
    bool rose = (forward && forward_changed) || (reverse && reverse_changed);
    if (rose && !drive->local_run && !cia402_faulted(&drive->cia402))
        local_run(drive, reverse);
}

void drive_local_load(drive_t *drive, uint8_t percent, co_time_t now)
{
    drive_motor_advance(&drive->motor, now);
    drive->load = percent;
    drive_motor_load(&drive->motor, percent);
}

bool drive_local_input(drive_t *drive, uint8_t input, bool on, co_time_t now)
{
    if (input == 0 || input > drive->profile->logic_inputs)
        return false;
    drive_motor_advance(&drive->motor, now);
    uint8_t bit = (uint8_t)(1u << (input - 1u));
    drive->inputs = (uint8_t)(on ? drive->inputs | bit : drive->inputs & ~bit);
    return true;
}

int drive_analog_find(const drive_t *drive, const char *name)
{
    for (uint8_t i = 0; i < drive->profile->analog_input_count; i++) {
        if (drive_same_code(drive->profile->analog_inputs[i].name, name))
            return i;
    }
    return -1;
}

static bool analog_in_range(drive_analog_kind_t kind, int32_t value)
{
    switch (kind) {
    case DRIVE_ANALOG_VOLTAGE:
        return value >= 0 && value <= DRIVE_ANALOG_VOLTAGE_MAX_MV;
    case DRIVE_ANALOG_BIPOLAR:
        return value >= -DRIVE_ANALOG_VOLTAGE_MAX_MV && value <= DRIVE_ANALOG_VOLTAGE_MAX_MV;
    case DRIVE_ANALOG_CURRENT:
        return value >= 0 && value <= DRIVE_ANALOG_CURRENT_MAX_UA;
    case DRIVE_ANALOG_POTENTIOMETER:
        return value >= 0 && value <= DRIVE_ANALOG_POTENTIOMETER_MAX;
    }
    return false;
}

bool drive_local_analog(drive_t *drive, uint8_t index, int32_t value, co_time_t now)
{
    if (index >= drive->profile->analog_input_count ||
        !analog_in_range(drive->profile->analog_inputs[index].kind, value))
        return false;
    drive_motor_advance(&drive->motor, now);
    drive->analog[index] = value;
    return true;
}

int32_t drive_analog(const drive_t *drive, uint8_t index)
{
    return index < drive->profile->analog_input_count ? drive->analog[index] : 0;
}

bool drive_input(const drive_t *drive, uint8_t input)
{
    return input != 0 && input <= drive->profile->logic_inputs &&
           (drive->inputs & (1u << (input - 1u))) != 0;
}

bool drive_local_runs(const drive_t *drive)
{
    return drive->local_run && drive->cia402.state == CIA402_OPERATION_ENABLED;
}

/* A local stop ends in Switch on disabled once the motor stands. */
void drive_local_motor_stopped(drive_t *drive)
{
    if (drive_local_control(drive) && !drive->local_run &&
        drive->cia402.state == CIA402_OPERATION_ENABLED)
        drive->cia402.state = CIA402_SWITCH_ON_DISABLED;
}

uint16_t drive_local_status(const drive_t *drive)
{
    uint16_t bits = drive_local_control(drive) ? 0 : CIA402_SW_REMOTE;
    return drive->stop_key ? (uint16_t)(bits | drive->profile->status_stop_key) : bits;
}

/* A network command that takes the drive out of Switch on disabled is the next run command: the
 * STOP key's bit clears. */
void drive_local_command_applied(drive_t *drive)
{
    if (drive->cia402.state != CIA402_SWITCH_ON_DISABLED && !cia402_faulted(&drive->cia402))
        drive->stop_key = false;
}
