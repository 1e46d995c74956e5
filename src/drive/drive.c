/* SPDX-License-Identifier: Apache-2.0 */
/* The drive: a CANopen node on a model's dictionary whose control word drives the CiA 402 state
 * machine and whose motor model publishes status, speed, current and torque. Communication loss
 * (heartbeat consumer or life guarding) is the network fault. The composition root of the layer:
 * the core's application hooks and every public entry point that changes the drive's state end
 * by settling it; the files below change the state and say what changed, and call none of this. */
#include "drive/drive_floors.h"

#include <string.h>

/* The EMCY error register of a CAN bus condition: 1001h bit 0 (generic) and bit 4
 * (communication), CiA 301 table 48; a model whose manual prints 1001h as 0 or 1 keeps bit 0 alone
 * by its node option (CO_NODE_ERROR_REGISTER_GENERIC), for every EMCY alike. */
#define COMMUNICATION_ERROR_REGISTER (CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION)

/* Recomputes the motor's target from the state and the dictionary, and publishes the status
 * word, speeds, current and torque. */
static void settle(drive_t *drive)
{
    if (drive_motor_stands(&drive->motor)) {
        cia402_motor_stopped(&drive->cia402);
        drive_local_motor_stopped(drive);
    }
    drive_output_steer(drive);
    drive_output_publish(drive);
}

/* A change of command channel is a freewheel stop to Switch on disabled, as forced local
 * control's. */
static void update_channels(drive_t *drive)
{
    if (drive_channels_update(drive))
        drive_local_channel_changed(drive);
}

/* Each fault raised settles the drive before the next: a later fault's reaction reads the ramp the
 * motor is on (faults.c, react). */
static void raise_fault(drive_t *drive, uint8_t index)
{
    if (drive_fault_raise(drive, index))
        settle(drive);
}

/* A communication loss latches the network fault code and, unless the model's mode parameter
 * says to ignore it, raises the model's communication-loss fault (the Altivars' CnF), latched
 * until a fault reset. A model without the mode parameter always faults. */
static void communication_fault(drive_t *drive, drive_comm_loss_t cause)
{
    const drive_profile_t *profile = drive->profile;
    drive->comm_loss = cause;
    drive_param_t mode = profile->communication_loss_mode;
    co_od_set_value(&drive->node, profile->network_fault_code.index,
                    profile->network_fault_code.subindex, DRIVE_NETWORK_FAULT_TIME_OUT);
    if (mode.index != 0 && drive_param_value(drive, mode) == DRIVE_COMMUNICATION_LOSS_IGNORE)
        return;
    raise_fault(drive, profile->faults->communication_loss);
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
    drive_entry_set(drive, drive->entries.control_word, control);
    drive_entry_set(drive, drive->entries.control_word_copy, control);
    if (drive->assigned_bits != 0)
        update_channels(drive);
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

/* 6042h (rpm) and the model's frequency reference (0.1 Hz) are one reference: a write to either
 * sets the other, converted through the nominal frequency and speed and held within the other's
 * limits (6042h = 20000 rpm is LFR = 500.0 Hz, its HighLimit, on a 1500 rpm 50 Hz motor). */
static void mirror_reference(drive_t *drive, const co_od_entry_t *entry)
{
    const drive_entries_t *e = &drive->entries;
    if (e->frequency_reference == NULL)
        return;
    if (entry == e->frequency_reference) {
        int32_t decihertz = (int32_t)drive_entry_value(drive, entry);
        drive_entry_set(drive, e->target_velocity, drive_signed_frequency_to_rpm(drive, decihertz));
    } else if (entry == e->target_velocity) {
        int32_t rpm = (int32_t)drive_entry_value(drive, entry);
        drive_entry_set(drive, e->frequency_reference, drive_signed_rpm_to_frequency(drive, rpm));
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
        update_channels(drive);
    settle(drive);
    advance_auto_tune(drive, node->now);
}

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    if (lost)
        communication_fault(drive_of(node),
                            (drive_comm_loss_t){DRIVE_COMM_LOSS_HEARTBEAT, producer});
}

static void on_guarding(co_node_t *node, bool lost)
{
    if (lost)
        communication_fault(drive_of(node), (drive_comm_loss_t){DRIVE_COMM_LOSS_GUARDING, 0});
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
    drive->service_received_at = CO_TIME_NEVER;
    drive->comm_loss = (drive_comm_loss_t){DRIVE_COMM_LOSS_NONE, 0};
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
        co_emcy_raise(node, drive->bus_events[i], COMMUNICATION_ERROR_REGISTER, NULL);
    drive_error_code_publish(drive);
    for (uint8_t i = 0; i < drive->profile->faults->count; i++) {
        if (drive_fault_cause_present(drive, i))
            raise_fault(drive, i);
    }
}

static const co_app_hooks_t drive_hooks = {
    .nmt_state = on_nmt_state,
    .reset = on_reset,
    .heartbeat = on_heartbeat,
    .guarding = on_guarding,
    .od_written = on_written,
};

/* CANopen off (drive_config_t.node_id 0): the core still holds the drive's dictionary, and a node
 * needs a node-id 1..127 to be initialised; this one never reaches the bus, for the node is never
 * started (co_node_receive and co_node_process do nothing in Initialising). */
#define CAN_OFF_NODE_ID 1u

int drive_init(drive_t *drive, const drive_config_t *config)
{
    bool can_off = config->node_id == 0;
    co_node_config_t node_config = {
        .node_id = can_off ? CAN_OFF_NODE_ID : config->node_id,
        .od = config->profile->od,
        .od_data = config->od_data,
        .send = config->send,
        .user = config->send_user,
        .hooks = &drive_hooks,
        .storage = config->storage,
        .options = config->profile->node_options | config->node_options,
        .options_code = config->node_options_code != NULL ? config->node_options_code
                                                          : config->profile->node_options_code,
        .tpdo_inhibit_ms = config->profile->tpdo_inhibit_ms,
    };
    if (!drive_faults_valid(config->profile))
        return DRIVE_INIT_BAD_FAULTS;
    if (config->profile->analog_input_count > DRIVE_ANALOG_MAX)
        return DRIVE_INIT_BAD_ANALOG;
    /* Every field from a known value, whatever the caller's memory held: no bus condition, fault
     * cause, input or load, not forced local. */
    memset(drive, 0, sizeof *drive);
    drive->profile = config->profile;
    int err = co_node_init(&drive->node, &node_config);
    if (err != 0)
        return err;
    drive->can_off = can_off;
    drive_param_t address = config->profile->can_address;
    if (can_off && address.index != 0)
        co_od_set_value(&drive->node, address.index, address.subindex, 0);
    drive_entries_find(drive);
    restart_drive(drive, 0);
    /* The channels of the dictionary's defaults, computed against the network commanding. */
    drive->command_from_network = true;
    drive_channels_update(drive);
    return 0;
}

/* Switched on below the full access level, the drive needs no status chart procedure (ATV312
 * DeviceNet manual, "In access level L1 or L2": "At switch-on, the drive is in control via the
 * terminals and changes automatically to the 'Operation enabled' state"); at the full level it
 * waits in Switch on disabled ("At switch-on, the drive configured for control via the bus changes
 * to the 'Switch on disabled' state"). Only at switch-on: a reset node or a disable voltage
 * leaves it in Switch on disabled, from where a run command still starts it. */
static void switch_on(drive_t *drive)
{
    if (!drive_access_full(drive) && drive->cia402.state == CIA402_SWITCH_ON_DISABLED)
        drive->cia402.state = CIA402_OPERATION_ENABLED;
}

void drive_start(drive_t *drive, co_time_t now)
{
    if (!drive->can_off)
        co_node_start(&drive->node, now);
    update_channels(drive);
    switch_on(drive);
    settle(drive);
}

/* An SDO request to the node or a data frame of one of its valid RPDOs: the services a card's
 * reception LED shows (NMT, SYNC, guarding and heartbeats are not). */
static bool is_service_request(const drive_t *drive, const co_frame_t *frame)
{
    if (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF))
        return false;
    if (frame->id == CO_CAN_ID_SDO_RX + drive->node.node_id)
        return true;
    for (size_t i = 0; i < CO_CONFIG_RPDO_MAX; i++) {
        const co_rpdo_t *rpdo = &drive->node.pdo.rpdo[i];
        if (rpdo->valid && rpdo->can_id == frame->id)
            return true;
    }
    return false;
}

void drive_receive(drive_t *drive, const co_frame_t *frame, co_time_t now)
{
    if (drive->can_off)
        return;
    if (is_service_request(drive, frame))
        drive->service_received_at = now;
    uint8_t errors = drive->node.emcy.active_count;
    co_node_receive(&drive->node, frame, now);
    if (drive->node.emcy.active_count != errors)
        drive_output_publish(drive); /* an RPDO's length error raised or ended: the warning bit */
}

co_time_t drive_last_service_request(const drive_t *drive)
{
    return drive->service_received_at;
}

/* A written entry settles the drive at once (on_written); a steady motor changes nothing over
 * time. So only a moving motor or a reset makes work here: most calls (a frame for the core
 * alone, a heartbeat due) touch neither the motor nor the dictionary. */
co_time_t drive_process(drive_t *drive, co_time_t now)
{
    if (drive->dirty || !drive_motor_at_target(&drive->motor)) {
        if (drive->dirty)
            update_channels(drive); /* a reset restored them without writes */
        drive->dirty = false;
        drive_motor_advance(&drive->motor, now);
        settle(drive);
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
        co_emcy_raise(&drive->node, emcy_code, COMMUNICATION_ERROR_REGISTER, NULL);
    else if (!drive_emcy_code_in_use(drive, emcy_code))
        co_emcy_clear(&drive->node, emcy_code);
    drive_error_code_publish(drive);
    drive_output_publish(drive); /* the warning bit */
}

void drive_bus_warning(drive_t *drive, bool active)
{
    drive->can_warning = active;
}

void drive_communication_loss(drive_t *drive, co_time_t now)
{
    drive_motor_advance(&drive->motor, now);
    communication_fault(drive, (drive_comm_loss_t){DRIVE_COMM_LOSS_NETWORK, 0});
}

const char *drive_state_name(const drive_t *drive)
{
    return cia402_state_name(drive->cia402.state);
}

void drive_set_local(drive_t *drive, bool local, co_time_t now)
{
    drive_local_force(drive, local, now);
    settle(drive);
}

/* A STOP key that resets faults (the ATV31's STOP/RESET) resets them as the fault reset edge
 * would: in Fault only, when every active fault accepts a reset by command. The network's
 * recorded control word stays, so its own reset still needs a new edge. */
static void stop_key_fault_reset(drive_t *drive)
{
    if (!drive->profile->stop_key_resets_faults || drive->cia402.state != CIA402_FAULT ||
        !drive_faults_resettable(drive))
        return;
    drive->cia402.state = CIA402_SWITCH_ON_DISABLED;
    drive_faults_acknowledge(drive);
}

void drive_stop_key(drive_t *drive, co_time_t now)
{
    drive_local_stop_key(drive, now);
    stop_key_fault_reset(drive);
    settle(drive);
}

bool drive_run_key(drive_t *drive, co_time_t now)
{
    if (!drive_local_run_key(drive, now))
        return false;
    settle(drive);
    return true;
}

void drive_set_load(drive_t *drive, uint8_t percent, co_time_t now)
{
    drive_local_load(drive, percent, now);
    settle(drive);
}

/* A reference channel assigned to the input follows it at once. */
bool drive_set_analog(drive_t *drive, uint8_t index, int32_t value, co_time_t now)
{
    if (!drive_local_analog(drive, index, value, now))
        return false;
    settle(drive);
    return true;
}

/* An input may be a switching source: the channels follow it before the drive settles. */
bool drive_set_input(drive_t *drive, uint8_t input, bool on, co_time_t now)
{
    uint8_t before = drive->inputs;
    if (!drive_local_input(drive, input, on, now))
        return false;
    update_channels(drive);
    drive_local_terminals(drive, before);
    settle(drive);
    return true;
}

void drive_fault_inject(drive_t *drive, uint8_t index, co_time_t now)
{
    if (drive_fault_cause_appears(drive, index, now))
        settle(drive);
}

void drive_fault_remove_cause(drive_t *drive, uint8_t index, co_time_t now)
{
    if (drive_fault_cause_ends(drive, index, now))
        settle(drive);
}
