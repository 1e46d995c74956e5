/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 58's profile. The card's manual names ACC (5FE5h:03) alone among the drive's
 * parameters; the others are the drive's own settings, fixed here (docs/atv58.md): 50 Hz is
 * 1500 rpm, the manual's "1500 rpm, the terminal displays 50 Hz (motor 4 poles)", and the high
 * speed, so that LFRD 1500 runs at 1500 rpm (its ETAD/RFRD example); DEC 3 s, the factory
 * setting of ACC as well. Control word bits 11-15 have no meaning the card's manual gives. */
#include "atv58/atv58.h"

const drive_profile_t atv58_profile = {
    .od = &atv58_od,
    .node_options = CO_NODE_PAD_DLC8 | CO_NODE_SDO_EXPEDITED_ONLY | CO_NODE_SDO_LONG_EXPEDITED |
                    CO_NODE_SDO_ERROR_CLASS | CO_NODE_NMT_DISCONNECT |
                    /* 1001h in every EMCY: "=0 no fault, =1 fault", the core's too. */
                    CO_NODE_ERROR_REGISTER_GENERIC,
    .node_options_code = &co_node_options,
    .faults = &atv58_faults,
    .indicators = atv58_indicators,
    .indicator_count = ATV58_INDICATORS,
    .acceleration = DRIVE_PARAM(0x5FE5, 3),
    .deceleration = DRIVE_FIXED(30),
    .low_speed = DRIVE_FIXED(0),
    .high_speed = DRIVE_FIXED(500),
    .nominal_frequency = DRIVE_FIXED(500),
    .nominal_speed = DRIVE_FIXED(1500),
};
