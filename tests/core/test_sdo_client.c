/* SPDX-License-Identifier: Apache-2.0 */
/* SDO client against the core's own SDO server, frame by frame with injected time: two server
 * nodes (4 and 5) and a master node (1) whose 1280h/1281h configure the clients, on one in-process
 * bus that delivers every frame to every party in order and can drop or repeat chosen frames.
 * Every transfer type in both directions at the size boundaries, the largest object the server
 * can hold, server aborts with their text, the client's own aborts with their exact frames (a
 * scripted server on node-id 9), timeouts, a cancelled transfer, lost and repeated block segments,
 * several clients. */
#include "check_main.h"
#include "co/co_sdo_client.h"
#include "test_bus.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define BIG_SIZE 65535u /* a DOMAIN's largest size (co_od_entry_t.size is 16 bits) */
#define STRING_SIZE 1000u
#define LOG_MAX 40000u /* frames of one test (a 65535-byte segmented round trip: 37452) */
#define SCRIPTED_ID 9u /* no node: the test answers as the server */
#define ALPHABET "ABCDEFGHIJKLMNOPQRSTUVWXYZ"

/* The dictionary of the three nodes: the SDO client parameters of the master, a string, a
 * DOMAIN and a few entries whose writes the server refuses. */
typedef struct big_od_data {
    uint8_t x1000[4];
    uint8_t x1280_0[1], x1280[3][4], x1281_0[1], x1281[3][4];
    uint8_t x2000_0[1], u32[4], u8lim[1], ro[2], wo[2], string[STRING_SIZE], domain[BIG_SIZE];
} big_od_data_t;

static const big_od_data_t big_defaults = {
    .x1280_0 = {3},
    .x1280 = {{0x04, 0x06}, {0x84, 0x05}, {4}}, /* 604h, 584h, node 4 */
    .x1281_0 = {3},
    .x1281 = {{0x05, 0x06, 0x00, 0x80}, {0x85, 0x05}, {5}}, /* 80000605h: not valid */
    .x2000_0 = {6},
    .ro = {0x34, 0x12},
};

static const co_od_limits_t lim_u8 = {10, 200};

#define E(idx, sub, type, flags, field, limits)                                                    \
    {                                                                                              \
        idx, sub, type, flags, sizeof(((big_od_data_t *)0)->field),                                \
            offsetof(big_od_data_t, field), limits, NULL                                           \
    }
#define RO CO_OD_ACCESS_RO
#define RW CO_OD_ACCESS_RW
#define WO CO_OD_ACCESS_WO

static const co_od_entry_t big_entries[] = {
    E(0x1000, 0, CO_DT_UNSIGNED32, RO, x1000, NULL),
    E(0x1280, 0, CO_DT_UNSIGNED8, RO, x1280_0, NULL),
    E(0x1280, 1, CO_DT_UNSIGNED32, RW, x1280[0], NULL),
    E(0x1280, 2, CO_DT_UNSIGNED32, RW, x1280[1], NULL),
    E(0x1280, 3, CO_DT_UNSIGNED8, RW, x1280[2][0], NULL),
    E(0x1281, 0, CO_DT_UNSIGNED8, RO, x1281_0, NULL),
    E(0x1281, 1, CO_DT_UNSIGNED32, RW, x1281[0], NULL),
    E(0x1281, 2, CO_DT_UNSIGNED32, RW, x1281[1], NULL),
    E(0x1281, 3, CO_DT_UNSIGNED8, RW, x1281[2][0], NULL),
    E(0x2000, 0, CO_DT_UNSIGNED8, RO, x2000_0, NULL),
    E(0x2000, 1, CO_DT_UNSIGNED32, RW, u32, NULL),
    E(0x2000, 2, CO_DT_UNSIGNED8, RW, u8lim, &lim_u8),
    E(0x2000, 3, CO_DT_UNSIGNED16, RO, ro, NULL),
    E(0x2000, 4, CO_DT_UNSIGNED16, WO, wo, NULL),
    E(0x2000, 5, CO_DT_VISIBLE_STRING, RW, string, NULL),
    E(0x2000, 6, CO_DT_DOMAIN, RW, domain, NULL),
};

static const co_od_t big_od = {
    .name = "sdo-client",
    .entries = big_entries,
    .count = sizeof(big_entries) / sizeof(big_entries[0]),
    .data_size = sizeof(big_od_data_t),
    .defaults = (const uint8_t *)&big_defaults,
};

/* The bus: every frame sent is logged, then delivered in order to every node and client. */
typedef struct bus {
    co_frame_t log[LOG_MAX];
    size_t count;     /* frames sent */
    size_t delivered; /* frames handed to the parties */
    size_t next;      /* first frame not yet checked by expect() */
    co_time_t now;
    /* Frames (by log position) the bus loses, and one it delivers twice. */
    size_t drop[4];
    size_t drops;
    size_t repeat;
} bus_t;

typedef struct server {
    co_node_t node;
    big_od_data_t data;
    co_sdo_buffer_t buffer;
    uint8_t buffer_data[BIG_SIZE];
} server_t;

typedef struct client {
    co_sdo_client_t sdo;
    co_sdo_client_result_t result;
    unsigned results;
} client_t;

static bus_t bus;
static server_t servers[3]; /* node-ids 4, 5 and the master 1 */
#define MASTER (&servers[2].node)
static client_t clients[2];
static uint8_t tx[BIG_SIZE + 7];
static uint8_t rx[BIG_SIZE + 7];

static void bus_send(void *user, const co_frame_t *frame)
{
    (void)user;
    ck_assert_msg(bus.count < LOG_MAX, "bus log overflow");
    bus.log[bus.count++] = *frame;
}

static bool dropped(size_t position)
{
    for (size_t i = 0; i < bus.drops; i++) {
        if (bus.drop[i] == position)
            return true;
    }
    return false;
}

static void deliver(const co_frame_t *frame)
{
    for (size_t i = 0; i < 3; i++) {
        co_node_receive(&servers[i].node, frame, bus.now);
        co_node_process(&servers[i].node, bus.now);
    }
    for (size_t i = 0; i < 2; i++)
        co_sdo_client_receive(&clients[i].sdo, frame, bus.now);
}

/* Delivers every frame not yet delivered, and those they cause. */
static void pump(void)
{
    while (bus.delivered < bus.count) {
        size_t position = bus.delivered++;
        co_frame_t frame = bus.log[position];
        if (dropped(position))
            continue;
        deliver(&frame);
        if (position == bus.repeat)
            deliver(&frame);
    }
}

static void client_done(void *user, const co_sdo_client_result_t *result)
{
    client_t *c = user;
    c->result = *result;
    c->results++;
}

static void start_server(server_t *s, uint8_t node_id)
{
    s->buffer = (co_sdo_buffer_t){.data = s->buffer_data, .size = sizeof(s->buffer_data)};
    co_node_config_t config = {
        .node_id = node_id,
        .od = &big_od,
        .od_data = (uint8_t *)&s->data,
        .send = bus_send,
        .sdo_buffer = &s->buffer,
    };
    ck_assert_int_eq(co_node_init(&s->node, &config), 0);
    co_node_start(&s->node, bus.now);
}

static void start_client(client_t *c, uint8_t server_node_id, uint8_t pst, uint8_t blksize)
{
    co_sdo_client_config_t config = {
        .server_node_id = server_node_id,
        .send = bus_send,
        .user = c,
        .done = client_done,
        .blksize = blksize,
        .pst = pst,
    };
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), 0);
    c->results = 0;
}

static void setup(void)
{
    memset(&bus, 0, sizeof(bus));
    bus.repeat = SIZE_MAX;
    start_server(&servers[0], 4);
    start_server(&servers[1], 5);
    start_server(&servers[2], 1);
    pump();
    bus.next = bus.count; /* the boot-up frames */
    start_client(&clients[0], 4, 0, 0);
    start_client(&clients[1], SCRIPTED_ID, 0, 0);
    for (size_t i = 0; i < sizeof(tx); i++)
        tx[i] = (uint8_t)(0x20 + (i * 7) % 90); /* never 0: a string's length is its content's */
    memcpy(tx, ALPHABET, 26);
    memset(rx, 0, sizeof(rx));
}

#define expect(text) expect_at(text, __FILE__, __LINE__)
static void expect_at(const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(bus.next < bus.count, "%s:%d: expected %s, bus is quiet", file, line, want);
    test_format(&bus.log[bus.next++], got);
    ck_assert_msg(strcmp(want, got) == 0, "%s:%d: expected %s, got %s", file, line, want, got);
}

#define expect_none() expect_none_at(__FILE__, __LINE__)
static void expect_none_at(const char *file, int line)
{
    char got[32];
    if (bus.next < bus.count)
        ck_abort_msg("%s:%d: expected silence, got %s", file, line,
                     test_format(&bus.log[bus.next], got));
}

/* The scripted server's frame, delivered at once. */
static void inject(const char *text)
{
    co_frame_t f = test_frame(text);
    bus_send(NULL, &f);
    pump();
    bus.next++;
}

static void expect_result(const client_t *c, co_sdo_client_status_t status, uint32_t code,
                          uint32_t size)
{
    ck_assert_uint_eq(c->results, 1);
    ck_assert_int_eq(c->result.status, status);
    ck_assert_uint_eq(c->result.abort_code, code);
    ck_assert_uint_eq(c->result.size, size);
}

static void download(client_t *c, uint16_t index, uint8_t sub, uint32_t len,
                     co_sdo_client_mode_t mode)
{
    c->results = 0;
    ck_assert_int_eq(co_sdo_client_download(&c->sdo, index, sub, tx, len, mode, 100, bus.now), 0);
    pump();
}

static void upload(client_t *c, uint16_t index, uint8_t sub, uint32_t cap,
                   co_sdo_client_mode_t mode)
{
    c->results = 0;
    memset(rx, 0, sizeof(rx));
    ck_assert_int_eq(co_sdo_client_upload(&c->sdo, index, sub, rx, cap, mode, 100, bus.now), 0);
    pump();
}

/* Writes `len` bytes to the string with one mode and reads them back with another. */
static void round_trip(uint16_t index, uint8_t sub, uint32_t len, co_sdo_client_mode_t down,
                       co_sdo_client_mode_t up)
{
    client_t *c = &clients[0];
    download(c, index, sub, len, down);
    expect_result(c, CO_SDO_CLIENT_OK, 0, len);
    upload(c, index, sub, sizeof(rx), up);
    expect_result(c, CO_SDO_CLIENT_OK, 0, len);
    ck_assert_msg(memcmp(rx, tx, len) == 0, "%u bytes read back differ", len);
    ck_assert_msg(!co_sdo_client_busy(&c->sdo), "client still busy");
    bus.count = bus.delivered = bus.next = 0; /* the frames are not checked here */
}

static const uint32_t boundary[] = {0, 1, 4, 5, 7, 8, 889, 890, STRING_SIZE};
#define BOUNDARIES (sizeof(boundary) / sizeof(boundary[0]))

START_TEST(expedited_frames)
{
    co_put_u32(tx, 0x12345678);
    download(&clients[0], 0x2000, 1, 4, CO_SDO_CLIENT_AUTO);
    expect("604#2300200178563412");
    expect("584#6000200100000000");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 4);
    upload(&clients[0], 0x2000, 1, 4, CO_SDO_CLIENT_AUTO);
    expect("604#4000200100000000");
    expect("584#4300200178563412");
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 4);
    ck_assert_uint_eq(co_get_u32(rx), 0x12345678);
    tx[0] = 20;
    download(&clients[0], 0x2000, 2, 1, CO_SDO_CLIENT_AUTO);
    expect("604#2F00200214000000");
    expect("584#6000200200000000");
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 1);
}
END_TEST

START_TEST(segmented_frames)
{
    memcpy(tx, "ABCDEFGH", 8);
    download(&clients[0], 0x2000, 5, 8, CO_SDO_CLIENT_SEGMENTED);
    expect("604#2100200508000000");
    expect("584#6000200500000000");
    expect("604#00414243444546 47");
    expect("584#2000000000000000");
    expect("604#1D48000000000000"); /* toggle, n = 6, c */
    expect("584#3000000000000000");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 8);
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_AUTO);
    expect("604#4000200500000000");
    expect("584#4100200508000000");
    expect("604#6000000000000000");
    expect("584#00414243444546 47");
    expect("604#7000000000000000");
    expect("584#1D48000000000000");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 8);
    ck_assert_mem_eq(rx, "ABCDEFGH", 8);
    download(&clients[0], 0x2000, 5, 0, CO_SDO_CLIENT_AUTO); /* empty: one segment, n = 7 */
    expect("604#2100200500000000");
    expect("584#6000200500000000");
    expect("604#0F00000000000000");
    expect("584#2000000000000000");
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 0);
}
END_TEST

START_TEST(block_frames)
{
    memcpy(tx, "ABCDEFGHI", 9);
    download(&clients[0], 0x2000, 5, 9, CO_SDO_CLIENT_BLOCK);
    expect("604#C600200509000000");
    expect("584#A40020057F000000");
    expect("604#01414243444546 47");
    expect("604#8248490000000000");
    expect("584#A2027F0000000000");
    char end[32];
    uint16_t crc = co_sdo_crc16(tx, 9);
    snprintf(end, sizeof(end), "604#D5%02X%02X0000000000", crc & 0xFF, crc >> 8); /* n = 5 */
    expect(end);
    expect("584#A100000000000000");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 9);
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("604#A40020057F000000"); /* blksize 127, pst 0 */
    expect("584#C600200509000000");
    expect("604#A300000000000000");
    expect("584#01414243444546 47");
    expect("584#8248490000000000");
    expect("604#A2027F0000000000");
    snprintf(end, sizeof(end), "584#D5%02X%02X0000000000", crc & 0xFF, crc >> 8);
    expect(end);
    expect("604#A100000000000000");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 9);
    ck_assert_mem_eq(rx, "ABCDEFGHI", 9);
}
END_TEST

START_TEST(segmented_sizes)
{
    for (size_t i = 0; i < BOUNDARIES; i++)
        round_trip(0x2000, 5, boundary[i], CO_SDO_CLIENT_SEGMENTED, CO_SDO_CLIENT_SEGMENTED);
}
END_TEST

START_TEST(block_sizes)
{
    for (size_t i = 0; i < BOUNDARIES; i++)
        round_trip(0x2000, 5, boundary[i], CO_SDO_CLIENT_BLOCK, CO_SDO_CLIENT_BLOCK);
}
END_TEST

/* Auto: expedited up to 4 bytes, block above pst, segmented between; an upload above pst asks
 * for a block and the server switches to the plain protocol for a value of at most pst bytes. */
START_TEST(auto_mode)
{
    start_client(&clients[0], 4, 16, 0);
    for (size_t i = 0; i < BOUNDARIES; i++)
        round_trip(0x2000, 5, boundary[i], CO_SDO_CLIENT_AUTO, CO_SDO_CLIENT_AUTO);
    download(&clients[0], 0x2000, 5, 3, CO_SDO_CLIENT_AUTO);
    expect("604#2700200541424300");
    bus.next = bus.count;
    download(&clients[0], 0x2000, 5, 16, CO_SDO_CLIENT_AUTO);
    expect("604#2100200510000000");
    bus.next = bus.count;
    download(&clients[0], 0x2000, 5, 17, CO_SDO_CLIENT_AUTO);
    expect("604#C600200511000000");
    bus.next = bus.count;
    memcpy(tx, "ABCDEF", 6);
    download(&clients[0], 0x2000, 5, 6, CO_SDO_CLIENT_AUTO);
    bus.next = bus.count;
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_AUTO);
    expect("604#A40020057F100000"); /* pst 16 */
    expect("584#4100200506000000"); /* the server switched */
    expect("604#6000000000000000");
    expect("584#03414243444546 00");
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 6);
    upload(&clients[0], 0x2000, 5, 16, CO_SDO_CLIENT_AUTO); /* buffer not above pst: plain */
    expect("604#4000200500000000");
    bus.next = bus.count;
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 6);
}
END_TEST

/* The largest object the server can hold, a 65535-byte DOMAIN, every way. */
START_TEST(large_domain)
{
    round_trip(0x2000, 6, BIG_SIZE, CO_SDO_CLIENT_BLOCK, CO_SDO_CLIENT_BLOCK);
    for (size_t i = 0; i < BIG_SIZE; i++)
        tx[i] = (uint8_t)(i * 13);
    round_trip(0x2000, 6, BIG_SIZE, CO_SDO_CLIENT_SEGMENTED, CO_SDO_CLIENT_SEGMENTED);
    ck_assert_mem_eq(servers[0].data.domain, tx, BIG_SIZE);
}
END_TEST

/* The server's aborts reach the application with their code and their CiA 301 text. */
START_TEST(server_aborts)
{
    static const struct {
        uint16_t index;
        uint8_t sub;
        bool write;
        uint32_t len;
        uint32_t code;
        const char *text;
    } cases[] = {
        {0x3000, 0, false, 0, CO_SDO_ABORT_NO_OBJECT,
         "object does not exist in the object dictionary"},
        {0x2000, 9, false, 0, CO_SDO_ABORT_NO_SUBINDEX, "sub-index does not exist"},
        {0x2000, 4, false, 0, CO_SDO_ABORT_WRITE_ONLY, "attempt to read a write only object"},
        {0x2000, 3, true, 2, CO_SDO_ABORT_READ_ONLY, "attempt to write a read only object"},
        {0x2000, 1, true, 2, CO_SDO_ABORT_LENGTH_LOW,
         "data type does not match, length of service parameter too low"},
        {0x2000, 5, true, STRING_SIZE + 1, CO_SDO_ABORT_LENGTH_HIGH,
         "data type does not match, length of service parameter too high"},
        {0x2000, 2, true, 1, CO_SDO_ABORT_VALUE_HIGH, "value of parameter written too high"},
    };
    tx[0] = 250;
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        for (int mode = CO_SDO_CLIENT_AUTO; mode <= CO_SDO_CLIENT_BLOCK; mode++) {
            if (cases[i].write)
                download(&clients[0], cases[i].index, cases[i].sub, cases[i].len,
                         (co_sdo_client_mode_t)mode);
            else
                upload(&clients[0], cases[i].index, cases[i].sub, sizeof(rx),
                       (co_sdo_client_mode_t)mode);
            expect_result(&clients[0], CO_SDO_CLIENT_SERVER_ABORT, cases[i].code, 0);
            /* The server's abort is the last frame: the client does not answer it. */
            ck_assert_uint_eq(bus.log[bus.count - 1].id, 0x584);
            ck_assert_uint_eq(bus.log[bus.count - 1].data[0], 0x80);
            ck_assert_str_eq(co_sdo_abort_text(clients[0].result.abort_code), cases[i].text);
            ck_assert_uint_eq(clients[0].result.index, cases[i].index);
            ck_assert_uint_eq(clients[0].result.subindex, cases[i].sub);
            ck_assert(!co_sdo_client_busy(&clients[0].sdo));
        }
    }
    upload(&clients[0], 0x3000, 0, 4, CO_SDO_CLIENT_AUTO);
    bus.next = bus.count - 2;
    expect("604#4000300000000000");
    expect("584#8000300000000206");
}
END_TEST

/* An abort frame without a code CiA 301 defines, too short to carry one or carrying 0 (which
 * the result keeps for success), is the server's general error: a failed transfer never reports
 * abort code 0. */
START_TEST(server_abort_without_code)
{
    client_t *c = &clients[1];
    static const char *const aborts[] = {"589#80002005", "589#8000200500000000"};
    for (size_t i = 0; i < sizeof aborts / sizeof aborts[0]; i++) {
        upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_SEGMENTED);
        expect("609#4000200500000000");
        inject(aborts[i]);
        expect_result(c, CO_SDO_CLIENT_SERVER_ABORT, CO_SDO_ABORT_GENERAL, 0);
        ck_assert(!co_sdo_client_busy(&c->sdo));
    }
}
END_TEST

/* The client's own aborts, against the scripted server: the exact abort frame, the result. */
START_TEST(client_abort_toggle)
{
    client_t *c = &clients[1];
    upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_SEGMENTED);
    expect("609#4000200500000000");
    inject("589#410020050E000000");
    expect("609#6000000000000000");
    inject("589#00414243444546 47");
    expect("609#7000000000000000");
    inject("589#00414243444546 47"); /* toggle 0 again */
    expect("609#8000200500000305");
    expect_none();
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_TOGGLE, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "toggle bit not alternated");

    download(c, 0x2000, 5, 10, CO_SDO_CLIENT_SEGMENTED);
    expect("609#210020050A000000");
    inject("589#6000200500000000");
    bus.next++;
    inject("589#3000000000000000"); /* confirms with toggle 1 */
    expect("609#8000200500000305");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_TOGGLE, 0);
}
END_TEST

START_TEST(client_abort_crc)
{
    client_t *c = &clients[1];
    upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("609#A40020057F000000");
    inject("589#C600200509000000");
    expect("609#A300000000000000");
    inject("589#01414243444546 47");
    inject("589#8248490000000000");
    expect("609#A2027F0000000000");
    uint16_t crc = co_sdo_crc16((const uint8_t *)"ABCDEFGHI", 9) ^ 1u;
    char end[32];
    snprintf(end, sizeof(end), "589#D5%02X%02X0000000000", crc & 0xFF, crc >> 8);
    inject(end);
    expect("609#8000200504000405");
    expect_none();
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_CRC, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "CRC error");
}
END_TEST

START_TEST(client_abort_sequence)
{
    client_t *c = &clients[1];
    start_client(c, SCRIPTED_ID, 0, 4);
    upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("609#A400200504000000");
    inject("589#C6002005FF000000");
    expect("609#A300000000000000");
    inject("589#05414243444546 47"); /* seqno 5 > blksize 4 */
    expect("609#8000200503000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_SEQUENCE, 0);

    download(c, 0x2000, 5, 9, CO_SDO_CLIENT_BLOCK);
    expect("609#C600200509000000");
    inject("589#A400200505000000");
    expect("609#01414243444546 47");
    expect("609#8248490000000000");
    inject("589#A203050000000000"); /* ackseq 3: only 2 were sent */
    expect("609#8000200503000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_SEQUENCE, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "invalid sequence number");
}
END_TEST

START_TEST(client_abort_block_size)
{
    client_t *c = &clients[1];
    download(c, 0x2000, 5, 9, CO_SDO_CLIENT_BLOCK);
    expect("609#C600200509000000");
    inject("589#A400200500000000"); /* blksize 0 */
    expect("609#8000200502000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_BLOCK_SIZE, 0);
    download(c, 0x2000, 5, 9, CO_SDO_CLIENT_BLOCK);
    expect("609#C600200509000000");
    inject("589#A400200501000000");
    expect("609#01414243444546 47");
    inject("589#A201800000000000"); /* blksize 128 */
    expect("609#8000200502000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_BLOCK_SIZE, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "invalid block size");
}
END_TEST

START_TEST(client_abort_command)
{
    client_t *c = &clients[1];
    upload(c, 0x2000, 1, 4, CO_SDO_CLIENT_AUTO);
    expect("609#4000200100000000");
    inject("589#6000200100000000"); /* a download response to an upload */
    expect("609#8000200101000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_COMMAND, 0);
    upload(c, 0x2000, 1, 4, CO_SDO_CLIENT_AUTO);
    expect("609#4000200100000000");
    inject("589#4300200278563412"); /* another sub-index */
    expect("609#8000200101000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_COMMAND, 0);
}
END_TEST

/* Out of memory: the value does not fit the application's buffer, announced or not. */
START_TEST(client_abort_no_memory)
{
    client_t *c = &clients[1];
    upload(c, 0x2000, 5, 10, CO_SDO_CLIENT_SEGMENTED);
    expect("609#4000200500000000");
    inject("589#410020050B000000"); /* 11 bytes */
    expect("609#8000200505000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_NO_MEMORY, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "out of memory");
    upload(c, 0x2000, 5, 10, CO_SDO_CLIENT_SEGMENTED);
    expect("609#4000200500000000");
    inject("589#4000200500000000"); /* size not indicated */
    expect("609#6000000000000000");
    inject("589#00414243444546 47");
    expect("609#7000000000000000");
    inject("589#10414243444546 47"); /* 14 bytes > 10 */
    expect("609#8000200505000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_NO_MEMORY, 0);
    upload(c, 0x2000, 1, 2, CO_SDO_CLIENT_AUTO);
    expect("609#4000200100000000");
    inject("589#4300200178563412"); /* expedited, 4 bytes > 2 */
    expect("609#8000200105000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_NO_MEMORY, 0);
    upload(c, 0x2000, 5, 10, CO_SDO_CLIENT_BLOCK);
    expect("609#A40020057F000000");
    inject("589#C60020050B000000");
    expect("609#8000200505000405");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_NO_MEMORY, 0);
}
END_TEST

/* The server sends another amount of data than it announced: 0x06070010. */
START_TEST(client_abort_length)
{
    client_t *c = &clients[1];
    upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_SEGMENTED);
    expect("609#4000200500000000");
    inject("589#410020050A000000"); /* 10 bytes announced, 8 sent */
    expect("609#6000000000000000");
    inject("589#00414243444546 47");
    expect("609#7000000000000000");
    inject("589#1D48000000000000");
    expect("609#8000200510000706");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_TYPE_LENGTH, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code),
                     "data type does not match, length of service parameter does not match");
    upload(c, 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("609#A40020057F000000");
    inject("589#C60020050A000000"); /* 10 announced, 9 sent */
    expect("609#A300000000000000");
    inject("589#01414243444546 47");
    inject("589#8248490000000000");
    expect("609#A2027F0000000000");
    uint16_t crc = co_sdo_crc16((const uint8_t *)"ABCDEFGHI", 9);
    char end[32];
    snprintf(end, sizeof(end), "589#D5%02X%02X0000000000", crc & 0xFF, crc >> 8);
    inject(end);
    expect("609#8000200510000706");
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_TYPE_LENGTH, 0);
}
END_TEST

/* The timeout: the abort goes out exactly timeout_ms after the request or the last frame. */
START_TEST(timeout)
{
    client_t *c = &clients[1];
    bus.now = 1000;
    ck_assert_int_eq(
        co_sdo_client_upload(&c->sdo, 0x2000, 5, rx, sizeof(rx), CO_SDO_CLIENT_AUTO, 5, bus.now),
        0);
    pump();
    expect("609#4000200500000000");
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 1000), 6000);
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 5999), 6000);
    expect_none();
    bus.now = 5000;
    inject("589#4100200510000000"); /* restarts it */
    expect("609#6000000000000000");
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 5000), 10000);
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 9999), 10000);
    expect_none();
    ck_assert_uint_eq(c->results, 0);
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 10000), CO_TIME_NEVER);
    expect("609#8000200500000405");
    expect_none();
    expect_result(c, CO_SDO_CLIENT_CLIENT_ABORT, CO_SDO_ABORT_TIMEOUT, 0);
    ck_assert_str_eq(co_sdo_abort_text(c->result.abort_code), "SDO protocol timed out");
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 20000), CO_TIME_NEVER);
    /* The PLC300's longest timeout, 5000 ms. */
    ck_assert_int_eq(
        co_sdo_client_download(&c->sdo, 0x2000, 1, tx, 4, CO_SDO_CLIENT_AUTO, 5000, 20000), 0);
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 20000), 5020000);
}
END_TEST

/* A cancelled transfer ends without a frame or a result, its late answer is not taken, and the
 * idle client serves the next request. */
START_TEST(cancel)
{
    client_t *c = &clients[1];
    bus.now = 1000;
    ck_assert_int_eq(
        co_sdo_client_upload(&c->sdo, 0x2000, 5, rx, sizeof(rx), CO_SDO_CLIENT_AUTO, 5, bus.now),
        0);
    pump();
    expect("609#4000200500000000");
    co_sdo_client_cancel(&c->sdo);
    ck_assert(!co_sdo_client_busy(&c->sdo));
    ck_assert_uint_eq(co_sdo_client_process(&c->sdo, 6000), CO_TIME_NEVER);
    inject("589#4F00200541000000");
    expect_none();
    ck_assert_uint_eq(c->results, 0);
    ck_assert_uint_eq(rx[0], 0);
    ck_assert_int_eq(
        co_sdo_client_upload(&c->sdo, 0x2000, 1, rx, sizeof(rx), CO_SDO_CLIENT_AUTO, 5, bus.now),
        0);
    pump();
    expect("609#4000200100000000");
    inject("589#4300200178563412");
    expect_result(c, CO_SDO_CLIENT_OK, 0, 4);
    ck_assert_mem_eq(rx, "\x78\x56\x34\x12", 4);
}
END_TEST

/* Block download, segment 2 of 4 lost: the server acknowledges segment 1, the client resends
 * from segment 2, numbered from 1. */
START_TEST(block_download_lost_segment)
{
    bus.drop[bus.drops++] = bus.count + 3; /* initiate, response, segment 1, segment 2 */
    download(&clients[0], 0x2000, 5, 26, CO_SDO_CLIENT_BLOCK);
    expect("604#C60020051A000000");
    expect("584#A40020057F000000");
    expect("604#01414243444546 47");
    expect("604#0248494A4B4C4D4E"); /* lost */
    expect("604#034F505152535455");
    expect("604#8456575859 5A0000");
    expect("584#A2017F0000000000");
    expect("604#0148494A4B4C4D4E");
    expect("604#024F505152535455");
    expect("604#8356575859 5A0000");
    expect("584#A2037F0000000000");
    bus.next += 2;
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 26);
    ck_assert_mem_eq(servers[0].data.string, ALPHABET, 26);
}
END_TEST

/* Block upload: a repeated segment is ignored; a lost one makes the client acknowledge the last
 * good one, and the server resends from the next. */
START_TEST(block_upload_repeated_segment)
{
    memcpy(servers[0].data.string, ALPHABET, 26);
    bus.repeat = bus.count + 3; /* initiate, response, start, segment 1 */
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("604#A40020057F000000");
    expect("584#C60020051A000000");
    expect("604#A300000000000000");
    expect("584#01414243444546 47"); /* delivered twice */
    expect("584#0248494A4B4C4D4E");
    expect("584#034F505152535455");
    expect("584#8456575859 5A0000");
    expect("604#A2047F0000000000");
    bus.next += 2;
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 26);
    ck_assert_mem_eq(rx, ALPHABET, 26);
}
END_TEST

START_TEST(block_upload_lost_segment)
{
    memcpy(servers[0].data.string, ALPHABET, 26);
    bus.drop[bus.drops++] = bus.count + 4; /* initiate, response, start, segment 1, segment 2 */
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("604#A40020057F000000");
    expect("584#C60020051A000000");
    expect("604#A300000000000000");
    expect("584#01414243444546 47");
    expect("584#0248494A4B4C4D4E"); /* lost */
    expect("584#034F505152535455");
    expect("584#8456575859 5A0000");
    expect("604#A2017F0000000000");
    expect("584#0148494A4B4C4D4E");
    expect("584#024F505152535455");
    expect("584#8356575859 5A0000");
    expect("604#A2037F0000000000");
    bus.next += 2;
    expect_none();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 26);
    ck_assert_mem_eq(rx, ALPHABET, 26);
}
END_TEST

/* Sub-blocks and the block sizes each side sets: the client's for upload, the server's (what its
 * buffer can still take) for download. */
START_TEST(block_size_negotiation)
{
    start_client(&clients[0], 4, 0, 2);
    memcpy(servers[0].data.string, ALPHABET, 26);
    upload(&clients[0], 0x2000, 5, sizeof(rx), CO_SDO_CLIENT_BLOCK);
    expect("604#A400200502000000");
    expect("584#C60020051A000000");
    expect("604#A300000000000000");
    expect("584#01414243444546 47");
    expect("584#0248494A4B4C4D4E");
    expect("604#A202020000000000");
    expect("584#014F505152535455");
    expect("584#8256575859 5A0000");
    expect("604#A202020000000000");
    bus.next += 2;
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 26);
    servers[0].buffer.size = 15; /* blksize 3, then what is left: 1 */
    download(&clients[0], 0x2000, 5, 15, CO_SDO_CLIENT_BLOCK);
    expect("604#C60020050F000000");
    expect("584#A400200503000000");
    expect("604#01414243444546 47");
    expect("604#0248494A4B4C4D4E");
    expect("604#834F000000000000");
    expect("584#A203010000000000");
    bus.next += 2;
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 15);
}
END_TEST

/* Two clients at once, configured from the master's 1280h, each with its own COB-ID pair and
 * server; their block transfers interleave on one bus. */
START_TEST(several_clients)
{
    co_sdo_client_config_t config = {.send = bus_send, .user = &clients[1], .done = client_done};
    ck_assert_int_eq(co_sdo_client_config_from_od(&config, MASTER, 0), 0);
    ck_assert_uint_eq(config.request_id, 0x604);
    ck_assert_uint_eq(config.response_id, 0x584);
    ck_assert_uint_eq(config.server_node_id, 4);
    ck_assert_int_eq(co_sdo_client_config_from_od(&config, MASTER, 1), CO_SDO_CLIENT_ERR_INVALID);
    ck_assert_int_eq(co_sdo_client_config_from_od(&config, MASTER, 2), CO_SDO_CLIENT_ERR_NO_OBJECT);
    ck_assert_int_eq(co_sdo_client_config_from_od(&config, MASTER, 200),
                     CO_SDO_CLIENT_ERR_NO_OBJECT);
    /* 1281h made valid for node 5. */
    co_od_set_value(MASTER, 0x1281, 1, 0x605);
    ck_assert_int_eq(co_sdo_client_config_from_od(&config, MASTER, 1), 0);
    ck_assert_uint_eq(config.request_id, 0x605);
    ck_assert_uint_eq(config.response_id, 0x585);
    ck_assert_uint_eq(config.server_node_id, 5);
    ck_assert_int_eq(co_sdo_client_init(&clients[1].sdo, &config), 0);
    clients[0].results = clients[1].results = 0;
    ck_assert_int_eq(
        co_sdo_client_download(&clients[0].sdo, 0x2000, 6, tx, 3000, CO_SDO_CLIENT_BLOCK, 100, 0),
        0);
    ck_assert_int_eq(co_sdo_client_download(&clients[1].sdo, 0x2000, 6, tx + 1, 2000,
                                            CO_SDO_CLIENT_SEGMENTED, 100, 0),
                     0);
    pump();
    expect_result(&clients[0], CO_SDO_CLIENT_OK, 0, 3000);
    expect_result(&clients[1], CO_SDO_CLIENT_OK, 0, 2000);
    ck_assert_mem_eq(servers[0].data.domain, tx, 3000);
    ck_assert_mem_eq(servers[1].data.domain, tx + 1, 2000);
    ck_assert_int_eq(
        co_sdo_client_upload(&clients[0].sdo, 0x2000, 5, rx, 0, CO_SDO_CLIENT_AUTO, 100, 0), 0);
    co_frame_t foreign = test_frame("585#4300200500000000");
    ck_assert(!co_sdo_client_receive(&clients[0].sdo, &foreign, 0));
    ck_assert(co_sdo_client_receive(&clients[1].sdo, &foreign, 0)); /* its own, idle: ignored */
}
END_TEST

/* 100 kB both ways by block transfer, with a scripted server (the core's own server holds at most
 * 65535 bytes): sub-blocks of 127 segments, n and the CRC of the end frames. */
#define HUNDRED_KB 102400u

static uint8_t big_tx[HUNDRED_KB], big_rx[HUNDRED_KB];

static void reply(const uint8_t p[8])
{
    co_frame_t f = {.id = 0x580u + SCRIPTED_ID, .len = 8};
    memcpy(f.data, p, 8);
    bus_send(NULL, &f);
    pump();
}

/* The next frame the client sent, skipping the scripted server's own. */
static co_frame_t next_request(void)
{
    for (;;) {
        ck_assert_msg(bus.next < bus.count, "the client is quiet");
        co_frame_t f = bus.log[bus.next++];
        if (f.id == 0x600u + SCRIPTED_ID)
            return f;
    }
}

START_TEST(hundred_kilobytes_block_download)
{
    client_t *c = &clients[1];
    for (size_t i = 0; i < HUNDRED_KB; i++)
        big_tx[i] = (uint8_t)(i * 31 + (i >> 8));
    c->results = 0;
    ck_assert_int_eq(
        co_sdo_client_download(&c->sdo, 0x2000, 6, big_tx, HUNDRED_KB, CO_SDO_CLIENT_BLOCK, 100, 0),
        0);
    co_frame_t f = next_request();
    ck_assert_uint_eq(f.data[0], 0xC6);
    ck_assert_uint_eq(co_get_u32(&f.data[4]), HUNDRED_KB);
    reply((const uint8_t[8]){0xA4, 0x00, 0x20, 0x06, 127});
    uint32_t offset = 0;
    unsigned subblocks = 0;
    bool last = false;
    while (!last) {
        f = next_request();
        uint8_t seqno = f.data[0] & 0x7F;
        last = (f.data[0] & 0x80) != 0;
        uint32_t pos = offset + (uint32_t)(seqno - 1) * 7;
        memcpy(&big_rx[pos], &f.data[1], HUNDRED_KB - pos < 7 ? HUNDRED_KB - pos : 7);
        if (seqno == 127 || last) {
            reply((const uint8_t[8]){0xA2, seqno, 127});
            offset += seqno * 7u;
            subblocks++;
        }
    }
    f = next_request();
    uint32_t unused = (f.data[0] >> 2) & 7u;
    ck_assert_uint_eq(f.data[0] & 0xE3u, 0xC1);
    ck_assert_uint_eq(offset - unused, HUNDRED_KB);
    ck_assert_uint_eq(co_get_u16(&f.data[1]), co_sdo_crc16(big_tx, HUNDRED_KB));
    ck_assert_uint_eq(subblocks, (HUNDRED_KB / 7 + 1 + 126) / 127);
    reply((const uint8_t[8]){0xA1});
    expect_result(c, CO_SDO_CLIENT_OK, 0, HUNDRED_KB);
    ck_assert_mem_eq(big_rx, big_tx, HUNDRED_KB);
}
END_TEST

START_TEST(hundred_kilobytes_block_upload)
{
    client_t *c = &clients[1];
    for (size_t i = 0; i < HUNDRED_KB; i++)
        big_tx[i] = (uint8_t)(i * 17 + (i >> 9));
    c->results = 0;
    ck_assert_int_eq(
        co_sdo_client_upload(&c->sdo, 0x2000, 6, big_rx, HUNDRED_KB, CO_SDO_CLIENT_BLOCK, 100, 0),
        0);
    co_frame_t f = next_request();
    ck_assert_uint_eq(f.data[0], 0xA4);
    uint8_t blksize = f.data[4];
    ck_assert_uint_eq(blksize, 127);
    uint8_t p[8] = {0xC6, 0x00, 0x20, 0x06};
    co_put_u32(&p[4], HUNDRED_KB);
    reply(p);
    ck_assert_uint_eq(next_request().data[0], 0xA3);
    uint32_t offset = 0;
    for (;;) {
        uint8_t sent = 0;
        bool last = false;
        while (sent < blksize && !last) {
            uint32_t pos = offset + sent * 7u;
            uint32_t count = HUNDRED_KB - pos < 7 ? HUNDRED_KB - pos : 7;
            last = pos + count == HUNDRED_KB;
            sent++;
            uint8_t segment[8] = {(uint8_t)(sent | (last ? 0x80 : 0))};
            memcpy(&segment[1], &big_tx[pos], count);
            reply(segment);
        }
        f = next_request();
        ck_assert_uint_eq(f.data[0], 0xA2);
        ck_assert_uint_eq(f.data[1], sent);
        blksize = f.data[2];
        offset += sent * 7u;
        if (last)
            break;
    }
    uint8_t end[8] = {(uint8_t)(0xC1 | (offset - HUNDRED_KB) << 2)};
    co_put_u16(&end[1], co_sdo_crc16(big_tx, HUNDRED_KB));
    reply(end);
    ck_assert_uint_eq(next_request().data[0], 0xA1);
    expect_result(c, CO_SDO_CLIENT_OK, 0, HUNDRED_KB);
    ck_assert_mem_eq(big_rx, big_tx, HUNDRED_KB);
}
END_TEST

/* A plausible answer for the client's state, with random fields (and now and then a random
 * command byte), so that the random answers below reach every state. */
static uint8_t plausible_command(const co_sdo_client_t *sdo, uint8_t r)
{
    if (r % 8 == 0)
        return (uint8_t)(r * 37);
    switch (sdo->state) {
    case CO_SDO_CLIENT_DOWNLOAD_EXPEDITED:
    case CO_SDO_CLIENT_DOWNLOAD_INITIATE:
        return 0x60;
    case CO_SDO_CLIENT_DOWNLOAD_SEGMENT:
        return (uint8_t)(0x20 | (r & 0x10));
    case CO_SDO_CLIENT_UPLOAD_INITIATE:
    case CO_SDO_CLIENT_BLOCK_UPLOAD_INITIATE:
        return (uint8_t)(r & 0x40 ? 0x40 | (r & 0x0F) : 0xC0 | (r & 0x06));
    case CO_SDO_CLIENT_UPLOAD_SEGMENT:
        return (uint8_t)(r & 0x1F);
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_INITIATE:
        return (uint8_t)(0xA0 | (r & 0x04));
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_ACK:
        return 0xA2;
    case CO_SDO_CLIENT_BLOCK_DOWNLOAD_END:
        return 0xA1;
    case CO_SDO_CLIENT_BLOCK_UPLOAD_SUB:
        return (uint8_t)((r % 5) | (r & 0x80));
    default:
        return (uint8_t)(0xC1 | (r & 0x1C));
    }
}

/* Random answers from the scripted server in every state: the client never writes outside the
 * application's buffer, reports at most `cap` bytes, and every transfer ends with one result. */
START_TEST(random_answers)
{
    client_t *c = &clients[1];
    uint32_t seed = 12345;
    unsigned ok = 0;
    for (unsigned run = 0; run < 2000; run++) {
        bus.count = bus.delivered = bus.next = 0;
        seed = seed * 1103515245u + 12345u;
        uint32_t cap = (seed >> 8) % 40;
        co_sdo_client_mode_t mode = (co_sdo_client_mode_t)((seed >> 20) % 3);
        memset(rx, 0xEE, 64);
        c->results = 0;
        if (seed & 0x10000)
            ck_assert_int_eq(co_sdo_client_upload(&c->sdo, 0x2000, 5, rx, cap, mode, 10, 0), 0);
        else
            ck_assert_int_eq(co_sdo_client_download(&c->sdo, 0x2000, 5, tx, cap, mode, 10, 0), 0);
        for (unsigned k = 0; k < 60 && c->results == 0; k++) {
            co_frame_t f = {.id = 0x580u + SCRIPTED_ID};
            uint8_t r[9];
            for (int i = 0; i < 9; i++) {
                seed = seed * 1103515245u + 12345u;
                r[i] = (uint8_t)(seed >> 16);
            }
            f.len = (uint8_t)(r[8] % 16 < 12 ? 8 : 1 + r[8] % 8);
            memcpy(f.data, r, 8);
            f.data[0] = plausible_command(&c->sdo, r[0]);
            if (f.data[0] != 0xA2 && (f.data[0] & 0xE0) != 0 && r[1] % 4 != 0) {
                /* the multiplexer, and a size or block size near the buffer's */
                co_put_u16(&f.data[1], 0x2000);
                f.data[3] = 5;
                co_put_u32(&f.data[4], r[4] % 48);
            } else if (f.data[0] == 0xA2) {
                f.data[1] = r[1] % 6;
                f.data[2] = r[2] % 6;
            }
            co_sdo_client_receive(&c->sdo, &f, 0);
        }
        if (c->results == 0)
            co_sdo_client_process(&c->sdo, 10000);
        ck_assert_uint_eq(c->results, 1);
        ck_assert(!co_sdo_client_busy(&c->sdo));
        if (c->result.status == CO_SDO_CLIENT_OK) {
            ck_assert_uint_le(c->result.size, cap);
            ok++;
        }
        for (uint32_t i = cap; i < 64; i++)
            ck_assert_msg(rx[i] == 0xEE, "run %u: byte %u beyond cap %u written", run, i, cap);
    }
    ck_assert_uint_gt(ok, 100); /* the answers reach the end of transfers, not only initiates */
}
END_TEST

/* Bad requests and configurations are refused without a frame. */
START_TEST(refused_requests)
{
    client_t *c = &clients[0];
    ck_assert_int_eq(co_sdo_client_upload(&c->sdo, 0x2000, 1, rx, 4, CO_SDO_CLIENT_AUTO, 0, 0),
                     CO_SDO_CLIENT_ERR_ARG);
    ck_assert_int_eq(co_sdo_client_upload(&c->sdo, 0x2000, 1, NULL, 4, CO_SDO_CLIENT_AUTO, 10, 0),
                     CO_SDO_CLIENT_ERR_ARG);
    ck_assert_int_eq(
        co_sdo_client_download(&c->sdo, 0x2000, 1, tx, 4, (co_sdo_client_mode_t)7, 10, 0),
        CO_SDO_CLIENT_ERR_ARG);
    expect_none();
    ck_assert_int_eq(co_sdo_client_upload(&c->sdo, 0x2000, 1, rx, 4, CO_SDO_CLIENT_AUTO, 10, 0), 0);
    ck_assert_int_eq(co_sdo_client_download(&c->sdo, 0x2000, 1, tx, 4, CO_SDO_CLIENT_AUTO, 10, 0),
                     CO_SDO_CLIENT_ERR_BUSY);
    ck_assert_uint_eq(bus.count - bus.next, 1);
    co_sdo_client_config_t config = {.server_node_id = 0, .send = bus_send, .done = client_done};
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), CO_SDO_CLIENT_ERR_CONFIG);
    config.server_node_id = 128;
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), CO_SDO_CLIENT_ERR_CONFIG);
    config = (co_sdo_client_config_t){
        .request_id = 0x800, .response_id = 0x580, .send = bus_send, .done = client_done};
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), CO_SDO_CLIENT_ERR_CONFIG);
    config.request_id = 0x600;
    config.blksize = 128;
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), CO_SDO_CLIENT_ERR_CONFIG);
    config.blksize = 0;
    config.done = NULL;
    ck_assert_int_eq(co_sdo_client_init(&c->sdo, &config), CO_SDO_CLIENT_ERR_CONFIG);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_client");
    TCase *tc = tcase_create("sdo_client");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, expedited_frames);
    tcase_add_test(tc, segmented_frames);
    tcase_add_test(tc, block_frames);
    tcase_add_test(tc, segmented_sizes);
    tcase_add_test(tc, block_sizes);
    tcase_add_test(tc, auto_mode);
    tcase_add_test(tc, large_domain);
    tcase_add_test(tc, server_aborts);
    tcase_add_test(tc, server_abort_without_code);
    tcase_add_test(tc, client_abort_toggle);
    tcase_add_test(tc, client_abort_crc);
    tcase_add_test(tc, client_abort_sequence);
    tcase_add_test(tc, client_abort_block_size);
    tcase_add_test(tc, client_abort_command);
    tcase_add_test(tc, client_abort_no_memory);
    tcase_add_test(tc, client_abort_length);
    tcase_add_test(tc, timeout);
    tcase_add_test(tc, cancel);
    tcase_add_test(tc, block_download_lost_segment);
    tcase_add_test(tc, block_upload_repeated_segment);
    tcase_add_test(tc, block_upload_lost_segment);
    tcase_add_test(tc, block_size_negotiation);
    tcase_add_test(tc, several_clients);
    tcase_add_test(tc, hundred_kilobytes_block_download);
    tcase_add_test(tc, hundred_kilobytes_block_upload);
    tcase_add_test(tc, random_answers);
    tcase_add_test(tc, refused_requests);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
