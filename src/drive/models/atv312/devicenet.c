/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 312 behind its DeviceNet card VW3A312 09 (Altivar 312 DeviceNet manual): the
 * Identity the manual gives, the motor data it lists and the application objects' address formula
 * ("Explicit Messaging": class ((ADL - 3000) / 200) + 70h, attribute ADL mod 200 + 1, instance 1,
 * classes 70h..A8h), on the dictionary's addresses of docs/decisions.md, D-MANUFACTURER-ADDRESS
 * (index 2000h + (ADL - 3000) / 100, sub-index ADL mod 100 + 1). */
#include "atv312/atv312_devicenet.h"

#include "atv312/atv312.h"

const drive_dn_profile_t atv312_devicenet_profile = {
    .drive = &atv312_devicenet_drive_profile,
    .vendor_id = 0x00F3,   /* Schneider Electric */
    .device_type = 0x0002, /* AC drive */
    .product_code = 6153,
    .major_revision = 1,
    .minor_revision = 1,
    .product_name = "ATV312",
    .motor_type = 7, /* squirrel cage induction motor */
    /* UnS, ADL 9601 (docs/decisions.md, D-DEVICENET-RATED-VOLTAGE). */
    .rated_voltage = DRIVE_PARAM(0x2042, 2),
    /* CFF, the incorrect configuration (at power on); CFI, an inconsistent one written. */
    .commissioning_faults = {"CFF", "CFI"},
    .class_first = 0x70,
    .class_last = 0xA8,
    .address_first = 3000,
    .addresses_per_class = 200,
    .index_first = 0x2000,
    .addresses_per_index = 100,
};
