/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 402 master helper: the controlling side of a drive's power state machine (CiA 402 "device
 * control"; the ATV312 CANopen manual's "IEC 61800-7 status chart", "CMD control word" and "ETA
 * status word"). Owns the state coding of the status word 6041h, the commands of the control word
 * 6040h, the path from any state towards a target state, and a non-blocking run to it that ends
 * at the target, at a fault or at a deadline. It only computes: the caller sends each control word
 * it asks for, by SDO (co_sdo_client.h) or in the RPDO that maps 6040h, and feeds it every status
 * word it reads or receives in a TPDO, with the time. No dictionary, no frames: a node or firmware
 * that does not call it does not link it. docs/comaster.md, "comaster drive", uses it. */
#ifndef CO_CIA402_MASTER_H
#define CO_CIA402_MASTER_H

#include "co_types.h"

/* The device control objects and the velocity mode (vl) reference, all UNSIGNED16 but 6042h,
 * INTEGER16 in rpm. */
#define CO_CIA402_CONTROL_WORD 0x6040u
#define CO_CIA402_STATUS_WORD 0x6041u
#define CO_CIA402_VL_TARGET_VELOCITY 0x6042u

/* The commands, as the typical values of the control word's command table (bits 0-3 and 7; the
 * transitions of the state chart they cause). */
#define CO_CIA402_CW_DISABLE_VOLTAGE 0x0000u   /* 7, 9, 10, 12 */
#define CO_CIA402_CW_QUICK_STOP 0x0002u        /* 11 from Operation enabled, else 7, 10 */
#define CO_CIA402_CW_SHUTDOWN 0x0006u          /* 2, 6, 8 */
#define CO_CIA402_CW_SWITCH_ON 0x0007u         /* 3 */
#define CO_CIA402_CW_DISABLE_OPERATION 0x0007u /* 5: the same word as Switch on */
#define CO_CIA402_CW_ENABLE_OPERATION 0x000Fu  /* 4 */
#define CO_CIA402_CW_FAULT_RESET 0x0080u       /* 15, on the 0 -> 1 edge of bit 7 only */

/* The states of the status word's state coding (bits 0-3, 5 and 6). */
typedef enum co_cia402_state {
    CO_CIA402_NO_STATE, /* the bits match no row of the state coding */
    CO_CIA402_NOT_READY_TO_SWITCH_ON,
    CO_CIA402_SWITCH_ON_DISABLED,
    CO_CIA402_READY_TO_SWITCH_ON,
    CO_CIA402_SWITCHED_ON,
    CO_CIA402_OPERATION_ENABLED,
    CO_CIA402_QUICK_STOP_ACTIVE,
    CO_CIA402_FAULT_REACTION_ACTIVE,
    CO_CIA402_FAULT
} co_cia402_state_t;

/* Where a run goes. */
typedef enum co_cia402_target {
    CO_CIA402_TO_OPERATION_ENABLED,
    CO_CIA402_TO_SWITCHED_ON,
    CO_CIA402_TO_READY_TO_SWITCH_ON,
    CO_CIA402_TO_SWITCH_ON_DISABLED,
    /* Quick stop: Operation enabled goes to Quick stop active (11); Ready to switch on and
     * Switched on, which drive no motor, to Switch on disabled (7, 10), where a drive also goes
     * by itself once its quick stop is complete (12): both end the run. */
    CO_CIA402_TO_QUICK_STOP,
    /* Out of Fault by a fault reset (15) to Switch on disabled; any state but Fault and Fault
     * reaction active is already there. */
    CO_CIA402_TO_FAULT_RESET
} co_cia402_target_t;

/* The state a status word codes. */
co_cia402_state_t co_cia402_state(uint16_t status);
/* "Switch on disabled", "Operation enabled", ...; NULL for CO_CIA402_NO_STATE. */
const char *co_cia402_state_name(co_cia402_state_t state);
/* Fault reaction active or Fault: only a fault reset leaves them. */
bool co_cia402_faulted(co_cia402_state_t state);
/* A drive in `state` is where `target` asks. */
bool co_cia402_reached(co_cia402_state_t state, co_cia402_target_t target);
/* The command that moves a drive in `state` one transition towards `target`, and the state it
 * leads to. False when no command does: the target is reached, the drive is in Fault (or Fault
 * reaction active) and the target is not a fault reset, or the drive moves on by itself (Not ready
 * to switch on, Fault reaction active) or shows no state. Quick stop active goes on through Switch
 * on disabled (12) to any other target: transition 16 back to Operation enabled exists only for
 * some quick stop option codes and the Altivars have none. */
bool co_cia402_next(co_cia402_state_t state, co_cia402_target_t target, uint16_t *control,
                    co_cia402_state_t *next);

/* What co_cia402_master_step asks of the caller. */
typedef enum co_cia402_step {
    CO_CIA402_WRITE,     /* send *control to 6040h now, then go on feeding status words */
    CO_CIA402_WAIT,      /* nothing to send: feed the next status word, or this one again later */
    CO_CIA402_REACHED,   /* the drive is where the target asks: the run is over */
    CO_CIA402_FAULTED,   /* Fault or Fault reaction active on the way to another target: over */
    CO_CIA402_TIMED_OUT, /* the state awaited did not come within the timeout: over */
} co_cia402_step_t;

/* One run towards a target. The fields after `timeout` are for reading (messages, traces). */
typedef struct co_cia402_master {
    co_cia402_target_t target;
    co_time_t timeout;         /* how long each awaited state may take, in microseconds */
    co_time_t deadline;        /* of the state awaited */
    co_cia402_state_t state;   /* the state of the last status word */
    co_cia402_state_t awaited; /* the state the last command leads to, or the drive by itself */
    uint16_t control;          /* the last control word asked for */
    bool sent;                 /* `control` was asked for in the current state */
    bool started;              /* a status word came */
    bool reset_bit_low;        /* a word with bit 7 at 0 was asked for since the last reset */
} co_cia402_master_t;

/* Starts a run: the next status word fed decides the first command. */
void co_cia402_master_start(co_cia402_master_t *m, co_cia402_target_t target, co_time_t timeout);
/* Feeds a status word received at `now` and says what to do; *control is set for WRITE. Each
 * command, and each change of state, gives the next state `timeout` from `now`. A fault reset
 * writes Disable voltage first (bit 7 at 0: the word written before the run is unknown), then
 * the reset, which stays in the control word until the next command clears it. */
co_cia402_step_t co_cia402_master_step(co_cia402_master_t *m, uint16_t status, co_time_t now,
                                       uint16_t *control);

#endif
