/* SPDX-License-Identifier: Apache-2.0 */
/* The view of a node, a drive or a plain node, in text and JSON (view.h). */
#include "atv312d/view.h"

#include "drive/panel.h"
#include "nodes/io/io401.h"
#include "nodes/plc300/plc300.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define STATUSWORD_INDEX 0x6041
#define TARGET_VELOCITY_INDEX 0x6042
#define VELOCITY_ACTUAL_INDEX 0x6044

void atv312d_text_put(atv312d_text_t *text, const char *format, ...)
{
    if (text->used >= text->len)
        return;
    va_list args;
    va_start(args, format);
    int n = vsnprintf(text->buf + text->used, text->len - text->used, format, args);
    va_end(args);
    if (n > 0)
        text->used += (size_t)n;
}

const char *atv312d_can_state(const co_linux_loop_t *loop)
{
    static const char *const names[] = {
        [CO_LINUX_CAN_DOWN] = "down",
        [CO_LINUX_CAN_BUS_OFF] = "bus-off",
        [CO_LINUX_CAN_ERROR_PASSIVE] = "error-passive",
        [CO_LINUX_CAN_ERROR_WARNING] = "error-warning",
        [CO_LINUX_CAN_ERROR_ACTIVE] = "error-active",
    };
    return names[co_linux_bus_can_state(&loop->bus)];
}

void atv312d_format_analog(drive_analog_kind_t kind, int32_t value, char *buf, size_t len)
{
    int32_t magnitude = value < 0 ? -value : value;
    if (kind == DRIVE_ANALOG_POTENTIOMETER)
        snprintf(buf, len, "%d.%d %%", (int)(value / 10), (int)(value % 10));
    else
        snprintf(buf, len, "%s%d.%03d %s", value < 0 ? "-" : "", (int)(magnitude / 1000),
                 (int)(magnitude % 1000), kind == DRIVE_ANALOG_CURRENT ? "mA" : "V");
}

/* What both forms of the state show of the drive's motion and front panel. */
typedef struct motion {
    unsigned statusword;
    int reference, speed; /* rpm */
    unsigned current;     /* 0.1 A */
    int torque;           /* % of nominal */
    char display[16];     /* the front panel: a code ("nSt") or the frequency ("50.0") */
} motion_t;

static motion_t read_motion(const drive_t *drive)
{
    const co_node_t *co = &drive->node;
    drive_param_t lcr = drive->profile->motor_current;
    drive_param_t otr = drive->profile->motor_torque;
    motion_t m = {
        .statusword = (unsigned)co_od_value(co, STATUSWORD_INDEX, 0),
        .reference = (int16_t)co_od_value(co, TARGET_VELOCITY_INDEX, 0),
        .speed = (int16_t)co_od_value(co, VELOCITY_ACTUAL_INDEX, 0),
        .current = (unsigned)co_od_value(co, lcr.index, lcr.subindex),
        .torque = (int16_t)co_od_value(co, otr.index, otr.subindex),
    };
    drive_display_t display = drive_panel_display(drive);
    if (display.code)
        snprintf(m.display, sizeof m.display, "%s", display.code);
    else
        snprintf(m.display, sizeof m.display, "%u.%u", display.decihertz / 10,
                 display.decihertz % 10);
    return m;
}

static const char *const comm_loss_by[] = {
    [DRIVE_COMM_LOSS_GUARDING] = "guarding",
    [DRIVE_COMM_LOSS_HEARTBEAT] = "heartbeat",
    [DRIVE_COMM_LOSS_NETWORK] = "network",
};

/* ---- the state line ---- */

/* What the bus sees of the drive: its NMT state on CANopen; on DeviceNet the card's MS and NS
 * LEDs and the Control supervisor's state. */
static void put_bus_state(const atv312d_control_node_t *node, atv312d_text_t *t)
{
    const drive_dn_t *dn = node->devicenet;
    if (!dn) {
        atv312d_text_put(t, "node %u: nmt %s, ", atv312d_node_id(node),
                         co_nmt_state_name(node->drive->node.nmt_state));
        return;
    }
    atv312d_text_put(t, "node %u: ms %s, ns %s, supervisor %s, ", atv312d_node_id(node),
                     drive_dn_led_name(dn_node_ms_led(&dn->node)),
                     drive_dn_led_name(dn_node_ns_led(&dn->node)),
                     drive_dn_state_name(drive_dn_state(dn)));
}

/* The CANopen card's LEDs as the model's manual names them: RUN and ERR (CiA 303-3), the ATV58
 * card's OK and COM ("OK on, COM flashing"); a DeviceNet card has MS and NS instead. */
static void put_canopen_leds(const atv312d_control_node_t *node, atv312d_text_t *t)
{
    if (node->devicenet)
        return;
    uint8_t count;
    const drive_indicator_t *leds = drive_panel_indicators(node->drive, &count);
    for (uint8_t i = 0; i < count; i++)
        atv312d_text_put(t, "%s %s, ", leds[i].name,
                         drive_led_name(leds[i].pattern(node->drive, node->device->loop->now)));
}

/* The cause of the communication loss the drive reacted to: "comm-loss heartbeat node 1, ",
 * "comm-loss guarding, " (nothing while there is none). */
static void put_comm_loss(const drive_t *drive, atv312d_text_t *t)
{
    drive_comm_loss_t loss = drive->comm_loss;
    if (loss.source == DRIVE_COMM_LOSS_HEARTBEAT)
        atv312d_text_put(t, "comm-loss %s node %u, ", comm_loss_by[loss.source], loss.node);
    else if (loss.source != DRIVE_COMM_LOSS_NONE)
        atv312d_text_put(t, "comm-loss %s, ", comm_loss_by[loss.source]);
}

/* The drive's traffic: the runtime's counts of its device, then the daemon's of its CANopen
 * services or its DeviceNet card's (dn_stats_t). */
static void put_counters(const atv312d_control_node_t *node, atv312d_text_t *t)
{
    const co_linux_device_stats_t *frames = &node->device->stats;
    atv312d_text_put(t, "frames received %llu, sent %llu, dropped %llu", frames->rx, frames->tx,
                     frames->tx_dropped);
    if (node->devicenet) {
        const dn_stats_t *s = &node->devicenet->stats;
        atv312d_text_put(t,
                         ", explicit requests %lu, error responses %lu, I/O messages %lu, "
                         "fragments %lu, timeouts %lu",
                         (unsigned long)s->explicit_requests, (unsigned long)s->error_responses,
                         (unsigned long)s->io_messages, (unsigned long)s->fragments,
                         (unsigned long)s->timeouts);
    } else {
        const atv312d_counters_t *services = node->counters;
        atv312d_text_put(t, ", SDO requests %llu, SDO aborts %llu, EMCY %llu",
                         services->sdo_requests, services->sdo_aborts, services->emcy);
    }
}

/* The logic inputs that are on: ", inputs LI1 LI3" (nothing when none is). */
static void put_inputs(const drive_t *drive, atv312d_text_t *t)
{
    bool first = true;
    for (uint8_t i = 1; i <= drive->profile->logic_inputs; i++) {
        if (!drive_input(drive, i))
            continue;
        atv312d_text_put(t, "%sLI%u", first ? ", inputs " : " ", i);
        first = false;
    }
}

/* The analogue inputs not at 0: ", analog AI2 5.000 V AI3 12.000 mA" (nothing when all are). */
static void put_analog(const drive_t *drive, atv312d_text_t *t)
{
    const drive_profile_t *profile = drive->profile;
    bool first = true;
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        const drive_analog_input_t *in = &profile->analog_inputs[i];
        int32_t value = drive_analog(drive, i);
        if (value == 0)
            continue;
        char shown[32];
        atv312d_format_analog(in->kind, value, shown, sizeof shown);
        atv312d_text_put(t, "%s%s %s", first ? ", analog " : " ", in->name, shown);
        first = false;
    }
}

/* ---- a plain node ---- */

static void counters_json(cli_json_t *json, const atv312d_control_node_t *node);

/* The marker bytes shown of an area: the first ones not at 0. */
#define PLAIN_MARKERS_SHOWN 16u

static const char *const plain_loss_by[] = {
    [PLAIN_LOSS_HEARTBEAT] = "heartbeat",
    [PLAIN_LOSS_GUARDING] = "guarding",
};

/* An area's bytes not at 0, as %IB/%QB markers: ", inputs %IB2000 E7 %IB2001 03" (" none"). */
static void put_plc300_area(const plain_node_t *plc, bool output, atv312d_text_t *t)
{
    atv312d_text_put(t, ", %s", output ? "outputs" : "inputs");
    unsigned shown = 0;
    for (uint16_t b = 0; b < PLC300_AREA_BYTES; b++) {
        uint8_t value = plc300_area_byte(plc, output, b);
        if (value == 0)
            continue;
        if (shown++ == PLAIN_MARKERS_SHOWN) {
            atv312d_text_put(t, " ...");
            break;
        }
        atv312d_text_put(t, " %%%cB%u %02X", output ? 'Q' : 'I', PLC300_MARKER_FIRST + b, value);
    }
    if (shown == 0)
        atv312d_text_put(t, " none");
}

/* The I/O node's terminals: ", inputs DI1 DI3, outputs DO2, analog AI1 100 AI2 -5". */
static void put_io401(const plain_node_t *io, atv312d_text_t *t)
{
    uint8_t bits[2] = {io401_inputs(io), io401_outputs(io)};
    for (size_t k = 0; k < 2; k++) {
        atv312d_text_put(t, ", %s", k ? "outputs" : "inputs");
        if (bits[k] == 0)
            atv312d_text_put(t, " none");
        for (uint8_t i = 0; i < 8; i++) {
            if (bits[k] & (1u << i))
                atv312d_text_put(t, " %s%u", k ? "DO" : "DI", i + 1u);
        }
    }
    atv312d_text_put(t, ", analog");
    for (uint8_t i = 1; i <= IO401_ANALOG_INPUTS; i++)
        atv312d_text_put(t, " AI%u %d", i, io401_analog(io, i));
    char time[CO_TIME_OF_DAY_TEXT_SIZE] = "none";
    if (io->time_received)
        co_time_of_day_format(&io->time, time);
    atv312d_text_put(t, ", time %s", time);
}

static void plain_state_text(atv312d_text_t *t, const atv312d_control_node_t *node)
{
    const plain_node_t *plain = node->plain;
    /* A node of --unconfigured is told by its serial number until LSS gives it a node-id. */
    if (plain->node.node_id == CO_LSS_NODE_ID_UNCONFIGURED)
        atv312d_text_put(t,
                         "node unconfigured, serial %08lXh: ", (unsigned long)plain->serial_number);
    else
        atv312d_text_put(t, "node %u: ", atv312d_node_id(node));
    atv312d_text_put(t, "nmt %s, model %s, RUN %s, ERR %s, ",
                     co_nmt_state_name(plain->node.nmt_state), node->model,
                     co_led_name(plain_node_run_led(plain)),
                     co_led_name(plain_node_err_led(plain)));
    if (plain->loss == PLAIN_LOSS_HEARTBEAT)
        atv312d_text_put(t, "error-control heartbeat node %u, ", plain->lost_producer);
    else if (plain->loss != PLAIN_LOSS_NONE)
        atv312d_text_put(t, "error-control %s, ", plain_loss_by[plain->loss]);
    put_counters(node, t);
    const atv312d_plain_surface_t *surface = atv312d_plain_surface(plain->model);
    if (surface)
        surface->text(plain, t);
}

/* {"%IB2000":231,...}: an area's bytes not at 0. */
static void plc300_area_json(cli_json_t *json, const plain_node_t *plc, bool output)
{
    cli_json_begin_object(json, output ? "outputs" : "inputs");
    unsigned shown = 0;
    for (uint16_t b = 0; b < PLC300_AREA_BYTES && shown < PLAIN_MARKERS_SHOWN; b++) {
        uint8_t value = plc300_area_byte(plc, output, b);
        if (value == 0)
            continue;
        char name[16];
        snprintf(name, sizeof name, "%%%cB%u", output ? 'Q' : 'I', PLC300_MARKER_FIRST + b);
        cli_json_uint(json, name, value);
        shown++;
    }
    cli_json_end_object(json);
}

static void io401_json(cli_json_t *json, const plain_node_t *io)
{
    uint8_t bits[2] = {io401_inputs(io), io401_outputs(io)};
    for (size_t k = 0; k < 2; k++) {
        cli_json_begin_array(json, k ? "outputs" : "inputs");
        for (uint8_t i = 0; i < 8; i++) {
            char name[8];
            snprintf(name, sizeof name, "%s%u", k ? "DO" : "DI", i + 1u);
            if (bits[k] & (1u << i))
                cli_json_str(json, NULL, name);
        }
        cli_json_end_array(json);
    }
    cli_json_begin_object(json, "analog");
    for (uint8_t i = 1; i <= IO401_ANALOG_INPUTS; i++) {
        char name[8];
        snprintf(name, sizeof name, "AI%u", i);
        cli_json_int(json, name, io401_analog(io, i));
    }
    cli_json_end_object(json);
    if (io->time_received) {
        char time[CO_TIME_OF_DAY_TEXT_SIZE];
        co_time_of_day_format(&io->time, time);
        cli_json_str(json, "time", time);
    } else {
        cli_json_null(json, "time");
    }
}

static void plc300_text(const plain_node_t *plc, atv312d_text_t *t)
{
    put_plc300_area(plc, false, t);
    put_plc300_area(plc, true, t);
}

static void plc300_json(cli_json_t *json, const plain_node_t *plc)
{
    plc300_area_json(json, plc, false);
    plc300_area_json(json, plc, true);
}

/* Each plain model's part of the surfaces: a model added to src/nodes/node_models.c gets a row. */
static const atv312d_plain_surface_t plain_surfaces[] = {
    {&plc300_model, "marker, state", plc300_text, plc300_json},
    {&io401_model, "input, analog, state", put_io401, io401_json},
};

const atv312d_plain_surface_t *atv312d_plain_surface(const plain_model_t *model)
{
    for (size_t i = 0; i < sizeof plain_surfaces / sizeof plain_surfaces[0]; i++)
        if (plain_surfaces[i].model == model)
            return &plain_surfaces[i];
    return NULL;
}

static void plain_state_json(cli_json_t *json, const atv312d_control_node_t *node)
{
    const plain_node_t *plain = node->plain;
    cli_json_begin_object(json, NULL);
    if (plain->node.node_id == CO_LSS_NODE_ID_UNCONFIGURED)
        cli_json_null(json, "node");
    else
        cli_json_uint(json, "node", atv312d_node_id(node));
    cli_json_str(json, "kind", atv312d_kind_name(atv312d_node_kind(node)));
    cli_json_str(json, "model", node->model);
    /* Its LSS address's serial number, what tells nodes without node-id apart. */
    if (plain->model->lss)
        cli_json_uint(json, "serial", plain->serial_number);
    cli_json_str(json, "nmt", co_nmt_state_name(plain->node.nmt_state));
    cli_json_str(json, "run_led", co_led_name(plain_node_run_led(plain)));
    cli_json_str(json, "err_led", co_led_name(plain_node_err_led(plain)));
    if (plain->loss == PLAIN_LOSS_NONE) {
        cli_json_null(json, "error_control");
    } else {
        cli_json_begin_object(json, "error_control");
        cli_json_str(json, "by", plain_loss_by[plain->loss]);
        if (plain->loss == PLAIN_LOSS_HEARTBEAT)
            cli_json_uint(json, "node", plain->lost_producer);
        cli_json_end_object(json);
    }
    counters_json(json, node);
    const atv312d_plain_surface_t *surface = atv312d_plain_surface(plain->model);
    if (surface)
        surface->json(json, plain);
    cli_json_end_object(json);
}

/* ---- a drive ---- */

void atv312d_state_text(atv312d_text_t *t, const atv312d_control_node_t *node)
{
    if (node->plain) {
        plain_state_text(t, node);
        return;
    }
    const drive_t *drive = node->drive;
    motion_t m = read_motion(drive);
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    put_bus_state(node, t);
    atv312d_text_put(
        t, "cia402 %s, statusword %04X, speed %d rpm, current %u.%u A, torque %d %%, display %s, ",
        drive_state_name(drive), m.statusword, m.speed, m.current / 10, m.current % 10, m.torque,
        m.display);
    put_canopen_leds(node, t);
    atv312d_text_put(t, "fault %s, ", fault ? fault->code : "none");
    put_comm_loss(drive, t);
    put_counters(node, t);
    put_inputs(drive, t);
    put_analog(drive, t);
}

/* ---- the state object ---- */

/* The CANopen card's LEDs: "run_led":"blinking", "ok_led":"on" (the LED's name in lower
 * case, then "_led"). */
static void canopen_leds_json(cli_json_t *json, const atv312d_control_node_t *node)
{
    if (node->devicenet)
        return;
    uint8_t count;
    const drive_indicator_t *leds = drive_panel_indicators(node->drive, &count);
    for (uint8_t i = 0; i < count; i++) {
        char key[32];
        size_t n = 0;
        for (const char *c = leds[i].name; *c && n + sizeof "_led" < sizeof key; c++)
            key[n++] = (char)tolower((unsigned char)*c);
        snprintf(key + n, sizeof key - n, "_led");
        cli_json_str(json, key,
                     drive_led_name(leds[i].pattern(node->drive, node->device->loop->now)));
    }
}

/* "comm_loss":{"by":"heartbeat","node":1}, {"by":"guarding"} or null. */
static void comm_loss_json(cli_json_t *json, const drive_t *drive)
{
    drive_comm_loss_t loss = drive->comm_loss;
    if (loss.source == DRIVE_COMM_LOSS_NONE) {
        cli_json_null(json, "comm_loss");
        return;
    }
    cli_json_begin_object(json, "comm_loss");
    cli_json_str(json, "by", comm_loss_by[loss.source]);
    if (loss.source == DRIVE_COMM_LOSS_HEARTBEAT)
        cli_json_uint(json, "node", loss.node);
    cli_json_end_object(json);
}

static void counters_json(cli_json_t *json, const atv312d_control_node_t *node)
{
    const co_linux_device_stats_t *frames = &node->device->stats;
    cli_json_begin_object(json, "frames");
    cli_json_uint(json, "received", frames->rx);
    cli_json_uint(json, "sent", frames->tx);
    cli_json_uint(json, "dropped", frames->tx_dropped);
    if (node->devicenet) {
        const dn_stats_t *s = &node->devicenet->stats;
        cli_json_uint(json, "explicit_requests", s->explicit_requests);
        cli_json_uint(json, "error_responses", s->error_responses);
        cli_json_uint(json, "io_messages", s->io_messages);
        cli_json_uint(json, "fragments", s->fragments);
        cli_json_uint(json, "timeouts", s->timeouts);
    } else {
        cli_json_uint(json, "sdo_requests", node->counters->sdo_requests);
        cli_json_uint(json, "sdo_aborts", node->counters->sdo_aborts);
        cli_json_uint(json, "emcy", node->counters->emcy);
    }
    cli_json_end_object(json);
}

/* A logic input by its name: "LI3". */
static void input_json(cli_json_t *json, uint8_t input)
{
    char name[8];
    snprintf(name, sizeof name, "LI%u", input);
    cli_json_str(json, NULL, name);
}

/* Every analogue input of the model in its unit: "analog":{"AI2":5.000,"AIP":50.5}. */
static void analog_json(cli_json_t *json, const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    cli_json_begin_object(json, "analog");
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        const drive_analog_input_t *in = &profile->analog_inputs[i];
        int32_t value = drive_analog(drive, i);
        int32_t magnitude = value < 0 ? -value : value;
        const char *sign = value < 0 ? "-" : "";
        if (in->kind == DRIVE_ANALOG_POTENTIOMETER)
            cli_json_number(json, in->name, "%s%d.%01d", sign, (int)(magnitude / 10),
                            (int)(magnitude % 10));
        else
            cli_json_number(json, in->name, "%s%d.%03d", sign, (int)(magnitude / 1000),
                            (int)(magnitude % 1000));
    }
    cli_json_end_object(json);
}

void atv312d_state_json(cli_json_t *json, const atv312d_control_node_t *node)
{
    if (node->plain) {
        plain_state_json(json, node);
        return;
    }
    const drive_t *drive = node->drive;
    const drive_dn_t *dn = node->devicenet;
    motion_t m = read_motion(drive);
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    cli_json_begin_object(json, NULL);
    cli_json_uint(json, "node", atv312d_node_id(node));
    if (dn) {
        cli_json_str(json, "ms", drive_dn_led_name(dn_node_ms_led(&dn->node)));
        cli_json_str(json, "ns", drive_dn_led_name(dn_node_ns_led(&dn->node)));
        cli_json_str(json, "supervisor", drive_dn_state_name(drive_dn_state(dn)));
    } else
        cli_json_str(json, "nmt", co_nmt_state_name(drive->node.nmt_state));
    cli_json_str(json, "cia402", drive_state_name(drive));
    cli_json_uint(json, "statusword", m.statusword);
    cli_json_int(json, "reference_rpm", m.reference);
    cli_json_int(json, "speed_rpm", m.speed);
    cli_json_number(json, "current_a", "%u.%u", m.current / 10, m.current % 10);
    cli_json_int(json, "torque_percent", m.torque);
    cli_json_str(json, "display", m.display);
    canopen_leds_json(json, node);
    if (fault)
        cli_json_str(json, "fault", fault->code);
    else
        cli_json_null(json, "fault");
    comm_loss_json(json, drive);
    counters_json(json, node);
    cli_json_begin_array(json, "inputs");
    for (uint8_t i = 1; i <= drive->profile->logic_inputs; i++) {
        if (drive_input(drive, i))
            input_json(json, i);
    }
    cli_json_end_array(json);
    analog_json(json, drive);
    /* Last, so that a reader of the drive's fields in their order finds them where they were. */
    cli_json_str(json, "kind", atv312d_kind_name(atv312d_node_kind(node)));
    cli_json_end_object(json);
}

void atv312d_format_state(const atv312d_control_node_t *node, bool json, char *buf, size_t len)
{
    if (json) {
        cli_json_t writer;
        cli_json_init(&writer, buf, len);
        atv312d_state_json(&writer, node);
        cli_json_finish(&writer);
        return;
    }
    atv312d_text_t text = {.buf = buf, .len = len};
    buf[0] = '\0';
    atv312d_state_text(&text, node);
}

/* ---- the bench ---- */

void atv312d_bench_drive_json(cli_json_t *json, const atv312d_control_node_t *node)
{
    const drive_t *drive = node->drive;
    char model[32];
    size_t n = 0;
    for (const char *c = node->model; *c && n + 1 < sizeof model; c++)
        model[n++] = (char)toupper((unsigned char)*c);
    model[n] = '\0';
    cli_json_begin_object(json, NULL);
    cli_json_uint(json, "node", atv312d_node_id(node));
    cli_json_str(json, "model", model);
    if (node->plain) {
        cli_json_str(json, "kind", atv312d_kind_name(atv312d_node_kind(node)));
        cli_json_begin_array(json, "faults");
        cli_json_end_array(json);
        cli_json_begin_array(json, "inputs");
        cli_json_end_array(json);
        cli_json_begin_array(json, "leds");
        cli_json_str(json, NULL, "RUN");
        cli_json_str(json, NULL, "ERR");
        cli_json_end_array(json);
        cli_json_end_object(json);
        return;
    }
    cli_json_begin_array(json, "faults");
    const drive_fault_table_t *faults = drive->profile->faults;
    for (uint8_t i = 0; i < faults->count; i++) {
        cli_json_begin_object(json, NULL);
        cli_json_str(json, "code", faults->faults[i].code);
        cli_json_str(json, "name", faults->faults[i].meaning);
        cli_json_end_object(json);
    }
    cli_json_end_array(json);
    cli_json_begin_array(json, "inputs");
    for (uint8_t i = 1; i <= drive->profile->logic_inputs; i++)
        input_json(json, i);
    cli_json_end_array(json);
    cli_json_begin_array(json, "leds");
    if (node->devicenet) {
        cli_json_str(json, NULL, "MS");
        cli_json_str(json, NULL, "NS");
    } else {
        uint8_t count;
        const drive_indicator_t *leds = drive_panel_indicators(drive, &count);
        for (uint8_t i = 0; i < count; i++)
            cli_json_str(json, NULL, leds[i].name);
    }
    cli_json_end_array(json);
    cli_json_end_object(json);
}
