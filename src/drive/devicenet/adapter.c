/* SPDX-License-Identifier: Apache-2.0 */
/* The drive on DeviceNet (drive_devicenet.h): the slave's configuration from the model's data,
 * the assemblies read from and written to the drive's dictionary, the ends of the connections (the
 * communication-loss fault), the Identity status of the drive's faults and the Identity Reset. */
#include "drive/devicenet/drive_dn_internal.h"

#include <string.h>

static const dn_assembly_t assemblies[] = {
    {DRIVE_DN_BASIC_OUTPUT, DRIVE_DN_ASSEMBLY_SIZE, false},
    {DRIVE_DN_EXTENDED_OUTPUT, DRIVE_DN_ASSEMBLY_SIZE, false},
    {DRIVE_DN_BASIC_INPUT, DRIVE_DN_ASSEMBLY_SIZE, true},
    {DRIVE_DN_EXTENDED_INPUT, DRIVE_DN_ASSEMBLY_SIZE, true},
    {DRIVE_DN_TRANSPARENT_OUTPUT, DRIVE_DN_ASSEMBLY_SIZE, false},
    {DRIVE_DN_TRANSPARENT_INPUT, DRIVE_DN_ASSEMBLY_SIZE, true},
};

/* Byte 0 bits of the ODVA assemblies (Altivar 312 DeviceNet manual, "Assembly object"). */
#define OUT_RUN_FWD 0x01u
#define OUT_RUN_REV 0x02u
#define OUT_FAULT_RESET 0x04u
#define OUT_NET_CTRL 0x20u
#define OUT_NET_REF 0x40u
#define IN_FAULTED 0x01u
#define IN_WARNING 0x02u
#define IN_RUNNING1 0x04u
#define IN_RUNNING2 0x08u
#define IN_READY 0x10u
#define IN_CTRL_FROM_NET 0x20u
#define IN_REF_FROM_NET 0x40u
#define IN_AT_REFERENCE 0x80u

static uint8_t bit(bool on, uint8_t mask)
{
    return on ? mask : 0u;
}

static void read_output(const drive_dn_t *dn, uint16_t instance, uint8_t *data)
{
    const drive_dn_command_t *c = &dn->command;
    data[0] = (uint8_t)(bit(c->run1, OUT_RUN_FWD) | bit(c->fault_reset, OUT_FAULT_RESET));
    if (instance == DRIVE_DN_EXTENDED_OUTPUT)
        data[0] |= (uint8_t)(bit(c->run2, OUT_RUN_REV) | bit(c->net_ctrl, OUT_NET_CTRL) |
                             bit(c->net_ref, OUT_NET_REF));
    data[1] = 0;
    co_put_u16(data + 2, (uint16_t)c->speed_reference);
}

static void read_input(const drive_dn_t *dn, uint16_t instance, uint8_t *data)
{
    const drive_t *drive = dn->drive;
    drive_dn_state_t state = drive_dn_state(dn);
    data[0] = (uint8_t)(bit(drive_dn_faulted(drive), IN_FAULTED) |
                        bit(drive_dn_running1(state), IN_RUNNING1));
    data[1] = 0;
    if (instance == DRIVE_DN_EXTENDED_INPUT) {
        data[0] |= (uint8_t)(bit(drive_dn_warning(drive), IN_WARNING) |
                             bit(drive_dn_ready(state), IN_READY) |
                             bit(drive_dn_control_from_net(drive), IN_CTRL_FROM_NET) |
                             bit(drive_dn_reference_from_net(drive), IN_REF_FROM_NET) |
                             bit(drive_dn_at_reference(drive), IN_AT_REFERENCE));
        data[1] = (uint8_t)state; /* Running2 (bit 3) is always 0 */
    }
    co_put_u16(data + 2, (uint16_t)drive_dn_speed_actual(drive));
}

static void on_read_assembly(void *user, uint16_t instance, uint8_t *data)
{
    const drive_dn_t *dn = user;
    const drive_t *drive = dn->drive;
    switch (instance) {
    case DRIVE_DN_BASIC_OUTPUT:
    case DRIVE_DN_EXTENDED_OUTPUT:
        read_output(dn, instance, data);
        break;
    case DRIVE_DN_TRANSPARENT_OUTPUT:
        co_put_u16(data, drive_dn_control_word(drive));
        co_put_u16(data + 2, (uint16_t)co_od_get(&drive->node, drive->entries.target_velocity));
        break;
    case DRIVE_DN_TRANSPARENT_INPUT:
        co_put_u16(data, drive_dn_status_word(drive));
        co_put_u16(data + 2, (uint16_t)drive_dn_speed_actual(drive));
        break;
    default:
        read_input(dn, instance, data);
        break;
    }
}

/* 6042h before 6040h, so that a run starts on its own reference; each only when it changes. */
static void write_transparent(drive_dn_t *dn, const uint8_t *data)
{
    co_node_t *node = &dn->drive->node;
    const drive_entries_t *e = &dn->drive->entries;
    if (co_get_u16(data + 2) != (uint16_t)co_od_get(node, e->target_velocity))
        (void)co_od_write(node, 0x6042, 0, data + 2, 2, CO_OD_ORIGIN_CARD);
    if (co_get_u16(data) != drive_dn_control_word(dn->drive))
        (void)co_od_write(node, 0x6040, 0, data, 2, CO_OD_ORIGIN_CARD);
}

static void on_write_assembly(void *user, uint16_t instance, const uint8_t *data)
{
    drive_dn_t *dn = user;
    (void)drive_process(dn->drive, dn->now); /* the drive's time is the frame's */
    if (instance == DRIVE_DN_TRANSPARENT_OUTPUT) {
        drive_dn_note_command_connection(dn);
        write_transparent(dn, data);
        return;
    }
    drive_dn_command_t next = dn->command;
    next.run1 = (data[0] & OUT_RUN_FWD) != 0;
    next.fault_reset = (data[0] & OUT_FAULT_RESET) != 0;
    if (instance == DRIVE_DN_EXTENDED_OUTPUT) {
        next.run2 = (data[0] & OUT_RUN_REV) != 0;
        next.net_ctrl = (data[0] & OUT_NET_CTRL) != 0;
        next.net_ref = (data[0] & OUT_NET_REF) != 0;
    }
    next.speed_reference = (int16_t)co_get_u16(data + 2);
    drive_dn_command(dn, &next);
}

/* The drive runs on a network command: Operation enabled (the Control supervisor's Enabled, not
 * a stop already under way), the command channel the network's. */
static bool runs_on_network_command(const drive_dn_t *dn)
{
    return drive_dn_state(dn) == DRIVE_DN_ENABLED && drive_dn_control_from_net(dn->drive);
}

/* Whether a connection carried the commands the drive runs on: the I/O connection of instance 2
 * while it is Established (each of its messages carries the whole command), else the explicit
 * connection whose requests last changed them (Sets of the Control supervisor, the AC/DC drive
 * or the output assembly, the Control supervisor's Reset), instance 1 until another does
 * (docs/decisions.md, D-DEVICENET-CONNECTION-END). */
static bool carried_the_commands(const drive_dn_t *dn, uint8_t instance)
{
    if (instance == DN_CONN_POLL)
        return true;
    return instance == dn->command_connection &&
           dn_node_connection_state(&dn->node, DN_CONN_POLL) != DN_CONN_ESTABLISHED;
}

/* A connection ended. An I/O connection timed out: the periodic data stopped, the drive's
 * communication loss (CnF on an Altivar, with the reaction of its COL) whatever it does. Any
 * other end (a release, a deletion, bus off, the interface lost, a restart) of the connection
 * that carried the commands while the drive runs on them stops them as surely: the same loss,
 * rather than a motor left at the last command that the network can no longer stop; a standing
 * or stopping drive keeps its state (D-DEVICENET-CONNECTION-END). Idle keeps the last command
 * (D-DEVICENET-DRIVE-IDLE). */
static void on_connection_ended(void *user, uint8_t instance, dn_end_cause_t cause)
{
    drive_dn_t *dn = user;
    (void)drive_process(dn->drive, dn->now); /* the state at the frame's time */
    bool io_timeout =
        cause == DN_END_TIMEOUT && (instance == DN_CONN_POLL || instance == DN_CONN_COS_CYCLIC);
    if (io_timeout || (carried_the_commands(dn, instance) && runs_on_network_command(dn)))
        drive_communication_loss(dn->drive, dn->now);
    if (instance == dn->command_connection)
        dn->command_connection = 0; /* a new connection of the instance carries nothing yet */
}

static void on_send(void *user, const co_frame_t *frame)
{
    drive_dn_t *dn = user;
    dn->send(dn->user, frame);
}

static bool on_store(void *user, const dn_stored_t *stored)
{
    drive_dn_t *dn = user;
    if (!dn->store(dn->user, stored))
        return false;
    dn->config.stored = *stored; /* what the next start (a reset) loads */
    return true;
}

static void on_reset(void *user, uint8_t type)
{
    drive_dn_t *dn = user;
    dn->pending_reset = type;
}

void drive_dn_drop_frame(void *user, const co_frame_t *frame)
{
    (void)user;
    (void)frame;
}

int drive_dn_init(drive_dn_t *dn, const drive_dn_config_t *config)
{
    if (!config->drive || !config->profile || !config->send)
        return DRIVE_DN_INIT_BAD_CONFIG;
    memset(dn, 0, sizeof *dn);
    dn->drive = config->drive;
    dn->profile = config->profile;
    dn->user = config->user;
    dn->send = config->send;
    dn->store = config->store;
    dn->pending_reset = -1;
    dn->command.net_ctrl = dn->command.net_ref = true; /* the network, until told otherwise */
    dn->command_connection = DN_CONN_EXPLICIT;
    for (size_t i = 0; i < DRIVE_DN_COMMISSIONING_FAULTS; i++) {
        const char *code = config->profile->commissioning_faults[i];
        dn->commissioning_fault[i] = code ? drive_fault_find(config->drive, code) : -1;
    }
    dn->app = (dn_app_t){.user = dn,
                         .send = on_send,
                         .read_assembly = on_read_assembly,
                         .write_assembly = on_write_assembly,
                         .connection_ended = on_connection_ended,
                         .store = config->store ? on_store : NULL,
                         .reset = on_reset,
                         .stats = &dn->stats};
    drive_dn_objects(dn, dn->objects);
    const drive_dn_profile_t *p = config->profile;
    dn->config = (dn_config_t){
        .mac_id = config->mac_id,
        .baud_rate = config->baud_rate,
        .mac_switch = config->mac_id,
        .baud_switch = config->baud_rate,
        .vendor_id = p->vendor_id,
        .device_type = p->device_type,
        .product_code = p->product_code,
        .major_revision = p->major_revision,
        .minor_revision = p->minor_revision,
        .serial_number = config->serial_number,
        .product_name = p->product_name,
        .assemblies = assemblies,
        .assembly_count = (uint8_t)(sizeof assemblies / sizeof assemblies[0]),
        .default_consumed_assembly = DRIVE_DN_EXTENDED_OUTPUT,
        .default_produced_assembly = DRIVE_DN_EXTENDED_INPUT,
        .stored = config->stored,
        .objects = dn->objects,
        .object_count = DRIVE_DN_OBJECT_COUNT,
        .app = &dn->app,
    };
    return dn_node_init(&dn->node, &dn->config);
}

/* Whether the drive's latched fault is one of a missing or incorrect configuration. */
static bool needs_commissioning(const drive_dn_t *dn)
{
    if (drive_fault_latched(dn->drive) == NULL)
        return false;
    for (size_t i = 0; i < DRIVE_DN_COMMISSIONING_FAULTS; i++)
        if (dn->commissioning_fault[i] == dn->drive->fault_latched)
            return true;
    return false;
}

/* The drive's faults in the Identity status: a drive in Fault is the manual's major recoverable
 * fault "Faulted"; one whose configuration is incorrect (CFF, CFI) also needs commissioning, MS
 * flashing green (docs/decisions.md, D-DEVICENET-LEDS). */
static void report_faults(drive_dn_t *dn)
{
    dn_node_set_faults(&dn->node, drive_dn_faulted(dn->drive) ? DN_STATUS_MAJOR_RECOVERABLE : 0u);
    dn_node_set_commissioning(&dn->node, needs_commissioning(dn));
}

void drive_dn_start(drive_dn_t *dn, co_time_t now)
{
    dn->now = now;
    drive_start(dn->drive, now);
    dn_node_power_up(&dn->node, now);
    report_faults(dn);
}

/* Identity Reset, after its response left: type 1 first returns the stored selection and Quick
 * Connect to their out-of-box values; then, as a power cycle, the drive restarts (a reset node of
 * its dictionary: stored parameters, Switch on disabled; the latched CnF code cleared) and the
 * card goes on the bus again with a new duplicate MAC ID check (docs/decisions.md,
 * D-DEVICENET-IDENTITY-RESET). */
static void carry_out_reset(drive_dn_t *dn, co_time_t now)
{
    uint8_t type = (uint8_t)dn->pending_reset;
    dn->pending_reset = -1;
    if (type == 1 && dn->store) {
        dn_stored_t out_of_box = {0, 0, false};
        if (dn->store(dn->user, &out_of_box))
            dn->config.stored = out_of_box;
    }
    co_frame_t reset_node = {.id = 0, .len = 2, .data = {0x81, dn->drive->node.node_id}};
    drive_receive(dn->drive, &reset_node, now);
    drive_dn_command_t start = {.net_ctrl = true, .net_ref = true};
    dn->command = start;
    dn->command_connection = DN_CONN_EXPLICIT;
    dn->reverse = false;
    dn_node_stop(&dn->node, now); /* its connections end on a drive that no longer runs */
    (void)dn_node_init(&dn->node, &dn->config);
    dn_node_power_up(&dn->node, now);
}

void drive_dn_receive(drive_dn_t *dn, const co_frame_t *frame, co_time_t now)
{
    dn->now = now;
    dn_node_receive(&dn->node, frame, now);
    report_faults(dn);
}

/* The reset waits for its response, which leaves in the node's processing. */
co_time_t drive_dn_process(drive_dn_t *dn, co_time_t now)
{
    dn->now = now;
    co_time_t drive_next = drive_process(dn->drive, now);
    report_faults(dn);
    co_time_t next = dn_node_process(&dn->node, now);
    if (dn->pending_reset >= 0) {
        carry_out_reset(dn, now);
        drive_next = drive_process(dn->drive, now);
        next = dn_node_process(&dn->node, now);
    }
    report_faults(dn); /* an I/O timeout may have faulted the drive */
    return co_time_min(next, drive_next);
}

/* The connections end before the node is built again: a drive running on their commands takes
 * its communication-loss reaction. */
void drive_dn_restart(drive_dn_t *dn, co_time_t now)
{
    dn->now = now;
    dn_node_stop(&dn->node, now);
    (void)dn_node_init(&dn->node, &dn->config);
    dn_node_start(&dn->node, now);
    report_faults(dn);
}

void drive_dn_bus_off(drive_dn_t *dn, co_time_t now)
{
    dn->now = now;
    dn_node_bus_off(&dn->node, now);
    report_faults(dn);
}
