/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 312's profiles: the family's (ATV312_FAMILY_PROFILE) on the dictionary generated
 * from eds/ATV312.eds, on CANopen and behind the DeviceNet card, whose manuals name the
 * communication loss differently (COF, CnF). */
#include "atv312/atv312.h"

/* The analogue inputs of the option card that replaces the base terminal board, the CANopen
 * daisy chain card VW3A31208 (the CANopen manual's "Control terminals characteristics") and the
 * DeviceNet card alike: AI2, "bipolar voltage input +/-10 V", and AI3, "current input X-Y mA by
 * programming X and Y from 0 to 20 mA" (CrL3, CrH3). No AI1: Fr = AI1 gives a zero reference. */
static const drive_analog_input_t atv312_analog_inputs[] = {
    {"AI2", ATV312_FR_AI2, DRIVE_ANALOG_BIPOLAR, DRIVE_FIXED(0), DRIVE_FIXED(0)},
    {"AI3", ATV312_FR_AI3, DRIVE_ANALOG_CURRENT, ATV312_AI3_LOW, ATV312_AI3_HIGH},
};

const drive_profile_t atv312_profile =
    ATV312_FAMILY_PROFILE(&atv312_od, ATV312_LOGIC_INPUTS, atv312_analog_inputs,
                          &atv312_family_faults, false, ATV312_TPDO_INHIBIT_MS);
const drive_profile_t atv312_devicenet_drive_profile =
    ATV312_FAMILY_PROFILE(&atv312_od, ATV312_LOGIC_INPUTS, atv312_analog_inputs,
                          &atv312_devicenet_faults, false, ATV312_TPDO_INHIBIT_MS);
