/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d: emulated Schneider Altivar drives on a SocketCAN interface, one process, one epoll
 * loop, one socket for all of them. Usage and behaviour: docs/atv312d.md. */
#include "atv312d/cli.h"
#include "atv312d/control_socket.h"
#include "atv312d/counters.h"
#include "atv312d/http.h"
#include "atv312d/leds.h"
#include "atv312d/notify.h"
#include "atv312d/status.h"
#include "cli/co_cli.h"
#include "co/co_store.h"
#include "co_linux/conditions.h"
#include "co_linux/file_store.h"
#include "co_linux/log.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/drive_devicenet.h"

#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

/* The node-id of the drive behind a DeviceNet card: the card's internal link to the drive, whose
 * frames are not on the bus (drive_dn_drop_frame), so any valid node-id does. */
#define DN_DRIVE_NODE_ID 1u
/* A DeviceNet drive's serial number (Identity attribute 6, in its duplicate MAC ID checks):
 * this base plus its MAC ID, so that every drive of a bench has its own (docs/atv312d.md). */
#define DN_SERIAL_BASE 0x31200000u

/* One drive and what the runtime and the logs need around it. */
typedef struct drive_slot {
    drive_t drive;
    uint8_t *od_data; /* the drive's dictionary data block, of its model's size */
    uint8_t id;       /* node-id on CANopen, MAC ID on DeviceNet */
    drive_dn_t *dn;   /* its DeviceNet card, NULL on CANopen */
    co_file_store_t *store;
    co_linux_device_t device;
    co_file_store_node_t store_node;
    co_storage_t storage;
    co_nmt_state_t nmt_state; /* last logged */
    const char *cia402_state; /* last logged */
    dn_led_t ms_led, ns_led;  /* last logged, DeviceNet */
    atv312d_counters_t counters;
} drive_slot_t;

static uint8_t slot_node_id(const drive_slot_t *slot)
{
    return slot->id;
}

static void log_led_change(const drive_slot_t *slot, const char *name, dn_led_t *logged,
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
static void log_state_changes(drive_slot_t *slot)
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
static void log_communication_loss(const drive_slot_t *slot, uint8_t reg)
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

static void log_emcy(const drive_slot_t *slot, const co_frame_t *frame)
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
    drive_slot_t *slot = user;
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
    drive_slot_t *slot = ctx;
    drive_start(&slot->drive, now);
    log_state_changes(slot);
}

/* After the interface was down, the master must learn that the drive is back and may have missed
 * frames: the drive resets communication (CiA 301 NMT command 0x82 addressed to it), which sends
 * the boot-up at once. Application state (motor, CiA 402) is kept. */
static void slot_restart(void *ctx, co_time_t now)
{
    drive_slot_t *slot = ctx;
    co_frame_t reset = {.id = 0, .len = 2, .data = {CO_NMT_CS_RESET_COMMUNICATION}};
    reset.data[1] = slot_node_id(slot);
    co_log(CO_LOG_INFO, "node %u: reset communication after the interface came back",
           slot_node_id(slot));
    drive_receive(&slot->drive, &reset, now);
    log_state_changes(slot);
}

static void slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    drive_slot_t *slot = ctx;
    atv312d_count_received(&slot->counters, slot_node_id(slot), frame);
    drive_receive(&slot->drive, frame, now);
    log_state_changes(slot);
}

static co_time_t slot_process(void *ctx, co_time_t now)
{
    drive_slot_t *slot = ctx;
    co_time_t next = drive_process(&slot->drive, now);
    log_state_changes(slot);
    return next;
}

static void slot_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    drive_slot_t *slot = ctx;
    drive_bus_event(&slot->drive, emcy_code, active);
}

static void slot_bus_warning(void *ctx, bool active)
{
    drive_slot_t *slot = ctx;
    drive_bus_warning(&slot->drive, active);
}

static const co_node_t *slot_node(void *ctx)
{
    drive_slot_t *slot = ctx;
    return &slot->drive.node;
}

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
    drive_slot_t *slot = user;
    co_linux_device_send(&slot->device, frame);
}

static void dn_slot_start(void *ctx, co_time_t now)
{
    drive_slot_t *slot = ctx;
    co_log(CO_LOG_INFO, "node %u: duplicate MAC ID check", slot->id);
    drive_dn_start(slot->dn, now);
    log_state_changes(slot);
}

/* After the interface was down the card goes on the bus again as after power-up: a new duplicate
 * MAC ID check, its connections gone; a drive that ran on their commands takes CnF, any other
 * keeps its state (docs/decisions.md, D-DEVICENET-CONNECTION-END). */
static void dn_slot_restart(void *ctx, co_time_t now)
{
    drive_slot_t *slot = ctx;
    co_log(CO_LOG_INFO, "node %u: duplicate MAC ID check after the interface came back", slot->id);
    drive_dn_restart(slot->dn, now);
    log_state_changes(slot);
}

static void dn_slot_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    drive_slot_t *slot = ctx;
    drive_dn_receive(slot->dn, frame, now);
    log_state_changes(slot);
}

static co_time_t dn_slot_process(void *ctx, co_time_t now)
{
    drive_slot_t *slot = ctx;
    co_time_t next = drive_dn_process(slot->dn, now);
    log_state_changes(slot);
    return next;
}

/* Bus off is the card's (its bus-off counter, BOI); the other conditions are CANopen
 * emergencies, which a DeviceNet card has not. */
static void dn_slot_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    drive_slot_t *slot = ctx;
    if (emcy_code == CO_LINUX_EMCY_BUS_OFF && active) {
        drive_dn_bus_off(slot->dn, slot->device.loop->now);
        log_state_changes(slot);
    }
}

_Static_assert(DN_NODE_CONSUMED_IDS <= CO_CONSUMERS_MAX, "a card's CAN-IDs fit a device's");

static size_t dn_slot_consumers(void *ctx, co_cob_t *cobs)
{
    const drive_slot_t *slot = ctx;
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
    drive_slot_t *slot = user;
    co_file_devicenet_t values = {.consumed_assembly = stored->consumed_assembly,
                                  .produced_assembly = stored->produced_assembly,
                                  .quick_connect = stored->quick_connect};
    if (co_file_store_set_devicenet(slot->store, slot->id, &values) == 0)
        return true;
    co_log(CO_LOG_WARN, "store %s: node %u: DeviceNet values not saved: %s", slot->store->path,
           slot->id, slot->store->reason);
    return false;
}

static dn_stored_t dn_slot_stored(const drive_slot_t *slot)
{
    co_file_devicenet_t values;
    if (!slot->store || !co_file_store_get_devicenet(slot->store, slot->id, &values))
        return (dn_stored_t){0, 0, false};
    return (dn_stored_t){values.consumed_assembly, values.produced_assembly, values.quick_connect};
}

static int report_open_error(const co_linux_loop_t *loop, co_linux_open_result_t result)
{
    const char *iface = loop->iface;
    const char *why = strerror(loop->open_errno);
    switch (result) {
    case CO_LINUX_OPEN_NO_CAN:
        co_log(CO_LOG_ERROR,
               "this kernel has no SocketCAN support (%s: %s): load it with modprobe can-raw "
               "vcan, or run inside the sandbox: tools/vcan-run atv312d vcan0 --node-id 4",
               loop->open_call, why);
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NO_IFACE:
        co_log(CO_LOG_ERROR,
               "no network interface '%s': create a virtual CAN bus with: ip link add dev %s "
               "type vcan && ip link set up %s (as root), or list the CAN interfaces with: ip "
               "link show type can",
               iface, strncmp(iface, "vcan", 4) == 0 ? iface : "vcan0",
               strncmp(iface, "vcan", 4) == 0 ? iface : "vcan0");
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NOT_CAN:
        co_log(CO_LOG_ERROR,
               "'%s' is not a CAN interface (%s: %s): give a SocketCAN interface such as can0 or "
               "vcan0",
               iface, loop->open_call, why);
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_OS_ERROR:
    case CO_LINUX_OPEN_OK:
        break;
    }
    co_log(CO_LOG_ERROR, "%s on %s failed: %s", loop->open_call, iface, why);
    return EX_OSERR;
}

static int open_trace(const char *path, FILE **trace)
{
    *trace = NULL;
    if (!path)
        return 0;
    if (strcmp(path, "-") == 0) {
        *trace = stdout;
        return 0;
    }
    *trace = fopen(path, "we");
    if (*trace)
        return 0;
    co_log(CO_LOG_ERROR, "cannot create the trace file '%s': %s", path, strerror(errno));
    return EX_CANTCREAT;
}

/* A store that can never be saved is a mistake better reported at start than at the first 1010h
 * write: the directory must exist and be writable. */
static int check_store_directory(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    if (access(dir, W_OK | X_OK) == 0)
        return 0;
    co_log(CO_LOG_ERROR,
           "store %s: its directory %s is not usable (%s): create it or give a writable --store "
           "path",
           path, dir, strerror(errno));
    return EX_CANTCREAT;
}

/* One line per node of a loaded store: which save wrote each image, so that after a crash the log
 * says whether the old or the new parameters came back. "area 2 save 7, area 3 save 8 (defaults)"
 * (co_store.h: the sequence and kind of each image header; "format 1" images have neither). */
static void log_store_images(const char *path, const co_file_store_t *store)
{
    for (size_t i = 0; i < store->count;) {
        uint8_t node_id = store->records[i].node_id;
        char line[512];
        size_t used = 0;
        for (; i < store->count && store->records[i].node_id == node_id; i++) {
            const co_file_record_t *r = &store->records[i];
            const char *sep = used ? ", " : "";
            if (used >= sizeof line || r->area == CO_FILE_STORE_AREA_DEVICENET)
                continue;
            if (r->len >= CO_STORE_IMAGE_HEADER_SIZE && memcmp(r->data, "COS\x02", 4) == 0)
                used +=
                    (size_t)snprintf(line + used, sizeof line - used, "%sarea %u save %lu%s", sep,
                                     r->area, (unsigned long)co_get_u32(r->data + 4),
                                     r->data[8] == CO_STORE_IMAGE_DEFAULTS ? " (defaults)" : "");
            else
                used += (size_t)snprintf(
                    line + used, sizeof line - used, "%sarea %u %s", sep, r->area,
                    r->len >= 4 && memcmp(r->data, "COS\x01", 4) == 0 ? "format 1"
                                                                      : "unknown format");
        }
        if (used)
            co_log(CO_LOG_INFO, "store %s: node %u: %s", path, node_id, line);
    }
    for (uint8_t mac_id = 0; mac_id <= CO_FILE_STORE_MAC_ID_MAX; mac_id++) {
        co_file_devicenet_t dn;
        if (!co_file_store_get_devicenet(store, mac_id, &dn))
            continue;
        char consumed[8] = "default", produced[8] = "default";
        if (dn.consumed_assembly)
            snprintf(consumed, sizeof consumed, "%u", dn.consumed_assembly);
        if (dn.produced_assembly)
            snprintf(produced, sizeof produced, "%u", dn.produced_assembly);
        co_log(CO_LOG_INFO,
               "store %s: MAC ID %u: consumed assembly %s, produced assembly %s, Quick Connect %s",
               path, mac_id, consumed, produced, dn.quick_connect ? "on" : "off");
    }
}

static int open_store(const char *path, co_file_store_t *store)
{
    int rc = check_store_directory(path);
    if (rc != 0)
        return rc;
    switch (co_file_store_open(store, path)) {
    case CO_FILE_STORE_LOADED:
        co_log(CO_LOG_INFO, "store %s: %zu stored image(s) loaded", path, store->count);
        log_store_images(path, store);
        return 0;
    case CO_FILE_STORE_MISSING:
        co_log(CO_LOG_INFO, "store %s: no file yet, defaults apply until a save (1010h)", path);
        return 0;
    case CO_FILE_STORE_IGNORED:
        co_log(CO_LOG_WARN, "store %s: ignored, defaults apply: %s", path, store->reason);
        return 0;
    case CO_FILE_STORE_ERROR:
        break;
    }
    co_log(CO_LOG_ERROR, "store %s: cannot be read: %s", path, store->reason);
    co_file_store_close(store);
    return EX_NOINPUT;
}

static const char *baud_text(atv312d_baud_t baud)
{
    switch (baud) {
    case ATV312D_BAUD_125K:
        return "125 kbit/s";
    case ATV312D_BAUD_250K:
        return "250 kbit/s";
    case ATV312D_BAUD_500K:
        return "500 kbit/s";
    }
    return "?";
}

/* "4,5 (atv312)" or, on a mixed bench, "4,5 (atv312), 6 (atv31)": node-ids ascending, each run
 * of one model followed by its name. */
static void format_node_ids(const atv312d_options_t *opts, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < opts->node_count && used < len; i++) {
        const char *separator = i == 0 ? "" : opts->models[i] == opts->models[i - 1] ? "," : ", ";
        used += (size_t)snprintf(buf + used, len - used, "%s%u", separator, opts->node_ids[i]);
        bool run_ends = i + 1 == opts->node_count || opts->models[i + 1] != opts->models[i];
        if (run_ends && used < len)
            used += (size_t)snprintf(buf + used, len - used, " (%s)", opts->models[i]->name);
    }
}

/* The drive of `model` on `profile`: the model's own, or the one behind its DeviceNet card. */
static int init_drive(drive_slot_t *slot, uint8_t node_id, const drive_model_t *model,
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
static int init_devicenet_drive(drive_slot_t *slot, const drive_model_t *model,
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

static int init_drives(drive_slot_t *slots, const atv312d_options_t *opts, co_file_store_t *store,
                       co_linux_loop_t *loop)
{
    for (size_t i = 0; i < opts->node_count; i++) {
        drive_slot_t *slot = &slots[i];
        slot->id = opts->node_ids[i];
        slot->store = store;
        int rc;
        if (opts->devicenet) {
            rc = init_devicenet_drive(slot, opts->models[i], opts);
        } else {
            const co_storage_t *storage = NULL;
            if (store) {
                co_file_store_bind(store, slot->id, &slot->store_node, &slot->storage);
                storage = &slot->storage;
            }
            rc = init_drive(slot, slot->id, opts->models[i], opts->models[i]->profile, storage,
                            slot_send);
        }
        if (rc != 0)
            return rc;
        slot->nmt_state = slot->drive.node.nmt_state;
        slot->cia402_state = drive_state_name(&slot->drive);
        co_linux_loop_add(loop, &slot->device, slot->dn ? &dn_slot_ops : &slot_ops, slot);
    }
    return 0;
}

/* The web surface's settings: --http's address, --http-actions and the secret of --http-token. */
static int http_settings(const atv312d_options_t *opts, atv312d_http_settings_t *settings)
{
    *settings =
        (atv312d_http_settings_t){.address = opts->http_address, .actions = opts->http_actions};
    if (!opts->http_token_path)
        return 0;
    char err[512];
    int rc = atv312d_http_read_token(opts->http_token_path, settings->token, sizeof settings->token,
                                     err, sizeof err);
    if (rc != 0)
        co_log(CO_LOG_ERROR, "%s", err);
    return rc;
}

/* The surfaces on the drives: control (--control; its commands also serve the web's actions),
 * status (--status, SIGUSR1) and web (--http). */
static int open_surfaces(atv312d_control_socket_t *control_socket, atv312d_control_t *control,
                         atv312d_status_t *status, atv312d_http_t *http, co_linux_loop_t *loop,
                         const atv312d_options_t *opts, drive_slot_t *slots,
                         atv312d_control_node_t *nodes)
{
    for (size_t i = 0; i < opts->node_count; i++)
        nodes[i] = (atv312d_control_node_t){.id = slots[i].id,
                                            .model = opts->models[i]->name,
                                            .drive = &slots[i].drive,
                                            .devicenet = slots[i].dn,
                                            .device = &slots[i].device,
                                            .counters = &slots[i].counters};
    control->nodes = nodes;
    control->count = opts->node_count;
    int rc = atv312d_status_open(status, loop, opts->status_path, nodes, opts->node_count);
    if (rc == 0 && opts->control_path)
        rc = atv312d_control_open(control_socket, loop, opts->control_path, control);
    atv312d_http_settings_t settings;
    if (rc == 0 && opts->http && (rc = http_settings(opts, &settings)) == 0)
        rc = atv312d_http_open(http, loop, &settings, control);
    return rc;
}

/* What systemd's Type=notify waits for (docs/atv312d.md, "systemd"). */
typedef struct readiness {
    const atv312d_options_t *opts;
    const drive_slot_t *slots;
} readiness_t;

static void notify(const char *state)
{
    if (atv312d_notify(state))
        return;
    co_log(CO_LOG_WARN, "NOTIFY_SOCKET %s: %s: the service manager was not told",
           getenv("NOTIFY_SOCKET"), strerror(errno));
}

/* READY=1 once every drive's start has reached the bus: on CANopen its boot-up written to the
 * socket (an interface down at start: after it came up and the boot-ups left); on DeviceNet, in
 * addition, every card's duplicate MAC ID check over, online or faulted. Told once. */
static void tell_when_ready(void *ctx, co_linux_loop_t *loop)
{
    const readiness_t *ready = ctx;
    if (!co_linux_loop_sent_all(loop))
        return;
    size_t faulted = 0;
    for (size_t i = 0; i < ready->opts->node_count; i++) {
        const drive_dn_t *dn = ready->slots[i].dn;
        if (dn && dn->node.link != DN_LINK_ONLINE && dn->node.link != DN_LINK_FAULTED)
            return;
        faulted += dn && dn->node.link == DN_LINK_FAULTED;
    }
    co_linux_loop_on_settled(loop, NULL, NULL);
    char state[256];
    size_t count = ready->opts->node_count;
    if (ready->opts->devicenet)
        snprintf(state, sizeof state,
                 "READY=1\nSTATUS=%zu drive(s) on DeviceNet on %s: %zu online, %zu faulted", count,
                 loop->iface, count - faulted, faulted);
    else
        snprintf(state, sizeof state, "READY=1\nSTATUS=%zu drive(s) booted on %s", count,
                 loop->iface);
    co_log(CO_LOG_DEBUG, "service manager told: %s", strchr(state, '\n') + 1);
    notify(state);
}

static int run(const atv312d_options_t *opts, FILE *trace, co_file_store_t *store)
{
    static atv312d_control_socket_t control_socket = {.server.listen_fd = -1};
    static atv312d_control_t control;
    static atv312d_status_t status = {.timer_fd = -1, .signal_fd = -1};
    static atv312d_http_t http = {.mhd_fd = -1, .timer_fd = -1};
    static atv312d_control_node_t control_nodes[ATV312D_NODE_ID_MAX];
    static co_linux_loop_t loop;
    co_linux_loop_config_t config = {.iface = opts->iface, .trace = trace};
    co_linux_open_result_t opened = co_linux_loop_open(&loop, &config);
    if (opened != CO_LINUX_OPEN_OK)
        return report_open_error(&loop, opened);
    drive_slot_t *slots = calloc(opts->node_count, sizeof *slots);
    int rc = slots ? init_drives(slots, opts, store, &loop) : EX_OSERR;
    if (rc == 0)
        rc = open_surfaces(&control_socket, &control, &status, &http, &loop, opts, slots,
                           control_nodes);
    if (rc == 0) {
        char ids[2048];
        format_node_ids(opts, ids, sizeof ids);
        if (opts->devicenet)
            co_log(CO_LOG_INFO,
                   "atv312d %s started on %s: %zu drive(s) on DeviceNet at %s, MAC ID %s",
                   ATV312D_VERSION, opts->iface, opts->node_count, baud_text(opts->baud), ids);
        else
            co_log(CO_LOG_INFO, "atv312d %s started on %s: %zu drive(s), node-id %s",
                   ATV312D_VERSION, opts->iface, opts->node_count, ids);
        readiness_t readiness = {.opts = opts, .slots = slots};
        co_linux_loop_on_settled(&loop, tell_when_ready, &readiness);
        rc = co_linux_loop_run(&loop);
        notify("STOPPING=1");
        co_log(CO_LOG_INFO,
               "stopped: %llu wake-ups, %llu frames received, %llu sent, %llu dropped, %llu lost "
               "while the interface was down, %llu error frames, %llu received for no drive, "
               "%llu sendmmsg calls, %llu receive filters set",
               loop.stats.wakeups, loop.stats.rx, loop.stats.tx, loop.stats.tx_dropped,
               loop.stats.down_dropped, loop.stats.error_frames, loop.stats.unrouted,
               loop.stats.tx_calls, loop.stats.filters);
    }
    atv312d_http_close(&http);
    atv312d_control_close(&control_socket);
    atv312d_status_close(&status);
    co_linux_loop_close(&loop);
    if (slots) {
        for (size_t i = 0; i < opts->node_count; i++) {
            co_file_store_unbind(&slots[i].store_node);
            free(slots[i].od_data);
            free(slots[i].dn);
        }
    }
    free(slots);
    return rc;
}

int main(int argc, char *argv[])
{
    atv312d_options_t opts;
    char err[256];
    co_log_setup("atv312d", CO_LOG_INFO);
    if (argc >= 2 && strcmp(argv[1], "ctl") == 0)
        return atv312d_control_client(argc - 2, argv + 2);
    int rc = atv312d_parse_args(argc, argv, &opts, err, sizeof err);
    if (rc != 0)
        return cli_fail(NULL, rc, "%s", err);
    if (opts.help) {
        atv312d_print_usage(stdout);
        return 0;
    }
    if (opts.version) {
        printf("atv312d %s\n", ATV312D_VERSION);
        return 0;
    }
    co_log_setup("atv312d", opts.log_level);
    /* A closed trace pipe must not kill the daemon: the write fails and tracing stops. */
    signal(SIGPIPE, SIG_IGN);

    FILE *trace;
    rc = open_trace(opts.trace_path, &trace);
    if (rc != 0)
        return rc;
    co_file_store_t store;
    if (opts.store_path)
        rc = open_store(opts.store_path, &store);
    if (rc == 0) {
        rc = run(&opts, trace, opts.store_path ? &store : NULL);
        if (opts.store_path)
            co_file_store_close(&store);
    }
    if (trace && trace != stdout)
        fclose(trace);
    return rc;
}
