/* The drive: a CANopen node on a model's dictionary whose control word drives the CiA 402 state
 * machine and whose motor model publishes status, speed, current and torque. Communication loss
 * (heartbeat consumer or life guarding) is the network fault. */
#include "drive_internal.h"

#include <stddef.h>

/* The EMCY error register of a CAN bus condition where the profile gives none: 1001h bit 0
 * (generic, "error (1)" in the ATV312 table) and bit 4 (communication), CiA 301 table 48. */
#define COMMUNICATION_ERROR_REGISTER (CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION)

static uint8_t bus_error_register(const drive_t *drive)
{
    uint8_t bits = drive->profile->bus_error_register;
    return bits ? bits : COMMUNICATION_ERROR_REGISTER;
}

/* Magnetising current at standstill, in % of nominal current; 100 % torque needs 100 %. */
#define MAGNETISING_CURRENT_PERCENT 30

drive_t *drive_of(co_node_t *node)
{
    return (drive_t *)(void *)((char *)node - offsetof(drive_t, node));
}

uint32_t drive_param_value(const drive_t *drive, drive_param_t param)
{
    if (param.index == 0)
        return param.fixed;
    return (uint32_t)co_od_value(&drive->node, param.index, param.subindex);
}

static int64_t entry_value(const drive_t *drive, const co_od_entry_t *entry)
{
    return entry != NULL ? co_od_get(&drive->node, entry) : 0;
}

static void entry_set(drive_t *drive, const co_od_entry_t *entry, int64_t value)
{
    if (entry != NULL)
        co_od_set(&drive->node, entry, value);
}

static const co_od_entry_t *param_entry(const drive_t *drive, drive_param_t param)
{
    return co_od_find(drive->profile->od, param.index, param.subindex);
}

static void find_entries(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const co_od_t *od = profile->od;
    drive->entries = (drive_entries_t){
        .error_code = co_od_find(od, CIA402_IDX_ERROR_CODE, 0),
        .control_word = co_od_find(od, CIA402_IDX_CONTROLWORD, 0),
        .status_word = co_od_find(od, CIA402_IDX_STATUSWORD, 0),
        .target_velocity = co_od_find(od, CIA402_IDX_TARGET_VELOCITY, 0),
        .velocity_demand = co_od_find(od, CIA402_IDX_VELOCITY_DEMAND, 0),
        .velocity_actual = co_od_find(od, CIA402_IDX_VELOCITY_ACTUAL, 0),
        .acceleration = param_entry(drive, profile->acceleration),
        .deceleration = param_entry(drive, profile->deceleration),
        .low_speed = param_entry(drive, profile->low_speed),
        .high_speed = param_entry(drive, profile->high_speed),
        .nominal_frequency = param_entry(drive, profile->nominal_frequency),
        .nominal_speed = param_entry(drive, profile->nominal_speed),
        .nominal_current = param_entry(drive, profile->nominal_current),
        .motor_current = param_entry(drive, profile->motor_current),
        .motor_torque = param_entry(drive, profile->motor_torque),
        .control_word_copy = param_entry(drive, profile->control_word_copy),
        .status_word_copy = param_entry(drive, profile->status_word_copy),
        .output_frequency = param_entry(drive, profile->output_frequency),
        .frequency_reference = param_entry(drive, profile->frequency_reference),
        .stop_type = param_entry(drive, profile->stop_type),
        .acceleration_2 = param_entry(drive, profile->acceleration_2),
        .deceleration_2 = param_entry(drive, profile->deceleration_2),
    };
}

/* A parameter of the profile through its entry; a setting the model's dictionary lacks reads as
 * its fixed value (DRIVE_FIXED), as drive_param_value does. */
static uint32_t param_unsigned(const drive_t *drive, const co_od_entry_t *entry,
                               drive_param_t param)
{
    return entry != NULL ? (uint32_t)co_od_get(&drive->node, entry) : param.fixed;
}

uint32_t drive_frequency_to_rpm(const drive_t *drive, uint32_t decihertz)
{
    uint32_t frs =
        param_unsigned(drive, drive->entries.nominal_frequency, drive->profile->nominal_frequency);
    uint32_t nsp =
        param_unsigned(drive, drive->entries.nominal_speed, drive->profile->nominal_speed);
    return frs ? (decihertz * nsp + frs / 2) / frs : 0;
}

uint32_t drive_rpm_to_frequency(const drive_t *drive, uint32_t rpm)
{
    uint64_t frs =
        param_unsigned(drive, drive->entries.nominal_frequency, drive->profile->nominal_frequency);
    uint64_t nsp =
        param_unsigned(drive, drive->entries.nominal_speed, drive->profile->nominal_speed);
    uint64_t decihertz = nsp ? ((uint64_t)rpm * frs + nsp / 2) / nsp : 0;
    return decihertz > UINT32_MAX ? UINT32_MAX : (uint32_t)decihertz;
}

int32_t drive_signed_rpm_to_frequency(const drive_t *drive, int32_t rpm)
{
    uint32_t decihertz = drive_rpm_to_frequency(drive, (uint32_t)(rpm < 0 ? -rpm : rpm));
    int32_t magnitude = decihertz > INT32_MAX ? INT32_MAX : (int32_t)decihertz;
    return rpm < 0 ? -magnitude : magnitude;
}

int32_t drive_signed_frequency_to_rpm(const drive_t *drive, int32_t decihertz)
{
    uint32_t magnitude = (uint32_t)(decihertz < 0 ? -decihertz : decihertz);
    int32_t rpm = (int32_t)drive_frequency_to_rpm(drive, magnitude);
    return decihertz < 0 ? -rpm : rpm;
}

int16_t drive_clamp_int16(int32_t value)
{
    return (int16_t)(value > INT16_MAX ? INT16_MAX : (value < INT16_MIN ? INT16_MIN : value));
}

/* The first ramp pair, or the second while the ramp switch's source is active; the fast ramp
 * divides the deceleration of the pair in use. */
static drive_ramp_t ramp_parameters(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const drive_entries_t *e = &drive->entries;
    bool second = drive->second_ramp;
    uint8_t divider = profile->fast_ramp_divider;
    uint32_t dec = second ? param_unsigned(drive, e->deceleration_2, profile->deceleration_2)
                          : param_unsigned(drive, e->deceleration, profile->deceleration);
    uint32_t acc = second ? param_unsigned(drive, e->acceleration_2, profile->acceleration_2)
                          : param_unsigned(drive, e->acceleration, profile->acceleration);
    uint32_t fast_dec = divider ? dec / divider : dec;
    return (drive_ramp_t){
        .acc = (uint16_t)acc,
        .dec = (uint16_t)dec,
        .fast_dec = (uint16_t)(fast_dec ? fast_dec : 1),
        .nominal_rpm =
            (uint16_t)param_unsigned(drive, e->nominal_speed, drive->profile->nominal_speed),
    };
}

/* The control word's bits among `bits` that keep the profile's meaning: those not assigned to a
 * switching source. */
static uint16_t control_bits(const drive_t *drive, uint16_t bits)
{
    return (uint16_t)(drive->cia402.control & bits & ~drive->assigned_bits);
}

/* The reference of a running drive: 6042h (0 from a channel other than the network), reversed by
 * the model's reverse bit, its magnitude held between the low and high speed (the drive runs at low
 * speed with a zero reference). */
static int32_t run_reference(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const drive_entries_t *e = &drive->entries;
    int32_t reference =
        drive_reference_from_network(drive) ? (int16_t)entry_value(drive, e->target_velocity) : 0;
    bool reverse = (reference < 0) != (control_bits(drive, profile->control_reverse) != 0);
    uint32_t wanted = (uint32_t)(reference < 0 ? -reference : reference);
    uint32_t high =
        drive_frequency_to_rpm(drive, param_unsigned(drive, e->high_speed, profile->high_speed));
    uint32_t low =
        drive_frequency_to_rpm(drive, param_unsigned(drive, e->low_speed, profile->low_speed));
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
    return (int32_t)param_unsigned(drive, drive->entries.stop_type, profile->stop_type);
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
static void steer_motor(drive_t *drive)
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

static uint16_t status_word(const drive_t *drive)
{
    const drive_motor_t *motor = &drive->motor;
    uint16_t status = cia402_status(&drive->cia402) | drive_local_status(drive);
    if (drive_motor_at_target(motor))
        status |= CIA402_SW_TARGET_REACHED;
    if (drive->limited)
        status |= CIA402_SW_INTERNAL_LIMIT;
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
    int32_t nominal = (int32_t)param_unsigned(drive, drive->entries.nominal_current,
                                              drive->profile->nominal_current);
    return nominal *
           (MAGNETISING_CURRENT_PERCENT + (100 - MAGNETISING_CURRENT_PERCENT) * load / 100) / 100;
}

static void publish(drive_t *drive)
{
    const drive_entries_t *e = &drive->entries;
    uint16_t status = status_word(drive);
    entry_set(drive, e->status_word, status);
    entry_set(drive, e->status_word_copy, status);
    int32_t rpm = drive_motor_rpm(&drive->motor);
    entry_set(drive, e->velocity_demand, rpm);
    entry_set(drive, e->velocity_actual, rpm);
    entry_set(drive, e->output_frequency, drive_signed_rpm_to_frequency(drive, rpm));
    bool on = drive_output_on(drive);
    int16_t torque = on ? drive_motor_torque(&drive->motor) : 0;
    int32_t current = on ? motor_current(drive, torque) : 0;
    entry_set(drive, e->motor_torque, torque);
    entry_set(drive, e->motor_current, current);
}

void drive_settle(drive_t *drive)
{
    if (drive_motor_stands(&drive->motor)) {
        cia402_motor_stopped(&drive->cia402);
        drive_local_motor_stopped(drive);
    }
    steer_motor(drive);
    publish(drive);
}

/* A communication loss latches the network fault code and, unless the model's mode parameter
 * says to ignore it, raises the model's communication-loss fault (the Altivars' CnF), latched
 * until a fault reset. A model without the mode parameter always faults. */
static void communication_fault(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    drive_param_t mode = profile->communication_loss_mode;
    co_od_set_value(&drive->node, profile->network_fault_code.index,
                    profile->network_fault_code.subindex, DRIVE_NETWORK_FAULT_TIME_OUT);
    if (mode.index != 0 && drive_param_value(drive, mode) == DRIVE_COMMUNICATION_LOSS_IGNORE)
        return;
    drive_fault_raise(drive, profile->faults->communication_loss);
}

static bool is_control_word(const drive_t *drive, const co_od_entry_t *entry)
{
    return entry == drive->entries.control_word || entry == drive->entries.control_word_copy;
}

/* Below the full access level (and in the I/O mode, below) a run command needs no status chart
 * procedure (ATV312 DeviceNet manual, "In access level L1 or L2": "when a run command is applied
 * (for example: CMD = 16#000F), it starts without needing to follow the IEC 61800-7 status chart
 * procedure"): from Switch on disabled it passes through Ready to switch on as from the shutdown
 * command. */
#define RUN_COMMAND                                                                                \
    (CIA402_CW_SWITCH_ON | CIA402_CW_ENABLE_VOLTAGE | CIA402_CW_QUICK_STOP |                       \
     CIA402_CW_ENABLE_OPERATION)

static void run_without_procedure(drive_t *drive, uint16_t control)
{
    if ((!drive_access_full(drive) || drive->io_mode) &&
        drive->cia402.state == CIA402_SWITCH_ON_DISABLED && (control & RUN_COMMAND) == RUN_COMMAND)
        drive->cia402.state = CIA402_READY_TO_SWITCH_ON;
}

/* In the I/O mode the word is read as terminals: bit 0 runs (enable operation, with no state
 * chart procedure) or stops on the ramp (disable operation, to Switched on); the fault reset
 * and bits 8-15 are kept. */
#define IO_RUN 0x0001u
#define IO_KEPT_BITS (CIA402_CW_FAULT_RESET | 0xFF00u)

static uint16_t io_command(uint16_t control)
{
    uint16_t command =
        (control & IO_RUN) ? RUN_COMMAND : (uint16_t)(RUN_COMMAND & ~CIA402_CW_ENABLE_OPERATION);
    return (uint16_t)(command | (control & IO_KEPT_BITS));
}

/* 6040h and the model's copy are the same word: both are kept equal. Bits assigned to switching
 * sources switch at once, before the word is applied on the channel they select. Under local
 * control the network's word is kept and ignored. In Fault a fault whose cause is present (or that
 * only a power cycle resets) keeps the drive there: the word is recorded, so that the reset edge
 * counts from it, and nothing else happens. */
static void apply_control_word(drive_t *drive, uint16_t control)
{
    entry_set(drive, drive->entries.control_word, control);
    entry_set(drive, drive->entries.control_word_copy, control);
    if (drive->assigned_bits != 0)
        drive_channels_update(drive);
    if (drive_local_control(drive))
        return;
    if (drive->cia402.state == CIA402_FAULT && !drive_faults_resettable(drive)) {
        drive->cia402.control = control;
        return;
    }
    uint16_t command = drive->io_mode ? io_command(control) : control;
    run_without_procedure(drive, command);
    if (cia402_command(&drive->cia402, command, drive_motor_stands(&drive->motor)))
        drive_faults_acknowledge(drive);
    drive_local_command_applied(drive);
}

/* A running auto-tune completes at its time, or ends unfinished (NO) when the drive leaves
 * Operation enabled. */
static void advance_auto_tune(drive_t *drive, co_time_t now)
{
    drive_param_t tune = drive->profile->auto_tune;
    if (drive->auto_tune_end == CO_TIME_NEVER)
        return;
    if (drive->cia402.state != CIA402_OPERATION_ENABLED)
        co_od_set_value(&drive->node, tune.index, tune.subindex, DRIVE_AUTO_TUNE_NO);
    else if (now >= drive->auto_tune_end)
        co_od_set_value(&drive->node, tune.index, tune.subindex, DRIVE_AUTO_TUNE_DONE);
    else
        return;
    drive->auto_tune_end = CO_TIME_NEVER;
}

bool drive_is_param(const co_od_entry_t *entry, drive_param_t param)
{
    return param.index != 0 && entry->index == param.index && entry->subindex == param.subindex;
}

/* 6042h (rpm) and the model's frequency reference (0.1 Hz) are one reference: a write to either
 * sets the other, converted through the nominal frequency and speed (clamped to 16 bits). */
static void mirror_reference(drive_t *drive, const co_od_entry_t *entry)
{
    const drive_entries_t *e = &drive->entries;
    if (e->frequency_reference == NULL)
        return;
    if (entry == e->frequency_reference) {
        int32_t decihertz = (int16_t)entry_value(drive, entry);
        int32_t rpm = drive_signed_frequency_to_rpm(drive, decihertz);
        entry_set(drive, e->target_velocity, drive_clamp_int16(rpm));
    } else if (entry == e->target_velocity) {
        int32_t rpm = (int16_t)entry_value(drive, entry);
        entry_set(drive, e->frequency_reference,
                  drive_clamp_int16(drive_signed_rpm_to_frequency(drive, rpm)));
    }
}

static void on_written(co_node_t *node, const co_od_entry_t *entry, co_od_origin_t origin)
{
    (void)origin;
    drive_t *drive = drive_of(node);
    drive_motor_advance(&drive->motor, node->now);
    if (is_control_word(drive, entry))
        apply_control_word(drive, (uint16_t)co_od_get(node, entry));
    mirror_reference(drive, entry);
    if (drive_channel_parameter(drive, entry))
        drive_channels_update(drive);
    drive_settle(drive);
    advance_auto_tune(drive, node->now);
}

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    (void)producer;
    if (lost)
        communication_fault(drive_of(node));
}

static void on_guarding(co_node_t *node, bool lost)
{
    if (lost)
        communication_fault(drive_of(node));
}

/* Switch on disabled, motor stopped: the state the dictionary's defaults describe. The bus
 * conditions, forced local control and the load are not the drive's state: they outlive a reset
 * node. */
static void restart_drive(drive_t *drive, co_time_t now)
{
    cia402_reset(&drive->cia402);
    drive_motor_reset(&drive->motor, now);
    drive_motor_load(&drive->motor, drive->load);
    drive->limited = false;
    drive->stop_key = false;
    drive->local_run = false;
    drive->auto_tune_end = CO_TIME_NEVER;
    drive_faults_restart(drive);
    drive->dirty = true;
}

/* Reset node restarts the drive too. Either reset restores defaults right after this without
 * writing them entry by entry: the next process settles the drive on them. */
static void on_reset(co_node_t *node, co_nmt_reset_t scope)
{
    drive_t *drive = drive_of(node);
    if (scope == CO_NMT_RESET_NODE)
        restart_drive(drive, node->now);
    drive->dirty = true;
}

/* The bus conditions and fault causes still present are errors again once a reset node has
 * emptied the EMCY producer's active errors (the boot-up comes first, then their EMCYs). Raising
 * an active error again does nothing, so every entry into Pre-operational may do it. */
static void on_nmt_state(co_node_t *node, co_nmt_state_t state)
{
    (void)state;
    drive_t *drive = drive_of(node);
    for (uint8_t i = 0; i < drive->bus_event_count; i++)
        co_emcy_raise(node, drive->bus_events[i], bus_error_register(drive), NULL);
    drive_faults_raise_present(drive);
}

static const co_app_hooks_t drive_hooks = {
    .nmt_state = on_nmt_state,
    .reset = on_reset,
    .heartbeat = on_heartbeat,
    .guarding = on_guarding,
    .od_written = on_written,
};

int drive_init(drive_t *drive, const drive_config_t *config)
{
    co_node_config_t node_config = {
        .node_id = config->node_id,
        .od = config->profile->od,
        .od_data = config->od_data,
        .send = config->send,
        .user = config->send_user,
        .hooks = &drive_hooks,
        .storage = config->storage,
        .options = config->profile->node_options | config->node_options,
        .options_code = config->node_options_code != NULL ? config->node_options_code
                                                          : config->profile->node_options_code,
    };
    if (!drive_faults_valid(config->profile))
        return DRIVE_INIT_BAD_FAULTS;
    drive->profile = config->profile;
    int err = co_node_init(&drive->node, &node_config);
    if (err != 0)
        return err;
    drive->local = false;
    drive->load = 0;
    drive->inputs = 0;
    drive->command_from_network = true;
    find_entries(drive);
    restart_drive(drive, 0);
    drive->bus_event_count = 0;
    drive->fault_causes = 0;
    return 0;
}

void drive_start(drive_t *drive, co_time_t now)
{
    co_node_start(&drive->node, now);
    drive_channels_update(drive);
    drive_settle(drive);
}

void drive_receive(drive_t *drive, const co_frame_t *frame, co_time_t now)
{
    co_node_receive(&drive->node, frame, now);
}

/* A written entry settles the drive at once (on_written); a steady motor changes nothing over
 * time. So only a moving motor or a reset makes work here: most calls (a frame for the core
 * alone, a heartbeat due) touch neither the motor nor the dictionary. */
co_time_t drive_process(drive_t *drive, co_time_t now)
{
    if (drive->dirty || !drive_motor_at_target(&drive->motor)) {
        if (drive->dirty)
            drive_channels_update(drive); /* a reset restored them without writes */
        drive->dirty = false;
        drive_motor_advance(&drive->motor, now);
        drive_settle(drive);
    }
    advance_auto_tune(drive, now);
    co_time_t next = co_node_process(&drive->node, now);
    next = co_time_min(next, drive->auto_tune_end);
    return co_time_min(next, drive_motor_deadline(&drive->motor));
}

static void remember_bus_event(drive_t *drive, uint16_t emcy_code, bool active)
{
    for (uint8_t i = 0; i < drive->bus_event_count; i++) {
        if (drive->bus_events[i] == emcy_code) {
            if (!active)
                drive->bus_events[i] = drive->bus_events[--drive->bus_event_count];
            return;
        }
    }
    if (active && drive->bus_event_count < DRIVE_BUS_EVENTS_MAX)
        drive->bus_events[drive->bus_event_count++] = emcy_code;
}

void drive_bus_event(drive_t *drive, uint16_t emcy_code, bool active)
{
    remember_bus_event(drive, emcy_code, active);
    if (active)
        co_emcy_raise(&drive->node, emcy_code, bus_error_register(drive), NULL);
    else
        co_emcy_clear(&drive->node, emcy_code);
}

const char *drive_state_name(const drive_t *drive)
{
    return cia402_state_name(drive->cia402.state);
}
