/* The Altivar 312's profiles: the family's (ATV312_FAMILY_PROFILE) on the dictionary generated
 * from eds/ATV312.eds, on CANopen and behind the DeviceNet card, whose manuals name the
 * communication loss differently (COF, CnF). */
#include "atv312/atv312.h"

const drive_profile_t atv312_profile =
    ATV312_FAMILY_PROFILE(&atv312_od, ATV312_LOGIC_INPUTS, &atv312_family_faults, false);
const drive_profile_t atv312_devicenet_drive_profile =
    ATV312_FAMILY_PROFILE(&atv312_od, ATV312_LOGIC_INPUTS, &atv312_devicenet_faults, false);
