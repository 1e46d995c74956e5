/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 402 power state machine of a drive (CiA 402 "device control"), as the Drivecom profile
 * of the Altivar drives applies it (ATV312 DeviceNet manual, "CMD control word", "ETA status word",
 * "IEC 61800-7 status chart"; docs/decisions.md, D-STATE-MACHINE): the states, the commands of
 * control word bits 0-3 and 7, the state bits of the status word. It knows nothing of a dictionary
 * or a motor: the drive (drive.h) feeds it the control word and tells it when the motor stands. */
#ifndef DRIVE_CIA402_H
#define DRIVE_CIA402_H

#include <stdbool.h>
#include <stdint.h>

/* "Not ready to switch on" is transient and never visible here: initialisation is instantaneous.
 * "Fault reaction active" ("Malfunction reaction active" in the Drivecom tables) lasts while a
 * fault's ramp or fast stop runs; a freewheel reaction goes straight on to Fault. */
typedef enum cia402_state {
    CIA402_SWITCH_ON_DISABLED,
    CIA402_READY_TO_SWITCH_ON,
    CIA402_SWITCHED_ON,
    CIA402_OPERATION_ENABLED,
    CIA402_QUICK_STOP_ACTIVE,
    CIA402_FAULT_REACTION_ACTIVE,
    CIA402_FAULT
} cia402_state_t;

/* The state and the last control word, for the fault reset edge. */
typedef struct cia402_state_machine {
    cia402_state_t state;
    uint16_t control; /* last control word written (6040h) */
} cia402_state_machine_t;

/* Control word 6040h bits that CiA 402 defines; bits 11-15 are the manufacturer's (the model's
 * drive_profile_t says what they do). */
#define CIA402_CW_SWITCH_ON 0x0001u
#define CIA402_CW_ENABLE_VOLTAGE 0x0002u
#define CIA402_CW_QUICK_STOP 0x0004u /* active at 0 */
#define CIA402_CW_ENABLE_OPERATION 0x0008u
#define CIA402_CW_FAULT_RESET 0x0080u /* on the 0 -> 1 edge only */

/* Status word 6041h: the state (mask 0x006F) and the CiA 402 bits the drive sets beyond it. */
#define CIA402_SW_STATE_MASK 0x006Fu
#define CIA402_SW_WARNING 0x0080u        /* a warning is present (the Altivars' "Alarm") */
#define CIA402_SW_REMOTE 0x0200u         /* network control (forced local is active at 0) */
#define CIA402_SW_TARGET_REACHED 0x0400u /* the speed equals its target */
#define CIA402_SW_INTERNAL_LIMIT 0x0800u /* the reference was clipped to the speed limits */

void cia402_reset(cia402_state_machine_t *sm);
/* Applies a control word written by SDO or RPDO. Returns true when it acknowledged a fault
 * (transition 15, on the 0 -> 1 edge of bit 7). */
bool cia402_command(cia402_state_machine_t *sm, uint16_t control, bool motor_stopped);
/* The motor stands: completes a disable operation (5) that waited for the end of its ramp, and
 * a fault reaction (14: Fault reaction active -> Fault). */
void cia402_motor_stopped(cia402_state_machine_t *sm);
/* Only Operation enabled, Quick stop active and Fault reaction active apply voltage to the motor;
 * every other state leaves it to coast (freewheel). */
bool cia402_drives_motor(const cia402_state_machine_t *sm);
/* Operation enabled with an enable operation command: the motor follows the reference (rather
 * than stopping on the DEC ramp for a pending disable operation). */
bool cia402_runs(const cia402_state_machine_t *sm);
/* Transition 13: Fault reaction active while the reaction stops the motor on a ramp
 * (`stopping`), else at once on to Fault (14). The control word is recorded and not obeyed
 * until Fault, where only the fault reset edge counts. */
void cia402_fault(cia402_state_machine_t *sm, bool stopping);
/* Fault reaction active or Fault: a fault latches the drive. */
bool cia402_faulted(const cia402_state_machine_t *sm);
/* The last fault ended by itself (a fault whose cause went away): Fault (or Fault reaction
 * active) -> Switch on disabled, as a fault reset would. */
void cia402_fault_cleared(cia402_state_machine_t *sm);
/* A configuration parameter changed: Ready to switch on, Switched on and Operation enabled
 * return to Switch on disabled. */
void cia402_configuration_changed(cia402_state_machine_t *sm);
/* The state bits of the status word (within CIA402_SW_STATE_MASK). */
uint16_t cia402_status(const cia402_state_machine_t *sm);
/* "Switch on disabled", "Operation enabled", ... */
const char *cia402_state_name(cia402_state_t state);

#endif
