/* SPDX-License-Identifier: Apache-2.0 */
/* comaster lss: the CiA 305 layer setting services from the core's LSS master (docs/lss.md):
 * switch the slaves' LSS state, give the one configuring a node-id or bit rate and store them,
 * read its identity, identify slaves, and find and number the non-configured ones by fastscan. */
#include "co/co_lss_master.h"
#include "comaster/comaster.h"
#include "comaster/value.h"

#include <stdio.h>
#include <string.h>

static const char lss_help[] =
    "usage: comaster lss SERVICE [ARGS...]\n"
    "\n"
    "CiA 305 layer setting services on 7E5h/7E4h. A slave in the LSS configuration\n"
    "state takes a node-id and a bit rate; switch one there by its address (switch\n"
    "VENDOR PRODUCT REVISION SERIAL) or by fastscan, or all with switch configuration.\n"
    "Each confirmed service waits up to --timeout for the answer.\n"
    "\n"
    "  switch waiting|configuration\n"
    "                 switch state global: every slave to that state\n"
    "  switch VENDOR PRODUCT REVISION SERIAL\n"
    "                 switch state selective: the slave of that address to configuration\n"
    "  set-node-id ID  configure node-id (1..127, or none): active after the slave's\n"
    "                 next NMT reset, or at once when it had none and is switched to\n"
    "                 waiting\n"
    "  set-bit-timing KBIT  configure bit timing: 1000, 800, 500, 250, 125, 50, 20,\n"
    "                 10 kbit/s or auto (CiA 305 table 0)\n"
    "  activate DELAY  activate bit timing: the slaves switch after DELAY ms and\n"
    "                 speak again DELAY ms later\n"
    "  store          store configuration: the slave keeps node-id and bit rate\n"
    "  inquire identity|node-id\n"
    "                 the configuring slave's address (1018h:01..04) or active node-id\n"
    "  identify VENDOR PRODUCT REV_LOW REV_HIGH SERIAL_LOW SERIAL_HIGH\n"
    "                 how many slaves have that vendor and product and a revision and\n"
    "                 serial in those ranges (bounds included)\n"
    "  identify non-configured\n"
    "                 how many slaves have no node-id\n"
    "  fastscan FIRST  find every slave without node-id, one by one, give them the\n"
    "                 node-ids FIRST, FIRST+1, ..., switch each to waiting and await its\n"
    "                 boot-up; prints each one's address and node-id\n"
    "  --vendor N, --product N, --revision N\n"
    "                 fastscan: the part of the address known, checked in one frame\n"
    "                 instead of 32\n"
    "  --store        fastscan: store each node-id given\n"
    "  --frame-ms MS  fastscan: how long the first frame waits for answers, and the\n"
    "                 most any other waits (default 20); those wait twice the slowest\n"
    "                 answer so far, at least 5 ms\n"
    "\n"
    "Numbers are decimal or 0x hex. Identify and fastscan end when their wait ends\n"
    "with no answer: exit status 2 when nothing answered at all.\n"
    "\n"
    "Example: comaster -i vcan0 lss fastscan 20 --vendor 0x5F\n";

#define FRAME_MS_DEFAULT 20u
/* The floor of a fastscan frame's wait after the reset (docs/decisions.md, D-LSS-FASTSCAN-WAIT). */
#define FRAME_MIN_US 5000u
#define FASTSCAN_TRIES 3 /* scans of one slave before giving up on it */
#define FASTSCAN_LOST (-1)

/* fastscan's own options, taken out of argv before the common parser sees it. */
typedef struct fastscan_options {
    co_lss_fastscan_known_t known;
    bool store;
    uint32_t frame_ms;
} fastscan_options_t;

typedef struct lss_job {
    comaster_bus_t *bus;
    const comaster_options_t *opts;
    fastscan_options_t fastscan;
    int open_status; /* the bus's opening: 0, or the exit status after its error */
    co_lss_master_t master;
    co_lss_master_result_t result;
    uint16_t boot_id; /* awaiting this boot-up (700h + node-id), 0 when not */
    co_time_t boot_deadline;
} lss_job_t;

/* The bus opens with the first frame, so that every argument is checked before, and an argument
 * error says so whether or not the interface exists. */
static void job_send(void *user, const co_frame_t *frame)
{
    lss_job_t *job = user;
    if (!job->bus->opened && job->open_status == 0)
        job->open_status = comaster_bus_open(job->bus, job->opts);
    if (job->open_status == 0)
        comaster_bus_send(job->bus, frame);
}

static void job_done(void *user, const co_lss_master_result_t *result)
{
    lss_job_t *job = user;
    job->result = *result;
    comaster_bus_finish(job->bus, CLI_EXIT_OK);
}

static void job_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    lss_job_t *job = ctx;
    if (job->boot_id != 0) {
        if (frame->id == job->boot_id && frame->len >= 1 && frame->data[0] == 0 &&
            !(frame->flags & CO_FRAME_RTR))
            comaster_bus_finish(job->bus, CLI_EXIT_OK);
        return;
    }
    co_lss_master_receive(&job->master, frame, now);
}

static co_time_t job_process(void *ctx, co_time_t now)
{
    lss_job_t *job = ctx;
    if (job->boot_id != 0) {
        if (now < job->boot_deadline)
            return job->boot_deadline;
        comaster_bus_finish(job->bus, CLI_EXIT_TIMEOUT);
        return CO_TIME_NEVER;
    }
    return co_lss_master_process(&job->master, now);
}

/* Sends what the unconfirmed request just queued. */
static int send_now(lss_job_t *job)
{
    return job->open_status != 0 ? job->open_status : comaster_bus_pause(job->bus, 0);
}

/* Runs the request just started (rc its start's result) to its end. */
static int run(lss_job_t *job, int rc)
{
    if (rc != 0)
        return EX_SOFTWARE;
    if (job->open_status != 0)
        return job->open_status;
    comaster_job_t j = {.receive = job_receive, .process = job_process, .ctx = job};
    return comaster_bus_run(job->bus, &j);
}

static co_time_t timeout_us(const comaster_options_t *opts)
{
    return (co_time_t)opts->timeout_ms * 1000u;
}

static bool parse_address(const comaster_options_t *opts, const char *const *text, size_t count,
                          uint32_t *values)
{
    for (size_t i = 0; i < count; i++) {
        if (!comaster_parse_number(text[i], UINT32_MAX, &values[i])) {
            comaster_fail(opts, EX_USAGE,
                          "lss: '%s' is not a 32-bit number: give decimal or 0x hex, "
                          "0..4294967295",
                          text[i]);
            return false;
        }
    }
    return true;
}

static int no_answer(const comaster_options_t *opts, const char *service)
{
    return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                         "lss %s: no answer within %u ms: is a slave in the LSS configuration "
                         "state on %s? (switch it there first; --timeout MS waits longer)",
                         service, opts->timeout_ms, opts->iface);
}

/* The slave's error code of a confirmation, as one line. */
static int slave_error(const comaster_options_t *opts, const char *service,
                       const co_lss_master_result_t *r, const char *meaning)
{
    if (r->error == CO_LSS_SPECIFIC_ERROR)
        return comaster_fail(opts, CLI_EXIT_REFUSED,
                             "lss %s: the slave refused with its own error 0x%02X", service,
                             r->specific);
    return comaster_fail(opts, CLI_EXIT_REFUSED, "lss %s: the slave refused: error %u (%s)",
                         service, r->error, meaning);
}

static void print_address(const comaster_options_t *opts, const co_lss_address_t *a, int node)
{
    if (opts->json) {
        printf("{\"vendor_id\": %u, \"product_code\": %u, \"revision\": %u, \"serial\": %u",
               a->part[0], a->part[1], a->part[2], a->part[3]);
        if (node > 0)
            printf(", \"node_id\": %d", node);
        printf("}\n");
        return;
    }
    printf("vendor-ID 0x%08X product code 0x%08X revision 0x%08X serial 0x%08X", a->part[0],
           a->part[1], a->part[2], a->part[3]);
    if (node > 0)
        printf(": node-id %d", node);
    printf("\n");
}

static int cmd_switch(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    if (a->count == 2) {
        const char *state = a->positional[1];
        co_lss_state_t s;
        if (strcmp(state, "waiting") == 0)
            s = CO_LSS_WAITING;
        else if (strcmp(state, "configuration") == 0)
            s = CO_LSS_CONFIGURATION;
        else
            return comaster_fail(opts, EX_USAGE,
                                 "lss switch: '%s' is not an LSS state: give waiting or "
                                 "configuration, or the four parts of an address",
                                 state);
        co_lss_master_switch_global(&job->master, s);
        return send_now(job);
    }
    if (a->count != 5)
        return comaster_fail(opts, EX_USAGE,
                             "lss switch: give waiting, configuration, or VENDOR PRODUCT "
                             "REVISION SERIAL (%d values given)",
                             a->count - 1);
    co_lss_address_t address;
    if (!parse_address(opts, &a->positional[1], 4, address.part))
        return EX_USAGE;
    int rc = run(job, co_lss_master_switch_selective(&job->master, &address, timeout_us(opts),
                                                     co_linux_now()));
    if (rc == 0 && job->result.status != CO_LSS_MASTER_OK)
        return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                             "lss switch: no slave of address 0x%08X 0x%08X 0x%08X 0x%08X "
                             "answered within %u ms: is it on %s and in the waiting state?",
                             address.part[0], address.part[1], address.part[2], address.part[3],
                             opts->timeout_ms, opts->iface);
    if (rc == 0)
        printf(opts->json ? "{\"selected\": true}\n" : "slave selected: configuration state\n");
    return rc;
}

static int cmd_set_node_id(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    const char *text = a->positional[1];
    uint32_t id;
    if (strcmp(text, "none") == 0)
        id = CO_LSS_NODE_ID_UNCONFIGURED;
    else if (!comaster_parse_number(text, CO_NODE_ID_MAX, &id) || id < 1)
        return comaster_fail(opts, EX_USAGE,
                             "lss set-node-id: '%s' is not a node-id: give 1..127, or none", text);
    int rc = run(job, co_lss_master_configure_node_id(&job->master, (uint8_t)id, timeout_us(opts),
                                                      co_linux_now()));
    if (rc != 0)
        return rc;
    if (job->result.status != CO_LSS_MASTER_OK)
        return no_answer(opts, "set-node-id");
    if (job->result.error != CO_LSS_OK)
        return slave_error(opts, "set-node-id", &job->result, "node-id out of range");
    printf(opts->json ? "{\"node_id\": \"pending\"}\n" : "node-id configured (pending)\n");
    return 0;
}

static int cmd_set_bit_timing(lss_job_t *job, const comaster_options_t *opts,
                              const comaster_args_t *a)
{
    const char *text = a->positional[1];
    uint32_t kbit = 0;
    uint8_t index;
    if (strcmp(text, "auto") == 0)
        index = CO_LSS_BIT_TIMING_AUTO;
    else if (comaster_parse_number(text, UINT16_MAX, &kbit))
        index = co_lss_bit_timing_index((uint16_t)kbit);
    else
        index = CO_LSS_BIT_TIMING_INDEX_MAX + 1;
    if (index > CO_LSS_BIT_TIMING_INDEX_MAX)
        return comaster_fail(opts, EX_USAGE,
                             "lss set-bit-timing: '%s' is not a bit rate of CiA 305 table 0: "
                             "give 1000, 800, 500, 250, 125, 50, 20, 10 (kbit/s) or auto",
                             text);
    int rc = run(job, co_lss_master_configure_bit_timing(&job->master, CO_LSS_BIT_TIMING_TABLE,
                                                         index, timeout_us(opts), co_linux_now()));
    if (rc != 0)
        return rc;
    if (job->result.status != CO_LSS_MASTER_OK)
        return no_answer(opts, "set-bit-timing");
    if (job->result.error != CO_LSS_OK)
        return slave_error(opts, "set-bit-timing", &job->result,
                           "bit timing not supported by the slave");
    printf(opts->json ? "{\"bit_timing\": \"pending\"}\n"
                      : "bit timing configured (pending: lss activate DELAY switches)\n");
    return 0;
}

static int cmd_activate(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    const char *text = a->positional[1];
    uint32_t ms;
    if (!comaster_parse_number(text, UINT16_MAX, &ms))
        return comaster_fail(opts, EX_USAGE,
                             "lss activate: '%s' is not a switch delay: give milliseconds "
                             "0..65535",
                             text);
    co_lss_master_activate_bit_timing(&job->master, (uint16_t)ms);
    return send_now(job);
}

static int cmd_store(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    (void)a; /* store takes no argument */
    int rc = run(job, co_lss_master_store(&job->master, timeout_us(opts), co_linux_now()));
    if (rc != 0)
        return rc;
    if (job->result.status != CO_LSS_MASTER_OK)
        return no_answer(opts, "store");
    if (job->result.error != CO_LSS_OK)
        return slave_error(opts, "store", &job->result,
                           job->result.error == CO_LSS_STORE_NOT_SUPPORTED ? "store not supported"
                           : job->result.error == CO_LSS_STORE_MEDIA_ERROR
                               ? "storage media access error"
                               : "reserved");
    printf(opts->json ? "{\"stored\": true}\n" : "configuration stored\n");
    return 0;
}

static int cmd_inquire(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    const char *what = a->positional[1];
    bool identity = strcmp(what, "identity") == 0;
    if (!identity && strcmp(what, "node-id") != 0)
        return comaster_fail(opts, EX_USAGE,
                             "lss inquire: '%s' is not something to inquire: give identity or "
                             "node-id",
                             what);
    if (!identity) {
        int rc = run(job, co_lss_master_inquire(&job->master, CO_LSS_CS_INQUIRE_NODE_ID,
                                                timeout_us(opts), co_linux_now()));
        if (rc == 0 && job->result.status != CO_LSS_MASTER_OK)
            return no_answer(opts, "inquire");
        if (rc == 0 && opts->json)
            printf("{\"node_id\": %u}\n", job->result.value);
        else if (rc == 0 && job->result.value == CO_LSS_NODE_ID_UNCONFIGURED)
            printf("node-id none (255)\n");
        else if (rc == 0)
            printf("node-id %u\n", job->result.value);
        return rc;
    }
    co_lss_address_t address;
    for (unsigned part = 0; part < CO_LSS_FASTSCAN_PARTS; part++) {
        int rc =
            run(job, co_lss_master_inquire(&job->master, (uint8_t)(CO_LSS_CS_INQUIRE_VENDOR + part),
                                           timeout_us(opts), co_linux_now()));
        if (rc != 0)
            return rc;
        if (job->result.status != CO_LSS_MASTER_OK)
            return no_answer(opts, "inquire");
        address.part[part] = job->result.value;
    }
    print_address(opts, &address, 0);
    return 0;
}

static int cmd_identify(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    int rc;
    if (a->count == 2 && strcmp(a->positional[1], "non-configured") == 0) {
        rc = run(job, co_lss_master_identify_non_configured(&job->master, timeout_us(opts),
                                                            co_linux_now()));
    } else if (a->count == 7) {
        uint32_t v[6];
        if (!parse_address(opts, &a->positional[1], 6, v))
            return EX_USAGE;
        co_lss_address_t low = {{v[0], v[1], v[2], v[4]}}, high = {{v[0], v[1], v[3], v[5]}};
        rc = run(job, co_lss_master_identify_remote(&job->master, &low, &high, timeout_us(opts),
                                                    co_linux_now()));
    } else {
        return comaster_fail(opts, EX_USAGE,
                             "lss identify: give non-configured, or VENDOR PRODUCT REV_LOW "
                             "REV_HIGH SERIAL_LOW SERIAL_HIGH (%d values given)",
                             a->count - 1);
    }
    if (rc != 0)
        return rc;
    if (job->result.answers == 0)
        return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                             "lss identify: no slave answered on %s within %u ms (--timeout MS "
                             "waits longer)",
                             opts->iface, opts->timeout_ms);
    if (opts->json)
        printf("{\"answers\": %u}\n", job->result.answers);
    else
        printf("%u slave%s answered\n", job->result.answers, job->result.answers == 1 ? "" : "s");
    return 0;
}

static int take_fastscan_options(comaster_options_t *opts, int *argc, char **argv,
                                 fastscan_options_t *fo)
{
    static const char *const part_option[CO_LSS_FASTSCAN_PARTS - 1] = {"--vendor", "--product",
                                                                       "--revision"};
    memset(fo, 0, sizeof *fo);
    fo->frame_ms = FRAME_MS_DEFAULT;
    int out = 0;
    for (int i = 0; i < *argc; i++) {
        const char *arg = argv[i];
        int part = -1;
        for (int p = 0; p < (int)CO_LSS_FASTSCAN_PARTS - 1; p++)
            if (strcmp(arg, part_option[p]) == 0)
                part = p;
        if (strcmp(arg, "--store") == 0) {
            fo->store = true;
            continue;
        }
        if (part < 0 && strcmp(arg, "--frame-ms") != 0) {
            argv[out++] = argv[i];
            continue;
        }
        if (i + 1 == *argc)
            return comaster_missing_value(opts, arg);
        uint32_t value;
        if (!comaster_parse_number(argv[++i], UINT32_MAX, &value))
            return comaster_fail(opts, EX_USAGE,
                                 "lss fastscan: %s '%s' is not a 32-bit number: give decimal "
                                 "or 0x hex",
                                 arg, argv[i]);
        if (part < 0) {
            if (value < 1 || value > 60000)
                return comaster_fail(opts, EX_USAGE,
                                     "lss fastscan: --frame-ms %u is out of range: give "
                                     "milliseconds 1..60000",
                                     value);
            fo->frame_ms = value;
        } else {
            fo->known.known |= (uint8_t)(1u << part);
            fo->known.address.part[part] = value;
        }
    }
    *argc = out;
    return -1;
}

/* One slave found (0, its address in job->result), none left (CLI_EXIT_TIMEOUT), or an error. In
 * the first scan the frames after the reset wait as long as the slaves' answers need, within
 * FRAME_MIN_US..frame_ms (docs/decisions.md, D-LSS-FASTSCAN-WAIT). A scan that lost the slave that
 * answered its first frame (an answer later than the frame's wait: a busy bus or node) is
 * repeated with every frame waiting frame_ms, then twice that (kept for the next slaves), all
 * slaves back in waiting first in case the lost one reached configuration; FASTSCAN_LOST after
 * FASTSCAN_TRIES scans. */
static int scan_one(lss_job_t *job, const co_lss_fastscan_known_t *known, uint32_t *frame_ms)
{
    for (int attempt = 0; attempt < FASTSCAN_TRIES; attempt++) {
        if (attempt > 1)
            *frame_ms *= 2;
        co_time_t wait_us = (co_time_t)*frame_ms * 1000u;
        co_time_t min_wait_us = attempt == 0 && wait_us > FRAME_MIN_US ? FRAME_MIN_US : wait_us;
        if (attempt > 0)
            co_lss_master_switch_global(&job->master, CO_LSS_WAITING);
        int rc = run(
            job, co_lss_master_fastscan(&job->master, known, wait_us, min_wait_us, co_linux_now()));
        if (rc != 0)
            return rc;
        if (job->result.status == CO_LSS_MASTER_OK)
            return 0;
        if (job->result.answers == 0)
            return CLI_EXIT_TIMEOUT;
    }
    return FASTSCAN_LOST;
}

static int cmd_fastscan(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a)
{
    const char *first_text = a->positional[1];
    const fastscan_options_t *fo = &job->fastscan;
    uint32_t first;
    if (!comaster_parse_number(first_text, CO_NODE_ID_MAX, &first) || first < 1)
        return comaster_fail(opts, EX_USAGE,
                             "lss fastscan: '%s' is not a node-id: give the first node-id to "
                             "assign, 1..127",
                             first_text);
    unsigned found = 0;
    uint32_t frame_ms = fo->frame_ms;
    co_lss_fastscan_known_t known = fo->known;
    for (uint32_t node = first;; node++) {
        int rc = scan_one(job, &known, &frame_ms);
        if (rc == CLI_EXIT_TIMEOUT)
            break;
        if (rc == FASTSCAN_LOST)
            return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                                 "lss fastscan: a slave without node-id answered, but %d scans "
                                 "lost it, the last waiting %u ms a frame: answers come late on "
                                 "%s (--frame-ms MS waits longer)",
                                 FASTSCAN_TRIES, frame_ms, opts->iface);
        if (rc != 0)
            return rc;
        co_lss_address_t address = job->result.address;
        /* The next slave is likely the same device: its vendor-ID, product code and revision
         * are tried in one frame each (the serial differs). */
        known.guessed = (uint8_t)(((1u << CO_LSS_SERIAL) - 1u) & ~known.known);
        for (unsigned part = 0; part < CO_LSS_SERIAL; part++)
            known.address.part[part] = address.part[part];
        if (node > CO_NODE_ID_MAX) {
            co_lss_master_switch_global(&job->master, CO_LSS_WAITING);
            send_now(job);
            return comaster_fail(opts, EX_USAGE,
                                 "lss fastscan: a slave is left (serial 0x%08X) and no node-id "
                                 "after 127: give a lower first node-id than %u",
                                 address.part[CO_LSS_SERIAL], first);
        }
        rc = run(job, co_lss_master_configure_node_id(&job->master, (uint8_t)node, timeout_us(opts),
                                                      co_linux_now()));
        if (rc == 0 && job->result.status != CO_LSS_MASTER_OK)
            return no_answer(opts, "fastscan (set-node-id)");
        if (rc == 0 && job->result.error != CO_LSS_OK)
            return slave_error(opts, "fastscan (set-node-id)", &job->result,
                               "node-id out of range");
        if (rc == 0 && fo->store) {
            rc = run(job, co_lss_master_store(&job->master, timeout_us(opts), co_linux_now()));
            if (rc == 0 && job->result.status != CO_LSS_MASTER_OK)
                return no_answer(opts, "fastscan (store)");
            if (rc == 0 && job->result.error != CO_LSS_OK)
                return slave_error(opts, "fastscan (store)", &job->result,
                                   "store not supported or failed");
        }
        if (rc != 0)
            return rc;
        co_lss_master_switch_global(&job->master, CO_LSS_WAITING);
        job->boot_id = (uint16_t)(CO_CAN_ID_ERROR_CONTROL + node);
        job->boot_deadline = co_linux_now() + timeout_us(opts);
        comaster_job_t j = {.receive = job_receive, .process = job_process, .ctx = job};
        rc = comaster_bus_run(job->bus, &j);
        job->boot_id = 0;
        if (rc == CLI_EXIT_TIMEOUT)
            return comaster_fail(opts, rc,
                                 "lss fastscan: node %u (serial 0x%08X) sent no boot-up within "
                                 "%u ms of its node-id (--timeout MS waits longer)",
                                 node, address.part[CO_LSS_SERIAL], opts->timeout_ms);
        if (rc != 0)
            return rc;
        print_address(opts, &address, (int)node);
        fflush(stdout);
        found++;
    }
    if (found == 0)
        return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                             "lss fastscan: no slave without node-id answered on %s within %u "
                             "ms (--frame-ms MS waits longer)",
                             opts->iface, fo->frame_ms);
    if (!opts->json)
        printf("%u slave%s configured\n", found, found == 1 ? "" : "s");
    return 0;
}

int comaster_lss_main(comaster_options_t *opts, int argc, char **argv)
{
    fastscan_options_t fo;
    int rc = take_fastscan_options(opts, &argc, argv, &fo);
    if (rc >= 0)
        return rc;
    comaster_args_t args;
    rc = comaster_parse_args(opts, &args, argc, argv, lss_help, "", 1, 7);
    if (rc >= 0)
        return rc;
    static const struct {
        const char *name;
        int args; /* positional arguments after the service, -1: any */
        int (*run)(lss_job_t *job, const comaster_options_t *opts, const comaster_args_t *a);
    } services[] = {{"switch", -1, cmd_switch},
                    {"set-node-id", 1, cmd_set_node_id},
                    {"set-bit-timing", 1, cmd_set_bit_timing},
                    {"activate", 1, cmd_activate},
                    {"store", 0, cmd_store},
                    {"inquire", 1, cmd_inquire},
                    {"identify", -1, cmd_identify},
                    {"fastscan", 1, cmd_fastscan}};
    const char *service = args.positional[0];
    size_t s = 0;
    while (s < sizeof services / sizeof services[0] && strcmp(services[s].name, service) != 0)
        s++;
    if (s == sizeof services / sizeof services[0])
        return comaster_fail(opts, EX_USAGE,
                             "lss: '%s' is not an LSS service: give switch, set-node-id, "
                             "set-bit-timing, activate, store, inquire, identify or fastscan",
                             service);
    if (services[s].args >= 0 && args.count - 1 != services[s].args)
        return comaster_fail(opts, EX_USAGE,
                             "lss %s: takes %d argument%s, %d given (see lss --help)", service,
                             services[s].args, services[s].args == 1 ? "" : "s", args.count - 1);
    static comaster_bus_t bus;
    static lss_job_t job;
    memset(&job, 0, sizeof job);
    memset(&bus, 0, sizeof bus);
    job.bus = &bus;
    job.opts = opts;
    job.fastscan = fo;
    co_lss_master_config_t config = {.send = job_send, .user = &job, .done = job_done};
    co_lss_master_init(&job.master, &config);
    rc = services[s].run(&job, opts, &args);
    comaster_bus_close(&bus);
    return rc;
}
