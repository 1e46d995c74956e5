/* SPDX-License-Identifier: Apache-2.0 */
/* dnscan's commands: each builds the slaves' sequences of steps, prints their results and
 * decides the exit status (docs/dnscan.md). */
#include "cli/co_cli.h"
#include "dnscan/run.h"
#include "trace/cip_assembly.h"
#include "trace/cip_text.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define IDENTITY_INSTANCE 1u
#define CHOICE_IO (DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED)
#define CHOICE_ALL (DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED | DN_ALLOC_COS | DN_ALLOC_CYCLIC)
/* The path segments of an assembly's data attribute: 8-bit and 16-bit instance. */
#define EPATH_INSTANCE_8 0x24u
#define EPATH_INSTANCE_16 0x25u

/* The argument parsers: true with the value, or false after the one-line usage error (the
 * command's exit status is then EX_USAGE). */
static bool parse_mac(const dnscan_options_t *opts, const char *text, uint8_t *mac_id)
{
    unsigned long n;
    if (!dnscan_parse_number(text, DN_MAC_ID_MAX, &n)) {
        dnscan_fail(opts, EX_USAGE, "'%s' is not a MAC ID: give a number 0..63", text);
        return false;
    }
    if (n == opts->mac_id) {
        dnscan_fail(opts, EX_USAGE,
                    "MAC ID %lu is the scanner's own: give the scanner another with --mac-id N", n);
        return false;
    }
    *mac_id = (uint8_t)n;
    return true;
}

/* poll's MAC IDs: one, a list and ranges (5,7,10-20), each once; false after the usage error. */
static bool parse_mac_list(const dnscan_options_t *opts, const char *text, bool chosen[64])
{
    memset(chosen, 0, 64 * sizeof chosen[0]);
    const char *item = text;
    for (;;) {
        size_t len = strcspn(item, ",");
        char part[16];
        unsigned long first, last;
        char *dash = NULL;
        bool ok = len > 0 && len < sizeof part;
        if (ok) {
            snprintf(part, sizeof part, "%.*s", (int)len, item);
            dash = strchr(part, '-');
            if (dash)
                *dash = '\0';
            ok = dnscan_parse_number(part, DN_MAC_ID_MAX, &first);
            last = first;
            if (ok && dash)
                ok = dnscan_parse_number(dash + 1, DN_MAC_ID_MAX, &last) && last >= first;
        }
        if (!ok) {
            dnscan_fail(opts, EX_USAGE,
                        "'%s' is not a MAC ID or a list of them: give 0..63, a range like 1-63 or "
                        "a list like 5,7",
                        text);
            return false;
        }
        for (unsigned long n = first; n <= last; n++) {
            if (n == opts->mac_id) {
                dnscan_fail(opts, EX_USAGE,
                            "MAC ID %lu is the scanner's own: give the scanner another with "
                            "--mac-id N",
                            n);
                return false;
            }
            chosen[n] = true;
        }
        if (item[len] == '\0')
            return true;
        item += len + 1;
    }
}

static bool parse_byte(const dnscan_options_t *opts, const char *what, const char *text,
                       unsigned long min, uint8_t *value)
{
    unsigned long n;
    if (!dnscan_parse_number(text, UINT8_MAX, &n) || n < min) {
        dnscan_fail(opts, EX_USAGE, "'%s' is not a%s %s: give %lu..255", text,
                    what[0] == 'a' || what[0] == 'i' ? "n" : "", what, min);
        return false;
    }
    *value = (uint8_t)n;
    return true;
}

/* Hexadecimal bytes, in one or several words ("B0 04", "B004"); false when not. */
static bool parse_hex(const char *const *words, int count, uint8_t *out, uint8_t cap, uint8_t *len)
{
    *len = 0;
    for (int w = 0; w < count; w++) {
        const char *p = words[w];
        while (*p) {
            if (*p == ' ') {
                p++;
                continue;
            }
            if (!isxdigit((unsigned char)p[0]) || !isxdigit((unsigned char)p[1]) || *len == cap)
                return false;
            char pair[3] = {p[0], p[1], 0};
            out[(*len)++] = (uint8_t)strtoul(pair, NULL, 16);
            p += 2;
        }
    }
    return *len > 0;
}

static void hex_text(const uint8_t *data, uint8_t len, char *out)
{
    out[0] = '\0';
    for (uint8_t i = 0; i < len; i++)
        sprintf(&out[2 * i], "%02X", data[i]);
}

/* The one-line error of a step's failure and its exit status. */
static int step_error(dnscan_run_t *run, const dnscan_sequence_t *seq, const char *what,
                      const dn_result_t *r)
{
    const dnscan_options_t *opts = run->opts;
    int status;
    switch (r->status) {
    case DN_RESULT_CIP_ERROR:
        status = dnscan_fail(
            opts, CLI_EXIT_REFUSED,
            "MAC ID %u, %s: CIP error 0x%02X (%s), additional code 0x%02X%s", seq->mac_id, what,
            r->general, cip_general_status_text(r->general), r->additional,
            r->general == DN_GS_OBJECT_STATE_CONFLICT && r->additional == DN_AC_ALLOCATION_CONFLICT
                ? ": another master owns the connections"
                : "");
        break;
    case DN_RESULT_TIMEOUT:
        status = dnscan_fail(opts, CLI_EXIT_TIMEOUT,
                             "MAC ID %u, %s: no answer within %u ms: is the slave on %s with "
                             "MAC ID %u? (--timeout MS waits longer)",
                             seq->mac_id, what, opts->timeout_ms, opts->iface, seq->mac_id);
        break;
    default:
        status = dnscan_fail(opts, CLI_EXIT_REFUSED, "MAC ID %u, %s: %s", seq->mac_id, what,
                             r->status == DN_RESULT_FRAGMENT_LOST ? "a response fragment was lost"
                             : r->status == DN_RESULT_FRAGMENT_ERROR ? "a fragment was refused"
                                                                     : "a malformed response");
        break;
    }
    run->status = status;
    return status;
}

/* An allocation of the explicit connection that another process of this scanner's MAC ID
 * already made (0x20/0x02 "already allocated") is used as it is and not released. */
static bool allocation_result(dnscan_run_t *run, dnscan_sequence_t *seq, const dn_result_t *r)
{
    if (r->status == DN_RESULT_OK) {
        seq->we_allocated = true;
        return true;
    }
    const dnscan_step_t *step = &seq->steps[seq->next];
    if (!step->ucmm && r->status == DN_RESULT_CIP_ERROR && r->general == DN_GS_INVALID_PARAMETER &&
        r->additional == DN_AC_INVALID_CHOICE && step->choice == DN_ALLOC_EXPLICIT) {
        seq->count--; /* the release at the end is not ours */
        return true;
    }
    step_error(run, seq, step->ucmm ? "open by UCMM" : "allocate", r);
    return false;
}

/* ---- get and set ------------------------------------------------------------------------- */

typedef struct attribute_command {
    uint8_t mac_id, class_id, instance, attribute;
} attribute_command_t;

/* MAC CLASS INST ATTR; -1 to go on, else the exit status. */
static int parse_attribute(const dnscan_options_t *opts, attribute_command_t *a)
{
    bool parsed = parse_mac(opts, opts->args[1], &a->mac_id) &&
                  parse_byte(opts, "class", opts->args[2], 1, &a->class_id) &&
                  parse_byte(opts, "instance", opts->args[3], 0, &a->instance) &&
                  parse_byte(opts, "attribute", opts->args[4], 1, &a->attribute);
    return parsed ? -1 : EX_USAGE;
}

static void print_value(const dnscan_options_t *opts, const dn_result_t *r)
{
    char hex[2 * DN_MESSAGE_MAX + 1];
    hex_text(r->data, r->len, hex);
    char value[64] = "";
    bool is_text = false;
    const char *t = opts->type;
    if (t && strcmp(t, "string") == 0 && r->len >= 1 && r->data[0] == r->len - 1) {
        snprintf(value, sizeof value, "%.*s", r->data[0], (const char *)&r->data[1]);
        is_text = true;
    } else if (t && r->len >= 1) {
        uint32_t u = r->data[0];
        if (r->len >= 2)
            u |= (uint32_t)r->data[1] << 8;
        if (r->len >= 4)
            u |= (uint32_t)r->data[2] << 16 | (uint32_t)r->data[3] << 24;
        if (strcmp(t, "u8") == 0)
            snprintf(value, sizeof value, "%u", u & 0xFFu);
        else if (strcmp(t, "i8") == 0)
            snprintf(value, sizeof value, "%d", (int8_t)u);
        else if (strcmp(t, "u16") == 0)
            snprintf(value, sizeof value, "%u", u & 0xFFFFu);
        else if (strcmp(t, "i16") == 0)
            snprintf(value, sizeof value, "%d", (int16_t)u);
        else if (strcmp(t, "u32") == 0)
            snprintf(value, sizeof value, "%u", u);
        else
            snprintf(value, sizeof value, "%d", (int32_t)u);
    }
    if (!opts->json) {
        printf("%s\n", value[0] ? value : hex);
        return;
    }
    printf("{\"data\": \"%s\"", hex);
    if (value[0]) {
        printf(", \"value\": ");
        if (is_text)
            cli_json_string(stdout, value);
        else
            fputs(value, stdout);
    }
    printf("}\n");
}

static bool attribute_result(dnscan_run_t *run, dnscan_sequence_t *seq, const dnscan_step_t *step,
                             const dn_result_t *r)
{
    if (step->kind == DNSCAN_ALLOCATE)
        return allocation_result(run, seq, r);
    if (step->kind != DNSCAN_REQUEST)
        return true; /* the release */
    if (r->status != DN_RESULT_OK) {
        char what[32];
        snprintf(what, sizeof what, "%s %u/%u/%u",
                 step->service == DN_SVC_GET_ATTRIBUTE_SINGLE ? "get" : "set", step->class_id,
                 step->instance, step->data[0]);
        step_error(run, seq, what, r);
    } else if (step->service == DN_SVC_GET_ATTRIBUTE_SINGLE) {
        print_value(run->opts, r);
    } else if (run->opts->json) {
        printf("{\"written\": %u}\n", (unsigned)(step->len - 1));
    }
    return true;
}

static int run_attribute(dnscan_options_t *opts, const attribute_command_t *a, uint8_t service,
                         const uint8_t *value, uint8_t len)
{
    static dnscan_run_t run;
    dnscan_run_init(&run, opts);
    run.on_result = attribute_result;
    dnscan_sequence_t *seq = dnscan_add_slave(&run, a->mac_id);
    dnscan_step_t *open = dnscan_add_step(seq, DNSCAN_ALLOCATE);
    open->choice = DN_ALLOC_EXPLICIT;
    open->ucmm = opts->ucmm;
    dnscan_step_t *step = dnscan_add_step(seq, DNSCAN_REQUEST);
    step->service = service;
    step->class_id = a->class_id;
    step->instance = a->instance;
    step->data[0] = a->attribute;
    if (len)
        memcpy(&step->data[1], value, len);
    step->len = (uint8_t)(1 + len);
    dnscan_step_t *close = dnscan_add_step(seq, DNSCAN_RELEASE);
    close->choice = DN_ALLOC_EXPLICIT;
    close->ucmm = opts->ucmm;
    return dnscan_run(&run);
}

int dnscan_get(dnscan_options_t *opts)
{
    static const char *const types[] = {"u8", "u16", "u32", "i8", "i16", "i32", "string"};
    bool known = opts->type == NULL;
    for (size_t i = 0; i < sizeof types / sizeof types[0] && !known; i++)
        known = strcmp(opts->type, types[i]) == 0;
    if (!known)
        return dnscan_fail(opts, EX_USAGE,
                           "--type: '%s' is not a type: give u8, u16, u32, i8, i16, i32 or string",
                           opts->type);
    attribute_command_t a;
    int rc = parse_attribute(opts, &a);
    return rc >= 0 ? rc : run_attribute(opts, &a, DN_SVC_GET_ATTRIBUTE_SINGLE, NULL, 0);
}

/* TYPE:NUMBER, little-endian. */
static bool parse_typed(const char *text, uint8_t *out, uint8_t *len)
{
    static const struct {
        const char *name;
        uint8_t size;
        long long min, max;
    } types[] = {{"u8", 1, 0, UINT8_MAX},          {"u16", 2, 0, UINT16_MAX},
                 {"u32", 4, 0, UINT32_MAX},        {"i8", 1, INT8_MIN, INT8_MAX},
                 {"i16", 2, INT16_MIN, INT16_MAX}, {"i32", 4, INT32_MIN, INT32_MAX}};
    const char *colon = strchr(text, ':');
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
        if (strncmp(text, types[i].name, (size_t)(colon - text)) != 0 ||
            strlen(types[i].name) != (size_t)(colon - text))
            continue;
        char *end;
        long long v = strtoll(colon + 1, &end, 0);
        if (end == colon + 1 || *end || v < types[i].min || v > types[i].max)
            return false;
        for (uint8_t b = 0; b < types[i].size; b++)
            out[b] = (uint8_t)((unsigned long long)v >> (8 * b));
        *len = types[i].size;
        return true;
    }
    return false;
}

int dnscan_set(dnscan_options_t *opts)
{
    attribute_command_t a;
    int rc = parse_attribute(opts, &a);
    if (rc >= 0)
        return rc;
    uint8_t value[DN_MESSAGE_MAX - 4];
    uint8_t len;
    const char *first = opts->args[5];
    bool ok = strchr(first, ':') && opts->arg_count == 6
                  ? parse_typed(first, value, &len)
                  : parse_hex(&opts->args[5], opts->arg_count - 5, value, sizeof value, &len);
    if (!ok)
        return dnscan_fail(opts, EX_DATAERR,
                           "'%s' is not a value: give hexadecimal bytes (B0 04) or TYPE:NUMBER "
                           "in the type's range (u16:1200)",
                           first);
    return run_attribute(opts, &a, DN_SVC_SET_ATTRIBUTE_SINGLE, value, len);
}

/* ---- allocate and release ------------------------------------------------------------------ */

static bool connection_result(dnscan_run_t *run, dnscan_sequence_t *seq, const dnscan_step_t *step,
                              const dn_result_t *r)
{
    bool allocate = step->kind == DNSCAN_ALLOCATE;
    if (r->status != DN_RESULT_OK) {
        step_error(run, seq, allocate ? "allocate" : "release", r);
        return false;
    }
    if (run->opts->json)
        printf("{\"mac_id\": %u, \"%s\": \"0x%02X\"}\n", seq->mac_id,
               allocate ? "allocated" : "released", step->choice);
    else
        printf("MAC ID %u: %s 0x%02X\n", seq->mac_id, allocate ? "allocated" : "released",
               step->choice);
    return true;
}

static int run_connections(dnscan_options_t *opts, dnscan_step_kind_t kind, uint8_t fallback)
{
    uint8_t mac_id, choice = fallback;
    if (!parse_mac(opts, opts->args[1], &mac_id) ||
        (opts->arg_count == 3 && !parse_byte(opts, "choice", opts->args[2], 1, &choice)))
        return EX_USAGE;
    static dnscan_run_t run;
    dnscan_run_init(&run, opts);
    run.on_result = connection_result;
    dnscan_add_step(dnscan_add_slave(&run, mac_id), kind)->choice = choice;
    return dnscan_run(&run);
}

int dnscan_allocate(dnscan_options_t *opts)
{
    return run_connections(opts, DNSCAN_ALLOCATE, CHOICE_IO);
}

int dnscan_release(dnscan_options_t *opts)
{
    return run_connections(opts, DNSCAN_RELEASE, CHOICE_ALL);
}

/* ---- scan --------------------------------------------------------------------------------- */

static const uint8_t identity_attributes[] = {1, 2, 3, 4, 6, 7};

static bool scan_result(dnscan_run_t *run, dnscan_sequence_t *seq, const dnscan_step_t *step,
                        const dn_result_t *r)
{
    (void)run;
    if (step->kind == DNSCAN_ALLOCATE) {
        if (r->status == DN_RESULT_OK) {
            seq->state = 1;
            return true;
        }
        if (r->status == DN_RESULT_CIP_ERROR)
            seq->state = 2; /* present, its connections another master's */
        return false;
    }
    if (step->kind != DNSCAN_REQUEST || r->status != DN_RESULT_OK)
        return true;
    const uint8_t *d = r->data;
    switch (step->data[0]) {
    case 1:
        seq->vendor = r->len >= 2 ? co_get_u16(d) : 0;
        break;
    case 2:
        seq->device_type = r->len >= 2 ? co_get_u16(d) : 0;
        break;
    case 3:
        seq->product_code = r->len >= 2 ? co_get_u16(d) : 0;
        break;
    case 4:
        if (r->len >= 2)
            memcpy(seq->revision, d, 2);
        break;
    case 6:
        if (r->len >= 4) {
            seq->serial_low = co_get_u16(d);
            seq->serial_high = co_get_u16(d + 2);
        }
        break;
    default:
        if (r->len >= 1 && d[0] <= r->len - 1)
            snprintf(seq->name, sizeof seq->name, "%.*s", d[0], (const char *)&d[1]);
        break;
    }
    return true;
}

static void print_slave(const dnscan_options_t *opts, const dnscan_sequence_t *s)
{
    uint32_t serial = (uint32_t)s->serial_high << 16 | s->serial_low;
    if (opts->json) {
        printf("{\"mac_id\": %u, ", s->mac_id);
        if (s->state == 2) {
            printf("\"owned_by_another_master\": true}\n");
            return;
        }
        printf("\"vendor\": %u, \"device_type\": %u, \"product_code\": %u, \"revision\": "
               "\"%u.%u\", \"serial\": \"0x%08X\", \"name\": ",
               s->vendor, s->device_type, s->product_code, s->revision[0], s->revision[1], serial);
        cli_json_string(stdout, s->name);
        printf("}\n");
    } else if (s->state == 2) {
        printf("%2u  connections allocated by another master\n", s->mac_id);
    } else {
        printf("%2u  vendor 0x%04X  type %u  product %u  revision %u.%u  serial 0x%08X  %s\n",
               s->mac_id, s->vendor, s->device_type, s->product_code, s->revision[0],
               s->revision[1], serial, s->name);
    }
}

int dnscan_scan(dnscan_options_t *opts)
{
    static dnscan_run_t run;
    dnscan_run_init(&run, opts);
    run.on_result = scan_result;
    for (uint8_t mac_id = 0; mac_id <= DN_MAC_ID_MAX; mac_id++) {
        if (mac_id == opts->mac_id)
            continue;
        dnscan_sequence_t *seq = dnscan_add_slave(&run, mac_id);
        dnscan_add_step(seq, DNSCAN_ALLOCATE)->choice = DN_ALLOC_EXPLICIT;
        for (size_t i = 0; i < sizeof identity_attributes; i++) {
            dnscan_step_t *step = dnscan_add_step(seq, DNSCAN_REQUEST);
            step->service = DN_SVC_GET_ATTRIBUTE_SINGLE;
            step->class_id = DN_CLASS_IDENTITY;
            step->instance = IDENTITY_INSTANCE;
            step->data[0] = identity_attributes[i];
            step->len = 1;
        }
        dnscan_add_step(seq, DNSCAN_RELEASE)->choice = DN_ALLOC_EXPLICIT;
    }
    int rc = dnscan_run(&run);
    if (rc != 0)
        return rc;
    int found = 0;
    for (uint8_t i = 0; i < run.config.slave_count; i++) {
        if (run.sequences[i].state) {
            print_slave(opts, &run.sequences[i]);
            found++;
        }
    }
    if (found == 0)
        return dnscan_fail(opts, CLI_EXIT_TIMEOUT, "no slave answered on %s", opts->iface);
    return 0;
}

/* ---- poll --------------------------------------------------------------------------------- */

typedef struct poll_command {
    const cip_assembly_t *out;
    const cip_assembly_t *in; /* --assembly's; else each slave's from its connection path */
    uint32_t count;           /* polls before the end; 0: until interrupted */
} poll_command_t;

static poll_command_t poll_state;

static void print_input(const dnscan_run_t *run, const dnscan_sequence_t *seq, const uint8_t *data,
                        uint8_t len)
{
    const cip_assembly_t *in = cip_assembly(seq->in_assembly);
    char hex[17];
    hex_text(data, len, hex);
    if (run->opts->json)
        printf("{\"mac_id\": %u, \"assembly\": %u, \"data\": \"%s\"", seq->mac_id,
               in ? in->instance : 0, hex);
    else
        printf("MAC ID %u", seq->mac_id);
    if (in && len == CIP_ASSEMBLY_SIZE) {
        printf(run->opts->json ? ", \"values\": {" : ":");
        for (uint8_t i = 0; i < in->field_count; i++) {
            const cip_field_t *f = &in->fields[i];
            if (run->opts->json)
                printf("%s\"%s\": %d", i ? ", " : "", f->name, (int)cip_field_get(f, data));
            else
                printf(" %s=%d", f->name, (int)cip_field_get(f, data));
        }
        printf(run->opts->json ? "}" : "");
    } else if (!run->opts->json) {
        printf(": %s", hex);
    }
    printf(run->opts->json ? "}\n" : "\n");
    fflush(stdout);
}

/* A line per answer; a late answer (its poll already reported missed) is only counted. */
static void poll_io(dnscan_run_t *run, dnscan_sequence_t *seq, dn_io_kind_t kind,
                    const uint8_t *data, uint8_t len)
{
    if (kind == DN_IO_POLL_MISSED) {
        run->status =
            dnscan_fail(run->opts, CLI_EXIT_TIMEOUT, "MAC ID %u: no answer to a poll within %u ms",
                        seq->mac_id, run->opts->timeout_ms);
        if (!run->every_us)
            dnscan_poll_done(run, seq, run->now);
        return;
    }
    if (kind != DN_IO_POLL_RESPONSE)
        return;
    print_input(run, seq, data, len);
    seq->polls++;
    if (poll_state.count && seq->polls >= poll_state.count)
        dnscan_poll_done(run, seq, run->now);
}

/* The assembly instance of a connection path (20 04 24 II 30 03 or 20 04 25 LL HH 30 03). */
static uint16_t path_instance(const uint8_t *p, uint8_t len)
{
    if (len >= 4 && p[0] == 0x20 && p[1] == DN_CLASS_ASSEMBLY && p[2] == EPATH_INSTANCE_8)
        return p[3];
    if (len >= 5 && p[0] == 0x20 && p[1] == DN_CLASS_ASSEMBLY && p[2] == EPATH_INSTANCE_16)
        return (uint16_t)(p[3] | p[4] << 8);
    return 0;
}

static bool poll_result(dnscan_run_t *run, dnscan_sequence_t *seq, const dnscan_step_t *step,
                        const dn_result_t *r)
{
    if (step->kind == DNSCAN_ALLOCATE) {
        if (r->status == DN_RESULT_OK)
            return true;
        step_error(run, seq, "allocate", r);
        return false;
    }
    if (step->kind != DNSCAN_REQUEST)
        return true;
    if (r->status != DN_RESULT_OK) {
        step_error(run, seq,
                   step->service == DN_SVC_SET_ATTRIBUTE_SINGLE ? "expected packet rate"
                                                                : "connection path",
                   r);
        dnscan_skip_to_release(run, seq);
        return true;
    }
    if (step->service == DN_SVC_GET_ATTRIBUTE_SINGLE) {
        uint16_t instance = path_instance(r->data, r->len);
        if (step->data[0] == DN_CONN_ATTR_PRODUCED_PATH)
            seq->in_assembly = instance;
        else
            poll_state.out = cip_assembly(instance);
    }
    return true;
}

/* A kept polled connection (--every): lost and re-established are warnings, a failed round of
 * tries an error (the exit status at the end); --json adds an object on stdout. */
static void poll_connection(dnscan_run_t *run, dnscan_sequence_t *seq, dn_connection_event_t event,
                            const dn_result_t *r)
{
    const dnscan_options_t *opts = run->opts;
    const dn_slave_t *slave = dn_scanner_slave(&run->scanner, seq->mac_id);
    if (event == DN_CONNECTION_FAILED) {
        char why[96];
        if (r->status == DN_RESULT_CIP_ERROR)
            snprintf(why, sizeof why, "CIP error 0x%02X (%s), additional code 0x%02X", r->general,
                     cip_general_status_text(r->general), r->additional);
        else
            snprintf(why, sizeof why, "%s",
                     r->status == DN_RESULT_TIMEOUT ? "no answer in time" : "a malformed answer");
        run->status = dnscan_fail(
            opts, r->status == DN_RESULT_CIP_ERROR ? CLI_EXIT_REFUSED : CLI_EXIT_TIMEOUT,
            "MAC ID %u: the polled connection is not re-established after %u tries %u s apart "
            "(%s: %s): trying again every %u s",
            seq->mac_id, DN_SCANNER_RECONNECT_TRIES, DN_SCANNER_RECONNECT_INTERVAL_US / 1000000u,
            r->service == DN_SVC_RELEASE    ? "release"
            : r->service == DN_SVC_ALLOCATE ? "allocate"
                                            : "expected packet rate",
            why, DN_SCANNER_RECONNECT_SLOW_US / 1000000u);
        return;
    }
    bool lost = event == DN_CONNECTION_LOST;
    if (lost)
        co_log(CO_LOG_WARN,
               "MAC ID %u: the polled connection is lost (%u polls in a row unanswered): "
               "re-establishing it",
               seq->mac_id, DN_SCANNER_LOST_AFTER_MISSED);
    else
        co_log(CO_LOG_WARN, "MAC ID %u: the polled connection is re-established (try %u)",
               seq->mac_id, slave->tries);
    if (opts->json) {
        printf("{\"mac_id\": %u, \"connection\": \"%s\"}\n", seq->mac_id,
               lost ? "lost" : "re-established");
        fflush(stdout);
    }
}

/* poll --every's last lines: each slave's polls, each answered or missed once or still awaiting
 * its answer (a slave that answered its Release but not the last poll before it), and the late
 * answers apart (D-DEVICENET-LATE-POLL). */
static void print_poll_summary(const dnscan_run_t *run)
{
    for (uint8_t i = 0; i < run->config.slave_count; i++) {
        const dn_slave_t *s = &run->slaves[i];
        unsigned awaiting = s->poll_deadline != CO_TIME_NEVER;
        if (run->opts->json)
            printf("{\"mac_id\": %u, \"polls\": %u, \"answered\": %u, \"missed\": %u, "
                   "\"awaiting\": %u, \"late\": %u, \"lost\": %u, \"reestablished\": %u}\n",
                   s->mac_id, s->polls, s->responses, s->missed, awaiting, s->late, s->lost,
                   s->restored);
        else
            printf("MAC ID %u: polls %u, answered %u, missed %u, awaiting %u, late %u, lost %u, "
                   "re-established %u\n",
                   s->mac_id, s->polls, s->responses, s->missed, awaiting, s->late, s->lost,
                   s->restored);
    }
}

/* OUT/IN of --assembly, and the output data of --output and --set. */
static int poll_output(dnscan_options_t *opts, dnscan_run_t *run)
{
    if (opts->assembly) {
        unsigned out = 0, in = 0;
        char extra;
        if (sscanf(opts->assembly, "%u/%u%c", &out, &in, &extra) != 2 ||
            !cip_assembly((uint16_t)out) || cip_assembly((uint16_t)out)->produced ||
            !cip_assembly((uint16_t)in) || !cip_assembly((uint16_t)in)->produced)
            return dnscan_fail(opts, EX_USAGE,
                               "--assembly: '%s' is not OUT/IN: give 20/70, 21/71 or 100/101 "
                               "(or a mix)",
                               opts->assembly);
        poll_state.out = cip_assembly((uint16_t)out);
        poll_state.in = cip_assembly((uint16_t)in);
    }
    run->output_len = CIP_ASSEMBLY_SIZE;
    if (opts->output &&
        !parse_hex(&opts->output, 1, run->output, sizeof run->output, &run->output_len))
        return dnscan_fail(opts, EX_DATAERR,
                           "--output: '%s' is not data: give hexadecimal bytes (61 00 B0 04)",
                           opts->output);
    if (opts->set_count && !poll_state.out)
        return dnscan_fail(opts, EX_USAGE,
                           "--set needs the output assembly: give --assembly OUT/IN (21/71)");
    for (int i = 0; i < opts->set_count; i++) {
        char name[40];
        long value;
        char *end;
        const char *eq = strchr(opts->sets[i], '=');
        const cip_field_t *f = NULL;
        if (eq && (size_t)(eq - opts->sets[i]) < sizeof name) {
            snprintf(name, sizeof name, "%.*s", (int)(eq - opts->sets[i]), opts->sets[i]);
            f = cip_field_by_name(poll_state.out, name);
        }
        if (!f)
            return dnscan_fail(opts, EX_USAGE,
                               "--set: '%s' is not NAME=VALUE with a field of assembly %u (see "
                               "docs/dnscan.md)",
                               opts->sets[i], poll_state.out->instance);
        value = strtol(eq + 1, &end, 0);
        if (end == eq + 1 || *end || !cip_field_set(f, value, run->output))
            return dnscan_fail(opts, EX_DATAERR, "--set: '%s' does not fit %s", eq + 1, f->name);
    }
    return -1;
}

/* A slave's poll: Allocate, the assemblies unless --assembly gave them, the expected packet
 * rate, the polls, Release. */
static void add_poll_sequence(const dnscan_options_t *opts, dnscan_run_t *run, uint8_t mac_id)
{
    dnscan_sequence_t *seq = dnscan_add_slave(run, mac_id);
    dnscan_add_step(seq, DNSCAN_ALLOCATE)->choice = CHOICE_IO;
    if (opts->assembly) {
        seq->in_assembly = poll_state.in->instance;
    } else {
        static const uint8_t paths[] = {DN_CONN_ATTR_CONSUMED_PATH, DN_CONN_ATTR_PRODUCED_PATH};
        for (size_t i = 0; i < sizeof paths; i++) {
            dnscan_step_t *step = dnscan_add_step(seq, DNSCAN_REQUEST);
            step->service = DN_SVC_GET_ATTRIBUTE_SINGLE;
            step->class_id = DN_CLASS_CONNECTION;
            step->instance = DN_CONN_POLL;
            step->data[0] = paths[i];
            step->len = 1;
        }
    }
    dnscan_step_t *epr = dnscan_add_step(seq, DNSCAN_REQUEST);
    epr->service = DN_SVC_SET_ATTRIBUTE_SINGLE;
    epr->class_id = DN_CLASS_CONNECTION;
    epr->instance = DN_CONN_POLL;
    epr->data[0] = DN_CONN_ATTR_EXPECTED_PACKET_RATE;
    co_put_u16(&epr->data[1], run->rate_ms);
    epr->len = 3;
    dnscan_add_step(seq, DNSCAN_POLL);
    dnscan_add_step(seq, DNSCAN_RELEASE)->choice = CHOICE_IO;
}

int dnscan_poll(dnscan_options_t *opts)
{
    bool chosen[DN_MAC_ID_MAX + 1];
    if (!parse_mac_list(opts, opts->args[1], chosen))
        return EX_USAGE;
    static dnscan_run_t run;
    dnscan_run_init(&run, opts);
    memset(&poll_state, 0, sizeof poll_state);
    int rc = poll_output(opts, &run);
    if (rc >= 0)
        return rc;
    run.on_result = poll_result;
    run.on_io = poll_io;
    run.on_connection = poll_connection;
    run.every_us = dnscan_ms(opts->every_ms);
    poll_state.count = opts->every_ms ? opts->count : 1;
    run.signal_is_the_end = poll_state.count == 0;
    /* The expected packet rate: the period, or the timeout for a single poll. */
    run.rate_ms = (uint16_t)(opts->every_ms                  ? opts->every_ms
                             : opts->timeout_ms > UINT16_MAX ? UINT16_MAX
                                                             : opts->timeout_ms);
    for (uint8_t mac_id = 0; mac_id <= DN_MAC_ID_MAX; mac_id++)
        if (chosen[mac_id])
            add_poll_sequence(opts, &run, mac_id);
    int status = dnscan_run(&run);
    if (opts->every_ms && run.started)
        print_poll_summary(&run);
    return status;
}

/* ---- monitor ------------------------------------------------------------------------------ */

static const char *frame_meaning(const dn_can_id_t *id, const co_frame_t *frame)
{
    if (id->group == 1) {
        switch (id->message_id) {
        case DN_G1_SLAVE_POLL_RESPONSE:
            return "poll response";
        case DN_G1_SLAVE_COS_CYCLIC:
            return "COS/cyclic data";
        default:
            return "group 1 message";
        }
    }
    if (id->group == 2) {
        switch (id->message_id) {
        case DN_G2_MASTER_COS_CYCLIC_ACK:
            return "COS/cyclic acknowledge";
        case DN_G2_SLAVE_EXPLICIT_RESPONSE:
            return "explicit response";
        case DN_G2_MASTER_EXPLICIT_REQUEST:
            return "explicit request";
        case DN_G2_MASTER_POLL_COS_CYCLIC:
            return "poll command";
        case DN_G2_UNCONNECTED_REQUEST:
            return "unconnected request";
        case DN_G2_DUPLICATE_MAC_CHECK:
            return frame->len && frame->data[0] & DN_DUP_MAC_RESPONSE
                       ? "duplicate MAC ID check response"
                       : "duplicate MAC ID check request";
        default:
            return "group 2 message";
        }
    }
    return id->group == 3 ? "group 3 message" : "group 4 message";
}

static uint32_t monitored;

static void monitor_frame(dnscan_run_t *run, const co_frame_t *frame)
{
    if (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF))
        return;
    dn_can_id_t id = dn_can_id_decode(frame->id);
    if (id.group == 0)
        return;
    char hex[17];
    hex_text(frame->data, frame->len, hex);
    const char *what = frame_meaning(&id, frame);
    if (run->opts->json) {
        printf("{\"id\": \"%03X\", \"group\": %u, \"message\": %u, \"mac_id\": %u, \"what\": "
               "\"%s\", \"data\": \"%s\"}\n",
               (unsigned)frame->id, id.group, id.message_id, id.mac_id, what, hex);
    } else {
        printf("%03X  MAC ID %2u  %-31s %s\n", (unsigned)frame->id, id.mac_id, what, hex);
    }
    fflush(stdout);
    if (run->opts->count && ++monitored >= run->opts->count)
        dnscan_finish(run, 0);
}

int dnscan_monitor(dnscan_options_t *opts)
{
    static dnscan_run_t run;
    dnscan_run_init(&run, opts);
    run.passive = true;
    run.signal_is_the_end = true;
    run.on_frame = monitor_frame;
    return dnscan_run(&run);
}
