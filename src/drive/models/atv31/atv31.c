/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 31's profiles: the family's (ATV312_FAMILY_PROFILE) on the dictionaries generated
 * from eds/ATV31.eds, with and without the heartbeat objects of firmware V1.2. Its STOP/RESET key
 * (the ATV31...A's front panel) is "used to stop the motor and to reset the current faults". Its
 * faults are the ATV312's on CANopen: its built-in CANopen port names the communication loss COF
 * too ("goes to COF fault"). */
#include "atv31/atv31.h"

/* Its analogue inputs, the project's choice where the manual names none but the potentiometer
 * (docs/atv31.md, "Front panel"): the ATV312 card's AI2 (+/-10 V) and AI3 (X-Y mA, CrL3/CrH3),
 * AI1 (0-10 V) of the ATV31's own terminal board, and the front panel's reference potentiometer
 * AIP ("only present on ATV 31pppppA"). */
static const drive_analog_input_t atv31_analog_inputs[] = {
    {"AI1", ATV312_FR_AI1, DRIVE_ANALOG_VOLTAGE, DRIVE_FIXED(0), DRIVE_FIXED(0)},
    {"AI2", ATV312_FR_AI2, DRIVE_ANALOG_BIPOLAR, DRIVE_FIXED(0), DRIVE_FIXED(0)},
    {"AI3", ATV312_FR_AI3, DRIVE_ANALOG_CURRENT, ATV312_AI3_LOW, ATV312_AI3_HIGH},
    {"AIP", ATV312_FR_AIP, DRIVE_ANALOG_POTENTIOMETER, DRIVE_FIXED(0), DRIVE_FIXED(0)},
};

const drive_profile_t atv31_profile =
    ATV312_FAMILY_PROFILE(&atv31_od, ATV31_LOGIC_INPUTS, atv31_analog_inputs, &atv312_family_faults,
                          true, ATV31_TPDO_INHIBIT_MS);
const drive_profile_t atv31_v11_profile =
    ATV312_FAMILY_PROFILE(&atv31_v11_od, ATV31_LOGIC_INPUTS, atv31_analog_inputs,
                          &atv312_family_faults, true, ATV31_TPDO_INHIBIT_MS);
