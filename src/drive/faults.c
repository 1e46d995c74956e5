/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's faults: injection and removal of a cause, the latch in state Fault, the EMCY,
 * 603Fh and the reset rules of each fault's class (include/drive/faults.h). The model supplies
 * the table; nothing here knows a fault by name. A raise or an end says whether it changed the
 * state; the composition root (drive.c) settles the drive on it. */
#include "drive/drive_floors.h"

static const drive_fault_def_t *fault_def(const drive_t *drive, uint8_t index)
{
    return &drive->profile->faults->faults[index];
}

static uint32_t fault_bit(uint8_t index)
{
    return (uint32_t)1u << index;
}

bool drive_faults_valid(const drive_profile_t *profile)
{
    const drive_fault_table_t *table = profile->faults;
    return table && table->faults && table->count > 0 && table->count <= DRIVE_FAULTS_MAX &&
           table->communication_loss < table->count;
}

int drive_fault_find(const drive_t *drive, const char *code)
{
    const drive_fault_table_t *table = drive->profile->faults;
    for (uint8_t i = 0; i < table->count; i++) {
        if (drive_same_code(table->faults[i].code, code))
            return i;
    }
    return -1;
}

bool drive_fault_cause_present(const drive_t *drive, uint8_t index)
{
    return (drive->fault_causes & fault_bit(index)) != 0;
}

const drive_fault_def_t *drive_fault_latched(const drive_t *drive)
{
    return drive->faults_active ? fault_def(drive, drive->fault_latched) : NULL;
}

/* The communication-loss fault stops as the model's mode parameter says (the Altivars' COL),
 * every other fault, and that one where the parameter is missing or says ignore (an injected
 * fault), as its table entry says. */
static drive_fault_reaction_t reaction_of(const drive_t *drive, uint8_t index)
{
    const drive_profile_t *profile = drive->profile;
    drive_param_t mode = profile->communication_loss_mode;
    if (index == profile->faults->communication_loss && mode.index != 0) {
        switch (drive_param_value(drive, mode)) {
        case DRIVE_COMMUNICATION_LOSS_FAULT:
            return DRIVE_FAULT_FREEWHEEL;
        case DRIVE_COMMUNICATION_LOSS_FAST_STOP:
            return DRIVE_FAULT_FAST_STOP;
        case DRIVE_COMMUNICATION_LOSS_RAMP_STOP:
            return DRIVE_FAULT_RAMP_STOP;
        }
    }
    return fault_def(drive, index)->reaction;
}

/* Transition 13. A ramp reaction runs only while the output drives a turning motor; one on the
 * fast ramp already (quick stop, fast stop, a fast reaction) stays on it. */
static void react(drive_t *drive, drive_fault_reaction_t reaction)
{
    bool stopping = reaction != DRIVE_FAULT_FREEWHEEL && drive_output_on(drive) &&
                    !drive_motor_stands(&drive->motor);
    if (reaction == DRIVE_FAULT_RAMP_STOP && drive->motor.fast)
        reaction = DRIVE_FAULT_FAST_STOP;
    drive->fault_reaction = reaction;
    cia402_fault(&drive->cia402, stopping);
}

void drive_error_code_publish(drive_t *drive)
{
    uint16_t code = 0;
    if (drive->faults_active)
        code = fault_def(drive, drive->fault_latched)->emcy_code;
    else if (drive->bus_event_count > 0)
        code = drive->bus_events[drive->bus_event_count - 1];
    co_od_set_value(&drive->node, CIA402_IDX_ERROR_CODE, 0, code);
}

bool drive_fault_raise(drive_t *drive, uint8_t index)
{
    if (drive->faults_active & fault_bit(index))
        return false;
    co_node_t *node = &drive->node;
    const drive_fault_def_t *def = fault_def(drive, index);
    drive_motor_advance(&drive->motor, node->now);
    if (!drive->faults_active)
        drive->fault_latched = index;
    drive->faults_active |= fault_bit(index);
    drive_error_code_publish(drive);
    react(drive, reaction_of(drive, index));
    co_emcy_raise(node, def->emcy_code, CO_ERR_REG_GENERIC | def->error_register, NULL);
    return true;
}

/* A fault reset is accepted when every active fault is of the command class and its cause is
 * gone (the manuals: "after the cause of the fault has been removed"). */
bool drive_faults_resettable(const drive_t *drive)
{
    const drive_fault_table_t *table = drive->profile->faults;
    for (uint8_t i = 0; i < table->count; i++) {
        if (!(drive->faults_active & fault_bit(i)))
            continue;
        if (table->faults[i].reset != DRIVE_FAULT_RESET_COMMAND ||
            drive_fault_cause_present(drive, i))
            return false;
    }
    return true;
}

bool drive_emcy_code_in_use(const drive_t *drive, uint16_t code)
{
    const drive_fault_table_t *table = drive->profile->faults;
    for (uint8_t i = 0; i < table->count; i++) {
        if ((drive->faults_active & fault_bit(i)) && table->faults[i].emcy_code == code)
            return true;
    }
    for (uint8_t i = 0; i < drive->bus_event_count; i++) {
        if (drive->bus_events[i] == code)
            return true;
    }
    return false;
}

/* The fault's EMCY code stays an active error while another fault or a bus condition reports it
 * (the Altivars' CFF and CFI are both 6300h). */
static void forget_fault(drive_t *drive, uint8_t index)
{
    uint16_t code = fault_def(drive, index)->emcy_code;
    drive->faults_active &= ~fault_bit(index);
    if (index == drive->profile->faults->communication_loss)
        drive->comm_loss = (drive_comm_loss_t){DRIVE_COMM_LOSS_NONE, 0};
    if (!drive_emcy_code_in_use(drive, code))
        co_emcy_clear(&drive->node, code);
}

void drive_faults_acknowledge(drive_t *drive)
{
    const drive_fault_table_t *table = drive->profile->faults;
    for (uint8_t i = 0; i < table->count; i++) {
        if (drive->faults_active & fault_bit(i))
            forget_fault(drive, i);
    }
    drive_error_code_publish(drive);
}

void drive_faults_restart(drive_t *drive)
{
    drive->faults_active = 0;
}

bool drive_fault_cause_appears(drive_t *drive, uint8_t index, co_time_t now)
{
    drive->node.now = now;
    drive->fault_causes |= fault_bit(index);
    return drive_fault_raise(drive, index);
}

/* An automatic fault that ends leaves the state Fault when it was the last one: the drive is in
 * Switch on disabled, as after a fault reset; 603Fh shows the next fault still active. */
static void end_automatic_fault(drive_t *drive, uint8_t index)
{
    forget_fault(drive, index);
    if (drive->faults_active == 0) {
        cia402_fault_cleared(&drive->cia402);
    } else if (drive->fault_latched == index) {
        uint8_t next = 0;
        while (!(drive->faults_active & fault_bit(next)))
            next++;
        drive->fault_latched = next;
    }
    drive_error_code_publish(drive);
}

bool drive_fault_cause_ends(drive_t *drive, uint8_t index, co_time_t now)
{
    drive->node.now = now;
    drive->fault_causes &= ~fault_bit(index);
    if (!(drive->faults_active & fault_bit(index)) ||
        fault_def(drive, index)->reset != DRIVE_FAULT_RESET_AUTOMATIC)
        return false;
    drive_motor_advance(&drive->motor, now);
    end_automatic_fault(drive, index);
    return true;
}
