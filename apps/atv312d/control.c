/* SPDX-License-Identifier: Apache-2.0 */
/* The control surface: command execution on the drives, its session on the runtime's line socket
 * in the daemon's loop, and the `atv312d ctl` client (control.h). */
#include "control.h"
#include "status.h"

#include "co_cli.h"
#include "co_linux/log.h"
#include "drive/panel.h"

#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

#define WORDS_MAX 4
#define JSON_PREFIX "json "
#define STATUSWORD_INDEX 0x6041
#define TARGET_VELOCITY_INDEX 0x6042
#define VELOCITY_ACTUAL_INDEX 0x6044

/* A reply being written: "ok ..." / "error: ..." or the JSON object. */
typedef struct reply {
    char *buf;
    size_t len, used;
    bool json;
} reply_t;

static void put(reply_t *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

static void put(reply_t *r, const char *format, ...)
{
    if (r->used >= r->len)
        return;
    va_list args;
    va_start(args, format);
    int n = vsnprintf(r->buf + r->used, r->len - r->used, format, args);
    va_end(args);
    if (n > 0)
        r->used += (size_t)n;
}

static bool fail(reply_t *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* Messages never contain quotes or backslashes (codes and node-ids are checked before they
 * are echoed), so they go into JSON as they are. */
static bool fail(reply_t *r, const char *format, ...)
{
    char message[ATV312D_CONTROL_LINE_MAX * 2];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    r->used = 0;
    if (r->json)
        put(r, "{\"ok\":false,\"error\":\"%s\"}", message);
    else
        put(r, "error: %s", message);
    return false;
}

static bool succeed(reply_t *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

static bool succeed(reply_t *r, const char *format, ...)
{
    char message[ATV312D_CONTROL_LINE_MAX * 2];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    if (r->json)
        put(r, "{\"ok\":true,\"message\":\"%s\"}", message);
    else
        put(r, "ok %s", message);
    return true;
}

/* A word is echoed in messages only when it is short and plain. */
static bool printable_word(const char *word)
{
    size_t n = 0;
    for (; word[n]; n++) {
        char c = word[n];
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              c == '-' || c == '_' || c == '.'))
            return false;
    }
    return n > 0 && n <= 16;
}

static const char *shown(const char *word)
{
    return printable_word(word) ? word : "(unprintable)";
}

static void list_nodes(const atv312d_control_t *control, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < control->count && used < len; i++)
        used +=
            (size_t)snprintf(buf + used, len - used, "%s%u", i ? "," : "", control->nodes[i].id);
}

static const atv312d_control_node_t *find_node(const atv312d_control_t *control, const char *word,
                                               reply_t *r)
{
    char *end;
    long id = strtol(word, &end, 10);
    if (*word >= '0' && *word <= '9' && *end == '\0') {
        for (size_t i = 0; i < control->count; i++) {
            if (control->nodes[i].id == id)
                return &control->nodes[i];
        }
    }
    char ids[512];
    list_nodes(control, ids, sizeof ids);
    fail(r, "node %s is not present: this daemon runs %s %s", shown(word),
         control->count && control->nodes[0].devicenet ? "MAC ID" : "node-id", ids);
    return NULL;
}

static void list_faults(const drive_t *drive, char *buf, size_t len)
{
    const drive_fault_table_t *table = drive->profile->faults;
    size_t used = 0;
    buf[0] = '\0';
    for (uint8_t i = 0; i < table->count && used < len; i++)
        used +=
            (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "", table->faults[i].code);
}

static int find_fault(const atv312d_control_node_t *node, const char *code, reply_t *r)
{
    const drive_t *drive = node->drive;
    int index = drive_fault_find(drive, code);
    if (index >= 0)
        return index;
    char codes[512];
    list_faults(drive, codes, sizeof codes);
    fail(r, "unknown fault '%s': node %u knows %s", shown(code), node->id, codes);
    return -1;
}

/* After a change: the drive runs its process (frames go out, its deadline is taken). */
static void changed(const atv312d_control_node_t *node)
{
    co_linux_device_process(node->device);
}

/* What a master sees of a fault that happened: on CANopen its EMCY; on DeviceNet, where the
 * drive's EMCY stays on the card's internal link, the Control supervisor's state and the
 * Identity's major recoverable fault, which the card shows for a drive in Fault. */
static bool succeed_fault(const atv312d_control_node_t *node, const drive_fault_def_t *def,
                          reply_t *r)
{
    const drive_dn_t *dn = node->devicenet;
    if (!dn)
        return succeed(r, "node %u: %s (%s), EMCY %04X", node->id, def->code, def->meaning,
                       def->emcy_code);
    bool major = (dn_node_identity_status(&dn->node) & DN_STATUS_MAJOR_RECOVERABLE) != 0;
    return succeed(r, "node %u: %s (%s), supervisor %s, Identity %s", node->id, def->code,
                   def->meaning, drive_dn_state_name(drive_dn_state(dn)),
                   major ? "major recoverable fault" : "no fault");
}

static bool inject(const atv312d_control_node_t *node, uint8_t index, reply_t *r)
{
    drive_t *drive = node->drive;
    const drive_fault_def_t *def = &drive->profile->faults->faults[index];
    if (drive_fault_cause_present(drive, index))
        return fail(r, "node %u: the cause of %s is present already", node->id, def->code);
    drive_fault_inject(drive, index, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: fault %s (%s) injected", node->id, def->code,
           def->meaning);
    return succeed_fault(node, def, r);
}

static void remove_cause(const atv312d_control_node_t *node, uint8_t index)
{
    drive_fault_remove_cause(node->drive, index, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: cause of %s removed", node->id,
           node->drive->profile->faults->faults[index].code);
}

static bool command_fault(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: fault NODE CODE (e.g. fault 4 OHF)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    int index = find_fault(node, words[2], r);
    return index >= 0 && inject(node, (uint8_t)index, r);
}

static bool clear_all(const atv312d_control_node_t *node, reply_t *r)
{
    const drive_fault_table_t *table = node->drive->profile->faults;
    char codes[512] = "";
    size_t used = 0;
    for (uint8_t i = 0; i < table->count; i++) {
        if (!drive_fault_cause_present(node->drive, i))
            continue;
        remove_cause(node, i);
        if (used < sizeof codes)
            used += (size_t)snprintf(codes + used, sizeof codes - used, "%s%s", used ? ", " : "",
                                     table->faults[i].code);
    }
    if (used == 0)
        return succeed(r, "node %u: no fault cause was present", node->id);
    return succeed(r, "node %u: causes removed: %s", node->id, codes);
}

static bool command_clear(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: clear NODE CODE|all (e.g. clear 4 OHF)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    if (strcmp(words[2], "all") == 0)
        return clear_all(node, r);
    int index = find_fault(node, words[2], r);
    if (index < 0)
        return false;
    const char *code = node->drive->profile->faults->faults[index].code;
    if (!drive_fault_cause_present(node->drive, (uint8_t)index))
        return fail(r, "node %u: no cause of %s is present", node->id, code);
    remove_cause(node, (uint8_t)index);
    return succeed(r, "node %u: cause of %s removed", node->id, code);
}

/* The mains undervoltage is the model's USF fault. */
static bool command_mains(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3 || (strcmp(words[2], "undervoltage") != 0 && strcmp(words[2], "normal") != 0))
        return fail(r, "usage: mains NODE undervoltage|normal");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    int index = find_fault(node, "USF", r);
    if (index < 0)
        return false;
    if (strcmp(words[2], "undervoltage") == 0)
        return inject(node, (uint8_t)index, r);
    if (drive_fault_cause_present(node->drive, (uint8_t)index))
        remove_cause(node, (uint8_t)index);
    return succeed(r, "node %u: mains normal", node->id);
}

static bool command_stop_key(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 2)
        return fail(r, "usage: stop-key NODE");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    drive_stop_key(drive, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: STOP key", node->id);
    if (fault && !drive_fault_latched(drive))
        return succeed(r, "node %u: STOP/RESET key: fault %s reset (status word bit 14)", node->id,
                       fault->code);
    if (fault)
        return succeed(r, "node %u: STOP key: still in fault %s (status word bit 14)", node->id,
                       drive_fault_latched(drive)->code);
    return succeed(r, "node %u: STOP key (%s stop, status word bit 14)", node->id,
                   drive_local_control(drive) ? "ramp" : "freewheel");
}

static bool command_run_key(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 2)
        return fail(r, "usage: run-key NODE");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    unsigned id = node->id;
    if (!drive_local_control(drive) && node->devicenet)
        return fail(r,
                    "node %u is under network control (CtrlFromNet 1): the RUN key works under "
                    "local control (local %u on, or a command channel other than DeviceNet: "
                    "NetCtrl 0 with CCS = C212)",
                    id, id);
    if (!drive_local_control(drive))
        return fail(r,
                    "node %u is under network control: the RUN key works under local control "
                    "(local %u on, or a command channel other than CANopen)",
                    id, id);
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    if (fault)
        return fail(r, "node %u is in fault %s: the RUN key does not reset a fault", id,
                    fault->code);
    drive_run_key(drive, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: RUN key", id);
    return succeed(r, "node %u: RUN key", id);
}

static bool command_local(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3 || (strcmp(words[2], "on") != 0 && strcmp(words[2], "off") != 0))
        return fail(r, "usage: local NODE on|off");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    bool local = strcmp(words[2], "on") == 0;
    if (drive->local == local)
        return fail(r, "node %u is under %s control already", node->id,
                    local ? "local" : "network");
    drive_set_local(drive, local, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: %s control", node->id, local ? "local" : "network");
    return succeed(r, "node %u: %s control (status word bit 9 = %d)", node->id,
                   local ? "local" : "network", local ? 0 : 1);
}

/* The torque limit of the motor model. */
#define LOAD_MAX_PERCENT 150

static bool command_load(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: load NODE PERCENT (0..%d %% of nominal torque)", LOAD_MAX_PERCENT);
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    char *end;
    long percent = strtol(words[2], &end, 10);
    if (!(words[2][0] >= '0' && words[2][0] <= '9') || *end != '\0' || percent > LOAD_MAX_PERCENT)
        return fail(r, "load %s: give a percentage of nominal torque, 0..%d", shown(words[2]),
                    LOAD_MAX_PERCENT);
    drive_set_load(node->drive, (uint8_t)percent, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: load %ld %%", node->id, percent);
    return succeed(r, "node %u: load %ld %%", node->id, percent);
}

/* A DeviceNet card's traffic as its slave library counts it (dn_stats_t), where the CANopen
 * services' counters stand. */
static void put_devicenet_counters(const dn_stats_t *s, reply_t *r)
{
    put(r,
        r->json ? ",\"explicit_requests\":%lu,\"error_responses\":%lu,\"io_messages\":%lu,"
                  "\"fragments\":%lu,\"timeouts\":%lu}"
                : ", explicit requests %lu, error responses %lu, I/O messages %lu, fragments %lu, "
                  "timeouts %lu",
        (unsigned long)s->explicit_requests, (unsigned long)s->error_responses,
        (unsigned long)s->io_messages, (unsigned long)s->fragments, (unsigned long)s->timeouts);
}

/* The drive's traffic: the runtime's counts of its device, then the daemon's of its CANopen
 * services or its DeviceNet card's. */
static void put_counters(const atv312d_control_node_t *node, reply_t *r)
{
    const co_linux_device_stats_t *frames = &node->device->stats;
    const atv312d_counters_t *services = node->counters;
    if (node->devicenet) {
        put(r,
            r->json ? "\"frames\":{\"received\":%llu,\"sent\":%llu,\"dropped\":%llu"
                    : "frames received %llu, sent %llu, dropped %llu",
            frames->rx, frames->tx, frames->tx_dropped);
        put_devicenet_counters(&node->devicenet->stats, r);
    } else if (r->json)
        put(r,
            "\"frames\":{\"received\":%llu,\"sent\":%llu,\"dropped\":%llu,\"sdo_requests\":%llu,"
            "\"sdo_aborts\":%llu,\"emcy\":%llu}",
            frames->rx, frames->tx, frames->tx_dropped, services->sdo_requests,
            services->sdo_aborts, services->emcy);
    else
        put(r,
            "frames received %llu, sent %llu, dropped %llu, SDO requests %llu, SDO aborts %llu, "
            "EMCY %llu",
            frames->rx, frames->tx, frames->tx_dropped, services->sdo_requests,
            services->sdo_aborts, services->emcy);
}

/* A logic input's name, "LI3" in any case: its number, or 0. */
static unsigned input_number(const char *word)
{
    if ((word[0] != 'L' && word[0] != 'l') || (word[1] != 'I' && word[1] != 'i') || word[2] < '1' ||
        word[2] > '9' || word[3] != '\0')
        return 0;
    return (unsigned)(word[2] - '0');
}

static bool command_input(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 4 || (strcmp(words[3], "on") != 0 && strcmp(words[3], "off") != 0))
        return fail(r, "usage: input NODE LIn on|off (e.g. input 4 LI3 on)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    unsigned id = node->id;
    unsigned count = drive->profile->logic_inputs;
    unsigned input = input_number(words[2]);
    bool on = strcmp(words[3], "on") == 0;
    if (count == 0)
        return fail(r, "node %u has no logic inputs", id);
    if (input == 0 || !drive_set_input(drive, (uint8_t)input, on, node->device->loop->now))
        return fail(r, "node %u has no input %s: its inputs are LI1..LI%u", id, shown(words[2]),
                    count);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: LI%u %s", id, input, words[3]);
    return succeed(r, "node %u: LI%u %s", id, input, words[3]);
}

/* A decimal number with at most `decimals` digits after the point ("-2.5"), in thousandths: false
 * when the word is none. */
static bool parse_thousandths(const char *word, int decimals, int32_t *value)
{
    const char *c = word;
    bool negative = *c == '-';
    if (negative)
        c++;
    if (*c < '0' || *c > '9')
        return false;
    int64_t whole = 0;
    for (; *c >= '0' && *c <= '9'; c++) {
        whole = whole * 10 + (*c - '0');
        if (whole > 1000000)
            return false;
    }
    int64_t fraction = 0;
    int digits = 0;
    if (*c == '.') {
        for (c++; *c >= '0' && *c <= '9' && digits < decimals; c++, digits++)
            fraction = fraction * 10 + (*c - '0');
        if (digits == 0)
            return false;
    }
    if (*c != '\0')
        return false;
    for (; digits < 3; digits++)
        fraction *= 10;
    int64_t thousandths = whole * 1000 + fraction;
    *value = (int32_t)(negative ? -thousandths : thousandths);
    return true;
}

static void list_analog_inputs(const drive_t *drive, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (uint8_t i = 0; i < drive->profile->analog_input_count && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                                 drive->profile->analog_inputs[i].name);
}

/* What a value of the input is given in, and its range, for the replies. */
static const char *analog_range(drive_analog_kind_t kind)
{
    switch (kind) {
    case DRIVE_ANALOG_VOLTAGE:
        return "a voltage of 0..10 V";
    case DRIVE_ANALOG_BIPOLAR:
        return "a voltage of -10..10 V";
    case DRIVE_ANALOG_CURRENT:
        return "a current of 0..20 mA";
    case DRIVE_ANALOG_POTENTIOMETER:
        break;
    }
    return "a percentage of 0..100";
}

/* A value of an input of `kind` in the unit the control surface takes: "-2.500 V", "12.000 mA",
 * "50.5 %". */
static void format_analog(drive_analog_kind_t kind, int32_t value, char *buf, size_t len)
{
    int32_t magnitude = value < 0 ? -value : value;
    if (kind == DRIVE_ANALOG_POTENTIOMETER)
        snprintf(buf, len, "%d.%d %%", (int)(value / 10), (int)(value % 10));
    else
        snprintf(buf, len, "%s%d.%03d %s", value < 0 ? "-" : "", (int)(magnitude / 1000),
                 (int)(magnitude % 1000), kind == DRIVE_ANALOG_CURRENT ? "mA" : "V");
}

/* Input `index` at the value of `word` (V, mA or %): the drive's unit is mV, uA or 0.1 %. */
static bool set_analog(const atv312d_control_node_t *node, uint8_t index, const char *word,
                       const char *command, reply_t *r)
{
    drive_t *drive = node->drive;
    const drive_analog_input_t *in = &drive->profile->analog_inputs[index];
    bool percent = in->kind == DRIVE_ANALOG_POTENTIOMETER;
    int32_t thousandths;
    int32_t value = 0;
    bool valid = parse_thousandths(word, percent ? 1 : 3, &thousandths);
    if (valid)
        value = percent ? thousandths / 100 : thousandths;
    if (!valid || !drive_set_analog(drive, index, value, node->device->loop->now))
        return fail(r, "%s %s %s: give %s", command, in->name, shown(word), analog_range(in->kind));
    changed(node);
    char shown_value[32];
    format_analog(in->kind, value, shown_value, sizeof shown_value);
    co_log(CO_LOG_INFO, "node %u: control: %s %s", node->id, in->name, shown_value);
    return succeed(r, "node %u: %s %s", node->id, in->name, shown_value);
}

static bool command_analog(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 4)
        return fail(r, "usage: analog NODE AIn VALUE (volts or mA as the input takes them, e.g. "
                       "analog 4 AI2 -2.5)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    const drive_t *drive = node->drive;
    if (drive->profile->analog_input_count == 0)
        return fail(r, "node %u has no analogue inputs", node->id);
    int index = drive_analog_find(drive, words[2]);
    if (index < 0) {
        char names[128];
        list_analog_inputs(drive, names, sizeof names);
        return fail(r, "node %u has no analogue input %s: its analogue inputs are %s", node->id,
                    shown(words[2]), names);
    }
    return set_analog(node, (uint8_t)index, words[3], "analog", r);
}

/* The reference potentiometer of the front panel (the ATV31's AIP). */
static bool command_pot(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: pot NODE PERCENT (0..100, e.g. pot 5 50)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    const drive_profile_t *profile = node->drive->profile;
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        if (profile->analog_inputs[i].kind == DRIVE_ANALOG_POTENTIOMETER)
            return set_analog(node, i, words[2], "pot", r);
    }
    return fail(r, "node %u has no reference potentiometer", node->id);
}

/* The logic inputs that are on: ", inputs LI1 LI3" (nothing when none is), or the JSON list. */
static void put_inputs(const drive_t *drive, reply_t *r)
{
    bool first = true;
    put(r, "%s", r->json ? ",\"inputs\":[" : "");
    for (uint8_t i = 1; i <= drive->profile->logic_inputs; i++) {
        if (!drive_input(drive, i))
            continue;
        if (r->json)
            put(r, "%s\"LI%u\"", first ? "" : ",", i);
        else
            put(r, "%sLI%u", first ? ", inputs " : " ", i);
        first = false;
    }
    put(r, "%s", r->json ? "]" : "");
}

/* The analogue inputs: in text those not at 0 (", analog AI2 5.000 V AI3 12.000 mA", nothing when
 * all are), in JSON every one of the model in its unit ("analog":{"AI2":5.0,"AI3":12.0}). */
static void put_analog(const drive_t *drive, reply_t *r)
{
    const drive_profile_t *profile = drive->profile;
    bool first = true;
    put(r, "%s", r->json ? ",\"analog\":{" : "");
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        const drive_analog_input_t *in = &profile->analog_inputs[i];
        int32_t value = drive_analog(drive, i);
        if (r->json) {
            int32_t per = in->kind == DRIVE_ANALOG_POTENTIOMETER ? 10 : 1000;
            int32_t magnitude = value < 0 ? -value : value;
            put(r,
                in->kind == DRIVE_ANALOG_POTENTIOMETER ? "%s\"%s\":%s%d.%01d"
                                                       : "%s\"%s\":%s%d.%03d",
                first ? "" : ",", in->name, value < 0 ? "-" : "", (int)(magnitude / per),
                (int)(magnitude % per));
        } else if (value != 0) {
            char shown_value[32];
            format_analog(in->kind, value, shown_value, sizeof shown_value);
            put(r, "%s%s %s", first ? ", analog " : " ", in->name, shown_value);
        } else
            continue;
        first = false;
    }
    put(r, "%s", r->json ? "}" : "");
}

/* What the bus sees of the drive: its NMT state on CANopen; on DeviceNet the card's MS and NS
 * LEDs and the Control supervisor's state. */
static void put_bus_state(const atv312d_control_node_t *node, reply_t *r)
{
    const drive_dn_t *dn = node->devicenet;
    if (!dn) {
        const char *nmt = co_nmt_state_name(node->drive->node.nmt_state);
        put(r, r->json ? "{\"node\":%u,\"nmt\":\"%s\"," : "node %u: nmt %s, ", node->id, nmt);
        return;
    }
    const char *ms = drive_dn_led_name(dn_node_ms_led(&dn->node));
    const char *ns = drive_dn_led_name(dn_node_ns_led(&dn->node));
    const char *supervisor = drive_dn_state_name(drive_dn_state(dn));
    put(r,
        r->json ? "{\"node\":%u,\"ms\":\"%s\",\"ns\":\"%s\",\"supervisor\":\"%s\","
                : "node %u: ms %s, ns %s, supervisor %s, ",
        node->id, ms, ns, supervisor);
}

/* An LED's JSON key: its name in lower case, then "_led" ("run_led", "ok_led"). */
static void put_led_key(const char *name, reply_t *r)
{
    put(r, "\"");
    for (const char *c = name; *c != '\0'; c++)
        put(r, "%c", tolower((unsigned char)*c));
    put(r, "_led\":");
}

/* The CANopen card's LEDs as the model's manual names them: RUN and ERR (CiA 303-3), the ATV58
 * card's OK and COM ("OK on, COM flashing"; JSON "ok_led":"on"); a DeviceNet card has MS and NS
 * instead. */
static void put_canopen_leds(const atv312d_control_node_t *node, reply_t *r)
{
    if (node->devicenet)
        return;
    uint8_t count;
    const drive_indicator_t *leds = drive_panel_indicators(node->drive, &count);
    for (uint8_t i = 0; i < count; i++) {
        const char *pattern = drive_led_name(leds[i].pattern(node->drive, node->device->loop->now));
        if (r->json) {
            put_led_key(leds[i].name, r);
            put(r, "\"%s\",", pattern);
        } else
            put(r, "%s %s, ", leds[i].name, pattern);
    }
}

/* The cause of the communication loss the drive reacted to: "comm-loss heartbeat node 1, ",
 * "comm-loss guarding, " (nothing while there is none); JSON "comm_loss":{"by":"heartbeat",
 * "node":1}, {"by":"guarding"} or null. */
static void put_comm_loss(const drive_t *drive, reply_t *r)
{
    static const char *const by[] = {
        [DRIVE_COMM_LOSS_GUARDING] = "guarding",
        [DRIVE_COMM_LOSS_HEARTBEAT] = "heartbeat",
        [DRIVE_COMM_LOSS_NETWORK] = "network",
    };
    drive_comm_loss_t loss = drive->comm_loss;
    bool producer = loss.source == DRIVE_COMM_LOSS_HEARTBEAT;
    if (r->json && loss.source == DRIVE_COMM_LOSS_NONE)
        put(r, "\"comm_loss\":null,");
    else if (r->json && producer)
        put(r, "\"comm_loss\":{\"by\":\"%s\",\"node\":%u},", by[loss.source], loss.node);
    else if (r->json)
        put(r, "\"comm_loss\":{\"by\":\"%s\"},", by[loss.source]);
    else if (producer)
        put(r, "comm-loss %s node %u, ", by[loss.source], loss.node);
    else if (loss.source != DRIVE_COMM_LOSS_NONE)
        put(r, "comm-loss %s, ", by[loss.source]);
}

static void put_state(const atv312d_control_node_t *node, reply_t *r)
{
    const drive_t *drive = node->drive;
    const co_node_t *co = &drive->node;
    drive_param_t lcr = drive->profile->motor_current;
    drive_param_t otr = drive->profile->motor_torque;
    int16_t reference = (int16_t)co_od_value(co, TARGET_VELOCITY_INDEX, 0);
    int16_t speed = (int16_t)co_od_value(co, VELOCITY_ACTUAL_INDEX, 0);
    unsigned current = (unsigned)co_od_value(co, lcr.index, lcr.subindex);
    int16_t torque = (int16_t)co_od_value(co, otr.index, otr.subindex);
    unsigned status = (unsigned)co_od_value(co, STATUSWORD_INDEX, 0);
    drive_display_t display = drive_panel_display(drive);
    char shows[16];
    if (display.code)
        snprintf(shows, sizeof shows, "%s", display.code);
    else
        snprintf(shows, sizeof shows, "%u.%u", display.decihertz / 10, display.decihertz % 10);
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    put_bus_state(node, r);
    if (r->json)
        put(r,
            "\"cia402\":\"%s\",\"statusword\":%u,\"reference_rpm\":%d,\"speed_rpm\":%d,"
            "\"current_a\":%u.%u,\"torque_percent\":%d,\"display\":\"%s\",",
            drive_state_name(drive), status, reference, speed, current / 10, current % 10, torque,
            shows);
    else
        put(r,
            "cia402 %s, statusword %04X, speed %d rpm, current %u.%u A, torque %d %%, display %s, ",
            drive_state_name(drive), status, speed, current / 10, current % 10, torque, shows);
    put_canopen_leds(node, r);
    if (r->json)
        put(r, "\"fault\":%s%s%s,", fault ? "\"" : "", fault ? fault->code : "null",
            fault ? "\"" : "");
    else
        put(r, "fault %s, ", fault ? fault->code : "none");
    put_comm_loss(drive, r);
    put_counters(node, r);
    put_inputs(drive, r);
    put_analog(drive, r);
    put(r, "%s", r->json ? "}" : "");
}

void atv312d_format_state(const atv312d_control_node_t *node, bool json, char *buf, size_t len)
{
    reply_t r = {.buf = buf, .len = len, .json = json};
    buf[0] = '\0';
    put_state(node, &r);
}

static bool command_state(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n > 2)
        return fail(r, "usage: state [NODE]");
    const atv312d_control_node_t *only = NULL;
    if (n == 2 && !(only = find_node(control, words[1], r)))
        return false;
    if (r->json) {
        const co_linux_loop_t *loop = control->nodes[0].device->loop;
        put(r, "{\"ok\":true,\"can\":{\"state\":\"%s\",\"bus_offs\":%llu},\"nodes\":[",
            atv312d_can_state(loop), loop->bus.conditions.bus_offs);
    } else
        put(r, "ok ");
    bool first = true;
    for (size_t i = 0; i < control->count; i++) {
        if (only && only != &control->nodes[i])
            continue;
        put(r, "%s", first ? "" : r->json ? "," : "; ");
        put_state(&control->nodes[i], r);
        first = false;
    }
    put(r, "%s", r->json ? "]}" : "");
    return true;
}

static const struct {
    const char *name;
    bool (*run)(const atv312d_control_t *control, char **words, size_t n, reply_t *r);
} commands[] = {
    {"fault", command_fault},       {"clear", command_clear},     {"mains", command_mains},
    {"stop-key", command_stop_key}, {"run-key", command_run_key}, {"local", command_local},
    {"load", command_load},         {"input", command_input},     {"analog", command_analog},
    {"pot", command_pot},           {"state", command_state},
};

#define COMMAND_NAMES                                                                              \
    "fault, clear, mains, stop-key, run-key, local, load, input, analog, pot, state"

bool atv312d_control_execute(const atv312d_control_t *control, const char *line, char *reply,
                             size_t reply_len)
{
    reply_t r = {.buf = reply, .len = reply_len};
    reply[0] = '\0';
    if (strncmp(line, JSON_PREFIX, strlen(JSON_PREFIX)) == 0) {
        r.json = true;
        line += strlen(JSON_PREFIX);
    }
    char copy[ATV312D_CONTROL_LINE_MAX];
    if (strlen(line) >= sizeof copy)
        return fail(&r, "command longer than %d characters", ATV312D_CONTROL_LINE_MAX - 1);
    strcpy(copy, line);
    char *words[WORDS_MAX + 1];
    size_t n = 0;
    char *save;
    for (char *w = strtok_r(copy, " \t\r", &save); w; w = strtok_r(NULL, " \t\r", &save)) {
        if (n == WORDS_MAX + 1)
            return fail(&r, "too many words (see atv312d --help, control commands)");
        words[n++] = w;
    }
    if (n == 0)
        return fail(&r, "empty command: give one of " COMMAND_NAMES);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        if (strcmp(words[0], commands[i].name) == 0)
            return commands[i].run(control, words, n, &r);
    }
    return fail(&r, "unknown command '%s': the commands are " COMMAND_NAMES, shown(words[0]));
}

/* ---- the socket in the loop ---- */

static size_t answer(void *ctx, const char *line, bool cut, char *reply, size_t cap)
{
    const atv312d_control_t *control = ctx;
    if (cut)
        snprintf(reply, cap, "error: command longer than %d characters",
                 ATV312D_CONTROL_LINE_MAX - 1);
    else
        atv312d_control_execute(control, line, reply, cap - 1);
    size_t len = strlen(reply);
    reply[len++] = '\n';
    return len;
}

int atv312d_control_open(atv312d_control_t *control, co_linux_loop_t *loop, const char *path,
                         const atv312d_control_node_t *nodes, size_t count)
{
    static char reply[ATV312D_CONTROL_REPLY_MAX];
    control->nodes = nodes;
    control->count = count;
    co_line_server_config_t config = {.mode = CO_LINE_SESSION,
                                      .answer = answer,
                                      .ctx = control,
                                      .reply = reply,
                                      .reply_cap = sizeof reply};
    const char *call = NULL;
    co_line_result_t result = co_line_server_open(&control->server, loop, path, &config, &call);
    if (result == CO_LINE_TOO_LONG)
        return cli_fail(NULL, EX_USAGE,
                        "--control %s: the path is longer than %zu characters: give a shorter one",
                        path, CO_LINE_PATH_MAX - 1);
    if (result != CO_LINE_OK) {
        /* Another daemon answers there, or the path is a file of another kind. */
        if (errno == EADDRINUSE)
            call = "bind (the path exists: another daemon's socket or a file)";
        co_log(CO_LOG_ERROR, "control socket %s: %s: %s", path, call, strerror(errno));
        return EX_CANTCREAT;
    }
    co_log(CO_LOG_INFO, "control socket %s: listening (atv312d ctl %s state)", path, path);
    return 0;
}

void atv312d_control_close(atv312d_control_t *control)
{
    co_line_server_close(&control->server);
}

/* ---- the client ---- */

static int client_usage(void)
{
    return cli_fail(NULL, EX_USAGE,
                    "ctl: give the daemon's socket and a command: atv312d ctl PATH [--json] "
                    "COMMAND..., e.g. atv312d ctl /tmp/atv312d.sock fault 4 OHF");
}

int atv312d_control_client(int argc, char *const argv[])
{
    if (argc < 2)
        return client_usage();
    const char *path = argv[0];
    char line[ATV312D_CONTROL_LINE_MAX + sizeof JSON_PREFIX];
    size_t used = 0;
    int first = 1;
    if (strcmp(argv[1], "--json") == 0) {
        used = (size_t)snprintf(line, sizeof line, "%s", JSON_PREFIX);
        first = 2;
    }
    if (first >= argc)
        return client_usage();
    for (int i = first; i < argc && used < sizeof line; i++)
        used += (size_t)snprintf(line + used, sizeof line - used, "%s%s", i > first ? " " : "",
                                 argv[i]);
    if (used + 1 >= sizeof line || strchr(line, '\n'))
        return cli_fail(NULL, EX_USAGE,
                        "ctl: the command has a newline or is longer than %d characters: give "
                        "one command of one line",
                        ATV312D_CONTROL_LINE_MAX - 1);
    static char reply[ATV312D_CONTROL_REPLY_MAX];
    switch (co_line_request(path, CO_LINE_SESSION, line, reply, sizeof reply)) {
    case CO_LINE_OK:
        break;
    case CO_LINE_TOO_LONG:
        return cli_fail(NULL, EX_USAGE,
                        "ctl: the path %s is longer than %zu characters: give a shorter one", path,
                        CO_LINE_PATH_MAX - 1);
    case CO_LINE_NO_SERVER:
        return cli_fail(NULL, EX_UNAVAILABLE,
                        "ctl: cannot connect to %s: %s: is atv312d running with --control %s?",
                        path, strerror(errno), path);
    default:
        return cli_fail(NULL, EX_PROTOCOL,
                        "ctl: no reply from %s: the daemon closed the connection", path);
    }
    bool json = first == 2;
    bool ok = strncmp(reply, "ok", 2) == 0 || strncmp(reply, "{\"ok\":true", 10) == 0;
    if (ok || json) {
        fputs(reply, stdout);
        return ok ? 0 : CLI_EXIT_REFUSED;
    }
    /* The daemon refused: "error: WHY" is the program's error. */
    const char *why = strncmp(reply, "error: ", 7) == 0 ? reply + 7 : reply;
    return cli_fail(NULL, CLI_EXIT_REFUSED, "%.*s", (int)strcspn(why, "\n"), why);
}
