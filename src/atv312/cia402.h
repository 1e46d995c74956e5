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

/* What a transition asks of the rest of the drive. */
#define ATV312_EVENT_FREEWHEEL 0x01u   /* output off: the motor coasts (transitions 8, 9) */
#define ATV312_EVENT_FAULT_RESET 0x02u /* transition 15: the fault is acknowledged */

void atv312_cia402_reset(atv312_cia402_t *sm);
/* Applies a control word written by SDO or RPDO. Returns ATV312_EVENT_* bits. */
unsigned atv312_cia402_command(atv312_cia402_t *sm, uint16_t control);
/* Transitions 13 and 14: the fault reaction (a freewheel stop) is immediate. */
void atv312_cia402_fault(atv312_cia402_t *sm);
/* A configuration parameter changed: Ready to switch on, Switched on and Operation enabled
 * return to Switch on disabled. */
void atv312_cia402_configuration_changed(atv312_cia402_t *sm);
/* The state bits of the status word (within ATV312_SW_STATE_MASK). */
uint16_t atv312_cia402_status(const atv312_cia402_t *sm);
const char *atv312_cia402_name(atv312_state_t state);

#endif
