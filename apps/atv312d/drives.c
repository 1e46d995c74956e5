/* SPDX-License-Identifier: Apache-2.0 */
/* The nodes on the bus as runtime devices (drives.h): the drives' and the plain nodes' callbacks
 * from the loop, the log of their state changes, boot-ups and emergencies, the DeviceNet cards'
 * stored values, and their initialisation from the command line. */
#include "atv312d/drives.h"

#include "atv312d/leds.h"
#include "co_linux/conditions.h"
#include "co_linux/log.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

/* The node-id of the drive behind a DeviceNet card: the card's internal link to the drive, whose
 * frames are not on the bus (drive_dn_drop_frame), so any valid node-id does. */
#define DN_DRIVE_NODE_ID 1u
/* A DeviceNet drive's serial number (Identity attribute 6, in its duplicate MAC ID checks):
 * this base plus its MAC ID, so that every drive of a bench has its own (docs/atv312d.md). */
#define DN_SERIAL_BASE 0x31200000u

static uint8_t slot_node_id(const atv312d_drive_t *slot)
{
    return slot->id;
}

static void log_led_change(const atv312d_drive_t *slot, const char *name, dn_led_t *logged,
                           dn_led_t now)
{
    if (now != *logged)
        co_log(atv312d_led_change_level(*logged, now), "node %u: %s LED %s -> %s", slot->id, name,
               drive_dn_led_name(*logged), drive_dn_led_name(now));
    *logged = now;
}

/* State changes are logged by comparing after every call into the drive: the drive owns the
 * core's application hooks. On DeviceNet the bus's view is the card's LEDs, not the drive's
 * internal NMT state. */
static void log_state_changes(atv312d_drive_t *slot)
{
    if (slot->dn) {
        log_led_change(slot, "MS", &slot->ms_led, dn_node_ms_led(&slot->dn->node));
        log_led_change(slot, "NS", &slot->ns_led, dn_node_ns_led(&slot->dn->node));
    } else if (slot->drive.node.nmt_state != slot->nmt_state) {
        co_nmt_state_t nmt = slot->drive.node.nmt_state;
        co_log(CO_LOG_INFO, "node %u: NMT %s -> %s", slot_node_id(slot),
               co_nmt_state_name(slot->nmt_state), co_nmt_state_name(nmt));
        slot->nmt_state = nmt;
    }
    const char *state = drive_state_name(&slot->drive);
    if (state != slot->cia402_state && strcmp(state, slot->cia402_state) != 0) {
        co_log(CO_LOG_INFO, "node %u: CiA 402 %s -> %s", slot_node_id(slot), slot->cia402_state,
               state);
    }
    slot->cia402_state = state;
}

/* Which error control lost the master: the drive knows it when its EMCY leaves. */
static void log_communication_loss(const atv312d_drive_t *slot, uint8_t reg)
{
    drive_comm_loss_t loss = slot->drive.comm_loss;
    char why[64];
    if (loss.source == DRIVE_COMM_LOSS_HEARTBEAT)
        snprintf(why, sizeof why, "heartbeat of node %u timed out", loss.node);
    else if (loss.source == DRIVE_COMM_LOSS_GUARDING)
        snprintf(why, sizeof why, "life guarding timed out");
    else
        snprintf(why, sizeof why, "heartbeat or life guarding timeout");
    co_log(CO_LOG_WARN, "node %u: communication loss (EMCY 8130, error register %02X): %s",
           slot_node_id(slot), reg, why);
}

static void log_emcy(const atv312d_drive_t *slot, const co_frame_t *frame)
{
    uint16_t code = co_get_u16(frame->data);
    uint8_t reg = frame->data[2];
    if (code == CO_EMCY_HEARTBEAT)
        log_communication_loss(slot, reg);
    else if (code == 0)
        co_log(CO_LOG_INFO, "node %u: EMCY 0000 error reset (error register %02X)",
               slot_node_id(slot), reg);
    else
        co_log(CO_LOG_INFO, "node %u: EMCY %04X (error register %02X)", slot_node_id(slot), code,
               reg);
}

/* The drive's send callback: counts the frame, notes boot-ups and emergencies for the log, then
 * transmits. */
static void slot_send(void *user, const co_frame_t *frame)
{
    atv312d_drive_t *slot = user;
    uint8_t node_id = slot_node_id(slot);
    atv312d_count_sent(&slot->counters, node_id, frame);
    if (frame->id == CO_CAN_ID_ERROR_CONTROL + node_id && frame->len == 1 && frame->data[0] == 0)
        co_log(CO_LOG_INFO, "node %u: boot-up", node_id);
    else if (frame->len == 8 && atv312d_is_emcy(node_id, frame))
        log_emcy(slot, frame);
    co_linux_device_send(&slot->device, frame);
}

static void slot_start(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    drive_start(&slot->drive, now);
    log_state_changes(slot);
}

/* After the interface was down, the master must learn that the drive is back and may have missed
 * frames: the drive resets communication (CiA 301 NMT command 0x82 addressed to it), which sends
 * the boot-up at once. Application state (motor, CiA 402) is kept. */
static void slot_restart(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_frame_t reset = {.id = 0, .len = 2, .data = {CO_NMT_CS_RESET_COMMUNICATION}};
    reset.data[1] = slot_node_id(slot);
    co_log(CO_LOG_INFO, "node %u: reset communication after the interface came back",
           slot_node_id(slot));
    drive_receive(&slot->drive, &reset, now);
    log_state_changes(slot);
}

static void slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    atv312d_count_received(&slot->counters, slot_node_id(slot), frame);
    drive_receive(&slot->drive, frame, now);
    log_state_changes(slot);
}

static co_time_t slot_process(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_time_t next = drive_process(&slot->drive, now);
    log_state_changes(slot);
    return next;
}

static void slot_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    atv312d_drive_t *slot = ctx;
    drive_bus_event(&slot->drive, emcy_code, active);
}

static void slot_bus_warning(void *ctx, bool active)
{
    atv312d_drive_t *slot = ctx;
    drive_bus_warning(&slot->drive, active);
}

static const co_node_t *slot_node(void *ctx)
{
    atv312d_drive_t *slot = ctx;
    return &slot->drive.node;
}

/* A plain node's state changes: the node-id LSS gave it, NMT, and the error control events its
 * model reacts to. The slot follows the node-id, so that every surface names the node by it. */
static void log_plain_changes(atv312d_drive_t *slot)
{
    const plain_node_t *plain = slot->plain;
    if (plain->node.node_id != slot->id) {
        if (slot->id == CO_LSS_NODE_ID_UNCONFIGURED)
            co_log(CO_LOG_INFO, "node with serial number %08lXh: node-id %u from LSS",
                   (unsigned long)plain->serial_number, plain->node.node_id);
        else
            co_log(CO_LOG_INFO, "node %u: node-id %u from LSS", slot->id, plain->node.node_id);
        slot->id = plain->node.node_id;
    }
    if (plain->node.nmt_state != slot->nmt_state) {
        co_log(CO_LOG_INFO, "node %u: NMT %s -> %s", slot->id, co_nmt_state_name(slot->nmt_state),
               co_nmt_state_name(plain->node.nmt_state));
        slot->nmt_state = plain->node.nmt_state;
    }
    if (plain->loss != slot->plain_loss && plain->loss == PLAIN_LOSS_HEARTBEAT)
        co_log(CO_LOG_WARN, "node %u: heartbeat of node %u timed out", slot->id,
               plain->lost_producer);
    else if (plain->loss != slot->plain_loss && plain->loss == PLAIN_LOSS_GUARDING)
        co_log(CO_LOG_WARN, "node %u: life guarding timed out", slot->id);
    slot->plain_loss = plain->loss;
}

static void plain_slot_start(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    plain_node_start(slot->plain, now);
    log_plain_changes(slot);
}

/* After the interface was down: reset communication, as a drive does (slot_restart). */
static void plain_slot_restart(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_frame_t reset = {.id = 0, .len = 2, .data = {CO_NMT_CS_RESET_COMMUNICATION, slot->id}};
    co_log(CO_LOG_INFO, "node %u: reset communication after the interface came back", slot->id);
    plain_node_receive(slot->plain, &reset, now);
    log_plain_changes(slot);
}

static void plain_slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    atv312d_count_received(&slot->counters, slot->id, frame);
    plain_node_receive(slot->plain, frame, now);
    log_plain_changes(slot);
}

static co_time_t plain_slot_process(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_time_t next = plain_node_process(slot->plain, now);
    log_plain_changes(slot);
    return next;
}

static void plain_slot_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    atv312d_drive_t *slot = ctx;
    plain_node_bus_event(slot->plain, emcy_code, active);
}

static void plain_slot_bus_warning(void *ctx, bool active)
{
    atv312d_drive_t *slot = ctx;
    plain_node_bus_warning(slot->plain, active);
}

static const co_node_t *plain_slot_node(void *ctx)
{
    atv312d_drive_t *slot = ctx;
    return &slot->plain->node;
}

static const co_linux_device_ops_t plain_slot_ops = {
    .start = plain_slot_start,
    .restart = plain_slot_restart,
    .receive = plain_slot_receive,
    .process = plain_slot_process,
    .bus_event = plain_slot_bus_event,
    .bus_warning = plain_slot_bus_warning,
    .node = plain_slot_node,
};

static const co_linux_device_ops_t slot_ops = {
    .start = slot_start,
    .restart = slot_restart,
    .receive = slot_receive,
    .process = slot_process,
    .bus_event = slot_bus_event,
    .bus_warning = slot_bus_warning,
    .node = slot_node,
};

/* The same drive slot behind its DeviceNet card (drive_devicenet.h): the card's frames go to the
 * bus, the drive's own are its internal link. No core node: the card names the CAN-IDs it acts
 * on (its MAC ID's), so a frame reaches one card and the socket's filter keeps the others out
 * (docs/runtime.md, "Routing and the receive filter"). */
static void dn_slot_send(void *user, const co_frame_t *frame)
{
    atv312d_drive_t *slot = user;
    co_linux_device_send(&slot->device, frame);
}

static void dn_slot_start(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_log(CO_LOG_INFO, "node %u: duplicate MAC ID check", slot->id);
    drive_dn_start(slot->dn, now);
    log_state_changes(slot);
}

/* After the interface was down the card goes on the bus again as after power-up: a new duplicate
 * MAC ID check, its connections gone; a drive that ran on their commands takes CnF, any other
 * keeps its state (docs/decisions.md, D-DEVICENET-CONNECTION-END). */
static void dn_slot_restart(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_log(CO_LOG_INFO, "node %u: duplicate MAC ID check after the interface came back", slot->id);
    drive_dn_restart(slot->dn, now);
    log_state_changes(slot);
}

static void dn_slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    drive_dn_receive(slot->dn, frame, now);
    log_state_changes(slot);
}

static co_time_t dn_slot_process(void *ctx, co_time_t now)
{
    atv312d_drive_t *slot = ctx;
    co_time_t next = drive_dn_process(slot->dn, now);
    log_state_changes(slot);
    return next;
}

/* Bus off is the card's (its bus-off counter, BOI); the other conditions are CANopen
 * emergencies, which a DeviceNet card has not. */
static void dn_slot_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    atv312d_drive_t *slot = ctx;
    if (emcy_code == CO_LINUX_EMCY_BUS_OFF && active) {
        drive_dn_bus_off(slot->dn, slot->device.loop->now);
        log_state_changes(slot);
    }
}

_Static_assert(DN_NODE_CONSUMED_IDS <= CO_LINUX_DEVICE_CONSUMERS_MAX,
               "a card's CAN-IDs fit a device's");

static size_t dn_slot_consumers(void *ctx, co_cob_t *cobs)
{
    const atv312d_drive_t *slot = ctx;
    uint16_t ids[DN_NODE_CONSUMED_IDS];
    size_t count = dn_node_consumed_ids(&slot->dn->node, ids);
    for (size_t i = 0; i < count; i++)
        cobs[i] = (co_cob_t){.can_id = ids[i], .rtr = false};
    return count;
}

static const co_linux_device_ops_t dn_slot_ops = {
    .start = dn_slot_start,
    .restart = dn_slot_restart,
    .receive = dn_slot_receive,
    .process = dn_slot_process,
    .bus_event = dn_slot_bus_event,
    .node = NULL,
    .consumers = dn_slot_consumers,
};

/* The card's stored values (Connection class attributes 100/101, Quick Connect) in the --store
 * file, keyed by MAC ID. */
static bool dn_slot_store(void *user, const dn_stored_t *stored)
{
    atv312d_drive_t *slot = user;
    co_file_devicenet_t values = {.consumed_assembly = stored->consumed_assembly,
                                  .produced_assembly = stored->produced_assembly,
                                  .quick_connect = stored->quick_connect};
    if (co_file_store_set_devicenet(slot->store, slot->id, &values) == 0)
        return true;
    co_log(CO_LOG_WARN, "store %s: node %u: DeviceNet values not saved: %s", slot->store->path,
           slot->id, slot->store->reason);
    return false;
}

static dn_stored_t dn_slot_stored(const atv312d_drive_t *slot)
{
    co_file_devicenet_t values;
    if (!slot->store || !co_file_store_get_devicenet(slot->store, slot->id, &values))
        return (dn_stored_t){0, 0, false};
    return (dn_stored_t){values.consumed_assembly, values.produced_assembly, values.quick_connect};
}

/* The drive of `model` on `profile`: the model's own, or the one behind its DeviceNet card. */
static int init_drive(atv312d_drive_t *slot, uint8_t node_id, const drive_model_t *model,
                      const drive_profile_t *profile, const co_storage_t *storage, co_send_fn send)
{
    slot->od_data = calloc(1, profile->od->data_size);
    if (!slot->od_data)
        return EX_OSERR;
    drive_config_t config = {
        .profile = profile,
        .od_data = slot->od_data,
        .node_id = node_id,
        .send = send,
        .send_user = slot,
        .storage = storage,
        /* The heartbeats of every drive on one grid: one wake-up per period for the whole bench,
         * however a master staggered its 1017h writes (docs/atv312d.md). */
        .node_options = CO_NODE_HEARTBEAT_GRID,
        .node_options_code = &co_node_options,
    };
    int rc = drive_init(&slot->drive, &config);
    if (rc == 0)
        return 0;
    co_log(CO_LOG_ERROR, "node %u: the %s drive cannot be initialised (error 0x%X)", slot->id,
           model->name, (unsigned)rc);
    return EX_SOFTWARE;
}

/* The drive behind its DeviceNet card, on the MAC ID of the slot. */
static int init_devicenet_drive(atv312d_drive_t *slot, const drive_model_t *model,
                                const atv312d_options_t *opts)
{
    int rc = init_drive(slot, DN_DRIVE_NODE_ID, model, model->devicenet->drive, NULL,
                        drive_dn_drop_frame);
    if (rc != 0)
        return rc;
    slot->dn = calloc(1, sizeof *slot->dn);
    if (!slot->dn)
        return EX_OSERR;
    drive_dn_config_t config = {
        .drive = &slot->drive,
        .profile = model->devicenet,
        .mac_id = slot->id,
        .baud_rate = (uint8_t)opts->baud,
        .serial_number = DN_SERIAL_BASE + slot->id,
        .stored = dn_slot_stored(slot),
        .send = dn_slot_send,
        .user = slot,
        .store = slot->store ? dn_slot_store : NULL,
    };
    rc = drive_dn_init(slot->dn, &config);
    if (rc == 0)
        return 0;
    co_log(CO_LOG_ERROR, "node %u: the %s's DeviceNet card cannot be initialised (error %d)",
           slot->id, model->name, rc);
    return EX_SOFTWARE;
}

/* CiA 305 store configuration: the pending node-id and bit timing in the --store file, under the
 * node's key; without --store, not supported. */
static uint8_t lss_store(co_node_t *node, uint8_t node_id, uint8_t bit_timing, uint8_t *specific)
{
    (void)specific;
    atv312d_drive_t *slot = node->user;
    if (!slot->store)
        return CO_LSS_STORE_NOT_SUPPORTED;
    if (co_file_store_set_lss(slot->store, slot->key, node_id, bit_timing) != 0) {
        co_log(CO_LOG_ERROR, "node %u: LSS store of node-id %u: %s", slot->id, node_id,
               slot->store->reason);
        return CO_LSS_STORE_MEDIA_ERROR;
    }
    co_log(CO_LOG_INFO, "node %u: LSS stored node-id %u", slot->id, node_id);
    return CO_LSS_OK;
}

static const co_lss_slave_hooks_t lss_hooks = {.store = lss_store};

/* The node-id a node with LSS starts with: the one LSS stored for its key, else its own (FFh for
 * one of --unconfigured). */
static uint8_t lss_start_node_id(const atv312d_drive_t *slot)
{
    uint8_t node_id, bit_timing;
    if (slot->store && co_file_store_get_lss(slot->store, slot->key, &node_id, &bit_timing))
        return node_id;
    return slot->id;
}

/* A plain node of `model` (a PLC300, an I/O node): its serial number the model's base plus its
 * key (its node-id, or 80h + k for the k-th unconfigured node: docs/decisions.md,
 * D-IO401-IDENTITY), the heartbeat grid as the drives'. */
static int init_plain(atv312d_drive_t *slot, const plain_model_t *model,
                      const co_storage_t *storage)
{
    if (model->lss)
        slot->id = lss_start_node_id(slot);
    slot->plain = calloc(1, sizeof *slot->plain);
    slot->od_data = calloc(1, model->od->data_size);
    if (!slot->plain || !slot->od_data)
        return EX_OSERR;
    plain_node_config_t config = {
        .model = model,
        .od_data = slot->od_data,
        .node_id = slot->id,
        .serial_number = model->serial_base + slot->key,
        .lss_hooks = &lss_hooks,
        /* The daemon runs at whatever rate ip link gave the interface: table 0's "auto". */
        .lss_bit_timing = CO_LSS_BIT_TIMING_AUTO,
        .send = slot_send,
        .send_user = slot,
        .storage = storage,
        .node_options = CO_NODE_HEARTBEAT_GRID,
        .node_options_code = &co_node_options,
    };
    int rc = plain_node_init(slot->plain, &config);
    if (rc == 0)
        return 0;
    co_log(CO_LOG_ERROR, "node %u: the %s node cannot be initialised (error 0x%X)", slot->id,
           model->name, (unsigned)rc);
    return EX_SOFTWARE;
}

/* A node on CANopen: bound to the store, a drive or a plain node by its model's kind. A drive
 * with CANopen off (AdCO = 0) has node-id 0 in the drive layer, its node never started
 * (D-ADCO-BDCO). */
static int init_canopen(atv312d_drive_t *slot, const atv312d_model_t *model, bool can_off)
{
    const co_storage_t *storage = NULL;
    if (slot->store) {
        co_file_store_bind(slot->store, slot->key, &slot->store_node, &slot->storage);
        storage = &slot->storage;
    }
    if (model->kind == ATV312D_KIND_NODE)
        return init_plain(slot, model->node, storage);
    int rc = init_drive(slot, can_off ? 0 : slot->id, model->drive, model->drive->profile, storage,
                        slot_send);
    if (rc == 0 && can_off)
        co_log(CO_LOG_INFO, "node %u: CANopen off (AdCO = 0): silent on the bus", slot->id);
    return rc;
}

int atv312d_drives_init(atv312d_drive_t *slots, const atv312d_options_t *opts,
                        co_file_store_t *store, co_linux_loop_t *loop)
{
    uint8_t unconfigured = 0;
    for (size_t i = 0; i < opts->node_count; i++) {
        atv312d_drive_t *slot = &slots[i];
        slot->id = opts->node_ids[i];
        slot->key = slot->id == CO_LSS_NODE_ID_UNCONFIGURED
                        ? (uint8_t)(CO_FILE_STORE_UNCONFIGURED_KEY + ++unconfigured)
                        : slot->id;
        slot->store = store;
        int rc = opts->devicenet ? init_devicenet_drive(slot, opts->models[i].drive, opts)
                                 : init_canopen(slot, &opts->models[i], opts->can_off[i]);
        if (rc != 0)
            return rc;
        if (slot->plain) {
            slot->nmt_state = slot->plain->node.nmt_state;
            co_linux_loop_add(loop, &slot->device, &plain_slot_ops, slot);
            continue;
        }
        slot->nmt_state = slot->drive.node.nmt_state;
        slot->cia402_state = drive_state_name(&slot->drive);
        co_linux_loop_add(loop, &slot->device, slot->dn ? &dn_slot_ops : &slot_ops, slot);
    }
    return 0;
}

void atv312d_drives_free(atv312d_drive_t *slots, size_t count)
{
    if (!slots)
        return;
    for (size_t i = 0; i < count; i++) {
        co_file_store_unbind(&slots[i].store_node);
        free(slots[i].od_data);
        free(slots[i].dn);
        free(slots[i].plain);
    }
    free(slots);
}
