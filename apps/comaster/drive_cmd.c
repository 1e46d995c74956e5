/* SPDX-License-Identifier: Apache-2.0 */
/* comaster drive: runs the CiA 402 power state machine of a drive with the core's CiA 402 master
 * helper (co_cia402_master.h), writing the control words it asks for by SDO to 6040h, or with
 * --rpdo in the drive's RPDO that maps 6040h, and feeding it the status word 6041h read over SDO
 * until the target state, printing every state it sees. */
#include "co/co_cia402_master.h"
#include "co/co_pdo.h"
#include "comaster/comaster.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How often the status word is read while a transition is awaited. */
#define POLL_MS 10u

/* The RPDOs looked at for --rpdo: the first eight (the ATV312 has RPDO1 and RPDO6). */
#define RPDO_COUNT 8u
#define PDO_MAPPED_MAX 8u
/* A mapping entry: index << 16 | sub-index << 8 | length in bits. */
#define MAP_CONTROL_WORD ((uint32_t)CO_CIA402_CONTROL_WORD << 16 | 16u)
#define MAP_TARGET_VELOCITY ((uint32_t)CO_CIA402_VL_TARGET_VELOCITY << 16 | 16u)

static const char drive_help[] =
    "usage: comaster drive NODE enable|disable|quick-stop|fault-reset|speed RPM [--rpdo]\n"
    "\n"
    "Runs the CiA 402 state machine of the drive at node NODE (1..127): writes the\n"
    "control word 6040h over SDO and reads the status word 6041h until it shows\n"
    "each state on the way (each within --timeout), printing every state seen.\n"
    "\n"
    "  enable       Shutdown, Switch on, Enable operation: to Operation enabled\n"
    "               (from Quick stop active through Switch on disabled)\n"
    "  disable      Disable voltage: to Switch on disabled (the motor coasts)\n"
    "  quick-stop   Quick stop: Operation enabled to Quick stop active, any other\n"
    "               state to Switch on disabled\n"
    "  fault-reset  bit 7 from 0 to 1: Fault to Switch on disabled\n"
    "  speed RPM    writes the target velocity 6042h (-32768..32767 rpm), then\n"
    "               enables the drive\n"
    "  --rpdo       send the control words (and the velocity, when mapped) in the\n"
    "               valid RPDO whose mapping holds 6040h, read over SDO, its other\n"
    "               objects at their current values: the node must be Operational\n"
    "\n"
    "A drive in Fault is left alone by every command but fault-reset, and a fault\n"
    "on the way ends the command (exit 4).\n"
    "\n"
    "Example: comaster -i vcan0 drive 4 speed 1200\n";

/* The RPDO that carries the control word (--rpdo). */
typedef struct rpdo {
    bool used;
    uint16_t cob_id;
    uint8_t len;
    uint8_t control_at; /* byte offset of 6040h */
    int speed_at;       /* byte offset of 6042h, -1 when not mapped */
    uint8_t data[8];    /* the frame: the other objects at their current values */
} rpdo_t;

typedef struct drive_session {
    comaster_bus_t *bus;
    const comaster_options_t *opts;
    rpdo_t rpdo;
    uint8_t node;
    uint16_t status;        /* the last status word read */
    const char *last_shown; /* the state last printed */
} drive_session_t;

static void show_state(drive_session_t *d)
{
    const char *state = co_cia402_state_name(co_cia402_state(d->status));
    if (!state)
        state = "no CiA 402 state";
    if (d->last_shown && strcmp(d->last_shown, state) == 0)
        return;
    d->last_shown = state;
    if (d->opts->json)
        printf("{\"node\": %u, \"state\": \"%s\", \"statusword\": \"0x%04X\"}\n", d->node, state,
               d->status);
    else
        printf("node %u: %s (6041h = 0x%04X)\n", d->node, state, d->status);
    fflush(stdout);
}

static int read_status(drive_session_t *d)
{
    uint8_t buf[2];
    co_sdo_client_result_t result;
    int rc = comaster_sdo_upload(d->bus, d->node, CO_CIA402_STATUS_WORD, 0, buf, sizeof buf,
                                 CO_SDO_CLIENT_AUTO, d->opts->timeout_ms, &result);
    if (rc == 0)
        rc = comaster_sdo_status(d->opts, d->node, &result);
    if (rc == 0 && result.size != 2)
        return comaster_fail(d->opts, EX_DATAERR,
                             "node %u: 6041h has %u bytes, not the 2 of a CiA 402 status word",
                             d->node, result.size);
    if (rc == 0) {
        d->status = co_get_u16(buf);
        show_state(d);
    }
    return rc;
}

static int write_u16(drive_session_t *d, uint16_t index, uint16_t value)
{
    uint8_t buf[2];
    co_put_u16(buf, value);
    co_sdo_client_result_t result;
    int rc = comaster_sdo_download(d->bus, d->node, index, 0, buf, sizeof buf, CO_SDO_CLIENT_AUTO,
                                   d->opts->timeout_ms, &result);
    return rc ? rc : comaster_sdo_status(d->opts, d->node, &result);
}

/* The RPDO with its current data, sent at once, as a PLC's cyclic frame would be. */
static int send_rpdo(drive_session_t *d)
{
    co_frame_t frame = {.id = d->rpdo.cob_id, .len = d->rpdo.len};
    memcpy(frame.data, d->rpdo.data, d->rpdo.len);
    comaster_bus_send(d->bus, &frame);
    return comaster_bus_pause(d->bus, 0);
}

/* The control word by SDO, or in the RPDO. */
static int write_control(drive_session_t *d, uint16_t control)
{
    if (!d->rpdo.used)
        return write_u16(d, CO_CIA402_CONTROL_WORD, control);
    co_put_u16(&d->rpdo.data[d->rpdo.control_at], control);
    return send_rpdo(d);
}

static int refuse_fault(drive_session_t *d)
{
    return comaster_fail(d->opts, CLI_EXIT_DRIVE_FAULT,
                         "node %u is in Fault (6041h = 0x%04X): reset it first: comaster drive "
                         "%u fault-reset",
                         d->node, d->status, d->node);
}

static int timed_out(drive_session_t *d, const co_cia402_master_t *m)
{
    const char *awaited = co_cia402_state_name(m->awaited);
    char command[32] = "";
    if (m->sent)
        snprintf(command, sizeof command, "control word 0x%04X: ", m->control);
    return comaster_fail(d->opts, CLI_EXIT_TIMEOUT,
                         "node %u: %sno %s within %u ms (6041h = 0x%04X)%s (--timeout MS waits "
                         "longer)",
                         d->node, command, awaited ? awaited : "CiA 402 state", d->opts->timeout_ms,
                         d->status,
                         d->rpdo.used && m->sent ? ": RPDOs count only in Operational: comaster "
                                                   "nmt start NODE"
                                                 : "");
}

/* The helper's run from the status word read last: each control word it asks for is written and
 * the status word read at once; while it waits, read again every POLL_MS. */
static int run_target(drive_session_t *d, co_cia402_target_t target)
{
    co_cia402_master_t m;
    co_cia402_master_start(&m, target, (co_time_t)d->opts->timeout_ms * 1000u);
    int rc = 0;
    while (rc == 0) {
        uint16_t control;
        switch (co_cia402_master_step(&m, d->status, co_linux_now(), &control)) {
        case CO_CIA402_WRITE:
            rc = write_control(d, control);
            break;
        case CO_CIA402_WAIT:
            rc = comaster_bus_pause(d->bus, POLL_MS);
            break;
        case CO_CIA402_REACHED:
            return 0;
        case CO_CIA402_FAULTED:
            return refuse_fault(d);
        case CO_CIA402_TIMED_OUT:
            return timed_out(d, &m);
        }
        if (rc == 0)
            rc = read_status(d);
    }
    return rc;
}

/* ---- --rpdo: the RPDO mapping 6040h, read over SDO ------------------------------------------ */

/* Reads up to 4 bytes; *size 0 when the node aborted (it has no such object). */
static int read_value(drive_session_t *d, uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap,
                      uint32_t *size)
{
    co_sdo_client_result_t result;
    *size = 0;
    int rc = comaster_sdo_upload(d->bus, d->node, index, sub, buf, cap, CO_SDO_CLIENT_AUTO,
                                 d->opts->timeout_ms, &result);
    if (rc == 0 && result.status == CO_SDO_CLIENT_CLIENT_ABORT &&
        result.abort_code == CO_SDO_ABORT_TIMEOUT)
        return comaster_sdo_status(d->opts, d->node, &result);
    if (rc == 0 && result.status == CO_SDO_CLIENT_OK)
        *size = result.size;
    return rc;
}

static int read_u32(drive_session_t *d, uint16_t index, uint8_t sub, uint32_t *value, bool *has)
{
    uint8_t buf[4] = {0};
    uint32_t size;
    int rc = read_value(d, index, sub, buf, sizeof buf, &size);
    *has = rc == 0 && size > 0;
    *value = co_get_u32(buf);
    return rc;
}

/* Reads the mapping of RPDO n; `candidate` is filled when it maps 6040h in at most 8 bytes of
 * whole-byte objects. Returns 0 or the status of a transfer that could not run. */
static int read_rpdo_mapping(drive_session_t *d, unsigned n, rpdo_t *candidate)
{
    uint32_t count, entry;
    bool has;
    int rc = read_u32(d, (uint16_t)(CO_PDO_RPDO_MAP + n), 0, &count, &has);
    if (rc != 0 || !has || count > PDO_MAPPED_MAX)
        return rc;
    candidate->control_at = 0xFF;
    candidate->speed_at = -1;
    unsigned offset = 0;
    for (uint8_t sub = 1; sub <= count; sub++) {
        rc = read_u32(d, (uint16_t)(CO_PDO_RPDO_MAP + n), sub, &entry, &has);
        unsigned bytes = (entry & 0xFFu) / 8u;
        if (rc != 0 || !has || (entry & 7u) || bytes == 0 || offset + bytes > 8)
            return rc;
        if (entry == MAP_CONTROL_WORD)
            candidate->control_at = (uint8_t)offset;
        else if (entry == MAP_TARGET_VELOCITY)
            candidate->speed_at = (int)offset;
        uint32_t size;
        rc = read_value(d, (uint16_t)(entry >> 16), (uint8_t)(entry >> 8), &candidate->data[offset],
                        bytes, &size);
        if (rc != 0)
            return rc;
        offset += bytes;
    }
    candidate->len = (uint8_t)offset;
    candidate->used = candidate->control_at != 0xFF;
    return 0;
}

static int find_rpdo(drive_session_t *d)
{
    for (unsigned n = 0; n < RPDO_COUNT; n++) {
        uint32_t cob_id;
        bool has;
        int rc = read_u32(d, (uint16_t)(CO_PDO_RPDO_COMM + n), 1, &cob_id, &has);
        if (rc != 0)
            return rc;
        if (!has || (cob_id & CO_PDO_COBID_INVALID))
            continue;
        rpdo_t candidate = {.cob_id = (uint16_t)(cob_id & CO_PDO_COBID_CAN_ID)};
        rc = read_rpdo_mapping(d, n, &candidate);
        if (rc != 0)
            return rc;
        if (candidate.used) {
            d->rpdo = candidate;
            return 0;
        }
    }
    return comaster_fail(d->opts, EX_DATAERR,
                         "node %u: --rpdo: no valid RPDO (1400h-1407h) maps the control word "
                         "6040h: make one valid (e.g. comaster write %u 0x1405:1 u32 0x%03X), or "
                         "drive by SDO without --rpdo",
                         d->node, d->node, CO_CAN_ID_RPDO2 + d->node);
}

static bool parse_rpm(const comaster_options_t *opts, const char *text, int16_t *rpm)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < INT16_MIN || v > INT16_MAX) {
        comaster_fail(opts, EX_USAGE, "drive: speed '%s' is not a velocity: give rpm -32768..32767",
                      text);
        return false;
    }
    *rpm = (int16_t)v;
    return true;
}

int comaster_drive_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, drive_help, "--rpdo", 2, 3);
    if (rc >= 0)
        return rc;
    static const struct {
        const char *name;
        co_cia402_target_t target;
    } actions[] = {{"enable", CO_CIA402_TO_OPERATION_ENABLED},
                   {"disable", CO_CIA402_TO_SWITCH_ON_DISABLED},
                   {"quick-stop", CO_CIA402_TO_QUICK_STOP},
                   {"fault-reset", CO_CIA402_TO_FAULT_RESET},
                   {"speed", CO_CIA402_TO_OPERATION_ENABLED}};
    const char *action = args.positional[1];
    size_t a = 0;
    while (a < sizeof actions / sizeof actions[0] && strcmp(actions[a].name, action) != 0)
        a++;
    if (a == sizeof actions / sizeof actions[0])
        return comaster_fail(opts, EX_USAGE,
                             "drive: '%s' is not an action: give enable, disable, quick-stop, "
                             "fault-reset or speed RPM",
                             action);
    bool speed = strcmp(action, "speed") == 0;
    if (speed != (args.count == 3))
        return comaster_fail(opts, EX_USAGE, "drive: %s",
                             speed ? "speed needs RPM: drive NODE speed 1200"
                                   : "only speed takes a value");
    int16_t rpm = 0;
    drive_session_t d = {.opts = opts};
    if (!comaster_parse_node(opts, args.positional[0], false, &d.node) ||
        (speed && !parse_rpm(opts, args.positional[2], &rpm)))
        return EX_USAGE;
    static comaster_bus_t bus;
    d.bus = &bus;
    rc = comaster_bus_open(&bus, opts);
    if (rc == 0 && args.rpdo)
        rc = find_rpdo(&d);
    if (rc == 0 && speed && d.rpdo.used && d.rpdo.speed_at >= 0) {
        /* With the control word as it is (read with the mapping): only the velocity changes. */
        co_put_u16(&d.rpdo.data[d.rpdo.speed_at], (uint16_t)rpm);
        rc = send_rpdo(&d);
    } else if (rc == 0 && speed) {
        rc = write_u16(&d, CO_CIA402_VL_TARGET_VELOCITY, (uint16_t)rpm);
    }
    if (rc == 0)
        rc = read_status(&d);
    if (rc == 0)
        rc = run_target(&d, actions[a].target);
    comaster_bus_close(&bus);
    return rc;
}
