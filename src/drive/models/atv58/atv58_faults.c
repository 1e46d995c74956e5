/* SPDX-License-Identifier: Apache-2.0 */
/* The faults of the Altivar 58 (docs/atv58.md, "Faults"): its CANopen card manual's EMCY code
 * table, the manuals' only one (docs/manuals.md), code for code (a code printed in brackets is the
 * project's reading). The card's error register is "=0 no fault, =1 fault": 1001h bit 0 alone, so
 * no entry adds a class bit. Reset classes as the Altivar 31/312 family's for the faults they
 * share (src/drive/models/atv312/atv312_faults.c), the ATV58's own ones (ANF, TSF, SPF) by command.
 * Every fault freewheels: the card's manual gives no stop (the project's choice, docs/atv58.md). */
#include "atv58/atv58.h"

#define COMMAND DRIVE_FAULT_RESET_COMMAND
#define AUTOMATIC DRIVE_FAULT_RESET_AUTOMATIC
#define POWER_CYCLE DRIVE_FAULT_RESET_POWER_CYCLE
#define FREEWHEEL DRIVE_FAULT_FREEWHEEL

/* Entry 0 is the life guarding time-out, the card's only communication-loss fault (it has no
 * heartbeat): "Communication error (Life Guard time out)", EMCY 8130h. */
static const drive_fault_def_t faults[] = {
    {"CnF", "communication error (life guard time out)", 0x8130, 0, COMMAND, FREEWHEEL},
    {"CrF", "load relay fault", 0x1000, 0, POWER_CYCLE, FREEWHEEL},
    {"OLF", "motor overload fault (thermal simulation or PTC)", 0x1000, 0, COMMAND, FREEWHEEL},
    {"SOF", "overspeed fault", 0x1000, 0, POWER_CYCLE, FREEWHEEL},
    {"OCF", "overcurrent fault (prolonged ICL)", 0x2310, 0, POWER_CYCLE, FREEWHEEL},
    {"SCF", "motor short-circuit fault (phase, earth)", 0x2320, 0, POWER_CYCLE, FREEWHEEL},
    {"OSF", "line supply overvoltage fault", 0x3110, 0, COMMAND, FREEWHEEL},
    {"USF", "line supply undervoltage fault (> 200 ms)", 0x3120, 0, AUTOMATIC, FREEWHEEL},
    {"PHF", "line supply phase loss fault (> 1 s)", 0x3130, 0, COMMAND, FREEWHEEL},
    {"ObF", "DC bus overvoltage fault", 0x3310, 0, COMMAND, FREEWHEEL},
    {"OPF", "motor phase loss fault", 0x3310, 0, COMMAND, FREEWHEEL},
    {"OHF", "drive overheating fault (on heatsink)", 0x4210, 0, COMMAND, FREEWHEEL},
    {"OtF", "motor overheating fault (PTC)", 0x4310, 0, COMMAND, FREEWHEEL},
    {"EEF", "EEPROM memory fault", 0x5520, 0, POWER_CYCLE, FREEWHEEL},
    {"InF", "internal fault", 0x6100, 0, POWER_CYCLE, FREEWHEEL},
    {"CFF", "configuration incorrect (on initialisation)", 0x6300, 0, AUTOMATIC, FREEWHEEL},
    {"CFI", "configuration invalid (when written)", 0x6300, 0, AUTOMATIC, FREEWHEEL},
    {"AnF", "load veering fault", 0x7300, 0, COMMAND, FREEWHEEL},
    {"LFF", "loss of 4-20 mA", 0x7300, 0, COMMAND, FREEWHEEL},
    {"tSF", "PTC probe fault", 0x7300, 0, COMMAND, FREEWHEEL},
    {"SPF", "speed feedback cut-off fault", 0x7310, 0, COMMAND, FREEWHEEL},
    {"SLF", "standard communication link fault (link break)", 0x7510, 0, COMMAND, FREEWHEEL},
    {"ILF", "fast communication link fault (link break)", 0x7520, 0, POWER_CYCLE, FREEWHEEL},
    {"EPF", "external fault", 0x9000, 0, COMMAND, FREEWHEEL},
};

const drive_fault_table_t atv58_faults = {
    .faults = faults,
    .count = sizeof faults / sizeof faults[0],
    .communication_loss = 0,
};
