/* SPDX-License-Identifier: Apache-2.0 */
/* The scanner (src/devicenet/scanner): its duplicate MAC ID check; wired to a slave of the
 * bench (MAC ID 63), allocation, Get and Set with fragmentation both ways, a UCMM connection
 * opened, used and closed (and its message IDs per slave; a Close refused or unanswered
 * forgets it), the expected packet
 * rate, polls once and at a period, COS data acknowledged; with scripted frames instead of the
 * slave, the error paths: a CIP error, another master owning the set, timeouts, a lost and a
 * repeated response fragment, a request fragment unacknowledged or refused, missed polls, and
 * 63 slaves polled every 25 ms; a kept polled connection lost and re-established (against the
 * slave, and scripted: the sequence, the bounded retry, a refusal), a late answer counted once,
 * and the Release of a program that stops during a try. Frames in candump text, time injected. */
#include "check_main.h"
#include "dn/dn_scanner.h"
#include "dn_bench.h"
#include "test_bus.h"

#include <stdio.h>
#include <string.h>

#define SLAVE 63u
#define FRAMES 512
#define RESULTS 16
#define IOS 16
#define EVENTS 8
#define MS 1000u
#define POLL_CONNECTION 1u /* the slave's conn[] of instance 2 (dn_node.h) */

typedef struct wire {
    dn_bench_t bench; /* the slave, first: its send callback finds the wire from it */
    bool connected;   /* the scanner's frames reach the slave; else they are only logged */
    dn_scanner_t scanner;
    dn_scanner_config_t config;
    dn_scanner_app_t app;
    dn_slave_t slaves[DN_MAC_ID_MAX + 1];
    co_time_t now;
    /* Every frame of both sides in order, and those not delivered yet. */
    co_frame_t log[FRAMES];
    co_time_t at[FRAMES];
    bool from_scanner[FRAMES];
    size_t logged;
    size_t delivered;
    size_t checked;
    dn_result_t results[RESULTS];
    uint8_t result_data[RESULTS][DN_MESSAGE_MAX];
    co_time_t result_at[RESULTS];
    size_t result_count;
    dn_io_kind_t io_kind[IOS];
    uint8_t io_data[IOS][8];
    uint8_t io_len[IOS];
    size_t io_count;
    dn_connection_event_t events[EVENTS];
    dn_result_t event_results[EVENTS]; /* status NONE-like (OK) when the event has none */
    co_time_t event_at[EVENTS];
    size_t event_count;
} wire_t;

static wire_t w;

static void record(wire_t *wire, const co_frame_t *frame, bool from_scanner)
{
    ck_assert_uint_lt(wire->logged, FRAMES);
    wire->log[wire->logged] = *frame;
    wire->at[wire->logged] = wire->now;
    wire->from_scanner[wire->logged++] = from_scanner;
}

static void slave_send(void *user, const co_frame_t *frame)
{
    record(user, frame, false); /* user is the bench, the wire's first member */
}

static void scanner_send(void *user, const co_frame_t *frame)
{
    record(user, frame, true);
}

static void scanner_done(void *user, const dn_result_t *result)
{
    wire_t *wire = user;
    ck_assert_uint_lt(wire->result_count, RESULTS);
    size_t i = wire->result_count++;
    wire->results[i] = *result;
    if (result->len)
        memcpy(wire->result_data[i], result->data, result->len);
    wire->results[i].data = wire->result_data[i];
    wire->result_at[i] = wire->now;
}

static void scanner_io(void *user, uint8_t mac_id, dn_io_kind_t kind, const uint8_t *data,
                       uint8_t len)
{
    wire_t *wire = user;
    (void)mac_id;
    if (wire->io_count == IOS)
        return; /* sixty_three_slaves counts them per slave */
    size_t i = wire->io_count++;
    wire->io_kind[i] = kind;
    wire->io_len[i] = len;
    if (len)
        memcpy(wire->io_data[i], data, len);
}

static void scanner_connection(void *user, uint8_t mac_id, dn_connection_event_t event,
                               const dn_result_t *r)
{
    wire_t *wire = user;
    (void)mac_id;
    ck_assert_uint_lt(wire->event_count, EVENTS);
    size_t i = wire->event_count++;
    wire->events[i] = event;
    wire->event_results[i] = r ? *r : (dn_result_t){0};
    wire->event_results[i].data = NULL;
    wire->event_at[i] = wire->now;
}

/* Hands every frame not yet delivered to the other side, then runs both. */
static void pump(wire_t *wire)
{
    while (wire->delivered < wire->logged) {
        size_t i = wire->delivered++;
        if (wire->from_scanner[i]) {
            if (wire->connected)
                dn_node_receive(&wire->bench.node, &wire->log[i], wire->now);
        } else {
            dn_scanner_receive(&wire->scanner, &wire->log[i], wire->now);
        }
        dn_node_process(&wire->bench.node, wire->now);
        dn_scanner_process(&wire->scanner, wire->now);
    }
}

static co_time_t next_deadline(wire_t *wire)
{
    co_time_t scanner = dn_scanner_process(&wire->scanner, wire->now);
    if (!wire->connected)
        return scanner;
    return co_time_min(scanner, dn_node_process(&wire->bench.node, wire->now));
}

static void advance(wire_t *wire, co_time_t us)
{
    co_time_t target = wire->now + us;
    for (;;) {
        pump(wire);
        co_time_t next = next_deadline(wire);
        if (wire->delivered < wire->logged)
            continue; /* what was due sent frames: deliver them first */
        if (next > target)
            break;
        if (next > wire->now)
            wire->now = next;
    }
    wire->now = target;
}

/* A frame of the slave's side, scripted. */
static void rx(wire_t *wire, const char *text)
{
    co_frame_t frame = test_frame(text);
    record(wire, &frame, false);
    pump(wire);
}

static co_time_t expect_at(wire_t *wire, const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    /* scripted frames are the test's own: skip them */
    while (wire->checked < wire->logged && !wire->from_scanner[wire->checked] && !wire->connected)
        wire->checked++;
    ck_assert_msg(wire->checked < wire->logged, "%s:%d: expected %s, bus is quiet", file, line,
                  want);
    test_format(&wire->log[wire->checked], got);
    ck_assert_msg(strcmp(want, got) == 0, "%s:%d: expected %s, got %s", file, line, want, got);
    return wire->at[wire->checked++];
}

static void expect_none_at(wire_t *wire, const char *file, int line)
{
    char got[32];
    while (wire->checked < wire->logged && !wire->from_scanner[wire->checked] && !wire->connected)
        wire->checked++;
    if (wire->checked < wire->logged)
        ck_abort_msg("%s:%d: expected silence, got %s", file, line,
                     test_format(&wire->log[wire->checked], got));
}

#define expect(text) expect_at(&w, (text), __FILE__, __LINE__)
#define expect_none() expect_none_at(&w, __FILE__, __LINE__)

static const dn_result_t *result(size_t i)
{
    ck_assert_uint_gt(w.result_count, i);
    return &w.results[i];
}

static void expect_result(size_t i, dn_result_status_t status, uint8_t general, uint8_t additional,
                          const char *hex)
{
    const dn_result_t *r = result(i);
    ck_assert_int_eq(r->status, status);
    ck_assert_uint_eq(r->mac_id, SLAVE);
    ck_assert_uint_eq(r->general, general);
    ck_assert_uint_eq(r->additional, additional);
    char text[2 * DN_MESSAGE_MAX + 1] = "";
    for (uint8_t k = 0; k < r->len; k++)
        snprintf(&text[2 * k], 3, "%02X", r->data[k]);
    ck_assert_str_eq(text, hex);
}

/* The scanner at MAC ID 0 with slaves `macs`, not started; the bench's slave 63 online. */
static void wire_setup(const uint8_t *macs, uint8_t count, bool connected)
{
    memset(&w, 0, sizeof(w));
    bench_online(&w.bench, SLAVE);
    w.bench.app.send = slave_send;
    w.now = w.bench.now;
    w.connected = connected;
    w.app = (dn_scanner_app_t){&w, scanner_send, scanner_done, scanner_io, scanner_connection};
    for (uint8_t i = 0; i < count; i++)
        w.slaves[i].mac_id = macs[i];
    w.config = (dn_scanner_config_t){
        DN_SCANNER_MAC_DEFAULT, 0x00F3, 0x00C0FFEE, 0, w.slaves, count, &w.app};
    ck_assert_int_eq(dn_scanner_init(&w.scanner, &w.config), DN_SCANNER_INIT_OK);
}

static void setup_wired(void)
{
    static const uint8_t macs[] = {SLAVE};
    wire_setup(macs, 1, true);
    dn_scanner_start_online(&w.scanner, w.now);
}

static void setup_scripted(void)
{
    static const uint8_t macs[] = {SLAVE};
    wire_setup(macs, 1, false);
    dn_scanner_start_online(&w.scanner, w.now);
}

static void allocate(uint8_t choice)
{
    ck_assert(dn_scanner_allocate(&w.scanner, SLAVE, choice, w.now));
    advance(&w, 0);
}

/* ---- the duplicate MAC ID check ------------------------------------------------------------ */

START_TEST(duplicate_mac_check_then_online)
{
    setup_scripted();
    dn_scanner_start(&w.scanner, w.now);
    co_time_t t0 = w.now;
    ck_assert(!dn_scanner_allocate(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT, w.now)); /* not yet */
    ck_assert_uint_eq(expect("407#00F300EEFFC000"), t0);
    advance(&w, DN_DUP_MAC_WAIT_US);
    ck_assert_uint_eq(expect("407#00F300EEFFC000"), t0 + DN_DUP_MAC_WAIT_US);
    advance(&w, DN_DUP_MAC_WAIT_US - 1);
    ck_assert_int_eq(w.scanner.link, DN_SCANNER_CHECKING);
    advance(&w, 1);
    ck_assert_int_eq(w.scanner.link, DN_SCANNER_ONLINE);
    expect_none();
    /* another node's check of MAC ID 0 is answered; a response is not */
    rx(&w, "407#000100FFFFFFFF");
    expect("407#80F300EEFFC000");
    rx(&w, "407#800100FFFFFFFF");
    expect_none();
}
END_TEST

START_TEST(duplicate_mac_answered_stays_off)
{
    setup_scripted();
    dn_scanner_start(&w.scanner, w.now);
    expect("407#00F300EEFFC000");
    rx(&w, "407#800100FFFFFFFF"); /* a node online with MAC ID 0 */
    ck_assert_int_eq(w.scanner.link, DN_SCANNER_DUPLICATE);
    advance(&w, 3 * DN_DUP_MAC_WAIT_US);
    expect_none();
    ck_assert(!dn_scanner_allocate(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT, w.now));
    expect_none();
}
END_TEST

START_TEST(init_refusals)
{
    setup_scripted();
    dn_scanner_t s;
    dn_scanner_config_t c = w.config;
    c.mac_id = 64;
    ck_assert_int_eq(dn_scanner_init(&s, &c), DN_SCANNER_INIT_BAD_MAC_ID);
    c = w.config;
    w.slaves[1].mac_id = SLAVE;
    c.slave_count = 2;
    ck_assert_int_eq(dn_scanner_init(&s, &c), DN_SCANNER_INIT_BAD_MAC_ID);
    c = w.config;
    dn_scanner_app_t app = w.app;
    app.done = NULL;
    c.app = &app;
    ck_assert_int_eq(dn_scanner_init(&s, &c), DN_SCANNER_INIT_BAD_CONFIG);
    ck_assert_ptr_null(dn_scanner_slave(&w.scanner, 25));
}
END_TEST

/* ---- against the slave ------------------------------------------------------------------- */

/* The UCMM: Open on group 3 message 6 (header: the slave's MAC ID), its response on message 5,
 * a Get over the connection (the scanner's message 0, the slave's 0) with no Allocate, a Get
 * whose response comes in fragments over it, then Close; afterwards the predefined set's IDs. */
START_TEST(ucmm_open_get_close)
{
    setup_wired();
    ck_assert(dn_scanner_ucmm_open(&w.scanner, SLAVE, w.now));
    advance(&w, 0);
    expect("780#3F4B0030");
    expect("77F#00CB00000A00");
    expect_result(0, DN_RESULT_OK, 0, 0, "00000A00");
    ck_assert_uint_eq(w.slaves[0].ucmm_instance, 10);
    ck_assert_uint_eq(w.slaves[0].allocated, 0);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    advance(&w, 0);
    expect("600#7F0E010101");
    expect("63F#408EF300");
    expect_result(1, DN_RESULT_OK, 0, 0, "F300");
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 7, w.now)); /* name */
    advance(&w, 0);
    expect("600#3F0E010107");
    expect("63F#80008E0641545633");
    expect("600#BFC000"); /* acknowledged over the connection, the header naming the slave */
    expect("63F#80813132");
    expect("600#BFC100");
    expect_result(2, DN_RESULT_OK, 0, 0, "06415456333132");
    ck_assert(dn_scanner_ucmm_close(&w.scanner, SLAVE, w.now));
    advance(&w, 0);
    expect("780#7F4C0A00");
    expect("77F#40CC");
    expect_result(3, DN_RESULT_OK, 0, 0, "");
    ck_assert_uint_eq(w.slaves[0].ucmm_instance, 0);
    ck_assert(!dn_scanner_ucmm_close(&w.scanner, SLAVE, w.now));
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    advance(&w, 0);
    expect("5FC#000E010101");
}
END_TEST

/* A second slave's connection takes the scanner's next message ID; a response that is not the
 * connection asked for (another message ID) is a bad response and opens nothing; an answer on
 * another CAN-ID than the connection's is not taken. */
START_TEST(ucmm_message_ids_and_bad_response)
{
    static const uint8_t macs[] = {SLAVE, 5};
    wire_setup(macs, 2, false);
    dn_scanner_start_online(&w.scanner, w.now);
    ck_assert(dn_scanner_ucmm_open(&w.scanner, SLAVE, w.now));
    expect("780#3F4B0030");
    rx(&w, "77F#00CB00020B00");
    expect_result(0, DN_RESULT_OK, 0, 0, "00020B00");
    ck_assert(dn_scanner_ucmm_open(&w.scanner, 5, w.now));
    expect("780#054B0031");
    rx(&w, "745#00CB00000A00"); /* names message 0, the other slave's */
    ck_assert_int_eq(result(1)->status, DN_RESULT_BAD_RESPONSE);
    ck_assert_uint_eq(w.slaves[1].ucmm_instance, 0);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    expect("600#7F0E010101");
    rx(&w, "5FB#408EF300"); /* the predefined set's ID: not this request's */
    ck_assert_uint_eq(w.result_count, 2);
    rx(&w, "6BF#408EF300"); /* the slave's message 2 */
    expect_result(2, DN_RESULT_OK, 0, 0, "F300");
}
END_TEST

/* A connection the slave's watchdog deleted: its Close is answered "object does not exist"
 * (0x16), and the scanner forgets it all the same, so the next request goes on the predefined
 * set rather than on a group 3 ID no one listens to. */
START_TEST(ucmm_close_of_a_deleted_connection_forgets_it)
{
    setup_wired();
    ck_assert(dn_scanner_ucmm_open(&w.scanner, SLAVE, w.now));
    advance(&w, 0);
    expect("780#3F4B0030");
    expect("77F#00CB00000A00");
    advance(&w, 10100 * MS); /* past 4 x 2504 ms */
    ck_assert(dn_scanner_ucmm_close(&w.scanner, SLAVE, w.now));
    advance(&w, 0);
    expect("780#7F4C0A00");
    expect("77F#409416FF");
    expect_result(1, DN_RESULT_CIP_ERROR, 0x16, 0xFF, "");
    ck_assert_uint_eq(w.slaves[0].ucmm_instance, 0);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    advance(&w, 0);
    expect("5FC#000E010101");
}
END_TEST

/* A Close unanswered: the connection is forgotten too (the slave's watchdog ends it). */
START_TEST(ucmm_close_timed_out_forgets_it)
{
    setup_scripted();
    ck_assert(dn_scanner_ucmm_open(&w.scanner, SLAVE, w.now));
    expect("780#3F4B0030");
    rx(&w, "77F#00CB00000A00");
    ck_assert(dn_scanner_ucmm_close(&w.scanner, SLAVE, w.now));
    expect("780#7F4C0A00");
    advance(&w, 1000 * MS);
    ck_assert_int_eq(result(1)->status, DN_RESULT_TIMEOUT);
    ck_assert_uint_eq(w.slaves[0].ucmm_instance, 0);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    expect("5FC#000E010101");
}
END_TEST

/* Two Opens in flight at once, to two slaves: each its own message ID of the scanner's. */
START_TEST(ucmm_opens_in_flight_take_distinct_message_ids)
{
    static const uint8_t macs[] = {SLAVE, 5};
    wire_setup(macs, 2, false);
    dn_scanner_start_online(&w.scanner, w.now);
    ck_assert(dn_scanner_ucmm_open(&w.scanner, SLAVE, w.now));
    expect("780#3F4B0030");
    ck_assert(dn_scanner_ucmm_open(&w.scanner, 5, w.now));
    expect("780#054B0031");
    rx(&w, "77F#00CB00000A00");
    rx(&w, "745#00CB00100A00");
    expect_result(0, DN_RESULT_OK, 0, 0, "00000A00");
    ck_assert_int_eq(result(1)->status, DN_RESULT_OK);
    ck_assert_uint_eq(w.slaves[0].ucmm_instance, 10);
    ck_assert_uint_eq(w.slaves[1].ucmm_instance, 10);
    ck_assert_uint_eq(w.slaves[0].ucmm_message, 0);
    ck_assert_uint_eq(w.slaves[1].ucmm_message, 1);
}
END_TEST

START_TEST(allocate_get_release)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT);
    expect("5FE#004B03010100");
    expect("5FB#00CB00");
    expect_result(0, DN_RESULT_OK, 0, 0, "00");
    ck_assert_uint_eq(w.slaves[0].allocated, DN_ALLOC_EXPLICIT);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 1, w.now));
    ck_assert(!dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 2, w.now)); /* busy */
    advance(&w, 0);
    expect("5FC#400E010101");
    expect("5FB#408EF300");
    expect_result(1, DN_RESULT_OK, 0, 0, "F300");
    ck_assert_uint_eq(result(1)->service, DN_SVC_GET_ATTRIBUTE_SINGLE);
    ck_assert(dn_scanner_release(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT, w.now));
    advance(&w, 0);
    expect("5FE#004C030101");
    expect("5FB#00CC");
    expect_result(2, DN_RESULT_OK, 0, 0, "");
    ck_assert_uint_eq(w.slaves[0].allocated, 0);
    expect_none();
}
END_TEST

/* The product name "ATV312" is 8 bytes with the service: two fragments, each acknowledged. */
START_TEST(response_in_fragments)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 7, w.now));
    advance(&w, 0);
    expect("5FE#004B03010100");
    expect("5FB#00CB00");
    expect("5FC#400E010107");
    expect("5FB#C0008E0641545633");
    expect("5FC#C0C000");
    expect("5FB#C0813132");
    expect("5FC#C0C100");
    expect_none();
    expect_result(1, DN_RESULT_OK, 0, 0, "06415456333132");
}
END_TEST

/* Set of class 0x70 attribute 1 with 10 bytes: 14 bytes in three fragments, each waiting for
 * the slave's acknowledgement; the slave refuses the length (0x15). */
START_TEST(request_in_fragments)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT);
    static const uint8_t value[10] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    ck_assert(dn_scanner_set(&w.scanner, SLAVE, 0x70, 1, 1, value, sizeof(value), w.now));
    advance(&w, 0);
    expect("5FE#004B03010100");
    expect("5FB#00CB00");
    expect("5FC#C000107001010102");
    expect("5FB#C0C000");
    expect("5FC#C041030405060708");
    expect("5FB#C0C100");
    expect("5FC#C082090A");
    expect("5FB#C0C200");
    expect("5FB#409415FF");
    expect_none();
    expect_result(1, DN_RESULT_CIP_ERROR, DN_GS_TOO_MUCH_DATA, DN_AC_NONE, "");
}
END_TEST

START_TEST(cip_error_and_another_master)
{
    setup_wired();
    /* another master (MAC ID 2) owns the set: the scanner's Allocate is refused */
    dn_node_receive(&w.bench.node,
                    &(co_frame_t){.id = 0x5FE, .len = 6, .data = {2, 0x4B, 3, 1, 1, 2}}, w.now);
    allocate(DN_ALLOC_EXPLICIT);
    expect("5FB#02CB00"); /* the other master's answer: ignored */
    expect("5FE#004B03010100");
    expect("5FB#00940C01");
    expect_result(0, DN_RESULT_CIP_ERROR, DN_GS_OBJECT_STATE_CONFLICT, DN_AC_ALLOCATION_CONFLICT,
                  "");
    ck_assert_uint_eq(w.slaves[0].allocated, 0);
    /* released by its master, the set is the scanner's; an attribute that does not exist */
    dn_node_receive(&w.bench.node, &(co_frame_t){.id = 0x5FE, .len = 5, .data = {2, 0x4C, 3, 1, 1}},
                    w.now);
    allocate(DN_ALLOC_EXPLICIT);
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 99, w.now));
    advance(&w, 0);
    expect("5FB#02CC");
    expect("5FE#404B03010100");
    expect("5FB#40CB00");
    expect("5FC#000E010163");
    expect("5FB#009414FF");
    expect_result(2, DN_RESULT_CIP_ERROR, DN_GS_ATTRIBUTE_NOT_SUPPORTED, DN_AC_NONE, "");
}
END_TEST

/* Allocate explicit and polled, the expected packet rate (100 ms, 104 in use), then polls once
 * and every 25 ms with assembly 21's data; the answers carry assembly 71. */
START_TEST(poll_once_and_periodically)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED);
    ck_assert(dn_scanner_set_expected_packet_rate(&w.scanner, SLAVE, DN_CONN_POLL, 100, w.now));
    advance(&w, 0);
    expect("5FE#004B03010300");
    expect("5FB#00CB00");
    expect("5FC#4010050209 6400");
    expect("5FB#40906800");
    expect_result(1, DN_RESULT_OK, 0, 0, "6800");
    memcpy(bench_assembly(&w.bench, 71), (uint8_t[]){0x27, 0x04, 0xB0, 0x04}, 4);
    static const uint8_t run[4] = {0x61, 0x00, 0xB0, 0x04};
    ck_assert(dn_scanner_set_output(&w.scanner, SLAVE, run, sizeof(run)));
    ck_assert(dn_scanner_poll(&w.scanner, SLAVE, w.now));
    advance(&w, 0);
    expect("5FD#6100B004");
    expect("3FF#2704B004");
    ck_assert_uint_eq(w.io_count, 1);
    ck_assert_int_eq(w.io_kind[0], DN_IO_POLL_RESPONSE);
    ck_assert_uint_eq(w.io_len[0], 4);
    ck_assert_mem_eq(bench_assembly(&w.bench, 21), run, 4);
    co_time_t t0 = w.now;
    ck_assert(dn_scanner_poll_every(&w.scanner, SLAVE, 25 * MS, w.now));
    advance(&w, 50 * MS);
    ck_assert_uint_eq(expect("5FD#6100B004"), t0);
    expect("3FF#2704B004");
    ck_assert_uint_eq(expect("5FD#6100B004"), t0 + 25 * MS);
    expect("3FF#2704B004");
    ck_assert_uint_eq(expect("5FD#6100B004"), t0 + 50 * MS);
    expect("3FF#2704B004");
    expect_none();
    ck_assert_uint_eq(w.slaves[0].polls, 4);
    ck_assert_uint_eq(w.slaves[0].responses, 4);
    ck_assert_uint_eq(w.slaves[0].missed, 0);
    ck_assert(dn_scanner_poll_every(&w.scanner, SLAVE, 0, w.now));
    advance(&w, 50 * MS);
    expect_none();
}
END_TEST

/* COS with acknowledgement: the slave produces at Established and the scanner acknowledges it
 * with an empty frame on group 2 message 2. */
START_TEST(cos_data_acknowledged)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT | DN_ALLOC_COS);
    memcpy(bench_assembly(&w.bench, 71), (uint8_t[]){0x40, 0x03, 0x00, 0x00}, 4);
    ck_assert(
        dn_scanner_set_expected_packet_rate(&w.scanner, SLAVE, DN_CONN_COS_CYCLIC, 1000, w.now));
    advance(&w, 0);
    expect("5FE#004B03011100");
    expect("5FB#00CB00");
    expect("5FC#4010050409E803");
    expect("5FB#4090E803");
    expect("37F#40030000");
    expect("5FA#");
    expect_none();
    ck_assert_uint_eq(w.io_count, 1);
    ck_assert_int_eq(w.io_kind[0], DN_IO_COS_DATA);
    ck_assert_int_eq(w.bench.node.awaiting_ack, false);
}
END_TEST

/* ---- scripted error paths ----------------------------------------------------------------- */

START_TEST(no_answer_is_a_timeout)
{
    setup_scripted();
    co_time_t t0 = w.now;
    allocate(DN_ALLOC_EXPLICIT);
    expect("5FE#004B03010100");
    advance(&w, DN_SCANNER_TIMEOUT_DEFAULT_US - 1);
    ck_assert_uint_eq(w.result_count, 0);
    advance(&w, 1);
    expect_result(0, DN_RESULT_TIMEOUT, 0, DN_AC_NONE, "");
    ck_assert_uint_eq(w.result_at[0], t0 + DN_SCANNER_TIMEOUT_DEFAULT_US);
    /* a late answer is not taken for the next request (its XID differs) */
    ck_assert(dn_scanner_allocate(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT, w.now));
    rx(&w, "5FB#00CB00");
    ck_assert_uint_eq(w.result_count, 1);
    rx(&w, "5FB#40CB00");
    expect_result(1, DN_RESULT_OK, 0, 0, "00");
    expect("5FE#404B03010100");
    expect_none();
}
END_TEST

START_TEST(lost_response_fragment)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT;
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 7, w.now));
    advance(&w, 0);
    expect("5FC#000E010107");
    rx(&w, "5FB#80008E0641545633");
    expect("5FC#80C000");
    rx(&w, "5FB#80823132"); /* count 2: fragment 1 was lost */
    expect_none();
    expect_result(0, DN_RESULT_FRAGMENT_LOST, 0, DN_AC_NONE, "");
}
END_TEST

START_TEST(repeated_response_fragment)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT;
    ck_assert(dn_scanner_get(&w.scanner, SLAVE, DN_CLASS_IDENTITY, 1, 7, w.now));
    advance(&w, 0);
    expect("5FC#000E010107");
    rx(&w, "5FB#80008E0641");
    expect("5FC#80C000");
    rx(&w, "5FB#8041545633313233");
    expect("5FC#80C100");
    rx(&w, "5FB#8041545633313233"); /* the acknowledgement was lost: again, dropped */
    expect("5FC#80C100");
    rx(&w, "5FB#8082");
    expect("5FC#80C200");
    expect_none();
    expect_result(0, DN_RESULT_OK, 0, 0, "0641545633313233");
}
END_TEST

/* A request fragment unacknowledged is sent once more after the timeout, then given up. */
START_TEST(request_fragment_unacknowledged)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT;
    static const uint8_t value[10] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    co_time_t t0 = w.now;
    ck_assert(dn_scanner_set(&w.scanner, SLAVE, 0x70, 1, 1, value, sizeof(value), w.now));
    advance(&w, 3 * DN_SCANNER_TIMEOUT_DEFAULT_US);
    ck_assert_uint_eq(expect("5FC#8000107001010102"), t0);
    ck_assert_uint_eq(expect("5FC#8000107001010102"), t0 + DN_SCANNER_TIMEOUT_DEFAULT_US);
    expect_none();
    expect_result(0, DN_RESULT_TIMEOUT, 0, DN_AC_NONE, "");
    ck_assert_uint_eq(w.result_at[0], t0 + 2 * DN_SCANNER_TIMEOUT_DEFAULT_US);
}
END_TEST

START_TEST(request_fragment_refused)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT;
    static const uint8_t value[10] = {0};
    ck_assert(dn_scanner_set(&w.scanner, SLAVE, 0x70, 1, 1, value, sizeof(value), w.now));
    advance(&w, 0);
    expect("5FC#8000107001010000");
    rx(&w, "5FB#80C000");
    expect("5FC#8041000000000000");
    rx(&w, "5FB#80C101"); /* too much data */
    expect_none();
    expect_result(0, DN_RESULT_FRAGMENT_ERROR, 0, DN_FRAG_ACK_TOO_MUCH_DATA, "");
}
END_TEST

START_TEST(missed_polls)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED;
    ck_assert(dn_scanner_poll_every(&w.scanner, SLAVE, 25 * MS, w.now));
    advance(&w, 25 * MS);
    expect("5FD#");
    expect("5FD#");
    ck_assert_uint_eq(w.io_count, 1); /* the first poll's answer is missing at the second */
    ck_assert_int_eq(w.io_kind[0], DN_IO_POLL_MISSED);
    rx(&w, "3FF#01020304");
    ck_assert_uint_eq(w.io_count, 2);
    ck_assert_int_eq(w.io_kind[1], DN_IO_POLL_RESPONSE);
    ck_assert_uint_eq(w.slaves[0].missed, 1);
    ck_assert_uint_eq(w.slaves[0].responses, 1);
}
END_TEST

/* 63 slaves polled every 25 ms: 63 poll commands at each period, one deadline for all. */
START_TEST(sixty_three_slaves)
{
    uint8_t macs[63];
    for (uint8_t i = 0; i < 63; i++)
        macs[i] = (uint8_t)(i + 1);
    wire_setup(macs, 63, false);
    dn_scanner_start_online(&w.scanner, w.now);
    for (uint8_t i = 0; i < 63; i++) {
        w.slaves[i].allocated = DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED;
        ck_assert(dn_scanner_poll_every(&w.scanner, macs[i], 25 * MS, w.now));
    }
    co_time_t t0 = w.now;
    ck_assert_uint_eq(dn_scanner_process(&w.scanner, w.now), t0 + 25 * MS);
    ck_assert_uint_eq(w.logged, 63);
    char text[32];
    for (uint8_t i = 0; i < 63; i++) {
        snprintf(text, sizeof(text), "%03X#",
                 0x400u | (i + 1u) << 3 | DN_G2_MASTER_POLL_COS_CYCLIC);
        ck_assert_uint_eq(expect(text), t0);
    }
    for (uint8_t i = 0; i < 63; i++) {
        snprintf(text, sizeof(text), "%03X#00000000", DN_G1_SLAVE_POLL_RESPONSE << 6 | (i + 1u));
        rx(&w, text);
    }
    advance(&w, 25 * MS);
    for (uint8_t i = 0; i < 63; i++) {
        snprintf(text, sizeof(text), "%03X#",
                 0x400u | (i + 1u) << 3 | DN_G2_MASTER_POLL_COS_CYCLIC);
        ck_assert_uint_eq(expect(text), t0 + 25 * MS);
        ck_assert_uint_eq(w.slaves[i].polls, 2);
        ck_assert_uint_eq(w.slaves[i].responses, 1);
        ck_assert_uint_eq(w.slaves[i].missed, 0);
    }
    expect_none();
}
END_TEST

/* ---- a kept polled connection ------------------------------------------------------------- */

/* Polls every 25 ms, kept, as a program does once the set is allocated and the rate set. */
static void keep_polling_scripted(void)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED;
    ck_assert(dn_scanner_keep_polling(&w.scanner, SLAVE, 25 * MS, 25, w.now));
}

static void expect_counts(uint32_t polls, uint32_t responses, uint32_t missed, uint32_t late)
{
    const dn_slave_t *s = &w.slaves[0];
    ck_assert_uint_eq(s->polls, polls);
    ck_assert_uint_eq(s->responses, responses);
    ck_assert_uint_eq(s->missed, missed);
    ck_assert_uint_eq(s->late, late);
}

/* Four polls in a row unanswered (the 4th is missed at the 5th's time, which is not sent): lost;
 * Release, Allocate and the expected packet rate, each on its answer; polls go on at the next
 * period; no done result for the scanner's own requests. */
START_TEST(kept_connection_reestablished)
{
    keep_polling_scripted();
    co_time_t t0 = w.now;
    advance(&w, 0);
    ck_assert_uint_eq(expect("5FD#"), t0);
    rx(&w, "3FF#01020304");
    advance(&w, 125 * MS - 1);
    for (unsigned i = 1; i <= 4; i++)
        ck_assert_uint_eq(expect("5FD#"), t0 + i * 25 * MS);
    expect_none();
    ck_assert_uint_eq(w.event_count, 0);
    advance(&w, 1);
    ck_assert_uint_eq(expect("5FE#004C030103"), t0 + 125 * MS);
    expect_none();
    ck_assert_uint_eq(w.event_count, 1);
    ck_assert_int_eq(w.events[0], DN_CONNECTION_LOST);
    ck_assert_int_eq(w.slaves[0].recovery, DN_RECOVERY_RELEASE);
    expect_counts(5, 1, 4, 0);
    ck_assert(!dn_scanner_poll(&w.scanner, SLAVE, w.now)); /* not while it is re-established */
    rx(&w, "5FB#00CC");
    expect("5FE#404B03010300");
    ck_assert_uint_eq(w.slaves[0].allocated, 0);
    rx(&w, "5FB#40CB00");
    expect("5FC#00100502091900");
    ck_assert_uint_eq(w.slaves[0].allocated, DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED);
    ck_assert_int_eq(w.slaves[0].recovery, DN_RECOVERY_RATE); /* allocated, not yet polled */
    expect_none();
    rx(&w, "5FB#00902000");
    ck_assert_uint_eq(w.event_count, 2);
    ck_assert_int_eq(w.events[1], DN_CONNECTION_RESTORED);
    ck_assert_uint_eq(w.result_count, 0);
    advance(&w, 25 * MS);
    ck_assert_uint_eq(expect("5FD#"), t0 + 150 * MS);
    rx(&w, "3FF#01020304");
    expect_none();
    expect_counts(6, 2, 4, 0);
    ck_assert_uint_eq(w.slaves[0].lost, 1);
    ck_assert_uint_eq(w.slaves[0].restored, 1);
    ck_assert_uint_eq(w.slaves[0].missed_in_row, 0);
}
END_TEST

/* No answer at all: three tries a second apart (each Release waits the 1 s timeout), reported
 * as failed once with the last step's result, then one try every 10 s until one goes through;
 * an Allocate refused by another master fails its try as a timeout does. */
START_TEST(kept_connection_bounded_retry)
{
    keep_polling_scripted();
    advance(&w, 100 * MS);
    for (unsigned i = 0; i < 4; i++)
        expect("5FD#");
    co_time_t lost = expect("5FE#004C030103");
    const co_time_t s = 1000 * MS;
    advance(&w, 4 * s);
    ck_assert_uint_eq(expect("5FE#404C030103"), lost + 2 * s);
    ck_assert_uint_eq(expect("5FE#004C030103"), lost + 4 * s);
    ck_assert_uint_eq(w.event_count, 1);
    advance(&w, 1 * s - 1);
    ck_assert_uint_eq(w.event_count, 1);
    advance(&w, 1);
    ck_assert_uint_eq(w.event_count, 2);
    ck_assert_int_eq(w.events[1], DN_CONNECTION_FAILED);
    ck_assert_uint_eq(w.event_at[1], lost + 5 * s);
    ck_assert_int_eq(w.event_results[1].status, DN_RESULT_TIMEOUT);
    ck_assert_uint_eq(w.event_results[1].service, DN_SVC_RELEASE);
    advance(&w, 21 * s);
    ck_assert_uint_eq(expect("5FE#404C030103"), lost + 15 * s);
    ck_assert_uint_eq(expect("5FE#004C030103"), lost + 26 * s);
    expect_none();
    ck_assert_uint_eq(w.event_count, 2); /* FAILED once */
    ck_assert_uint_eq(w.slaves[0].tries, 5);
    /* the fifth try: released, then another master answers the Allocate */
    rx(&w, "5FB#00CC");
    expect("5FE#404B03010300");
    rx(&w, "5FB#40940C01");
    ck_assert_int_eq(w.slaves[0].recovery, DN_RECOVERY_WAITING);
    ck_assert_uint_eq(w.slaves[0].next_try, w.now + 10 * s);
    advance(&w, 10 * s);
    ck_assert_uint_eq(expect("5FE#004C030103"), w.now);
    rx(&w, "5FB#00CC");
    expect("5FE#404B03010300");
    rx(&w, "5FB#40CB00");
    expect("5FC#00100502091900");
    rx(&w, "5FB#00902000");
    ck_assert_uint_eq(w.event_count, 3);
    ck_assert_int_eq(w.events[2], DN_CONNECTION_RESTORED);
    ck_assert_uint_eq(w.slaves[0].tries, 6);
    expect_counts(4, 0, 4, 0);
    ck_assert_uint_eq(w.result_count, 0);
}
END_TEST

/* A poll missed at its timeout (1 s, the period being 2 s), then its answer: late, not answered
 * too; a poll answered in time is answered once. sent = answered + missed. */
START_TEST(late_answer_counted_once)
{
    setup_scripted();
    w.slaves[0].allocated = DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED;
    ck_assert(dn_scanner_poll_every(&w.scanner, SLAVE, 2000 * MS, w.now));
    advance(&w, 1000 * MS);
    expect("5FD#");
    expect_counts(1, 0, 1, 0);
    advance(&w, 500 * MS);
    rx(&w, "3FF#01020304");
    expect_counts(1, 0, 1, 1);
    ck_assert_uint_eq(w.io_count, 2);
    ck_assert_int_eq(w.io_kind[0], DN_IO_POLL_MISSED);
    ck_assert_int_eq(w.io_kind[1], DN_IO_POLL_LATE);
    ck_assert_uint_eq(w.io_len[1], 4);
    advance(&w, 500 * MS);
    expect("5FD#");
    rx(&w, "3FF#01020304");
    rx(&w, "3FF#01020304"); /* a second answer to the same poll */
    expect_counts(2, 1, 1, 2);
    ck_assert_int_eq(w.io_kind[2], DN_IO_POLL_RESPONSE);
    ck_assert_int_eq(w.io_kind[3], DN_IO_POLL_LATE);
}
END_TEST

/* A program stopping during a try (the Allocate awaiting its answer): polling and the
 * supervision stop, the try is dropped, its Release goes out at once with the next XID; the
 * Allocate's late answer is ignored, the Release's is the program's result. */
START_TEST(release_while_reestablishing)
{
    keep_polling_scripted();
    advance(&w, 100 * MS);
    for (unsigned i = 0; i < 4; i++)
        expect("5FD#");
    expect("5FE#004C030103");
    rx(&w, "5FB#00CC");
    expect("5FE#404B03010300");
    ck_assert(!dn_scanner_release(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED, w.now));
    ck_assert(dn_scanner_poll_every(&w.scanner, SLAVE, 0, w.now));
    ck_assert(!w.slaves[0].busy);
    ck_assert(dn_scanner_release(&w.scanner, SLAVE, DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED, w.now));
    expect("5FE#004C030103");
    rx(&w, "5FB#40CB00"); /* the Allocate's answer: dropped */
    ck_assert_uint_eq(w.result_count, 0);
    rx(&w, "5FB#00CC");
    expect_result(0, DN_RESULT_OK, 0, 0, "");
    ck_assert_uint_eq(result(0)->service, DN_SVC_RELEASE);
    ck_assert_uint_eq(w.slaves[0].allocated, 0);
    ck_assert_int_eq(w.slaves[0].recovery, DN_RECOVERY_NONE);
    advance(&w, 30000 * MS);
    expect_none();
}
END_TEST

/* Against the slave: polls every 25 ms at an expected packet rate of 25 ms (32 in use); the
 * slave hears nothing for 300 ms and times the connection out (4 x 32 ms); the scanner finds it
 * lost, and its Release, Allocate and rate make it Established again, its polls answered. */
START_TEST(kept_connection_against_the_slave)
{
    setup_wired();
    allocate(DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED);
    ck_assert(dn_scanner_set_expected_packet_rate(&w.scanner, SLAVE, DN_CONN_POLL, 25, w.now));
    advance(&w, 0);
    ck_assert(dn_scanner_keep_polling(&w.scanner, SLAVE, 25 * MS, 25, w.now));
    advance(&w, 100 * MS);
    ck_assert_uint_eq(w.slaves[0].responses, 5);
    w.connected = false;
    advance(&w, 300 * MS);
    dn_node_process(&w.bench.node, w.now); /* the slave's time goes on too */
    ck_assert_int_eq(w.bench.node.conn[POLL_CONNECTION].state, DN_CONN_TIMED_OUT);
    ck_assert_uint_eq(w.slaves[0].lost, 1);
    ck_assert_int_eq(w.slaves[0].recovery, DN_RECOVERY_RELEASE); /* unanswered: it times out */
    w.connected = true;
    advance(&w, 2000 * MS);
    ck_assert_uint_eq(w.slaves[0].restored, 1);
    ck_assert_int_eq(w.bench.node.conn[POLL_CONNECTION].state, DN_CONN_ESTABLISHED);
    uint32_t answered = w.slaves[0].responses;
    advance(&w, 100 * MS);
    ck_assert_uint_eq(w.slaves[0].responses, answered + 4);
    const dn_slave_t *s = &w.slaves[0];
    ck_assert_uint_eq(s->polls, s->responses + s->missed + (s->poll_deadline != CO_TIME_NEVER));
    ck_assert_uint_eq(s->late, 0);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet scanner");
    TCase *tc = tcase_create("scanner");
    tcase_add_test(tc, duplicate_mac_check_then_online);
    tcase_add_test(tc, duplicate_mac_answered_stays_off);
    tcase_add_test(tc, init_refusals);
    tcase_add_test(tc, allocate_get_release);
    tcase_add_test(tc, ucmm_open_get_close);
    tcase_add_test(tc, ucmm_close_of_a_deleted_connection_forgets_it);
    tcase_add_test(tc, ucmm_close_timed_out_forgets_it);
    tcase_add_test(tc, ucmm_opens_in_flight_take_distinct_message_ids);
    tcase_add_test(tc, ucmm_message_ids_and_bad_response);
    tcase_add_test(tc, response_in_fragments);
    tcase_add_test(tc, request_in_fragments);
    tcase_add_test(tc, cip_error_and_another_master);
    tcase_add_test(tc, poll_once_and_periodically);
    tcase_add_test(tc, cos_data_acknowledged);
    tcase_add_test(tc, no_answer_is_a_timeout);
    tcase_add_test(tc, lost_response_fragment);
    tcase_add_test(tc, repeated_response_fragment);
    tcase_add_test(tc, request_fragment_unacknowledged);
    tcase_add_test(tc, request_fragment_refused);
    tcase_add_test(tc, missed_polls);
    tcase_add_test(tc, sixty_three_slaves);
    tcase_add_test(tc, kept_connection_reestablished);
    tcase_add_test(tc, kept_connection_bounded_retry);
    tcase_add_test(tc, late_answer_counted_once);
    tcase_add_test(tc, release_while_reestablishing);
    tcase_add_test(tc, kept_connection_against_the_slave);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
