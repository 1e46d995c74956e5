/* SPDX-License-Identifier: Apache-2.0 */
/* The ODVA AC drive profile translated to the drive's Drivecom profile, as the Altivar 312
 * DeviceNet manual's tables say ("Run/Stop event triggers", "DRIVECOM status to State
 * translation"): the card writes the drive's control word and reference and reads its status
 * word; the drive's state machine does the rest. */
#include "drive/devicenet/drive_dn_internal.h"

uint16_t drive_dn_status_word(const drive_t *drive)
{
    return (uint16_t)co_od_get(&drive->node, drive->entries.status_word);
}

uint16_t drive_dn_control_word(const drive_t *drive)
{
    return (uint16_t)co_od_get(&drive->node, drive->entries.control_word);
}

int16_t drive_dn_speed_actual(const drive_t *drive)
{
    return (int16_t)co_od_get(&drive->node, drive->entries.velocity_actual);
}

/* Through the dictionary, as the card's write request (CO_OD_ORIGIN_CARD): the checks and the
 * drive's hooks of an SDO download. */
static void write_word(drive_dn_t *dn, uint16_t index, uint16_t value)
{
    uint8_t data[2];
    co_put_u16(data, value);
    (void)co_od_write(&dn->drive->node, index, 0, data, sizeof data, CO_OD_ORIGIN_CARD);
}

static void write_control(drive_dn_t *dn, uint16_t word)
{
    if (word != drive_dn_control_word(dn->drive))
        write_word(dn, 0x6040, word);
}

/* NetCtrl and NetRef switch the channels through control word bits 12 and 13 (the manual's
 * configuration for assemblies 20/70 and 21/71: CCS = C212, rFC = C213, channel 1 the network):
 * 1 (network) is the bit at 0, channel 1. A bit no switch uses keeps its profile meaning (bit 12
 * is the Stt stop) and stays 0 (docs/decisions.md, D-DEVICENET-NETCTRL). */
static uint16_t switching_bits(const drive_dn_t *dn)
{
    uint16_t bits = 0;
    if (!dn->command.net_ctrl)
        bits |= DN_DRIVECOM_NET_CTRL_BIT;
    if (!dn->command.net_ref)
        bits |= DN_DRIVECOM_NET_REF_BIT;
    return (uint16_t)(bits & dn->drive->assigned_bits);
}

static int16_t clamp_rpm(int32_t rpm)
{
    return (int16_t)(rpm > INT16_MAX ? INT16_MAX : rpm < INT16_MIN ? INT16_MIN : rpm);
}

/* The reference the drive runs to: the speed reference, negated after a Run2 (the manual:
 * "Enable operation, Reversed speed reference"). */
static void write_reference(drive_dn_t *dn)
{
    int32_t rpm = dn->reverse ? -(int32_t)dn->command.speed_reference : dn->command.speed_reference;
    uint16_t value = (uint16_t)clamp_rpm(rpm);
    if (value != (uint16_t)co_od_get(&dn->drive->node, dn->drive->entries.target_velocity))
        write_word(dn, 0x6042, value);
}

/* Enable operation: the card steps the drive through the state chart, one command per state
 * (Shutdown, Switch on, Enable operation), as a master on CANopen would; a state the commands
 * cannot leave (Fault, Quick stop active, local control) ends the steps. */
static void run(drive_dn_t *dn)
{
    for (int step = 0; step < 3; step++) {
        cia402_state_t state = dn->drive->cia402.state;
        if (state == CIA402_SWITCH_ON_DISABLED) {
            write_word(dn, 0x6040, (uint16_t)(switching_bits(dn) | DN_DRIVECOM_SHUTDOWN));
        } else if (state == CIA402_READY_TO_SWITCH_ON) {
            write_word(dn, 0x6040, (uint16_t)(switching_bits(dn) | DN_DRIVECOM_SWITCH_ON));
        } else {
            write_control(dn, (uint16_t)(switching_bits(dn) | DN_DRIVECOM_ENABLE_OPERATION));
            return;
        }
        if (dn->drive->cia402.state == state)
            return;
    }
}

/* Stop: Disable operation in Operation enabled (a stop on the deceleration ramp to Switched
 * on), Shutdown in Switch on disabled and Switched on (to Ready to switch on); nothing where the
 * drive is already there or cannot go (Fault, Quick stop active). */
static void stop(drive_dn_t *dn)
{
    cia402_state_t state = dn->drive->cia402.state;
    if (state == CIA402_OPERATION_ENABLED)
        write_control(dn, (uint16_t)(switching_bits(dn) | DN_DRIVECOM_SWITCH_ON));
    else if (state == CIA402_SWITCH_ON_DISABLED || state == CIA402_SWITCHED_ON)
        write_word(dn, 0x6040, (uint16_t)(switching_bits(dn) | DN_DRIVECOM_SHUTDOWN));
}

typedef enum run_event { RUN_NONE, RUN_STOP, RUN_FORWARD, RUN_REVERSE } run_event_t;

/* The manual's Run/Stop event table: both 0 stop; one of them alone at 1 runs in its direction
 * when it just rose or the other just fell; both at 1, or nothing new, keep the last command. */
static run_event_t run_event(const drive_dn_command_t *was, const drive_dn_command_t *now)
{
    if (!now->run1 && !now->run2)
        return RUN_STOP;
    if (now->run1 && now->run2)
        return RUN_NONE;
    if (now->run1)
        return (!was->run1 || was->run2) ? RUN_FORWARD : RUN_NONE;
    return (!was->run2 || was->run1) ? RUN_REVERSE : RUN_NONE;
}

/* FaultRst 0 -> 1 is a rising edge of control word bit 7: the word with the bit, then without
 * it, so that the next edge counts. */
static void fault_reset(drive_dn_t *dn)
{
    uint16_t word = (uint16_t)(drive_dn_control_word(dn->drive) & ~DN_DRIVECOM_FAULT_RESET);
    write_control(dn, word);
    write_word(dn, 0x6040, (uint16_t)(word | DN_DRIVECOM_FAULT_RESET));
    write_word(dn, 0x6040, word);
}

void drive_dn_note_command_connection(drive_dn_t *dn)
{
    uint8_t connection = dn_node_request_connection(&dn->node);
    if (connection != 0) /* an explicit request's, not an I/O message's */
        dn->command_connection = connection;
}

void drive_dn_command(drive_dn_t *dn, const drive_dn_command_t *next)
{
    drive_dn_command_t was = dn->command;
    dn->command = *next;
    drive_dn_note_command_connection(dn);
    run_event_t event = run_event(&was, next);
    if (event == RUN_FORWARD || event == RUN_REVERSE)
        dn->reverse = event == RUN_REVERSE;
    write_reference(dn);
    if (next->fault_reset && !was.fault_reset)
        fault_reset(dn);
    if (event == RUN_STOP)
        stop(dn);
    else if (event != RUN_NONE)
        run(dn);
    /* NetCtrl or NetRef alone changed: the switching bits on the word in force. */
    uint16_t word = drive_dn_control_word(dn->drive);
    write_control(dn, (uint16_t)((word & ~(DN_DRIVECOM_NET_CTRL_BIT | DN_DRIVECOM_NET_REF_BIT)) |
                                 switching_bits(dn)));
}

/* The manual's DRIVECOM status to State table (status word & 006Fh); Operation enabled with
 * control word bit 3 at 0 is a disable operation on its ramp: Stopping. */
drive_dn_state_t drive_dn_state(const drive_dn_t *dn)
{
    const drive_t *drive = dn->drive;
    switch (drive_dn_status_word(drive) & CIA402_SW_STATE_MASK) {
    case 0x0040:
    case 0x0060:
        return DRIVE_DN_NOT_READY;
    case 0x0021:
    case 0x0023:
        return DRIVE_DN_READY;
    case 0x0027:
        if (!drive_local_control(drive) &&
            !(drive_dn_control_word(drive) & CIA402_CW_ENABLE_OPERATION))
            return DRIVE_DN_STOPPING;
        return DRIVE_DN_ENABLED;
    case 0x0007:
    case 0x000F:
    case 0x002F:
        return DRIVE_DN_STOPPING;
    case 0x0008:
    case 0x0028:
        return DRIVE_DN_FAULTED;
    default:
        return DRIVE_DN_STARTUP;
    }
}

const char *drive_dn_state_name(drive_dn_state_t state)
{
    static const char *const names[] = {"",        "startup",  "not-ready",  "ready",
                                        "enabled", "stopping", "fault-stop", "faulted"};
    return (unsigned)state < sizeof names / sizeof names[0] ? names[state] : "?";
}

const char *drive_dn_led_name(dn_led_t led)
{
    switch (led) {
    case DN_LED_OFF:
        return "off";
    case DN_LED_GREEN:
        return "green";
    case DN_LED_FLASHING_GREEN:
        return "flashing-green";
    case DN_LED_RED:
        return "red";
    case DN_LED_FLASHING_RED:
        return "flashing-red";
    }
    return "?";
}

/* Running1: Enabled, Stopping or Fault_Stop; Ready: Ready, Enabled or Stopping (Control
 * supervisor attributes 7 and 9). */
bool drive_dn_running1(drive_dn_state_t state)
{
    return state == DRIVE_DN_ENABLED || state == DRIVE_DN_STOPPING || state == DRIVE_DN_FAULT_STOP;
}

bool drive_dn_ready(drive_dn_state_t state)
{
    return state == DRIVE_DN_READY || state == DRIVE_DN_ENABLED || state == DRIVE_DN_STOPPING;
}

/* Faulted: status word bit 3 (latched by the drive until the reset); Warning: bit 7 (alarm). */
bool drive_dn_faulted(const drive_t *drive)
{
    return (drive_dn_status_word(drive) & 0x0008u) != 0;
}

bool drive_dn_warning(const drive_t *drive)
{
    return (drive_dn_status_word(drive) & 0x0080u) != 0;
}

bool drive_dn_at_reference(const drive_t *drive)
{
    return (drive_dn_status_word(drive) & CIA402_SW_TARGET_REACHED) != 0;
}

bool drive_dn_control_from_net(const drive_t *drive)
{
    return !drive_local_control(drive);
}

bool drive_dn_reference_from_net(const drive_t *drive)
{
    return drive->reference_from_network && !drive->local;
}
