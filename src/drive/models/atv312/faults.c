/* The faults of the Altivar 31/312 family (docs/atv312.md, "Faults"). Codes as the front panel
 * shows them; EMCY codes from the manuals' only code table, the Altivar 58 CANopen card manual's
 * (the ATV31/312 manuals: "the Emergency Error Code is the same as the variable Fault code
 * (603F)" without a list), where the ATV58 and the ATV312 share the fault; the error register
 * class is the CiA 301 class of the code. Reset classes after the Altivar 31/312 programming
 * manual's three lists (not among docs/manuals.md: the project's reading). Every fault freewheels:
 * the manuals give a stop to CnF alone, chosen by COL (the profile's communication_loss_mode), and
 * nothing for the others (the project's choice, docs/atv312.md). */
#include "atv312/atv312.h"
#include "co/co_emcy.h"

#define CURRENT CO_ERR_REG_CURRENT
#define VOLTAGE CO_ERR_REG_VOLTAGE
#define TEMPERATURE CO_ERR_REG_TEMPERATURE
#define COMMUNICATION CO_ERR_REG_COMMUNICATION
#define COMMAND DRIVE_FAULT_RESET_COMMAND
#define AUTOMATIC DRIVE_FAULT_RESET_AUTOMATIC
#define POWER_CYCLE DRIVE_FAULT_RESET_POWER_CYCLE
#define FREEWHEEL DRIVE_FAULT_FREEWHEEL

/* The communication-loss fault (life guarding or heartbeat consumer timeout) is entry 0: CnF,
 * the network fault as the DeviceNet manual names it (docs/decisions.md, D-COMM-LOSS-CNF; the
 * ATV312 CANopen manual calls the life guarding fault COF), EMCY 0x8130. */
static const drive_fault_def_t faults[] = {
    {"CnF", "network fault (life guarding, heartbeat)", 0x8130, COMMUNICATION, COMMAND, FREEWHEEL},
    {"ILF", "internal communication link fault (option card)", 0x7520, COMMUNICATION, POWER_CYCLE,
     FREEWHEEL},
    {"SLF", "Modbus serial link fault", 0x7510, COMMUNICATION, COMMAND, FREEWHEEL},
    {"OCF", "overcurrent", 0x2310, CURRENT, POWER_CYCLE, FREEWHEEL},
    {"SCF", "motor short circuit (phase, earth)", 0x2320, CURRENT, POWER_CYCLE, FREEWHEEL},
    {"OSF", "line supply overvoltage", 0x3110, VOLTAGE, COMMAND, FREEWHEEL},
    {"USF", "line supply undervoltage", 0x3120, VOLTAGE, AUTOMATIC, FREEWHEEL},
    {"PHF", "line supply phase loss", 0x3130, VOLTAGE, COMMAND, FREEWHEEL},
    {"ObF", "DC bus overvoltage (overbraking)", 0x3310, VOLTAGE, COMMAND, FREEWHEEL},
    {"OPF", "motor phase loss", 0x3310, VOLTAGE, COMMAND, FREEWHEEL},
    {"OHF", "drive overheating", 0x4210, TEMPERATURE, COMMAND, FREEWHEEL},
    {"OtF", "motor overheating", 0x4310, TEMPERATURE, COMMAND, FREEWHEEL},
    {"OLF", "motor overload", 0x1000, 0, COMMAND, FREEWHEEL},
    {"SOF", "overspeed", 0x1000, 0, POWER_CYCLE, FREEWHEEL},
    {"CrF", "load relay (precharge) fault", 0x1000, 0, POWER_CYCLE, FREEWHEEL},
    {"EEF", "EEPROM memory fault", 0x5520, 0, POWER_CYCLE, FREEWHEEL},
    {"InF", "internal fault", 0x6100, 0, POWER_CYCLE, FREEWHEEL},
    {"CFF", "incorrect configuration (at power on)", 0x6300, 0, AUTOMATIC, FREEWHEEL},
    {"CFI", "invalid configuration (written)", 0x6300, 0, AUTOMATIC, FREEWHEEL},
    {"LFF", "loss of the 4-20 mA reference", 0x7300, 0, COMMAND, FREEWHEEL},
    {"EPF", "external fault", 0x9000, 0, COMMAND, FREEWHEEL},
};

const drive_fault_table_t atv312_family_faults = {
    .faults = faults,
    .count = sizeof faults / sizeof faults[0],
    .communication_loss = 0,
};
