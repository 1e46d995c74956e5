/* The Schneider Altivar 312 model of the CiA 402 velocity drive (drive/drive.h): its object
 * dictionary atv312_od (generated from eds/ATV312.eds with the hooks of src/atv312/atv312.hooks;
 * a node's data block is ATV312_OD_DATA_SIZE bytes) and its profile, where its parameters are and
 * what its control word bits 11-14 do. The behaviour is the drive layer's: give atv312_profile to
 * drive_init. Portable like the core: no malloc, no OS calls, no globals. */
#ifndef ATV312_H
#define ATV312_H

#include "atv312_od.h" /* generated */
#include "drive/drive.h"

extern const drive_profile_t atv312_profile;

#endif
