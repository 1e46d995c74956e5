/* CiA 402 / Drivecom power state machine of the ATV312 (ATV312 DeviceNet manual, "CMD control
 * word", "ETA status word", "Drive state machine"; SPEC section 3). */
#ifndef ATV312_CIA402_H
#define ATV312_CIA402_H

#include "atv312/atv312.h"

/* Control word 6040h (CMD), bits 0-7 per CiA 402, bits 11-14 per the ATV312 default
 * assignment ("CMD = 16#080F: reverse operation" ...). */
#define ATV312_CW_SWITCH_ON 0x0001u
#define ATV312_CW_ENABLE_VOLTAGE 0x0002u
#define ATV312_CW_QUICK_STOP 0x0004u /* active at 0 */
#define ATV312_CW_ENABLE_OPERATION 0x0008u
#define ATV312_CW_FAULT_RESET 0x0080u /* on the 0 -> 1 edge only */
#define ATV312_CW_REVERSE 0x0800u
#define ATV312_CW_STOP 0x1000u         /* ramp stop (Stt = ramp), run command kept */
#define ATV312_CW_DC_INJECTION 0x2000u /* DC injection stop */
#define ATV312_CW_FAST_STOP 0x4000u    /* short ramp, stays in Operation enabled */

/* Status word 6041h (ETA) bits beyond the state (mask 0x006F). */
#define ATV312_SW_STATE_MASK 0x006Fu
#define ATV312_SW_REMOTE 0x0200u         /* network control (forced local is active at 0) */
#define ATV312_SW_TARGET_REACHED 0x0400u /* reference reached */
#define ATV312_SW_INTERNAL_LIMIT 0x0800u /* reference exceeded: clipped to LSP / HSP */
#define ATV312_SW_REVERSE 0x8000u        /* direction of rotation */

void atv312_cia402_reset(atv312_cia402_t *sm);
/* Applies a control word written by SDO or RPDO. Returns true when it acknowledged a fault
 * (transition 15, on the 0 -> 1 edge of bit 7). */
bool atv312_cia402_command(atv312_cia402_t *sm, uint16_t control, bool motor_stopped);
/* The motor stands: completes a disable operation (5) that waited for the end of its ramp. */
void atv312_cia402_motor_stopped(atv312_cia402_t *sm);
/* Only Operation enabled and Quick stop active apply voltage to the motor; every other state
 * leaves it to coast (freewheel). */
bool atv312_cia402_drives_motor(const atv312_cia402_t *sm);
/* Operation enabled with an enable operation command: the motor follows the reference (rather
 * than stopping on the DEC ramp for a pending disable operation). */
bool atv312_cia402_runs(const atv312_cia402_t *sm);
/* Transitions 13 and 14: the fault reaction (a freewheel stop) is immediate. */
void atv312_cia402_fault(atv312_cia402_t *sm);
/* A configuration parameter changed: Ready to switch on, Switched on and Operation enabled
 * return to Switch on disabled. */
void atv312_cia402_configuration_changed(atv312_cia402_t *sm);
/* The state bits of the status word (within ATV312_SW_STATE_MASK). */
uint16_t atv312_cia402_status(const atv312_cia402_t *sm);
const char *atv312_cia402_name(atv312_state_t state);

#endif
