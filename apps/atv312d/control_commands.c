/* SPDX-License-Identifier: Apache-2.0 */
/* The control commands' interpreter (control_commands.h): the words of a line, the command
 * they name, its checks, its action on the drive and its reply. */
#include "atv312d/control_commands.h"

#include "co_linux/log.h"
#include "nodes/io/io401.h"
#include "nodes/plc300/plc300.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WORDS_MAX 4

/* A reply being written: "ok ..." / "error: ..." or the JSON object. */
typedef struct reply {
    char *buf;
    size_t len;
    bool json;
} reply_t;

/* The whole reply: "ok MESSAGE", "error: MESSAGE", or {"ok":true,"message":"MESSAGE"},
 * {"ok":false,"error":"MESSAGE"}. */
static void reply_with(reply_t *r, bool ok, const char *format, va_list args)
{
    char message[ATV312D_CONTROL_LINE_MAX * 2];
    vsnprintf(message, sizeof message, format, args);
    if (!r->json) {
        snprintf(r->buf, r->len, "%s%s", ok ? "ok " : "error: ", message);
        return;
    }
    cli_json_t json;
    cli_json_init(&json, r->buf, r->len);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", ok);
    cli_json_str(&json, ok ? "message" : "error", message);
    cli_json_end_object(&json);
    cli_json_finish(&json);
}

static bool fail(reply_t *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

static bool fail(reply_t *r, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    reply_with(r, false, format, args);
    va_end(args);
    return false;
}

static bool succeed(reply_t *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

static bool succeed(reply_t *r, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    reply_with(r, true, format, args);
    va_end(args);
    return true;
}

/* A word is echoed in messages only when it is short and plain. */
static bool printable_word(const char *word)
{
    size_t n = 0;
    for (; word[n]; n++) {
        char c = word[n];
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              c == '-' || c == '_' || c == '.' || c == '%'))
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
        used += (size_t)snprintf(buf + used, len - used, "%s%u", i ? "," : "",
                                 atv312d_node_id(&control->nodes[i]));
}

static const atv312d_control_node_t *find_node(const atv312d_control_t *control, const char *word,
                                               reply_t *r)
{
    char *end;
    long id = strtol(word, &end, 10);
    if (*word >= '0' && *word <= '9' && *end == '\0') {
        for (size_t i = 0; i < control->count; i++) {
            if (atv312d_node_id(&control->nodes[i]) == id)
                return &control->nodes[i];
        }
    }
    char ids[512];
    list_nodes(control, ids, sizeof ids);
    fail(r, "node %s is not present: this daemon runs %s %s", shown(word),
         control->count && control->nodes[0].devicenet ? "MAC ID" : "node-id", ids);
    return NULL;
}

/* What the node is, for a refusal: "an io node", "a plc300 node", "an atv312 drive". */
static void node_phrase(const atv312d_control_node_t *node, char *buf, size_t len)
{
    bool vowel = node->model[0] && strchr("aeiou", node->model[0]);
    snprintf(buf, len, "%s %s %s", vowel ? "an" : "a", node->model, node->plain ? "node" : "drive");
}

/* The commands a plain node of each model takes, for the refusal of a drive's command. */
static const char *plain_commands(const atv312d_control_node_t *node)
{
    const atv312d_plain_surface_t *surface = atv312d_plain_surface(node->plain->model);
    return surface ? surface->commands : "state";
}

/* The node NODE names when it is a drive: a plain node has no drive commands. */
static const atv312d_control_node_t *find_drive(const atv312d_control_t *control, const char *word,
                                                const char *command, reply_t *r)
{
    const atv312d_control_node_t *node = find_node(control, word, r);
    if (node && node->plain) {
        char what[64];
        node_phrase(node, what, sizeof what);
        fail(r, "node %u is %s, not a drive: %s is a drive's command; its commands are %s",
             atv312d_node_id(node), what, command, plain_commands(node));
        return NULL;
    }
    return node;
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
    fail(r, "unknown fault '%s': node %u knows %s", shown(code), atv312d_node_id(node), codes);
    return -1;
}

/* After a change: the node runs its process (frames go out, a TPDO whose data changed among
 * them; its deadline is taken). */
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
        return succeed(r, "node %u: %s (%s), EMCY %04X", atv312d_node_id(node), def->code,
                       def->meaning, def->emcy_code);
    bool major = (dn_node_identity_status(&dn->node) & DN_STATUS_MAJOR_RECOVERABLE) != 0;
    return succeed(r, "node %u: %s (%s), supervisor %s, Identity %s", atv312d_node_id(node),
                   def->code, def->meaning, drive_dn_state_name(drive_dn_state(dn)),
                   major ? "major recoverable fault" : "no fault");
}

static bool inject(const atv312d_control_node_t *node, uint8_t index, reply_t *r)
{
    drive_t *drive = node->drive;
    const drive_fault_def_t *def = &drive->profile->faults->faults[index];
    if (drive_fault_cause_present(drive, index))
        return fail(r, "node %u: the cause of %s is present already", atv312d_node_id(node),
                    def->code);
    drive_fault_inject(drive, index, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: fault %s (%s) injected", atv312d_node_id(node),
           def->code, def->meaning);
    return succeed_fault(node, def, r);
}

static void remove_cause(const atv312d_control_node_t *node, uint8_t index)
{
    drive_fault_remove_cause(node->drive, index, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: cause of %s removed", atv312d_node_id(node),
           node->drive->profile->faults->faults[index].code);
}

static bool command_fault(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: fault NODE CODE (e.g. fault 4 OHF)");
    const atv312d_control_node_t *node = find_drive(control, words[1], "fault", r);
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
        return succeed(r, "node %u: no fault cause was present", atv312d_node_id(node));
    return succeed(r, "node %u: causes removed: %s", atv312d_node_id(node), codes);
}

static bool command_clear(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: clear NODE CODE|all (e.g. clear 4 OHF)");
    const atv312d_control_node_t *node = find_drive(control, words[1], "clear", r);
    if (!node)
        return false;
    if (strcmp(words[2], "all") == 0)
        return clear_all(node, r);
    int index = find_fault(node, words[2], r);
    if (index < 0)
        return false;
    const char *code = node->drive->profile->faults->faults[index].code;
    if (!drive_fault_cause_present(node->drive, (uint8_t)index))
        return fail(r, "node %u: no cause of %s is present", atv312d_node_id(node), code);
    remove_cause(node, (uint8_t)index);
    return succeed(r, "node %u: cause of %s removed", atv312d_node_id(node), code);
}

/* The mains undervoltage is the model's USF fault. */
static bool command_mains(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3 || (strcmp(words[2], "undervoltage") != 0 && strcmp(words[2], "normal") != 0))
        return fail(r, "usage: mains NODE undervoltage|normal");
    const atv312d_control_node_t *node = find_drive(control, words[1], "mains", r);
    if (!node)
        return false;
    int index = find_fault(node, "USF", r);
    if (index < 0)
        return false;
    if (strcmp(words[2], "undervoltage") == 0)
        return inject(node, (uint8_t)index, r);
    if (drive_fault_cause_present(node->drive, (uint8_t)index))
        remove_cause(node, (uint8_t)index);
    return succeed(r, "node %u: mains normal", atv312d_node_id(node));
}

static bool command_stop_key(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 2)
        return fail(r, "usage: stop-key NODE");
    const atv312d_control_node_t *node = find_drive(control, words[1], "stop-key", r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    drive_stop_key(drive, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: STOP key", atv312d_node_id(node));
    if (fault && !drive_fault_latched(drive))
        return succeed(r, "node %u: STOP/RESET key: fault %s reset (status word bit 14)",
                       atv312d_node_id(node), fault->code);
    if (fault)
        return succeed(r, "node %u: STOP key: still in fault %s (status word bit 14)",
                       atv312d_node_id(node), drive_fault_latched(drive)->code);
    return succeed(r, "node %u: STOP key (%s stop, status word bit 14)", atv312d_node_id(node),
                   drive_local_control(drive) ? "ramp" : "freewheel");
}

static bool command_run_key(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 2)
        return fail(r, "usage: run-key NODE");
    const atv312d_control_node_t *node = find_drive(control, words[1], "run-key", r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    unsigned id = atv312d_node_id(node);
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
    const atv312d_control_node_t *node = find_drive(control, words[1], "local", r);
    if (!node)
        return false;
    drive_t *drive = node->drive;
    bool local = strcmp(words[2], "on") == 0;
    if (drive->local == local)
        return fail(r, "node %u is under %s control already", atv312d_node_id(node),
                    local ? "local" : "network");
    drive_set_local(drive, local, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: %s control", atv312d_node_id(node),
           local ? "local" : "network");
    return succeed(r, "node %u: %s control (status word bit 9 = %d)", atv312d_node_id(node),
                   local ? "local" : "network", local ? 0 : 1);
}

/* The torque limit of the motor model. */
#define LOAD_MAX_PERCENT 150

static bool command_load(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: load NODE PERCENT (0..%d %% of nominal torque)", LOAD_MAX_PERCENT);
    const atv312d_control_node_t *node = find_drive(control, words[1], "load", r);
    if (!node)
        return false;
    char *end;
    long percent = strtol(words[2], &end, 10);
    if (!(words[2][0] >= '0' && words[2][0] <= '9') || *end != '\0' || percent > LOAD_MAX_PERCENT)
        return fail(r, "load %s: give a percentage of nominal torque, 0..%d", shown(words[2]),
                    LOAD_MAX_PERCENT);
    drive_set_load(node->drive, (uint8_t)percent, node->device->loop->now);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: load %ld %%", atv312d_node_id(node), percent);
    return succeed(r, "node %u: load %ld %%", atv312d_node_id(node), percent);
}

/* A logic input's name, "LI3" in any case: its number, or 0. */
static unsigned input_number(const char *word)
{
    if ((word[0] != 'L' && word[0] != 'l') || (word[1] != 'I' && word[1] != 'i') || word[2] < '1' ||
        word[2] > '9' || word[3] != '\0')
        return 0;
    return (unsigned)(word[2] - '0');
}

/* A plain node's terminal: "DI3" in any case, its number 1..9, or 0. */
static unsigned terminal_number(const char *word, char first, char second)
{
    if (toupper((unsigned char)word[0]) != first || toupper((unsigned char)word[1]) != second ||
        word[2] < '1' || word[2] > '9' || word[3] != '\0')
        return 0;
    return (unsigned)(word[2] - '0');
}

/* `input NODE DIn on|off` on an I/O node: 6000h:01's bit n-1. */
static bool plain_input(const atv312d_control_node_t *node, char **words, reply_t *r)
{
    char what[64];
    node_phrase(node, what, sizeof what);
    if (node->plain->model != &io401_model)
        return fail(r, "node %u is %s: it has no inputs to set; its commands are %s",
                    atv312d_node_id(node), what, plain_commands(node));
    unsigned input = terminal_number(words[2], 'D', 'I');
    bool on = strcmp(words[3], "on") == 0;
    if (input == 0 || !io401_set_input(node->plain, (uint8_t)input, on))
        return fail(r, "node %u has no input %s: its inputs are DI1..DI%u", atv312d_node_id(node),
                    shown(words[2]), IO401_DIGITAL_INPUTS);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: DI%u %s", atv312d_node_id(node), input, words[3]);
    return succeed(r, "node %u: DI%u %s (6000h:01 = %02X)", atv312d_node_id(node), input, words[3],
                   io401_inputs(node->plain));
}

/* `analog NODE AIn VALUE` on an I/O node: 6401h:0n, a raw INTEGER16. */
static bool plain_analog(const atv312d_control_node_t *node, char **words, reply_t *r)
{
    char what[64];
    node_phrase(node, what, sizeof what);
    if (node->plain->model != &io401_model)
        return fail(r, "node %u is %s: it has no analogue inputs; its commands are %s",
                    atv312d_node_id(node), what, plain_commands(node));
    unsigned input = terminal_number(words[2], 'A', 'I');
    if (input == 0 || input > IO401_ANALOG_INPUTS)
        return fail(r, "node %u has no analogue input %s: its analogue inputs are AI1..AI%u",
                    atv312d_node_id(node), shown(words[2]), IO401_ANALOG_INPUTS);
    char *end;
    long value = strtol(words[3], &end, 10);
    if (end == words[3] || *end != '\0' || value < INT16_MIN || value > INT16_MAX)
        return fail(r, "analog AI%u %s: give the raw value of 6401h:%02u, -32768..32767", input,
                    shown(words[3]), input);
    io401_set_analog(node->plain, (uint8_t)input, (int16_t)value);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: AI%u %ld", atv312d_node_id(node), input, value);
    return succeed(r, "node %u: AI%u %ld (6401h:%02u)", atv312d_node_id(node), input, value, input);
}

static bool command_input(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 4 || (strcmp(words[3], "on") != 0 && strcmp(words[3], "off") != 0))
        return fail(r, "usage: input NODE LIn|DIn on|off (e.g. input 4 LI3 on)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    if (node->plain)
        return plain_input(node, words, r);
    drive_t *drive = node->drive;
    unsigned id = atv312d_node_id(node);
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
    atv312d_format_analog(in->kind, value, shown_value, sizeof shown_value);
    co_log(CO_LOG_INFO, "node %u: control: %s %s", atv312d_node_id(node), in->name, shown_value);
    return succeed(r, "node %u: %s %s", atv312d_node_id(node), in->name, shown_value);
}

static bool command_analog(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 4)
        return fail(r, "usage: analog NODE AIn VALUE (volts or mA as the input takes them, e.g. "
                       "analog 4 AI2 -2.5)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    if (node->plain)
        return plain_analog(node, words, r);
    const drive_t *drive = node->drive;
    if (drive->profile->analog_input_count == 0)
        return fail(r, "node %u has no analogue inputs", atv312d_node_id(node));
    int index = drive_analog_find(drive, words[2]);
    if (index < 0) {
        char names[128];
        list_analog_inputs(drive, names, sizeof names);
        return fail(r, "node %u has no analogue input %s: its analogue inputs are %s",
                    atv312d_node_id(node), shown(words[2]), names);
    }
    return set_analog(node, (uint8_t)index, words[3], "analog", r);
}

/* The reference potentiometer of the front panel (the ATV31's AIP). */
static bool command_pot(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3)
        return fail(r, "usage: pot NODE PERCENT (0..100, e.g. pot 5 50)");
    const atv312d_control_node_t *node = find_drive(control, words[1], "pot", r);
    if (!node)
        return false;
    const drive_profile_t *profile = node->drive->profile;
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        if (profile->analog_inputs[i].kind == DRIVE_ANALOG_POTENTIOMETER)
            return set_analog(node, i, words[2], "pot", r);
    }
    return fail(r, "node %u has no reference potentiometer", atv312d_node_id(node));
}

/* A marker's value as written: decimal, or hexadecimal with 0x; false when it does not fit. */
static bool parse_marker_value(const char *word, uint8_t size, uint32_t *value)
{
    char *end;
    bool hex = word[0] == '0' && (word[1] == 'x' || word[1] == 'X');
    if (!isdigit((unsigned char)word[0]) || (hex && !isxdigit((unsigned char)word[2])))
        return false;
    unsigned long long v = strtoull(word, &end, hex ? 16 : 10);
    if (*end != '\0' || (size < 4 && v >> (8 * size)) || v > UINT32_MAX)
        return false;
    *value = (uint32_t)v;
    return true;
}

/* `marker NODE MARKER [VALUE]` on a PLC300: the PLC program reads or writes a network marker
 * (docs/plc300.md): an output marker that TPDOs send, an input marker the master wrote. */
static bool command_marker(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n != 3 && n != 4)
        return fail(r, "usage: marker NODE MARKER [VALUE] (e.g. marker 1 %%QW2000 1234)");
    const atv312d_control_node_t *node = find_node(control, words[1], r);
    if (!node)
        return false;
    if (!node->plain || node->plain->model != &plc300_model) {
        char what[64];
        node_phrase(node, what, sizeof what);
        return fail(r, "node %u is %s: markers are a PLC300's", atv312d_node_id(node), what);
    }
    plc300_marker_t marker;
    if (!plc300_marker_parse(words[2], &marker))
        return fail(r,
                    "'%s' is no network marker: give %%IB, %%IW or %%ID (inputs), %%QB, %%QW or "
                    "%%QD (outputs) and its number, 2000..2511 (a word's even, a double word's "
                    "a multiple of 4)",
                    shown(words[2]));
    char name[16];
    plc300_marker_name(&marker, name, sizeof name);
    if (n == 3) {
        uint32_t value = plc300_marker_get(node->plain, &marker);
        return succeed(r, "node %u: %s = %lu (0x%0*lX, %04Xh)", atv312d_node_id(node), name,
                       (unsigned long)value, marker.size * 2, (unsigned long)value, marker.index);
    }
    uint32_t value;
    if (!parse_marker_value(words[3], marker.size, &value))
        return fail(r, "marker %s %s: give 0..%lu (or 0x in hexadecimal)", name, shown(words[3]),
                    marker.size == 4 ? 0xFFFFFFFFul : (1ul << (8 * marker.size)) - 1);
    uint32_t abort = plc300_marker_set(node->plain, &marker, value);
    if (abort != 0)
        return fail(r, "node %u: %s refused (abort code %08lX)", atv312d_node_id(node), name,
                    (unsigned long)abort);
    changed(node);
    co_log(CO_LOG_INFO, "node %u: control: %s = %lu", atv312d_node_id(node), name,
           (unsigned long)value);
    return succeed(r, "node %u: %s = %lu (%04Xh)", atv312d_node_id(node), name,
                   (unsigned long)value, marker.index);
}

/* `state [NODE]`: the view of each drive (view.h), after the CAN controller's in JSON. */
static bool command_state(const atv312d_control_t *control, char **words, size_t n, reply_t *r)
{
    if (n > 2)
        return fail(r, "usage: state [NODE]");
    const atv312d_control_node_t *only = NULL;
    if (n == 2 && !(only = find_node(control, words[1], r)))
        return false;
    if (!r->json) {
        atv312d_text_t text = {.buf = r->buf, .len = r->len};
        atv312d_text_put(&text, "ok ");
        for (size_t i = 0; i < control->count; i++) {
            if (only && only != &control->nodes[i])
                continue;
            atv312d_text_put(&text, "%s", only || i == 0 ? "" : "; ");
            atv312d_state_text(&text, &control->nodes[i]);
        }
        return true;
    }
    const co_linux_loop_t *loop = control->nodes[0].device->loop;
    cli_json_t json;
    cli_json_init(&json, r->buf, r->len);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", true);
    cli_json_begin_object(&json, "can");
    cli_json_str(&json, "state", atv312d_can_state(loop));
    cli_json_uint(&json, "bus_offs", loop->bus.conditions.bus_offs);
    cli_json_end_object(&json);
    cli_json_begin_array(&json, "nodes");
    for (size_t i = 0; i < control->count; i++) {
        if (!only || only == &control->nodes[i])
            atv312d_state_json(&json, &control->nodes[i]);
    }
    cli_json_end_array(&json);
    cli_json_end_object(&json);
    if (cli_json_finish(&json) == 0)
        return fail(r, "the state is longer than the reply's %zu bytes", r->len);
    return true;
}

static const struct {
    const char *name;
    bool (*run)(const atv312d_control_t *control, char **words, size_t n, reply_t *r);
} commands[] = {
    {"fault", command_fault},       {"clear", command_clear},     {"mains", command_mains},
    {"stop-key", command_stop_key}, {"run-key", command_run_key}, {"local", command_local},
    {"load", command_load},         {"input", command_input},     {"analog", command_analog},
    {"pot", command_pot},           {"marker", command_marker},   {"state", command_state},
};

#define COMMAND_NAMES                                                                              \
    "fault, clear, mains, stop-key, run-key, local, load, input, analog, pot, marker, state"

bool atv312d_control_execute(const atv312d_control_t *control, const char *line, char *reply,
                             size_t reply_len)
{
    reply_t r = {.buf = reply, .len = reply_len};
    if (strncmp(line, ATV312D_CONTROL_JSON_PREFIX, strlen(ATV312D_CONTROL_JSON_PREFIX)) == 0) {
        r.json = true;
        line += strlen(ATV312D_CONTROL_JSON_PREFIX);
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
