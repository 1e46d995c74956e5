/* The faults of a drive: a model's table of the faults its manuals list (front panel code, EMCY
 * code, error register class, how the fault may be reset), and the drive layer's handling of
 * them: a fault injected by a test or raised by the drive (communication loss) latches the power
 * state machine in Fault (a freewheel stop: state Fault drives nothing), puts its EMCY code in
 * 603Fh, sends the EMCY (which records it in 1001h and 1003h), and is reset by the rule of its
 * class. The cause of an injected fault stays present until it is removed. Portable like the
 * core. See docs/drive.md, "Faults". */
#ifndef DRIVE_FAULTS_H
#define DRIVE_FAULTS_H

#include "co/co_types.h"

/* How a fault is reset: the three classes of the Altivar programming manuals. */
typedef enum drive_fault_reset {
    /* A fault reset (the 0 -> 1 edge of 6040h bit 7) once the cause is gone; refused before. */
    DRIVE_FAULT_RESET_COMMAND,
    /* Resets itself as soon as the cause is gone (mains undervoltage, bad configuration). */
    DRIVE_FAULT_RESET_AUTOMATIC,
    /* Only a power cycle (NMT reset node, for an emulated drive) with the cause gone. */
    DRIVE_FAULT_RESET_POWER_CYCLE
} drive_fault_reset_t;

typedef struct drive_fault_def {
    const char *code;       /* as the front panel shows it: "OHF", "CnF" */
    const char *meaning;    /* "drive overheating" */
    uint16_t emcy_code;     /* EMCY error code, also 603Fh */
    uint8_t error_register; /* 1001h bits besides the generic bit 0 (CO_ERR_REG_*) */
    drive_fault_reset_t reset;
} drive_fault_def_t;

/* At most this many faults a model: the drive keeps one bit per fault. */
#define DRIVE_FAULTS_MAX 32

typedef struct drive_fault_table {
    const drive_fault_def_t *faults;
    uint8_t count; /* 1..DRIVE_FAULTS_MAX */
    /* The entry of the network fault the drive raises itself on a heartbeat consumer or life
     * guarding timeout. */
    uint8_t communication_loss;
} drive_fault_table_t;

#endif
