/* SPDX-License-Identifier: Apache-2.0 */
#include "minimal_model.h"

#include "co/co_emcy.h"

/* One fault of each reset class, the communication loss not first: the drive must follow the
 * table, not an Altivar's order; one fault of each reaction. */
static const drive_fault_def_t faults[] = {
    [FAULT_HOT] = {"HoT", "overheating", 0x4210, CO_ERR_REG_TEMPERATURE, DRIVE_FAULT_RESET_COMMAND,
                   DRIVE_FAULT_FREEWHEEL},
    [FAULT_LOW] = {"LoW", "undervoltage", 0x3120, CO_ERR_REG_VOLTAGE, DRIVE_FAULT_RESET_AUTOMATIC,
                   DRIVE_FAULT_FREEWHEEL},
    [FAULT_NET] = {"NeT", "communication loss", 0x8130, CO_ERR_REG_COMMUNICATION,
                   DRIVE_FAULT_RESET_COMMAND, DRIVE_FAULT_FREEWHEEL},
    [FAULT_CPU] = {"CpU", "internal", 0x6100, 0, DRIVE_FAULT_RESET_POWER_CYCLE,
                   DRIVE_FAULT_FREEWHEEL},
    [FAULT_EXT] = {"ExT", "external", 0x9000, 0, DRIVE_FAULT_RESET_COMMAND, DRIVE_FAULT_RAMP_STOP},
    [FAULT_FAN] = {"FaN", "fan", 0x4310, CO_ERR_REG_TEMPERATURE, DRIVE_FAULT_RESET_AUTOMATIC,
                   DRIVE_FAULT_FAST_STOP},
};

static const drive_fault_table_t fault_table = {
    .faults = faults,
    .count = sizeof faults / sizeof faults[0],
    .communication_loss = FAULT_NET,
};

const drive_profile_t minimal_profile = {
    .od = &minimal_od,
    .control_reverse = CW_REVERSE,
    .control_ramp_stop = CW_RAMP_STOP,
    .control_fast_stop = CW_FAST_STOP,
    .status_reverse = SW_REVERSE,
    .status_stop_key = SW_STOP_KEY,
    .fast_ramp_divider = 2,
    .acceleration = DRIVE_PARAM(PARAMS, ACC),
    .deceleration = DRIVE_PARAM(PARAMS, DEC),
    .low_speed = DRIVE_PARAM(PARAMS, LSP),
    .high_speed = DRIVE_PARAM(PARAMS, HSP),
    .nominal_frequency = DRIVE_PARAM(PARAMS, FRS),
    .nominal_speed = DRIVE_PARAM(PARAMS, NSP),
    .nominal_current = DRIVE_PARAM(PARAMS, NCR),
    .motor_current = DRIVE_PARAM(OUTPUTS, CURRENT),
    .motor_torque = DRIVE_PARAM(OUTPUTS, TORQUE),
    .faults = &fault_table,
    .stop_type = DRIVE_PARAM(PARAMS, STOP_TYPE),
    .channel_mode = DRIVE_PARAM(PARAMS, CHANNEL_MODE),
    .channel_mode_separate = 0,
    .channel_mode_io = 2,
    .command_channels = {DRIVE_PARAM(PARAMS, COMMAND_1), DRIVE_PARAM(PARAMS, COMMAND_2),
                         DRIVE_PARAM(PARAMS, COMMAND_SELECT), 1, 0},
    .reference_channels = {DRIVE_PARAM(PARAMS, REFERENCE), DRIVE_FIXED(1),
                           DRIVE_PARAM(PARAMS, REFERENCE_SELECT), 1, 0},
    .output_frequency = DRIVE_PARAM(OUTPUTS, FREQUENCY),
    .frequency_reference = DRIVE_PARAM(PARAMS, FREQUENCY_REF),
    .auto_tune = DRIVE_PARAM(PARAMS, AUTO_TUNE),
    .ramp_switch = DRIVE_PARAM(PARAMS, RAMP_SWITCH),
    .acceleration_2 = DRIVE_PARAM(PARAMS, ACC_2),
    .deceleration_2 = DRIVE_PARAM(PARAMS, DEC_2),
    .logic_inputs = INPUTS,
    .access_level = DRIVE_PARAM(PARAMS, ACCESS),
    .access_level_full = 1,
};
