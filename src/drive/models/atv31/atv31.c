/* The Altivar 31's profiles: the family's (ATV312_FAMILY_PROFILE) on the dictionaries generated
 * from eds/ATV31.eds, with and without the heartbeat objects of firmware V1.2. Its STOP/RESET key
 * (the ATV31...A's front panel) is "used to stop the motor and to reset the current faults". */
#include "atv31/atv31.h"

const drive_profile_t atv31_profile =
    ATV312_FAMILY_PROFILE(&atv31_od, ATV31_LOGIC_INPUTS, &atv31_family_faults, true);
const drive_profile_t atv31_v11_profile =
    ATV312_FAMILY_PROFILE(&atv31_v11_od, ATV31_LOGIC_INPUTS, &atv31_family_faults, true);
