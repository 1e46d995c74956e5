/* SPDX-License-Identifier: Apache-2.0 */
/* The faults of a drive: a model's table of the faults its manuals list (front panel code, EMCY
 * code, error register class, how the fault may be reset, how it stops the motor), and the drive
 * layer's handling of them: a fault injected by a test or raised by the drive (communication
 * loss) stops the motor as its reaction says (CiA 402 Fault reaction active while a ramp runs)
 * and latches the power state machine in Fault (state Fault drives nothing), puts its EMCY code
 * in 603Fh, sends the EMCY (which records it in 1001h and 1003h), and is reset by the rule of its
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

/* How a fault stops the motor (the fault reaction of CiA 402), quickest first. A ramp or fast
 * stop runs in Fault reaction active with the output on, then the drive is in Fault; a motor that
 * is not driven (output off, or standing) goes to Fault at once. A stop already running on the
 * fast ramp is never slowed by a ramp reaction, and a freewheel fault during a reaction cuts it. */
typedef enum drive_fault_reaction {
    DRIVE_FAULT_FREEWHEEL, /* the output is cut at once: Fault, the motor coasts */
    DRIVE_FAULT_FAST_STOP, /* the fast ramp (the profile's fast_ramp_divider) */
    DRIVE_FAULT_RAMP_STOP  /* the deceleration ramp */
} drive_fault_reaction_t;

typedef struct drive_fault_def {
    const char *code;       /* as the front panel shows it: "OHF", "CnF" */
    const char *meaning;    /* "drive overheating" */
    uint16_t emcy_code;     /* EMCY error code, also 603Fh */
    uint8_t error_register; /* 1001h bits besides the generic bit 0 (CO_ERR_REG_*) */
    drive_fault_reset_t reset;
    /* The communication-loss fault's is the profile's communication_loss_mode where the model
     * has that parameter (drive.h); this one where it has not, or says ignore. */
    drive_fault_reaction_t reaction;
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
