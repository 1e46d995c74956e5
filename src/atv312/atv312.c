/* The drive: a CANopen node on the ATV312 dictionary whose control word drives the CiA 402 state
 * machine and whose motor model publishes status, speed, current and torque. Communication loss
 * (heartbeat consumer or life guarding) is the ATV312 network fault. */
#include "cia402.h"
#include "drive.h"
#include "motor.h"

#include <stddef.h>

/* The EMCY error register of a communication fault: 1001h bit 0 (generic, "error (1)" in the
 * ATV312 table) and bit 4 (communication), CiA 301 table 48. */
#define COMMUNICATION_ERROR_REGISTER (CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION)

/* Fast stop and quick stop ramp: DEC divided by the ATV312's default ramp divider (dCF = 4). */
#define FAST_RAMP_DIVIDER 4u

/* Magnetising current at standstill, in % of nominal current; 100 % torque needs 100 %. */
#define MAGNETISING_CURRENT_PERCENT 30

atv312_t *atv312_of(co_node_t *node)
{
    return (atv312_t *)(void *)((char *)node - offsetof(atv312_t, node));
}

uint16_t atv312_param(const atv312_t *drive, uint16_t index, uint8_t subindex)
{
    return (uint16_t)co_od_value(&drive->node, index, subindex);
}

uint32_t atv312_frequency_to_rpm(const atv312_t *drive, uint32_t decihertz)
{
    uint32_t frs = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_FRS);
    uint32_t nsp = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NSP);
    return frs ? (decihertz * nsp + frs / 2) / frs : 0;
}

uint32_t atv312_rpm_to_frequency(const atv312_t *drive, uint32_t rpm)
{
    uint64_t frs = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_FRS);
    uint64_t nsp = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NSP);
    uint64_t decihertz = nsp ? ((uint64_t)rpm * frs + nsp / 2) / nsp : 0;
    return decihertz > UINT32_MAX ? UINT32_MAX : (uint32_t)decihertz;
}

void atv312_advance(atv312_t *drive, co_time_t now)
{
    atv312_motor_advance(&drive->motor, now);
}

bool atv312_motor_running(const atv312_t *drive)
{
    return drive->motor.speed != 0 || drive->motor.target != 0;
}

static atv312_ramp_t ramp_parameters(const atv312_t *drive)
{
    uint16_t dec = atv312_param(drive, ATV312_IDX_RAMPS, ATV312_SUB_DEC);
    uint16_t fast_dec = (uint16_t)(dec / FAST_RAMP_DIVIDER);
    return (atv312_ramp_t){
        .acc = atv312_param(drive, ATV312_IDX_RAMPS, ATV312_SUB_ACC),
        .dec = dec,
        .fast_dec = fast_dec ? fast_dec : 1,
        .nominal_rpm = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NSP),
    };
}

/* The reference of a running drive: 6042h, reversed by control word bit 11, its magnitude
 * held between LSP and HSP (the drive runs at LSP with a zero reference). */
static int32_t run_reference(atv312_t *drive)
{
    int32_t reference = (int16_t)atv312_param(drive, ATV312_IDX_TARGET_VELOCITY, 0);
    bool reverse = (reference < 0) != ((drive->cia402.control & ATV312_CW_REVERSE) != 0);
    uint32_t wanted = (uint32_t)(reference < 0 ? -reference : reference);
    uint32_t high =
        atv312_frequency_to_rpm(drive, atv312_param(drive, ATV312_IDX_LIMITS, ATV312_SUB_HSP));
    uint32_t low =
        atv312_frequency_to_rpm(drive, atv312_param(drive, ATV312_IDX_LIMITS, ATV312_SUB_LSP));
    uint32_t speed = wanted > high ? high : (wanted < low ? low : wanted);
    drive->limited = speed != wanted;
    return reverse ? -(int32_t)speed : (int32_t)speed;
}

/* Only Operation enabled and Quick stop active drive the motor: in any other state the output is
 * off and the motor coasts, whatever the transition that led there (freewheel on 8, 9, 12 and
 * faults). In Operation enabled the motor follows the reference unless a stop is asked: bit 12
 * on DEC, bits 13 and 14 on the fast ramp, a pending disable operation (5) on DEC; Quick stop
 * active always stops on the fast ramp. */
static void steer_motor(atv312_t *drive)
{
    const atv312_cia402_t *sm = &drive->cia402;
    uint16_t control = sm->control;
    bool enabled = sm->state == ATV312_OPERATION_ENABLED;
    bool stop_bits = control & (ATV312_CW_STOP | ATV312_CW_DC_INJECTION | ATV312_CW_FAST_STOP);
    bool fast = sm->state == ATV312_QUICK_STOP_ACTIVE ||
                (enabled && (control & (ATV312_CW_DC_INJECTION | ATV312_CW_FAST_STOP)));
    if (!atv312_cia402_drives_motor(sm))
        atv312_motor_coast(&drive->motor);
    drive->limited = false;
    int32_t target = atv312_cia402_runs(sm) && !stop_bits ? run_reference(drive) : 0;
    atv312_ramp_t ramp = ramp_parameters(drive);
    atv312_motor_steer(&drive->motor, target, fast, &ramp);
}

static uint16_t status_word(const atv312_t *drive)
{
    const atv312_motor_t *motor = &drive->motor;
    uint16_t status = atv312_cia402_status(&drive->cia402) | ATV312_SW_REMOTE;
    if (atv312_motor_at_target(motor))
        status |= ATV312_SW_TARGET_REACHED;
    if (drive->limited)
        status |= ATV312_SW_INTERNAL_LIMIT;
    if (motor->speed < 0 || (motor->speed == 0 && motor->target < 0))
        status |= ATV312_SW_REVERSE;
    return status;
}

static void publish(atv312_t *drive)
{
    co_node_t *node = &drive->node;
    uint16_t status = status_word(drive);
    co_od_set_value(node, ATV312_IDX_STATUSWORD, 0, status);
    co_od_set_value(node, ATV312_IDX_MONITORING, ATV312_SUB_ETA, status);
    int32_t rpm = atv312_motor_rpm(&drive->motor);
    co_od_set_value(node, ATV312_IDX_VELOCITY_DEMAND, 0, rpm);
    co_od_set_value(node, ATV312_IDX_VELOCITY_ACTUAL, 0, rpm);
    /* The output is on in Operation enabled, and in Quick stop active until the motor stopped
     * (then the drive locks). */
    bool energised = drive->cia402.state == ATV312_OPERATION_ENABLED ||
                     (drive->cia402.state == ATV312_QUICK_STOP_ACTIVE && drive->motor.speed != 0);
    int16_t torque = energised ? atv312_motor_torque(&drive->motor) : 0;
    int32_t load = torque < 0 ? -torque : torque;
    int32_t nominal_current = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NCR);
    int32_t current =
        energised
            ? nominal_current *
                  (MAGNETISING_CURRENT_PERCENT + (100 - MAGNETISING_CURRENT_PERCENT) * load / 100) /
                  100
            : 0;
    co_od_set_value(node, ATV312_IDX_MONITORING, ATV312_SUB_OTR, torque);
    co_od_set_value(node, ATV312_IDX_MONITORING, ATV312_SUB_LCR, current);
}

void atv312_settle(atv312_t *drive)
{
    if (drive->motor.speed == 0)
        atv312_cia402_motor_stopped(&drive->cia402);
    steer_motor(drive);
    publish(drive);
}

/* The ATV312 network fault (CnF / COF): freewheel stop (state Fault drives nothing), latched until
 * a fault reset, reported in 603Fh and by EMCY 0x8130 (which also records it in 1003h). */
static void network_fault(atv312_t *drive)
{
    if (drive->cia402.state == ATV312_FAULT)
        return;
    co_node_t *node = &drive->node;
    atv312_advance(drive, node->now);
    atv312_cia402_fault(&drive->cia402);
    co_od_set_value(node, ATV312_IDX_ERROR_CODE, 0, CO_EMCY_HEARTBEAT);
    co_emcy_raise(node, CO_EMCY_HEARTBEAT, COMMUNICATION_ERROR_REGISTER, NULL);
    atv312_settle(drive);
}

static void acknowledge_fault(atv312_t *drive)
{
    co_node_t *node = &drive->node;
    uint16_t code = atv312_param(drive, ATV312_IDX_ERROR_CODE, 0);
    co_od_set_value(node, ATV312_IDX_ERROR_CODE, 0, 0);
    co_emcy_clear(node, code);
}

static bool is_control_word(const co_od_entry_t *entry)
{
    return (entry->index == ATV312_IDX_CONTROLWORD && entry->subindex == 0) ||
           (entry->index == ATV312_IDX_COMMAND && entry->subindex == ATV312_SUB_CMD);
}

/* CMDD (6040h) and CMD (2037h:02) are the same word: both are kept equal. */
static void apply_control_word(atv312_t *drive, uint16_t control)
{
    co_od_set_value(&drive->node, ATV312_IDX_CONTROLWORD, 0, control);
    co_od_set_value(&drive->node, ATV312_IDX_COMMAND, ATV312_SUB_CMD, control);
    if (atv312_cia402_command(&drive->cia402, control, drive->motor.speed == 0))
        acknowledge_fault(drive);
}

static void on_written(co_node_t *node, const co_od_entry_t *entry, co_od_origin_t origin)
{
    (void)origin;
    atv312_t *drive = atv312_of(node);
    atv312_advance(drive, node->now);
    if (is_control_word(entry))
        apply_control_word(drive, (uint16_t)co_od_get(node, entry));
    atv312_settle(drive);
}

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    (void)producer;
    if (lost)
        network_fault(atv312_of(node));
}

static void on_guarding(co_node_t *node, bool lost)
{
    if (lost)
        network_fault(atv312_of(node));
}

/* Reset node restarts the drive too: Switch on disabled, motor stopped (the dictionary's
 * defaults, restored right after this, describe that state). */
static void on_reset(co_node_t *node, co_nmt_reset_t scope)
{
    if (scope != CO_NMT_RESET_NODE)
        return;
    atv312_t *drive = atv312_of(node);
    atv312_cia402_reset(&drive->cia402);
    atv312_motor_reset(&drive->motor, node->now);
    drive->limited = false;
}

/* The bus conditions still present are errors again once a reset node has emptied the EMCY
 * producer's active errors (the boot-up comes first, then their EMCYs). Raising an active error
 * again does nothing, so every entry into Pre-operational may do it. */
static void on_nmt_state(co_node_t *node, co_nmt_state_t state)
{
    (void)state;
    atv312_t *drive = atv312_of(node);
    for (uint8_t i = 0; i < drive->bus_event_count; i++)
        co_emcy_raise(node, drive->bus_events[i], COMMUNICATION_ERROR_REGISTER, NULL);
}

static const co_app_hooks_t drive_hooks = {
    .nmt_state = on_nmt_state,
    .reset = on_reset,
    .heartbeat = on_heartbeat,
    .guarding = on_guarding,
    .od_written = on_written,
};

int atv312_init(atv312_t *drive, uint8_t node_id, co_send_fn send, void *send_user,
                const co_storage_t *storage)
{
    co_node_config_t config = {
        .node_id = node_id,
        .od = &atv312_od,
        .od_data = drive->od_data,
        .send = send,
        .user = send_user,
        .hooks = &drive_hooks,
        .storage = storage,
    };
    int err = co_node_init(&drive->node, &config);
    if (err != 0)
        return err;
    atv312_cia402_reset(&drive->cia402);
    atv312_motor_reset(&drive->motor, 0);
    drive->limited = false;
    drive->bus_event_count = 0;
    return 0;
}

void atv312_start(atv312_t *drive, co_time_t now)
{
    co_node_start(&drive->node, now);
    atv312_settle(drive);
}

void atv312_receive(atv312_t *drive, const co_frame_t *frame, co_time_t now)
{
    co_node_receive(&drive->node, frame, now);
}

co_time_t atv312_process(atv312_t *drive, co_time_t now)
{
    atv312_advance(drive, now);
    atv312_settle(drive);
    co_time_t next = co_node_process(&drive->node, now);
    return co_time_min(next, atv312_motor_deadline(&drive->motor));
}

static void remember_bus_event(atv312_t *drive, uint16_t emcy_code, bool active)
{
    for (uint8_t i = 0; i < drive->bus_event_count; i++) {
        if (drive->bus_events[i] == emcy_code) {
            if (!active)
                drive->bus_events[i] = drive->bus_events[--drive->bus_event_count];
            return;
        }
    }
    if (active && drive->bus_event_count < ATV312_BUS_EVENTS_MAX)
        drive->bus_events[drive->bus_event_count++] = emcy_code;
}

void atv312_bus_event(atv312_t *drive, uint16_t emcy_code, bool active)
{
    remember_bus_event(drive, emcy_code, active);
    if (active)
        co_emcy_raise(&drive->node, emcy_code, COMMUNICATION_ERROR_REGISTER, NULL);
    else
        co_emcy_clear(&drive->node, emcy_code);
}

const char *atv312_state_name(const atv312_t *drive)
{
    return atv312_cia402_name(drive->cia402.state);
}
