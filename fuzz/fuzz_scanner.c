/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the DeviceNet scanner (src/devicenet/scanner/scanner.c): a scanner of MAC
 * ID 0, online, talks to slaves 1, 2 and 63 as the input's commands ask, and the input's frames
 * and time steps (steps.h) are the bus, right or wrong: the slaves' answers, their I/O, other
 * nodes' duplicate MAC ID checks. The scanner is run the way dnscan's loop runs it: process after
 * every frame and command and at every deadline. After each call the harness holds it to what
 * include/dn/dn_scanner.h promises (docs/fuzzing.md). Commands, E0h..EFh (the low nibble), each
 * followed by 3 bytes: the slave (mod 3), then a and b:
 *
 *     0 allocate, choice a        1 release, choice a        2 Get class a, instance b, attr 1
 *     3 Set class 70h instance 1 attribute 1 with a mod 24 bytes (fragmented above 7)
 *     4 keep polling every a + 1 ms at rate b ms             5 poll every a ms (0 stops)
 *     6 one poll                  7 output data of a mod 10 bytes (9 is refused)
 *     8 abandon the request       9 start again: the duplicate MAC ID check
 *
 * fuzz/seeds.py writes the seeds from readable commands and candump frames. */
#include "dn/dn_scanner.h"
#include "rig.h"
#include "steps.h"

#include <string.h>

#define SLAVES 3
#define COMMAND_ARGS 3
#define US_PER_MS 1000u
#define SET_MAX 24u
#define OUTPUT_MAX 10u
/* As in rig.c: deadlines handled one by one within a time step, then the scanner wakes up late. */
#define DEADLINES_PER_STEP 64

static const uint8_t slave_macs[SLAVES] = {1, 2, 63};

/* What each slave looked like before a call, to tell what the call changed. */
typedef struct before {
    uint8_t allocated;
    uint32_t restored;
    uint32_t late;
} before_t;

static struct harness {
    dn_scanner_t scanner;
    dn_scanner_config_t config;
    dn_scanner_app_t app;
    dn_slave_t slaves[SLAVES];
    co_time_t now;
    co_time_t deadline;
    before_t before[SLAVES];
} h;

static dn_slave_t *slave_of(uint8_t mac_id)
{
    dn_slave_t *slave = dn_scanner_slave(&h.scanner, mac_id);
    rig_check(slave != NULL, "a callback for a MAC ID that is not configured");
    return slave;
}

/* Every frame the scanner sends: a CAN frame of 11 bits, and only the check while not online;
 * a poll command only on a polled connection that no try is re-establishing. */
static void on_send(void *user, const co_frame_t *frame)
{
    (void)user;
    rig_check(frame->len <= CO_FRAME_DLC_MAX && frame->id <= 0x7FFu && frame->flags == 0,
              "a frame that is not an 11-bit CAN frame");
    dn_can_id_t id = dn_can_id_decode(frame->id);
    bool check = id.group == 2 && id.message_id == DN_G2_DUPLICATE_MAC_CHECK;
    rig_check(check || h.scanner.link == DN_SCANNER_ONLINE, "a frame sent while not online");
    rig_check(h.scanner.link != DN_SCANNER_DUPLICATE, "a frame sent with the MAC ID in use");
    if (id.group == 2 && id.message_id == DN_G2_MASTER_POLL_COS_CYCLIC) {
        const dn_slave_t *slave = slave_of(id.mac_id);
        rig_check((slave->allocated & DN_ALLOC_POLLED) && slave->recovery == DN_RECOVERY_NONE,
                  "a poll command without an established polled connection");
    }
}

static void on_done(void *user, const dn_result_t *result)
{
    (void)user;
    const dn_slave_t *slave = slave_of(result->mac_id);
    rig_check(!slave->busy, "a result while the request is still in progress");
    rig_check(result->len == 0 || result->data != NULL, "result data without a pointer");
}

static void on_io(void *user, uint8_t mac_id, dn_io_kind_t kind, const uint8_t *data, uint8_t len)
{
    (void)user;
    slave_of(mac_id);
    rig_check(len <= CO_FRAME_DLC_MAX && (len == 0 || data != NULL), "I/O data out of bounds");
    rig_check(kind != DN_IO_POLL_MISSED || len == 0, "a missed poll with data");
}

static void on_connection(void *user, uint8_t mac_id, dn_connection_event_t event,
                          const dn_result_t *result)
{
    (void)user;
    const dn_slave_t *slave = slave_of(mac_id);
    rig_check(slave->keep_choice != 0, "a connection event of a connection not kept");
    rig_check((event == DN_CONNECTION_FAILED) == (result != NULL),
              "a failed round without its result, or a result without a failure");
}

static void remember(void)
{
    for (unsigned i = 0; i < SLAVES; i++) {
        const dn_slave_t *s = &h.slaves[i];
        h.before[i] = (before_t){s->allocated, s->restored, s->late};
    }
}

/* The slave's answer to a service: its explicit response identifier, not a fragment, with the
 * scanner's MAC ID in the header and the service with the response bit. */
static bool answer_to(const co_frame_t *frame, const dn_slave_t *slave, uint8_t service)
{
    return frame != NULL && frame->id == slave->ids.explicit_response && frame->len >= 2 &&
           !(frame->data[0] & DN_HDR_FRAG) && (frame->data[0] & DN_HDR_MAC) == h.config.mac_id &&
           frame->data[1] == (service | DN_SERVICE_RESPONSE);
}

/* After each call of the scanner (`frame`: the frame it was given, else NULL). */
static void check_slaves(const co_frame_t *frame)
{
    for (unsigned i = 0; i < SLAVES; i++) {
        const dn_slave_t *s = &h.slaves[i];
        const before_t *b = &h.before[i];
        uint32_t awaiting = s->poll_deadline != CO_TIME_NEVER;
        rig_check(s->polls == s->responses + s->missed + awaiting,
                  "polls sent differ from those answered, missed and awaiting");
        rig_check(!(s->allocated & ~b->allocated) || answer_to(frame, s, DN_SVC_ALLOCATE),
                  "a connection marked allocated without the slave's Allocate answer");
        rig_check(s->restored == b->restored || (s->restored == b->restored + 1 &&
                                                 answer_to(frame, s, DN_SVC_SET_ATTRIBUTE_SINGLE)),
                  "a connection re-established without the answer to its rate");
        rig_check(s->late == b->late ||
                      (s->late == b->late + 1 && frame != NULL &&
                       frame->id == (uint32_t)(DN_G1_SLAVE_POLL_RESPONSE << 6 | s->mac_id)),
                  "a late answer counted without a poll response");
        rig_check(s->recovery == DN_RECOVERY_NONE || s->keep_choice != 0,
                  "a connection re-established that is not kept");
        rig_check(!s->recovering_request || s->busy, "a try's request that is not in progress");
        rig_check(s->restored <= s->lost, "more connections re-established than lost");
    }
}

static void process(void)
{
    remember();
    h.deadline = dn_scanner_process(&h.scanner, h.now);
    rig_check(h.deadline > h.now, "a deadline not in the future");
    check_slaves(NULL);
}

static void deliver(const co_frame_t *frame)
{
    remember();
    dn_scanner_receive(&h.scanner, frame, h.now);
    check_slaves(frame);
    process();
}

static void advance(co_time_t us)
{
    co_time_t end = h.now + us;
    for (int i = 0; i < DEADLINES_PER_STEP && h.deadline <= end; i++) {
        h.now = h.deadline;
        process();
    }
    h.now = end;
    process();
}

static void command(uint8_t which, const uint8_t *args)
{
    uint8_t mac_id = slave_macs[args[0] % SLAVES];
    uint8_t a = args[1], b = args[2];
    remember();
    switch (which) {
    case 0:
        dn_scanner_allocate(&h.scanner, mac_id, a, h.now);
        break;
    case 1:
        dn_scanner_release(&h.scanner, mac_id, a, h.now);
        break;
    case 2:
        dn_scanner_get(&h.scanner, mac_id, a, b, 1, h.now);
        break;
    case 3: {
        uint8_t value[SET_MAX];
        for (unsigned i = 0; i < SET_MAX; i++)
            value[i] = (uint8_t)(i * 31u + 7u);
        dn_scanner_set(&h.scanner, mac_id, 0x70, 1, 1, value, (uint8_t)(a % SET_MAX), h.now);
        break;
    }
    case 4:
        dn_scanner_keep_polling(&h.scanner, mac_id, (co_time_t)(a + 1u) * US_PER_MS, b, h.now);
        break;
    case 5:
        dn_scanner_poll_every(&h.scanner, mac_id, (co_time_t)a * US_PER_MS, h.now);
        break;
    case 6:
        dn_scanner_poll(&h.scanner, mac_id, h.now);
        break;
    case 7: {
        uint8_t output[OUTPUT_MAX] = {0};
        bool taken = dn_scanner_set_output(&h.scanner, mac_id, output, (uint8_t)(a % OUTPUT_MAX));
        rig_check(taken == (a % OUTPUT_MAX <= DN_FRAME_BODY + 1u), "output data of 9 bytes taken");
        break;
    }
    case 8:
        dn_scanner_abandon(&h.scanner, mac_id);
        break;
    case 9:
        dn_scanner_start(&h.scanner, h.now);
        break;
    default:
        break;
    }
    check_slaves(NULL);
    process();
}

static void setup(void)
{
    memset(&h, 0, sizeof h);
    h.now = 1000000u;
    h.app = (dn_scanner_app_t){&h, on_send, on_done, on_io, on_connection};
    for (unsigned i = 0; i < SLAVES; i++)
        h.slaves[i].mac_id = slave_macs[i];
    h.config =
        (dn_scanner_config_t){DN_SCANNER_MAC_DEFAULT, 0, 0x43534E44u, 0, h.slaves, SLAVES, &h.app};
    rig_check(dn_scanner_init(&h.scanner, &h.config) == DN_SCANNER_INIT_OK, "init refused");
    dn_scanner_start_online(&h.scanner, h.now);
    process();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input_t input = {data, size};
    setup();
    fuzz_step_t step;
    while (fuzz_next_step(&input, true, &step)) {
        if (step.kind == FUZZ_STEP_TIME) {
            advance(step.us);
        } else if (step.kind == FUZZ_STEP_FRAME) {
            deliver(&step.frame);
        } else {
            const uint8_t *args = fuzz_take(&input, COMMAND_ARGS);
            if (args == NULL)
                break;
            command(step.command, args);
        }
    }
    /* Online, every request ends by its answer or its timeout: a minute later nothing is in
     * progress but a kept connection's try. (A scanner checking its MAC ID again holds its
     * requests, for good once the MAC ID is in use: dnscan then exits.) A second at a time, so
     * that a scanner waking late still runs each request's timeouts. */
    for (int second = 0; second < 60; second++)
        advance(1000000u);
    for (unsigned i = 0; i < SLAVES; i++)
        rig_check(h.scanner.link != DN_SCANNER_ONLINE || !h.slaves[i].busy ||
                      h.slaves[i].recovering_request,
                  "an application's request that never ends");
    return 0;
}
