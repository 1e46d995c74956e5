#include "minimal_model.h"

const drive_profile_t minimal_profile = {
    .od = &minimal_od,
    .fault_error_register = CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION,
    .control_reverse = CW_REVERSE,
    .control_ramp_stop = CW_RAMP_STOP,
    .control_fast_stop = CW_FAST_STOP,
    .status_reverse = SW_REVERSE,
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
};
