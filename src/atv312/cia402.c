/* CiA 402 / Drivecom power state machine: the command table and the state table of the ATV312
 * DeviceNet manual ("CMD control word", "ETA status word"), the transition numbers of CiA 402. */
#include "cia402.h"

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
    if (!(control & ATV312_CW_ENABLE_VOLTAGE))
        return COMMAND_DISABLE_VOLTAGE;
    if (!(control & ATV312_CW_QUICK_STOP))
        return COMMAND_QUICK_STOP;
    if (!(control & ATV312_CW_SWITCH_ON))
        return COMMAND_SHUTDOWN;
    if (!(control & ATV312_CW_ENABLE_OPERATION))
        return COMMAND_SWITCH_ON;
    return COMMAND_ENABLE_OPERATION;
}

/* One transition of the state chart. Disable operation (5) is the only one that waits for the
 * motor: the drive stays in Operation enabled while it stops on the DEC ramp (the DeviceNet
 * manual's status table: "Operation enabled 0x0027" with "cmdd bit 3 = 0"), since Switched on
 * applies no voltage to the motor. */
static atv312_state_t transition(atv312_state_t state, command_t command, bool motor_stopped)
{
    switch (state) {
    case ATV312_SWITCH_ON_DISABLED:
        return command == COMMAND_SHUTDOWN ? ATV312_READY_TO_SWITCH_ON : state;
    case ATV312_READY_TO_SWITCH_ON:
        if (command == COMMAND_DISABLE_VOLTAGE || command == COMMAND_QUICK_STOP)
            return ATV312_SWITCH_ON_DISABLED;
        if (command == COMMAND_SWITCH_ON || command == COMMAND_ENABLE_OPERATION)
            return ATV312_SWITCHED_ON;
        return state;
    case ATV312_SWITCHED_ON:
        if (command == COMMAND_DISABLE_VOLTAGE || command == COMMAND_QUICK_STOP)
            return ATV312_SWITCH_ON_DISABLED;
        if (command == COMMAND_SHUTDOWN)
            return ATV312_READY_TO_SWITCH_ON;
        if (command == COMMAND_ENABLE_OPERATION)
            return ATV312_OPERATION_ENABLED;
        return state;
    case ATV312_OPERATION_ENABLED:
        /* "Exiting the Operation enabled status via a Disable voltage (9) or Shutdown (8)
         * command causes a freewheel stop": the new state drives nothing. */
        if (command == COMMAND_DISABLE_VOLTAGE)
            return ATV312_SWITCH_ON_DISABLED;
        if (command == COMMAND_SHUTDOWN)
            return ATV312_READY_TO_SWITCH_ON;
        if (command == COMMAND_QUICK_STOP)
            return ATV312_QUICK_STOP_ACTIVE;
        if (command == COMMAND_SWITCH_ON && motor_stopped)
            return ATV312_SWITCHED_ON;
        return state;
    case ATV312_QUICK_STOP_ACTIVE:
        /* Locked: "restarting is only possible after the drive has changed to the Switch on
         * disabled state" (no transition 16). Disable voltage (12) cuts the output: freewheel. */
        return command == COMMAND_DISABLE_VOLTAGE ? ATV312_SWITCH_ON_DISABLED : state;
    case ATV312_FAULT:
        return state;
    }
    return state;
}

void atv312_cia402_reset(atv312_cia402_t *sm)
{
    sm->state = ATV312_SWITCH_ON_DISABLED;
    sm->control = 0;
}

bool atv312_cia402_command(atv312_cia402_t *sm, uint16_t control, bool motor_stopped)
{
    bool reset_edge = (control & ATV312_CW_FAULT_RESET) && !(sm->control & ATV312_CW_FAULT_RESET);
    bool fault_reset = sm->state == ATV312_FAULT && reset_edge;
    sm->control = control;
    if (sm->state == ATV312_FAULT && !fault_reset)
        return false;
    if (fault_reset)
        sm->state = ATV312_SWITCH_ON_DISABLED;
    /* The word is a level: follow it until the state is stable (0x000F from Ready to switch on
     * passes through Switched on to Operation enabled). Three steps reach any state. */
    command_t command = decode(control);
    for (int step = 0; step < 3; step++) {
        atv312_state_t next = transition(sm->state, command, motor_stopped);
        if (next == sm->state)
            break;
        sm->state = next;
    }
    return fault_reset;
}

void atv312_cia402_motor_stopped(atv312_cia402_t *sm)
{
    if (sm->state == ATV312_OPERATION_ENABLED && decode(sm->control) == COMMAND_SWITCH_ON)
        sm->state = ATV312_SWITCHED_ON;
}

bool atv312_cia402_drives_motor(const atv312_cia402_t *sm)
{
    return sm->state == ATV312_OPERATION_ENABLED || sm->state == ATV312_QUICK_STOP_ACTIVE;
}

bool atv312_cia402_runs(const atv312_cia402_t *sm)
{
    return sm->state == ATV312_OPERATION_ENABLED && decode(sm->control) == COMMAND_ENABLE_OPERATION;
}

void atv312_cia402_fault(atv312_cia402_t *sm)
{
    sm->state = ATV312_FAULT;
}

void atv312_cia402_configuration_changed(atv312_cia402_t *sm)
{
    if (sm->state == ATV312_READY_TO_SWITCH_ON || sm->state == ATV312_SWITCHED_ON ||
        sm->state == ATV312_OPERATION_ENABLED)
        sm->state = ATV312_SWITCH_ON_DISABLED;
}

/* The manual's MSK values (ETA & 0x006F); where it allows two, bit 5 (quick stop) is 1 only
 * in the states where the quick stop function is available. */
uint16_t atv312_cia402_status(const atv312_cia402_t *sm)
{
    switch (sm->state) {
    case ATV312_SWITCH_ON_DISABLED:
        return 0x0040;
    case ATV312_READY_TO_SWITCH_ON:
        return 0x0021;
    case ATV312_SWITCHED_ON:
        return 0x0023;
    case ATV312_OPERATION_ENABLED:
        return 0x0027;
    case ATV312_QUICK_STOP_ACTIVE:
        return 0x0007;
    case ATV312_FAULT:
        return 0x0008;
    }
    return 0x0008;
}

const char *atv312_cia402_name(atv312_state_t state)
{
    switch (state) {
    case ATV312_SWITCH_ON_DISABLED:
        return "Switch on disabled";
    case ATV312_READY_TO_SWITCH_ON:
        return "Ready to switch on";
    case ATV312_SWITCHED_ON:
        return "Switched on";
    case ATV312_OPERATION_ENABLED:
        return "Operation enabled";
    case ATV312_QUICK_STOP_ACTIVE:
        return "Quick stop active";
    case ATV312_FAULT:
        return "Fault";
    }
    return "Fault";
}
