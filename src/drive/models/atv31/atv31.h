/* SPDX-License-Identifier: Apache-2.0 */
/* The Schneider Altivar 31 model of the CiA 402 velocity drive (drive/drive.h). The ATV31 is the
 * ATV312 under another name (its manual's tables are the ATV312's but for 1008h "ATV31"), so its
 * profiles are the family's (atv312/atv312.h) on its own dictionaries, both generated from
 * eds/ATV31.eds with the ATV312's hooks:
 * - atv31_profile, atv31_od (ATV31_OD_DATA_SIZE bytes a node): firmware V1.2 and later, with the
 *   heartbeat objects 1016h/1017h;
 * - atv31_v11_profile, atv31_v11_od (ATV31_V11_OD_DATA_SIZE): before V1.2, which has no heartbeat
 *   (manual, foreword): 1016h and 1017h do not exist, error control is node guarding only.
 * Portable like the core: no malloc, no OS calls, no globals. */
#ifndef ATV31_H
#define ATV31_H

#include "atv312/atv312.h"
#include "atv31_od.h"     /* generated */
#include "atv31_v11_od.h" /* generated */

/* Logic inputs LI1-LI6 on the ATV31's own terminals (its CANopen port is built in; the project's
 * choice: the ATV31 manual names no input), switching sources. */
#define ATV31_LOGIC_INPUTS 6

/* The ATV31 manual's object table prints "unit = 1 ms" for the inhibit time of both TPDO1 and TPDO6
 * (1800h:03, 1805h:03), where the ATV312's prints 0.1 ms for TPDO6 (docs/decisions.md,
 * D-INHIBIT-TIME): the bits of TPDO1 and TPDO6 (co_node_config_t.tpdo_inhibit_ms). */
#define ATV31_TPDO_INHIBIT_MS ((1u << 0) | (1u << 5))

extern const drive_profile_t atv31_profile;
extern const drive_profile_t atv31_v11_profile;

#endif
