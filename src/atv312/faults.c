/* The faults of the Altivar 31/312 family (docs/atv312.md, "Faults"). Codes as the front panel
 * shows them; EMCY codes from the only code table of the seeds, the Altivar 58 CANopen manual's
 * (the ATV31/312 manuals: "the Emergency Error Code is the same as the variable Fault code
 * (603F)" without a list), where the ATV58 and the ATV312 share the fault; the error register
 * class is the CiA 301 class of the code. Reset classes after the Altivar 31/312 programming
 * manual's three lists (not among the seeds: the project's reading). */
#include "atv312/atv312.h"
#include "co/co_emcy.h"

#define CURRENT CO_ERR_REG_CURRENT
#define VOLTAGE CO_ERR_REG_VOLTAGE
#define TEMPERATURE CO_ERR_REG_TEMPERATURE
#define COMMUNICATION CO_ERR_REG_COMMUNICATION
#define COMMAND DRIVE_FAULT_RESET_COMMAND
#define AUTOMATIC DRIVE_FAULT_RESET_AUTOMATIC
#define POWER_CYCLE DRIVE_FAULT_RESET_POWER_CYCLE

/* The communication-loss fault (life guarding or heartbeat consumer timeout) is entry 0: CnF,
 * the network fault as SPEC section 3 names it (the ATV312 CANopen manual calls the life guarding
 * fault COF), EMCY 0x8130. */
static const drive_fault_def_t faults[] = {
    {"CnF", "network fault (life guarding, heartbeat)", 0x8130, COMMUNICATION, COMMAND},
    {"ILF", "internal communication link fault (option card)", 0x7520, COMMUNICATION, POWER_CYCLE},
    {"SLF", "Modbus serial link fault", 0x7510, COMMUNICATION, COMMAND},
    {"OCF", "overcurrent", 0x2310, CURRENT, POWER_CYCLE},
    {"SCF", "motor short circuit (phase, earth)", 0x2320, CURRENT, POWER_CYCLE},
    {"OSF", "line supply overvoltage", 0x3110, VOLTAGE, COMMAND},
    {"USF", "line supply undervoltage", 0x3120, VOLTAGE, AUTOMATIC},
    {"PHF", "line supply phase loss", 0x3130, VOLTAGE, COMMAND},
    {"ObF", "DC bus overvoltage (overbraking)", 0x3310, VOLTAGE, COMMAND},
    {"OPF", "motor phase loss", 0x3310, VOLTAGE, COMMAND},
    {"OHF", "drive overheating", 0x4210, TEMPERATURE, COMMAND},
    {"OtF", "motor overheating", 0x4310, TEMPERATURE, COMMAND},
    {"OLF", "motor overload", 0x1000, 0, COMMAND},
    {"SOF", "overspeed", 0x1000, 0, POWER_CYCLE},
    {"CrF", "load relay (precharge) fault", 0x1000, 0, POWER_CYCLE},
    {"EEF", "EEPROM memory fault", 0x5520, 0, POWER_CYCLE},
    {"InF", "internal fault", 0x6100, 0, POWER_CYCLE},
    {"CFF", "incorrect configuration (at power on)", 0x6300, 0, AUTOMATIC},
    {"CFI", "invalid configuration (written)", 0x6300, 0, AUTOMATIC},
    {"LFF", "loss of the 4-20 mA reference", 0x7300, 0, COMMAND},
    {"EPF", "external fault", 0x9000, 0, COMMAND},
};

const drive_fault_table_t atv312_family_faults = {
    .faults = faults,
    .count = sizeof faults / sizeof faults[0],
    .communication_loss = 0,
};
