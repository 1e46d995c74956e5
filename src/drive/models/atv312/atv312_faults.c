/* SPDX-License-Identifier: Apache-2.0 */
/* The faults of the Altivar 31/312 family (docs/atv312.md, "Faults"). Codes as the front panel
 * shows them; EMCY codes from the manuals' only code table, the Altivar 58 CANopen card manual's
 * (the ATV31/312 manuals: "the Emergency Error Code is the same as the variable Fault code
 * (603F)" without a list), where the ATV58 and the ATV312 share the fault. No entry adds a class
 * bit to 1001h: the manuals' EMCY byte 2 is "=0 (no error) =1 (error)" (docs/decisions.md,
 * D-ERROR-REGISTER). Reset classes after the Altivar 31/312 programming manual's three lists (not
 * among docs/manuals.md: the project's reading). Every fault freewheels: the manuals give a stop
 * to the communication loss alone, chosen by COL (the profile's communication_loss_mode), and
 * nothing for the others (the project's choice, docs/atv312.md). */
#include "atv312/atv312.h"

#define COMMAND DRIVE_FAULT_RESET_COMMAND
#define AUTOMATIC DRIVE_FAULT_RESET_AUTOMATIC
#define POWER_CYCLE DRIVE_FAULT_RESET_POWER_CYCLE
#define FREEWHEEL DRIVE_FAULT_FREEWHEEL

/* The communication-loss fault (life guarding or heartbeat consumer timeout) is entry 0, EMCY
 * 0x8130 (docs/decisions.md, D-COMM-LOSS-CNF), named as the manual of the bus the drive is on
 * names it (D-ATV312-COF): on CANopen COF, the ATV312 CANopen manual's life guarding fault ("the
 * drive will display COF (CANopen communication fault)"), as the ATV31's ("goes to COF fault");
 * behind the DeviceNet card CnF, the DeviceNet manual's "communication between the master ... and
 * the drive is broken: ... (CnF)". */
static const drive_fault_def_t atv312_faults[] = {
    {"COF", "CANopen communication fault (life guarding, heartbeat)", 0x8130, 0, COMMAND,
     FREEWHEEL},
#include "atv312/family_faults.inc"
};

/* Behind the DeviceNet card, COF is the card itself not working (the DeviceNet manual's "The
 * communication card is not working properly ... (COF)", "Interruption in communication between
 * the option card and the drive"): ILF's cause and EMCY code, reset by command once the card
 * works again ("Check the option card"), where ILF needs a power cycle ("Replace the option
 * card"). */
static const drive_fault_def_t atv312_devicenet_faults_defs[] = {
    {"CnF", "network fault (I/O connection time out)", 0x8130, 0, COMMAND, FREEWHEEL},
    {"COF", "communication card fault (the card and the drive do not communicate)", 0x7520, 0,
     COMMAND, FREEWHEEL},
#include "atv312/family_faults.inc"
};

const drive_fault_table_t atv312_family_faults = {
    .faults = atv312_faults,
    .count = sizeof atv312_faults / sizeof atv312_faults[0],
    .communication_loss = 0,
};

const drive_fault_table_t atv312_devicenet_faults = {
    .faults = atv312_devicenet_faults_defs,
    .count = sizeof atv312_devicenet_faults_defs / sizeof atv312_devicenet_faults_defs[0],
    .communication_loss = 0,
};
