/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 312 on DeviceNet: the model's data for the drive's DeviceNet adapter
 * (drive/drive_devicenet.h), its Identity, motor data and application objects. */
#ifndef ATV312_DEVICENET_H
#define ATV312_DEVICENET_H

#include "drive/drive_devicenet.h"

extern const drive_dn_profile_t atv312_devicenet_profile;

#endif
