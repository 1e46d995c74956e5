/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 402 / Drivecom power state machine: the command table and the state table of the ATV312
 * DeviceNet manual ("CMD control word", "ETA status word"), the transition numbers of CiA 402. */
#include "drive/cia402.h"

/* The commands of the manual's table, decoded from bits 0-3 in its priority order. */
typedef enum command {
    COMMAND_DISABLE_VOLTAGE, /* bit 1 = 0: transitions 7, 9, 10, 12 */
    COMMAND_QUICK_STOP,      /* bit 2 = 0, bit 1 = 1: transitions 7, 10, 11 */
    COMMAND_SHUTDOWN,        /* x110: transitions 2, 6, 8 */
    COMMAND_SWITCH_ON,       /* 0111: transition 3, disable operation 5 */
    COMMAND_ENABLE_OPERATION /* 1111: transition 4 (3 then 4 from Ready to switch on) */
} command_t;

static command_t decode(uint16_t control)
{
    if (!(control & CIA402_CW_ENABLE_VOLTAGE))
        return COMMAND_DISABLE_VOLTAGE;
    if (!(control & CIA402_CW_QUICK_STOP))
        return COMMAND_QUICK_STOP;
    if (!(control & CIA402_CW_SWITCH_ON))
        return COMMAND_SHUTDOWN;
    if (!(control & CIA402_CW_ENABLE_OPERATION))
        return COMMAND_SWITCH_ON;
    return COMMAND_ENABLE_OPERATION;
}

/* One transition of the state chart. Disable operation (5) is the only one that waits for the
 * motor: the drive stays in Operation enabled while it stops on the DEC ramp (the DeviceNet
 * manual's status table: "Operation enabled 0x0027" with "cmdd bit 3 = 0"), since Switched on
 * applies no voltage to the motor. */
static cia402_state_t transition(cia402_state_t state, command_t command, bool motor_stopped)
{
    switch (state) {
    case CIA402_SWITCH_ON_DISABLED:
        return command == COMMAND_SHUTDOWN ? CIA402_READY_TO_SWITCH_ON : state;
    case CIA402_READY_TO_SWITCH_ON:
        if (command == COMMAND_DISABLE_VOLTAGE || command == COMMAND_QUICK_STOP)
            return CIA402_SWITCH_ON_DISABLED;
        if (command == COMMAND_SWITCH_ON || command == COMMAND_ENABLE_OPERATION)
            return CIA402_SWITCHED_ON;
        return state;
    case CIA402_SWITCHED_ON:
        if (command == COMMAND_DISABLE_VOLTAGE || command == COMMAND_QUICK_STOP)
            return CIA402_SWITCH_ON_DISABLED;
        if (command == COMMAND_SHUTDOWN)
            return CIA402_READY_TO_SWITCH_ON;
        if (command == COMMAND_ENABLE_OPERATION)
            return CIA402_OPERATION_ENABLED;
        return state;
    case CIA402_OPERATION_ENABLED:
        /* "Exiting the Operation enabled status via a Disable voltage (9) or Shutdown (8)
         * command causes a freewheel stop": the new state drives nothing. */
        if (command == COMMAND_DISABLE_VOLTAGE)
            return CIA402_SWITCH_ON_DISABLED;
        if (command == COMMAND_SHUTDOWN)
            return CIA402_READY_TO_SWITCH_ON;
        if (command == COMMAND_QUICK_STOP)
            return CIA402_QUICK_STOP_ACTIVE;
        if (command == COMMAND_SWITCH_ON && motor_stopped)
            return CIA402_SWITCHED_ON;
        return state;
    case CIA402_QUICK_STOP_ACTIVE:
        /* Locked: "restarting is only possible after the drive has changed to the Switch on
         * disabled state" (no transition 16). Disable voltage (12) cuts the output: freewheel. */
        return command == COMMAND_DISABLE_VOLTAGE ? CIA402_SWITCH_ON_DISABLED : state;
    case CIA402_FAULT_REACTION_ACTIVE:
    case CIA402_FAULT:
        return state;
    }
    return state;
}

void cia402_reset(cia402_state_machine_t *sm)
{
    sm->state = CIA402_SWITCH_ON_DISABLED;
    sm->control = 0;
}

bool cia402_command(cia402_state_machine_t *sm, uint16_t control, bool motor_stopped)
{
    bool reset_edge = (control & CIA402_CW_FAULT_RESET) && !(sm->control & CIA402_CW_FAULT_RESET);
    bool fault_reset = sm->state == CIA402_FAULT && reset_edge;
    sm->control = control;
    if (cia402_faulted(sm) && !fault_reset)
        return false;
    if (fault_reset)
        sm->state = CIA402_SWITCH_ON_DISABLED;
    /* The word is a level: follow it until the state is stable (0x000F from Ready to switch on
     * passes through Switched on to Operation enabled). Three steps reach any state. */
    command_t command = decode(control);
    for (int step = 0; step < 3; step++) {
        cia402_state_t next = transition(sm->state, command, motor_stopped);
        if (next == sm->state)
            break;
        sm->state = next;
    }
    return fault_reset;
}

void cia402_motor_stopped(cia402_state_machine_t *sm)
{
    if (sm->state == CIA402_OPERATION_ENABLED && decode(sm->control) == COMMAND_SWITCH_ON)
        sm->state = CIA402_SWITCHED_ON;
    else if (sm->state == CIA402_FAULT_REACTION_ACTIVE)
        sm->state = CIA402_FAULT;
}

bool cia402_drives_motor(const cia402_state_machine_t *sm)
{
    return sm->state == CIA402_OPERATION_ENABLED || sm->state == CIA402_QUICK_STOP_ACTIVE ||
           sm->state == CIA402_FAULT_REACTION_ACTIVE;
}

bool cia402_runs(const cia402_state_machine_t *sm)
{
    return sm->state == CIA402_OPERATION_ENABLED && decode(sm->control) == COMMAND_ENABLE_OPERATION;
}

void cia402_fault(cia402_state_machine_t *sm, bool stopping)
{
    sm->state = stopping ? CIA402_FAULT_REACTION_ACTIVE : CIA402_FAULT;
}

bool cia402_faulted(const cia402_state_machine_t *sm)
{
    return sm->state == CIA402_FAULT_REACTION_ACTIVE || sm->state == CIA402_FAULT;
}

void cia402_fault_cleared(cia402_state_machine_t *sm)
{
    if (cia402_faulted(sm))
        sm->state = CIA402_SWITCH_ON_DISABLED;
}

void cia402_configuration_changed(cia402_state_machine_t *sm)
{
    if (sm->state == CIA402_READY_TO_SWITCH_ON || sm->state == CIA402_SWITCHED_ON ||
        sm->state == CIA402_OPERATION_ENABLED)
        sm->state = CIA402_SWITCH_ON_DISABLED;
}

/* The manual's MSK values (ETA & 0x006F); where it allows two, bit 5 (quick stop) is 1 only
 * in the states where the quick stop function is available. */
uint16_t cia402_status(const cia402_state_machine_t *sm)
{
    switch (sm->state) {
    case CIA402_SWITCH_ON_DISABLED:
        return 0x0040;
    case CIA402_READY_TO_SWITCH_ON:
        return 0x0021;
    case CIA402_SWITCHED_ON:
        return 0x0023;
    case CIA402_OPERATION_ENABLED:
        return 0x0027;
    case CIA402_QUICK_STOP_ACTIVE:
        return 0x0007;
    case CIA402_FAULT_REACTION_ACTIVE:
        return 0x000F;
    case CIA402_FAULT:
        return 0x0008;
    }
    return 0x0008;
}

const char *cia402_state_name(cia402_state_t state)
{
    switch (state) {
    case CIA402_SWITCH_ON_DISABLED:
        return "Switch on disabled";
    case CIA402_READY_TO_SWITCH_ON:
        return "Ready to switch on";
    case CIA402_SWITCHED_ON:
        return "Switched on";
    case CIA402_OPERATION_ENABLED:
        return "Operation enabled";
    case CIA402_QUICK_STOP_ACTIVE:
        return "Quick stop active";
    case CIA402_FAULT_REACTION_ACTIVE:
        return "Fault reaction active";
    case CIA402_FAULT:
        return "Fault";
    }
    return "Fault";
}
