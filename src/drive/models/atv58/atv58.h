/* SPDX-License-Identifier: Apache-2.0 */
/* The Schneider Altivar 58 with its VW3-A58308 CANopen card, a model of the CiA 402 velocity drive
 * (drive/drive.h): its dictionary atv58_od (generated from eds/ATV58.eds without 1018h, with the
 * hooks of src/drive/models/atv58/atv58.hooks; ATV58_OD_DATA_SIZE bytes a node) and its profile.
 * The card is an older profile (DS301 V4.0): the profile picks the core's options for it (8-byte
 * frames, expedited-only SDO with its error layout, long expedited writes, NMT Disconnect), and
 * its dictionary has what the card lacks absent: no SYNC, no heartbeat, one fixed PDO pair.
 * Node-ids are 1..ATV58_NODE_ID_MAX. docs/atv58.md. Portable like the core: no malloc, no OS
 * calls, no globals. */
#ifndef ATV58_H
#define ATV58_H

#include "atv58/atv58_emcy.h"
#include "atv58_od.h" /* generated */
#include "drive/drive.h"
#include "drive/panel.h"

/* The card's address switches 3 to 8: 1..63 (0 unused). */
#define ATV58_NODE_ID_MAX 63

extern const drive_profile_t atv58_profile;
/* The faults of its manual's EMCY table (src/drive/models/atv58/atv58_faults.c). */
extern const drive_fault_table_t atv58_faults;
/* The card's green OK and yellow COM LEDs (src/drive/models/atv58/indicators.c). */
#define ATV58_INDICATORS 2
extern const drive_indicator_t atv58_indicators[ATV58_INDICATORS];

#endif
