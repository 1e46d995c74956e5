/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 402 master helper: the state coding, the path towards a target and a run to it, from the
 * controlling side (CiA 402 "device control"; the ATV312 CANopen manual's "IEC 61800-7 status
 * chart", "CMD control word", "ETA status word"). */
#include "co/co_cia402_master.h"

co_cia402_state_t co_cia402_state(uint16_t status)
{
    /* The state coding: bits 0-3 and 6, with bit 5 (quick stop, active at 0) telling the states
     * where the drive can be switched on or is on; every other bit is not significant. */
    static const struct {
        uint16_t mask, value;
        co_cia402_state_t state;
    } coding[] = {
        {0x004F, 0x0000, CO_CIA402_NOT_READY_TO_SWITCH_ON},
        {0x004F, 0x0040, CO_CIA402_SWITCH_ON_DISABLED},
        {0x006F, 0x0021, CO_CIA402_READY_TO_SWITCH_ON},
        {0x006F, 0x0023, CO_CIA402_SWITCHED_ON},
        {0x006F, 0x0027, CO_CIA402_OPERATION_ENABLED},
        {0x006F, 0x0007, CO_CIA402_QUICK_STOP_ACTIVE},
        {0x004F, 0x000F, CO_CIA402_FAULT_REACTION_ACTIVE},
        {0x004F, 0x0008, CO_CIA402_FAULT},
    };
    for (size_t i = 0; i < sizeof coding / sizeof coding[0]; i++) {
        if ((status & coding[i].mask) == coding[i].value)
            return coding[i].state;
    }
    return CO_CIA402_NO_STATE;
}

const char *co_cia402_state_name(co_cia402_state_t state)
{
    static const char *const names[] = {
        [CO_CIA402_NO_STATE] = NULL,
        [CO_CIA402_NOT_READY_TO_SWITCH_ON] = "Not ready to switch on",
        [CO_CIA402_SWITCH_ON_DISABLED] = "Switch on disabled",
        [CO_CIA402_READY_TO_SWITCH_ON] = "Ready to switch on",
        [CO_CIA402_SWITCHED_ON] = "Switched on",
        [CO_CIA402_OPERATION_ENABLED] = "Operation enabled",
        [CO_CIA402_QUICK_STOP_ACTIVE] = "Quick stop active",
        [CO_CIA402_FAULT_REACTION_ACTIVE] = "Fault reaction active",
        [CO_CIA402_FAULT] = "Fault",
    };
    return (unsigned)state < sizeof names / sizeof names[0] ? names[state] : NULL;
}

bool co_cia402_faulted(co_cia402_state_t state)
{
    return state == CO_CIA402_FAULT || state == CO_CIA402_FAULT_REACTION_ACTIVE;
}

bool co_cia402_reached(co_cia402_state_t state, co_cia402_target_t target)
{
    switch (target) {
    case CO_CIA402_TO_OPERATION_ENABLED:
        return state == CO_CIA402_OPERATION_ENABLED;
    case CO_CIA402_TO_SWITCHED_ON:
        return state == CO_CIA402_SWITCHED_ON;
    case CO_CIA402_TO_READY_TO_SWITCH_ON:
        return state == CO_CIA402_READY_TO_SWITCH_ON;
    case CO_CIA402_TO_SWITCH_ON_DISABLED:
        return state == CO_CIA402_SWITCH_ON_DISABLED;
    case CO_CIA402_TO_QUICK_STOP:
        return state == CO_CIA402_QUICK_STOP_ACTIVE || state == CO_CIA402_SWITCH_ON_DISABLED;
    case CO_CIA402_TO_FAULT_RESET:
        return !co_cia402_faulted(state);
    }
    return false;
}

static bool command(uint16_t word, co_cia402_state_t leads_to, uint16_t *control,
                    co_cia402_state_t *next)
{
    *control = word;
    *next = leads_to;
    return true;
}

bool co_cia402_next(co_cia402_state_t state, co_cia402_target_t target, uint16_t *control,
                    co_cia402_state_t *next)
{
    if (co_cia402_reached(state, target))
        return false;
    /* Below, `target` is never the state the drive is in (nor Switch on disabled for a quick
     * stop, nor anything but a reset for a fault). */
    bool off = target == CO_CIA402_TO_SWITCH_ON_DISABLED;
    bool quick = target == CO_CIA402_TO_QUICK_STOP;
    switch (state) {
    case CO_CIA402_SWITCH_ON_DISABLED: /* on the way up: 2 */
        return command(CO_CIA402_CW_SHUTDOWN, CO_CIA402_READY_TO_SWITCH_ON, control, next);
    case CO_CIA402_READY_TO_SWITCH_ON:
        if (off || quick) /* 7 */
            return command(off ? CO_CIA402_CW_DISABLE_VOLTAGE : CO_CIA402_CW_QUICK_STOP,
                           CO_CIA402_SWITCH_ON_DISABLED, control, next);
        return command(CO_CIA402_CW_SWITCH_ON, CO_CIA402_SWITCHED_ON, control, next); /* 3 */
    case CO_CIA402_SWITCHED_ON:
        if (off || quick) /* 10 */
            return command(off ? CO_CIA402_CW_DISABLE_VOLTAGE : CO_CIA402_CW_QUICK_STOP,
                           CO_CIA402_SWITCH_ON_DISABLED, control, next);
        if (target == CO_CIA402_TO_READY_TO_SWITCH_ON) /* 6 */
            return command(CO_CIA402_CW_SHUTDOWN, CO_CIA402_READY_TO_SWITCH_ON, control, next);
        return command(CO_CIA402_CW_ENABLE_OPERATION, CO_CIA402_OPERATION_ENABLED, control,
                       next); /* 4 */
    case CO_CIA402_OPERATION_ENABLED:
        if (off) /* 9 */
            return command(CO_CIA402_CW_DISABLE_VOLTAGE, CO_CIA402_SWITCH_ON_DISABLED, control,
                           next);
        if (quick) /* 11 */
            return command(CO_CIA402_CW_QUICK_STOP, CO_CIA402_QUICK_STOP_ACTIVE, control, next);
        if (target == CO_CIA402_TO_READY_TO_SWITCH_ON) /* 8 */
            return command(CO_CIA402_CW_SHUTDOWN, CO_CIA402_READY_TO_SWITCH_ON, control, next);
        return command(CO_CIA402_CW_DISABLE_OPERATION, CO_CIA402_SWITCHED_ON, control,
                       next);         /* 5 */
    case CO_CIA402_QUICK_STOP_ACTIVE: /* 12 */
        return command(CO_CIA402_CW_DISABLE_VOLTAGE, CO_CIA402_SWITCH_ON_DISABLED, control, next);
    case CO_CIA402_FAULT: /* 15 */
        return target == CO_CIA402_TO_FAULT_RESET &&
               command(CO_CIA402_CW_FAULT_RESET, CO_CIA402_SWITCH_ON_DISABLED, control, next);
    case CO_CIA402_NO_STATE:
    case CO_CIA402_NOT_READY_TO_SWITCH_ON:
    case CO_CIA402_FAULT_REACTION_ACTIVE:
        break;
    }
    return false;
}

void co_cia402_master_start(co_cia402_master_t *m, co_cia402_target_t target, co_time_t timeout)
{
    *m = (co_cia402_master_t){.target = target, .timeout = timeout};
}

/* The state a drive goes to by itself (transitions 1 and 14); none for a status word without a
 * state. */
static co_cia402_state_t moves_on_to(co_cia402_state_t state)
{
    switch (state) {
    case CO_CIA402_NOT_READY_TO_SWITCH_ON:
        return CO_CIA402_SWITCH_ON_DISABLED;
    case CO_CIA402_FAULT_REACTION_ACTIVE:
        return CO_CIA402_FAULT;
    default:
        return CO_CIA402_NO_STATE;
    }
}

co_cia402_step_t co_cia402_master_step(co_cia402_master_t *m, uint16_t status, co_time_t now,
                                       uint16_t *control)
{
    co_cia402_state_t state = co_cia402_state(status);
    if (!m->started || state != m->state) {
        /* A new state: the drive moved, and whatever was asked in the old one is done. */
        m->started = true;
        m->state = state;
        m->sent = false;
        m->deadline = now + m->timeout;
        m->awaited = moves_on_to(state);
    }
    if (co_cia402_reached(state, m->target))
        return CO_CIA402_REACHED;
    if (co_cia402_faulted(state) && m->target != CO_CIA402_TO_FAULT_RESET)
        return CO_CIA402_FAULTED;
    uint16_t word;
    co_cia402_state_t next;
    if (co_cia402_next(state, m->target, &word, &next) && !(m->sent && m->control == word)) {
        if ((word & CO_CIA402_CW_FAULT_RESET) && !m->reset_bit_low) {
            /* The reset is the 0 -> 1 edge of bit 7: the bit goes to 0 first. */
            word = CO_CIA402_CW_DISABLE_VOLTAGE;
            next = state;
        }
        m->reset_bit_low = !(word & CO_CIA402_CW_FAULT_RESET);
        m->control = word;
        m->sent = true;
        m->awaited = next;
        m->deadline = now + m->timeout;
        *control = word;
        return CO_CIA402_WRITE;
    }
    return now >= m->deadline ? CO_CIA402_TIMED_OUT : CO_CIA402_WAIT;
}
