/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's output: the target and ramp the power state, the control word and the channels
 * steer the motor to, whether the output is on (it drives current and torque, and a fault
 * reaction can stop it on a ramp), and what the drive publishes of it: the status word, speeds,
 * current and torque. */
#include "drive/drive_floors.h"

/* Magnetising current at standstill, in % of nominal current; 100 % torque needs 100 %. */
#define MAGNETISING_CURRENT_PERCENT 30

/* The first ramp pair, or the second while the ramp switch's source is active; the fast ramp
 * divides the deceleration of the pair in use. */
static drive_ramp_t ramp_parameters(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const drive_entries_t *e = &drive->entries;
    bool second = drive->second_ramp;
    uint8_t divider = profile->fast_ramp_divider;
    uint32_t dec = second ? drive_entry_param(drive, e->deceleration_2, profile->deceleration_2)
                          : drive_entry_param(drive, e->deceleration, profile->deceleration);
    uint32_t acc = second ? drive_entry_param(drive, e->acceleration_2, profile->acceleration_2)
                          : drive_entry_param(drive, e->acceleration, profile->acceleration);
    uint32_t fast_dec = divider ? dec / divider : dec;
    return (drive_ramp_t){
        .acc = (uint16_t)acc,
        .dec = (uint16_t)dec,
        .fast_dec = (uint16_t)(fast_dec ? fast_dec : 1),
        .nominal_rpm =
            (uint16_t)drive_entry_param(drive, e->nominal_speed, drive->profile->nominal_speed),
    };
}

/* The control word's bits among `bits` that keep the profile's meaning: those not assigned to a
 * switching source. */
static uint16_t control_bits(const drive_t *drive, uint16_t bits)
{
    return (uint16_t)(drive->cia402.control & bits & ~drive->assigned_bits);
}

/* Where analogue input `index` stands in its range, as part / span (0 .. 1): a voltage's
 * magnitude of 10 V, the potentiometer's turn, a current between its low and high currents (none
 * of it while the high current is not above the low one). */
static void analog_fraction(const drive_t *drive, uint8_t index, uint32_t *part, uint32_t *span)
{
    const drive_analog_input_t *input = &drive->profile->analog_inputs[index];
    int32_t value = drive->analog[index];
    uint32_t magnitude = (uint32_t)(value < 0 ? -value : value);
    *part = magnitude;
    if (input->kind == DRIVE_ANALOG_POTENTIOMETER) {
        *span = DRIVE_ANALOG_POTENTIOMETER_MAX;
    } else if (input->kind != DRIVE_ANALOG_CURRENT) {
        *span = DRIVE_ANALOG_VOLTAGE_MAX_MV;
    } else {
        const drive_entries_t *e = &drive->entries;
        uint32_t from = drive_entry_param(drive, e->analog_low[index], input->low) * 100u;
        uint32_t to = drive_entry_param(drive, e->analog_high[index], input->high) * 100u;
        uint32_t held = magnitude < from ? from : magnitude > to ? to : magnitude;
        *part = to > from ? held - from : 0;
        *span = to > from ? to - from : 1;
    }
}

/* The reference of an analogue input (rpm): the low speed at the bottom of its range, the high
 * speed at the top, linearly between, rounded; a negative voltage reverses it. */
static int32_t analog_reference(const drive_t *drive, uint32_t low, uint32_t high)
{
    uint8_t index = (uint8_t)drive->reference_analog;
    uint32_t part, span;
    analog_fraction(drive, index, &part, &span);
    uint32_t range = high > low ? high - low : 0;
    int32_t rpm = (int32_t)(low + (uint32_t)(((uint64_t)range * part + span / 2) / span));
    return drive->analog[index] < 0 ? -rpm : rpm;
}

/* The reference of a running drive: 6042h from the network, an analogue input's, or 0 from any
 * other channel; reversed by the model's reverse bit, its magnitude held between the low and high
 * speed (the drive runs at low speed with a zero reference). */
static int32_t run_reference(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const drive_entries_t *e = &drive->entries;
    uint32_t high =
        drive_frequency_to_rpm(drive, drive_entry_param(drive, e->high_speed, profile->high_speed));
    uint32_t low =
        drive_frequency_to_rpm(drive, drive_entry_param(drive, e->low_speed, profile->low_speed));
    int32_t reference = 0;
    if (drive_reference_from_network(drive))
        reference = (int16_t)drive_entry_value(drive, e->target_velocity);
    else if (drive_reference_analog(drive) != NULL)
        reference = analog_reference(drive, low, high);
    bool reversed = control_bits(drive, profile->control_reverse) != 0 ||
                    (drive_local_control(drive) && drive->terminal_reverse);
    bool reverse = (reference < 0) != reversed;
    uint32_t wanted = (uint32_t)(reference < 0 ? -reference : reference);
    uint32_t speed = wanted > high ? high : (wanted < low ? low : wanted);
    drive->limited = speed != wanted;
    return reverse ? -(int32_t)speed : (int32_t)speed;
}

/* The stop the ramp stop bit asks for: a DRIVE_STOP_* value, or -1 when the bit is clear or the
 * network does not command. */
static int32_t requested_ramp_stop(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    if (drive_local_control(drive) || control_bits(drive, profile->control_ramp_stop) == 0)
        return -1;
    return (int32_t)drive_entry_param(drive, drive->entries.stop_type, profile->stop_type);
}

/* A freewheel stop type cuts the output in Operation enabled while its bit is set. */
static bool freewheeling(const drive_t *drive)
{
    return drive->cia402.state == CIA402_OPERATION_ENABLED &&
           requested_ramp_stop(drive) == DRIVE_STOP_FREEWHEEL;
}

/* Only Operation enabled, Quick stop active and Fault reaction active drive the motor: in any
 * other state the output is off and the motor coasts, whatever the transition that led there
 * (freewheel on 8, 9, 12 and a freewheel fault). In Operation enabled the motor follows the
 * reference unless a stop is asked: the ramp stop bit as the stop type says, the fast stop bits
 * on the fast ramp, a pending disable operation (5) on the deceleration ramp; Quick stop active
 * always stops on the fast ramp, Fault reaction active on its reaction's ramp. The control word
 * only counts under network control. */
void drive_output_steer(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const cia402_state_machine_t *sm = &drive->cia402;
    bool local = drive_local_control(drive);
    bool enabled = sm->state == CIA402_OPERATION_ENABLED;
    bool fast_stop = !local && control_bits(drive, profile->control_fast_stop) != 0;
    int32_t ramp_stop = requested_ramp_stop(drive);
    bool fast_ramp_stop = ramp_stop == DRIVE_STOP_FAST || ramp_stop == DRIVE_STOP_DC_INJECTION;
    bool fast_reaction =
        sm->state == CIA402_FAULT_REACTION_ACTIVE && drive->fault_reaction == DRIVE_FAULT_FAST_STOP;
    bool fast = sm->state == CIA402_QUICK_STOP_ACTIVE || fast_reaction ||
                (enabled && (fast_stop || fast_ramp_stop));
    if (!cia402_drives_motor(sm) || freewheeling(drive))
        drive_motor_coast(&drive->motor);
    drive->limited = false;
    bool runs = local ? drive_local_runs(drive) : cia402_runs(sm);
    int32_t target = runs && !fast_stop && ramp_stop < 0 ? run_reference(drive) : 0;
    drive_ramp_t ramp = ramp_parameters(drive);
    drive_motor_steer(&drive->motor, target, fast, &ramp);
}

/* Status word bit 7 (D-STATUS-ALARM): the node reports an error by EMCY that is not one of the
 * drive's active faults (a CAN bus condition, an RPDO length or timeout error). */
static bool warning_present(const drive_t *drive)
{
    const drive_fault_table_t *table = drive->profile->faults;
    const co_emcy_t *emcy = &drive->node.emcy;
    for (uint8_t e = 0; e < emcy->active_count; e++) {
        bool fault = false;
        for (uint8_t i = 0; i < table->count && !fault; i++)
            fault = (drive->faults_active & ((uint32_t)1u << i)) &&
                    table->faults[i].emcy_code == emcy->active[e].code;
        if (!fault)
            return true;
    }
    return false;
}

static uint16_t status_word(const drive_t *drive)
{
    const drive_motor_t *motor = &drive->motor;
    uint16_t status = cia402_status(&drive->cia402) | drive_local_status(drive);
    if (drive_motor_at_target(motor))
        status |= CIA402_SW_TARGET_REACHED;
    if (drive->limited)
        status |= CIA402_SW_INTERNAL_LIMIT;
    if (warning_present(drive))
        status |= CIA402_SW_WARNING;
    if (drive_motor_reverse(motor))
        status |= drive->profile->status_reverse;
    return status;
}

/* The output is on in Operation enabled but for a freewheel stop, and in Quick stop active and
 * Fault reaction active until the motor stopped (then the drive locks). */
bool drive_output_on(const drive_t *drive)
{
    cia402_state_t state = drive->cia402.state;
    bool stopping = state == CIA402_QUICK_STOP_ACTIVE || state == CIA402_FAULT_REACTION_ACTIVE;
    return (state == CIA402_OPERATION_ENABLED && !freewheeling(drive)) ||
           (stopping && !drive_motor_stands(&drive->motor));
}

/* Current (0.1 A) of a given torque: the magnetising current plus the torque's share. */
static int32_t motor_current(const drive_t *drive, int16_t torque)
{
    int32_t load = torque < 0 ? -torque : torque;
    int32_t nominal = (int32_t)drive_entry_param(drive, drive->entries.nominal_current,
                                                 drive->profile->nominal_current);
    return nominal *
           (MAGNETISING_CURRENT_PERCENT + (100 - MAGNETISING_CURRENT_PERCENT) * load / 100) / 100;
}

void drive_output_publish(drive_t *drive)
{
    const drive_entries_t *e = &drive->entries;
    uint16_t status = status_word(drive);
    drive_entry_set(drive, e->status_word, status);
    drive_entry_set(drive, e->status_word_copy, status);
    int32_t rpm = drive_motor_rpm(&drive->motor);
    drive_entry_set(drive, e->velocity_demand, rpm);
    drive_entry_set(drive, e->velocity_actual, rpm);
    drive_entry_set(drive, e->output_frequency, drive_signed_rpm_to_frequency(drive, rpm));
    bool on = drive_output_on(drive);
    int16_t torque = on ? drive_motor_torque(&drive->motor) : 0;
    int32_t current = on ? motor_current(drive, torque) : 0;
    drive_entry_set(drive, e->motor_torque, torque);
    drive_entry_set(drive, e->motor_current, current);
}
