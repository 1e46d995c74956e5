#include "minimal_model.h"

const drive_profile_t minimal_profile = {
    .od = &minimal_od,
    .control_reverse = CW_REVERSE,
    .control_ramp_stop = CW_RAMP_STOP,
    .control_fast_stop = CW_FAST_STOP,
    .status_reverse = SW_REVERSE,
    .fast_ramp_divider = 2,
    .acceleration = {PARAMS, ACC},
    .deceleration = {PARAMS, DEC},
    .low_speed = {PARAMS, LSP},
    .high_speed = {PARAMS, HSP},
    .nominal_frequency = {PARAMS, FRS},
    .nominal_speed = {PARAMS, NSP},
    .nominal_current = {PARAMS, NCR},
    .motor_current = {OUTPUTS, CURRENT},
    .motor_torque = {OUTPUTS, TORQUE},
};
