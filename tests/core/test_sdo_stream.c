/* SPDX-License-Identifier: Apache-2.0 */
/* Streamed DOMAIN entries (co_od_stream_t): the core's SDO client against the core's SDO server on
 * an in-process bus, frame by frame with injected time. The server (node 4) holds a 100 kB value
 * in its application, not in the dictionary, and has a transfer buffer of 16 bytes only: every
 * transfer type in both directions at the size boundaries and at 102400 bytes, with exact frame
 * counts and contents, a lost block segment, a CRC error, aborts by the client, the timeout and
 * sizes the application refuses. The application checks that it is written in sequence, each
 * byte once, and counts the ends of downloads. */
#include "check_main.h"
#include "co/co_sdo_client.h"
#include "test_bus.h"

#include <stddef.h>
#include <string.h>

#define SERVER_ID 4u
#define VALUE_MAX 102400u /* the largest value the application takes */
#define LOG_MAX 30000u    /* frames of one test (a 102400-byte segmented transfer: 29260) */
#define BUFFER_SIZE 16u   /* the server's transfer buffer: far too small for the value */
#define STREAM_INDEX 0x2100u
#define STREAM_SUB 1u

/* The application's streamed value: what an upload reads, and a download in progress. */
typedef struct app {
    uint8_t value[VALUE_MAX];
    uint32_t size;
    uint8_t incoming[VALUE_MAX];
    uint32_t written; /* bytes of the download in progress */
    bool no_room;     /* begin refuses with 0x05040005 */
    unsigned begins, ends, ends_ok;
    uint32_t end_total;
} app_t;

static app_t app;

static uint32_t stream_size(co_node_t *node, const co_od_entry_t *entry, uint32_t *size)
{
    (void)node;
    (void)entry;
    *size = app.size;
    return 0;
}

static uint32_t stream_read(co_node_t *node, const co_od_entry_t *entry, uint32_t offset,
                            uint8_t *buf, size_t len)
{
    (void)node;
    (void)entry;
    ck_assert_uint_le(offset + len, app.size);
    memcpy(buf, &app.value[offset], len);
    return 0;
}

static uint32_t stream_begin(co_node_t *node, const co_od_entry_t *entry, bool size_indicated,
                             uint32_t size)
{
    (void)node;
    (void)entry;
    app.begins++;
    if (size_indicated && size > VALUE_MAX)
        return CO_SDO_ABORT_LENGTH_HIGH;
    if (app.no_room)
        return CO_SDO_ABORT_NO_MEMORY;
    app.written = 0;
    return 0;
}

static uint32_t stream_write(co_node_t *node, const co_od_entry_t *entry, uint32_t offset,
                             const uint8_t *data, size_t len)
{
    (void)node;
    (void)entry;
    ck_assert_msg(offset == app.written, "write at %u after %u bytes", offset, app.written);
    ck_assert_uint_ge(len, 1);
    if (offset + len > VALUE_MAX)
        return CO_SDO_ABORT_LENGTH_HIGH;
    memcpy(&app.incoming[offset], data, len);
    app.written += (uint32_t)len;
    return 0;
}

static uint32_t stream_end(co_node_t *node, const co_od_entry_t *entry, uint32_t total, bool ok)
{
    (void)node;
    (void)entry;
    app.ends++;
    app.end_total = total;
    if (ok) {
        ck_assert_uint_eq(total, app.written);
        memcpy(app.value, app.incoming, total);
        app.size = total;
        app.ends_ok++;
    }
    return 0;
}

static const co_od_stream_t stream = {
    .size = stream_size,
    .read = stream_read,
    .begin = stream_begin,
    .write = stream_write,
    .end = stream_end,
};

typedef struct od_data {
    uint8_t x1000[4];
    uint8_t x2100_0[1];
} od_data_t;

static const od_data_t defaults = {.x2100_0 = {1}};

static const co_od_entry_t entries[] = {
    {0x1000, 0, CO_DT_UNSIGNED32, CO_OD_ACCESS_RO, 4, offsetof(od_data_t, x1000), NULL, NULL},
    {0x2100, 0, CO_DT_UNSIGNED8, CO_OD_ACCESS_RO, 1, offsetof(od_data_t, x2100_0), NULL, NULL},
    {0x2100, 1, CO_DT_DOMAIN, CO_OD_ACCESS_RW | CO_OD_STREAM, 0, 0, NULL, &stream.hook},
};

static const co_od_t od = {
    .name = "sdo-stream",
    .entries = entries,
    .count = sizeof(entries) / sizeof(entries[0]),
    .data_size = sizeof(od_data_t),
    .defaults = (const uint8_t *)&defaults,
    .streaming = &co_od_streaming,
};

/* The bus: every frame sent is logged, then delivered in order to the server and the client;
 * frames at chosen log positions are lost. */
typedef struct bus {
    co_frame_t log[LOG_MAX];
    size_t count;
    size_t delivered;
    size_t next; /* first frame not yet checked by expect() */
    co_time_t now;
    size_t drop;
} bus_t;

static bus_t bus;
static co_node_t server;
static od_data_t server_data;
static uint8_t buffer_data[BUFFER_SIZE];
static co_sdo_buffer_t buffer;
static co_sdo_client_t client;
static co_sdo_client_result_t result;
static unsigned results;
static uint8_t tx[VALUE_MAX + 1];
static uint8_t rx[VALUE_MAX + 1];

static void bus_send(void *user, const co_frame_t *frame)
{
    (void)user;
    ck_assert_msg(bus.count < LOG_MAX, "bus log overflow");
    bus.log[bus.count++] = *frame;
}

/* Delivers the frames not yet delivered, and those they cause, up to log position `until`. */
static void pump_until(size_t until)
{
    while (bus.delivered < bus.count && bus.delivered < until) {
        size_t position = bus.delivered++;
        co_frame_t frame = bus.log[position];
        if (position == bus.drop)
            continue;
        co_node_receive(&server, &frame, bus.now);
        co_node_process(&server, bus.now);
        co_sdo_client_receive(&client, &frame, bus.now);
    }
}

static void pump(void)
{
    pump_until(SIZE_MAX);
}

static void client_done(void *user, const co_sdo_client_result_t *r)
{
    (void)user;
    result = *r;
    results++;
}

static void setup(void)
{
    memset(&bus, 0, sizeof(bus));
    memset(&app, 0, sizeof(app));
    bus.drop = SIZE_MAX;
    buffer = (co_sdo_buffer_t){.data = buffer_data, .size = sizeof(buffer_data)};
    co_node_config_t config = {
        .node_id = SERVER_ID,
        .od = &od,
        .od_data = (uint8_t *)&server_data,
        .send = bus_send,
        .sdo_buffer = &buffer,
    };
    ck_assert_int_eq(co_node_init(&server, &config), 0);
    co_node_start(&server, bus.now);
    pump();
    bus.next = bus.count; /* the boot-up */
    co_sdo_client_config_t client_config = {
        .server_node_id = SERVER_ID, .send = bus_send, .done = client_done};
    ck_assert_int_eq(co_sdo_client_init(&client, &client_config), 0);
    results = 0;
    for (size_t i = 0; i < sizeof(tx); i++)
        tx[i] = (uint8_t)(i * 131u + (i >> 8));
    memcpy(tx, "ABCDEFGHIJKLMNOPQRSTUVWXYZ", 26);
    memcpy(app.value, tx, VALUE_MAX);
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

/* The last `n` frames of the log are next. */
static void skip_to_last(size_t n)
{
    ck_assert_uint_ge(bus.count, bus.next + n);
    bus.next = bus.count - n;
}

/* A frame of the test in the client's place, delivered at once. */
static void inject(const char *text)
{
    co_frame_t f = test_frame(text);
    bus_send(NULL, &f);
    pump();
    bus.next++;
}

static void expect_result(co_sdo_client_status_t status, uint32_t code, uint32_t size)
{
    ck_assert_uint_eq(results, 1);
    ck_assert_int_eq(result.status, status);
    ck_assert_uint_eq(result.abort_code, code);
    ck_assert_uint_eq(result.size, size);
}

static void download_start(uint32_t len, co_sdo_client_mode_t mode)
{
    results = 0;
    ck_assert_int_eq(
        co_sdo_client_download(&client, STREAM_INDEX, STREAM_SUB, tx, len, mode, 100, bus.now), 0);
}

static void download(uint32_t len, co_sdo_client_mode_t mode)
{
    download_start(len, mode);
    pump();
}

static void upload(co_sdo_client_mode_t mode)
{
    results = 0;
    memset(rx, 0, sizeof(rx));
    ck_assert_int_eq(
        co_sdo_client_upload(&client, STREAM_INDEX, STREAM_SUB, rx, sizeof(rx), mode, 100, bus.now),
        0);
    pump();
}

/* One committed download of `len` bytes of tx. */
static void expect_committed(uint32_t len)
{
    expect_result(CO_SDO_CLIENT_OK, 0, len);
    ck_assert_uint_eq(app.begins, 1);
    ck_assert_uint_eq(app.ends, 1);
    ck_assert_uint_eq(app.ends_ok, 1);
    ck_assert_uint_eq(app.size, len);
    ck_assert_msg(memcmp(app.value, tx, len) == 0, "%u bytes committed differ", len);
}

/* One download that ended without a commit. */
static void expect_discarded(void)
{
    ck_assert_uint_eq(app.begins, 1);
    ck_assert_uint_eq(app.ends, 1);
    ck_assert_uint_eq(app.ends_ok, 0);
}

static void expect_uploaded(uint32_t len)
{
    expect_result(CO_SDO_CLIENT_OK, 0, len);
    ck_assert_msg(memcmp(rx, tx, len) == 0, "%u bytes uploaded differ", len);
    ck_assert_uint_eq(app.begins, 0);
}

/* 102400 bytes are 14629 segments (14628 of 7 bytes, one of 4). */
START_TEST(segmented_download_100k)
{
    download(VALUE_MAX, CO_SDO_CLIENT_SEGMENTED);
    expect("604#2100210100900100");
    expect("584#6000210100000000");
    expect("604#00414243444546 47");
    expect("584#2000000000000000");
    expect("604#1048494A4B4C4D4E");
    expect("584#3000000000000000");
    ck_assert_uint_eq(bus.count - 1, 2 + 2 * 14629u);
    skip_to_last(2);
    char last[32];
    co_frame_t want = {.id = 0x604, .len = 8, .data = {0x07}}; /* toggle 0, 3 unused, c */
    memcpy(&want.data[1], &tx[VALUE_MAX - 4], 4);
    expect(test_format(&want, last));
    expect("584#2000000000000000");
    expect_committed(VALUE_MAX);
}
END_TEST

START_TEST(segmented_upload_100k)
{
    app.size = VALUE_MAX;
    upload(CO_SDO_CLIENT_SEGMENTED);
    expect("604#4000210100000000");
    expect("584#4100210100900100");
    expect("604#6000000000000000");
    expect("584#00414243444546 47");
    ck_assert_uint_eq(bus.count - 1, 2 + 2 * 14629u);
    skip_to_last(2);
    expect("604#6000000000000000");
    char last[32];
    co_frame_t want = {.id = 0x584, .len = 8, .data = {0x07}}; /* toggle 0, 3 unused, c */
    memcpy(&want.data[1], &tx[VALUE_MAX - 4], 4);
    expect(test_format(&want, last));
    expect_uploaded(VALUE_MAX);
}
END_TEST

/* 14629 segments in 116 sub-blocks of 127 (the last of 24); the server's block size is 127
 * whatever its buffer, and the CRC covers the whole value. */
START_TEST(block_download_100k)
{
    download(VALUE_MAX, CO_SDO_CLIENT_BLOCK);
    expect("604#C600210100900100");
    expect("584#A40021017F000000");
    expect("604#01414243444546 47");
    ck_assert_uint_eq(bus.count - 1, 2 + 14629u + 116u + 2);
    bus.next = 1 + 2 + 127;
    expect("584#A27F7F0000000000");
    skip_to_last(3);
    expect("584#A2187F0000000000");
    char end[32];
    co_frame_t want = {.id = 0x604, .len = 8, .data = {0xCD}}; /* 3 unused, end */
    co_put_u16(&want.data[1], co_sdo_crc16(tx, VALUE_MAX));
    expect(test_format(&want, end));
    expect("584#A100000000000000");
    expect_committed(VALUE_MAX);
}
END_TEST

START_TEST(block_upload_100k)
{
    app.size = VALUE_MAX;
    upload(CO_SDO_CLIENT_BLOCK);
    expect("604#A40021017F000000");
    expect("584#C600210100900100");
    expect("604#A300000000000000");
    expect("584#01414243444546 47");
    ck_assert_uint_eq(bus.count - 1, 3 + 14629u + 116u + 2);
    bus.next = 1 + 3 + 127;
    expect("604#A27F7F0000000000");
    skip_to_last(3);
    expect("604#A2187F0000000000");
    char end[32];
    co_frame_t want = {.id = 0x584, .len = 8, .data = {0xCD}};
    co_put_u16(&want.data[1], co_sdo_crc16(tx, VALUE_MAX));
    expect(test_format(&want, end));
    expect("604#A100000000000000");
    expect_uploaded(VALUE_MAX);
}
END_TEST

static const uint32_t boundary[] = {0, 1, 4, 5, 7, 8, 889, 890};
#define BOUNDARIES (sizeof(boundary) / sizeof(boundary[0]))

/* Each size down and up again with each protocol; 1..4 bytes go expedited in AUTO mode and in a
 * plain upload, through the same stream. */
START_TEST(boundaries)
{
    static const co_sdo_client_mode_t modes[] = {CO_SDO_CLIENT_AUTO, CO_SDO_CLIENT_SEGMENTED,
                                                 CO_SDO_CLIENT_BLOCK};
    for (size_t m = 0; m < 3; m++) {
        for (size_t i = 0; i < BOUNDARIES; i++) {
            uint32_t len = boundary[i];
            memset(&app, 0, sizeof(app));
            bus.count = bus.delivered = bus.next = 0;
            download(len, modes[m]);
            expect_committed(len);
            bool expedited = modes[m] == CO_SDO_CLIENT_AUTO && len >= 1 && len <= 4;
            if (expedited)
                ck_assert_uint_eq(bus.count, 2);
            upload(modes[m]);
            expect_result(CO_SDO_CLIENT_OK, 0, len);
            ck_assert_msg(memcmp(rx, tx, len) == 0, "%u bytes read back differ", len);
        }
    }
}
END_TEST

START_TEST(expedited_frames)
{
    download(3, CO_SDO_CLIENT_AUTO);
    expect("604#2700210141424300");
    expect("584#6000210100000000");
    expect_committed(3);
    upload(CO_SDO_CLIENT_SEGMENTED);
    expect("604#4000210100000000");
    expect("584#4700210141424300");
    expect_result(CO_SDO_CLIENT_OK, 0, 3);
}
END_TEST

/* Segment 2 of 4 lost: the server acknowledges segment 1 and the application gets only the
 * segments in sequence, each once; the client resends from segment 2. */
START_TEST(block_download_lost_segment)
{
    bus.drop = bus.count + 3; /* initiate, response, segment 1, segment 2 */
    download(26, CO_SDO_CLIENT_BLOCK);
    expect("604#C60021011A000000");
    expect("584#A40021017F000000");
    expect("604#01414243444546 47");
    expect("604#0248494A4B4C4D4E"); /* lost */
    expect("604#034F505152535455");
    expect("604#8456575859 5A0000");
    expect("584#A2017F0000000000");
    expect("604#0148494A4B4C4D4E");
    expect("604#024F505152535455");
    expect("604#8356575859 5A0000");
    expect("584#A2037F0000000000");
    expect_committed(26);
}
END_TEST

/* The same in the middle of 100 kB: the value arrives whole and its CRC matches. */
START_TEST(block_download_100k_lost_segment)
{
    /* After the boot-up, the initiate and its response, sub-blocks of 127 segments and an
     * acknowledge: segment 50 of sub-block 4 is lost. */
    bus.drop = 3 + 3 * 128 + 49;
    download(VALUE_MAX, CO_SDO_CLIENT_BLOCK);
    bus.next = 3 + 3 * 128 + 127;
    expect("584#A2317F0000000000"); /* 49 acknowledged */
    expect_committed(VALUE_MAX);
}
END_TEST

START_TEST(block_upload_100k_lost_segment)
{
    app.size = VALUE_MAX;
    bus.drop = 4 + 128 + 9; /* segment 10 of sub-block 2, after initiate, response and start */
    upload(CO_SDO_CLIENT_BLOCK);
    bus.next = 4 + 128 + 127;
    expect("604#A2097F0000000000"); /* 9 acknowledged */
    expect_uploaded(VALUE_MAX);
}
END_TEST

/* A block download whose end request carries a wrong CRC: 0x05040004, and the application
 * discards the value. */
START_TEST(crc_error)
{
    inject("604#C600210109000000");
    expect("584#A40021017F000000");
    inject("604#01414243444546 47");
    inject("604#8248490000000000");
    expect("584#A2027F0000000000");
    inject("604#D534120000000000"); /* 5 unused, a CRC that is not the value's */
    expect("584#8000210104000405");
    expect_discarded();
    ck_assert_uint_eq(app.end_total, 9);
    ck_assert_uint_eq(app.written, 9);
    inject("604#C600210102000000"); /* a new transfer is not disturbed by the old */
    expect("584#A40021017F000000");
    ck_assert_uint_eq(app.ends, 1);
}
END_TEST

/* The client aborts a segmented download half-way: the application hears once, and no byte
 * more is written. */
START_TEST(client_abort_segmented)
{
    download_start(VALUE_MAX, CO_SDO_CLIENT_SEGMENTED);
    pump_until(2 + 2 * 1000);
    uint32_t written = app.written;
    ck_assert_uint_eq(written, 7 * 1000);
    bus.delivered = bus.next = bus.count; /* the server's response is lost */
    inject("604#8000210100000008");
    ck_assert_uint_eq(bus.count, bus.delivered);
    expect_discarded();
    ck_assert_uint_eq(app.end_total, written);
    inject("604#00414243444546 47"); /* a late segment is not taken */
    expect("584#8000000001000405");
    ck_assert_uint_eq(app.written, written);
    ck_assert_uint_eq(app.ends, 1);
}
END_TEST

START_TEST(client_abort_block)
{
    download_start(VALUE_MAX, CO_SDO_CLIENT_BLOCK);
    pump_until(3 + 5 * 128 + 59); /* up to segment 59 of sub-block 6 */
    bus.delivered = bus.next = bus.count;
    inject("604#8000210100000008");
    expect_discarded();
    ck_assert_uint_eq(app.written, 7u * (5 * 127 + 59));
    co_sdo_client_process(&client, bus.now + 200000); /* the client gives up too */
    pump();
    ck_assert_uint_eq(app.ends, 1);
}
END_TEST

/* An upload aborted half-way: no end (there was no begin), the next transfer works. */
START_TEST(client_abort_upload)
{
    app.size = VALUE_MAX;
    results = 0;
    ck_assert_int_eq(co_sdo_client_upload(&client, STREAM_INDEX, STREAM_SUB, rx, sizeof(rx),
                                          CO_SDO_CLIENT_BLOCK, 100, bus.now),
                     0);
    pump_until(4 + 20);
    bus.delivered = bus.next = bus.count;
    inject("604#8000210100000008");
    ck_assert_uint_eq(app.ends, 0);
    co_sdo_client_process(&client, bus.now + 200000);
    pump();
    bus.next = bus.count;
    upload(CO_SDO_CLIENT_SEGMENTED);
    expect_uploaded(VALUE_MAX);
}
END_TEST

/* The server's timeout ends a stalled streamed download: 0x05040000 and one end. */
START_TEST(timeout)
{
    co_sdo_set_timeout(&server, 1000);
    inject("604#2100210100900100");
    expect("584#6000210100000000");
    inject("604#00414243444546 47");
    expect("584#2000000000000000");
    bus.now += 1000;
    co_node_process(&server, bus.now);
    expect("584#8000210100000405");
    expect_discarded();
    ck_assert_uint_eq(app.end_total, 7);
}
END_TEST

/* A new request replaces a streamed download under way: its end comes first. */
START_TEST(replaced_by_new_request)
{
    inject("604#2100210100900100");
    expect("584#6000210100000000");
    inject("604#4000100000000000");
    expect("584#4300100000000000");
    expect_discarded();
}
END_TEST

/* A reset of communication ends a streamed download under way like an abort. */
START_TEST(reset_ends_download)
{
    inject("604#2100210100900100");
    expect("584#6000210100000000");
    inject("000#8204");
    expect("704#00");
    expect_discarded();
}
END_TEST

/* Sizes the application refuses at the initiate, before any data: 0x06070012 above what the
 * object can hold, 0x05040005 when it has no room now; no end follows a refused begin. */
START_TEST(size_too_big)
{
    download(VALUE_MAX + 1, CO_SDO_CLIENT_SEGMENTED);
    expect("604#2100210101900100");
    expect("584#8000210112000706");
    expect_result(CO_SDO_CLIENT_SERVER_ABORT, CO_SDO_ABORT_LENGTH_HIGH, 0);
    download(VALUE_MAX + 1, CO_SDO_CLIENT_BLOCK);
    expect("604#C600210101900100");
    expect("584#8000210112000706");
    expect_result(CO_SDO_CLIENT_SERVER_ABORT, CO_SDO_ABORT_LENGTH_HIGH, 0);
    app.no_room = true;
    download(100, CO_SDO_CLIENT_BLOCK);
    expect("604#C600210164000000");
    expect("584#8000210105000405");
    expect_result(CO_SDO_CLIENT_SERVER_ABORT, CO_SDO_ABORT_NO_MEMORY, 0);
    download(2, CO_SDO_CLIENT_AUTO);
    expect("604#2B00210141420000");
    expect("584#8000210105000405");
    ck_assert_uint_eq(app.begins, 4);
    ck_assert_uint_eq(app.ends, 0);
}
END_TEST

/* More data than announced never reaches the application: 0x06070010 at the first byte too
 * many. */
START_TEST(more_than_announced)
{
    inject("604#2100210109000000");
    expect("584#6000210100000000");
    inject("604#00414243444546 47");
    expect("584#2000000000000000");
    inject("604#1048494A4B4C4D4E");
    expect("584#8000210110000706");
    expect_discarded();
    ck_assert_uint_eq(app.written, 7);
}
END_TEST

/* A streamed entry must be a DOMAIN of size 0 with the functions of its access. */
START_TEST(validation)
{
    static const co_od_stream_t read_only = {.size = stream_size, .read = stream_read};
    co_od_entry_t bad[2] = {entries[0], entries[2]};
    co_od_t table = od;
    table.entries = bad;
    table.count = 2;
    uint16_t position;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_VALID);
    bad[1].size = 1;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_ERR_STREAM);
    ck_assert_uint_eq(position, 1);
    bad[1] = entries[2];
    bad[1].type = CO_DT_OCTET_STRING;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_ERR_STREAM);
    bad[1] = entries[2];
    bad[1].hook = &read_only.hook;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_ERR_STREAM);
    bad[1].flags = CO_OD_ACCESS_RO | CO_OD_STREAM;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_VALID);
    bad[1].hook = NULL;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_ERR_STREAM);
    ck_assert_ptr_null(co_od_stream(&entries[1]));
    ck_assert_ptr_eq(co_od_stream(&entries[2]), &stream);
}
END_TEST

/* A dictionary with a streamed entry but without the streaming code (co_od_t.streaming NULL: a
 * table written by hand) is refused at that entry, and so is a node on it: the SDO server never
 * meets a stream it has no code for. */
START_TEST(streamed_entry_without_streaming_code)
{
    co_od_t table = od;
    table.streaming = NULL;
    uint16_t position;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_ERR_STREAM);
    ck_assert_uint_eq(position, 2);
    co_node_t node;
    co_node_config_t config = {.node_id = 4,
                               .od = &table,
                               .od_data = (uint8_t *)&server_data,
                               .send = bus_send,
                               .sdo_buffer = &buffer};
    ck_assert_int_eq(co_node_init(&node, &config), CO_OD_ERR_STREAM);
    table.entries = entries;
    table.count = 2;
    ck_assert_int_eq(co_od_validate(&table, &position), CO_OD_VALID);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_stream");
    TCase *tc = tcase_create("stream");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, segmented_download_100k);
    tcase_add_test(tc, segmented_upload_100k);
    tcase_add_test(tc, block_download_100k);
    tcase_add_test(tc, block_upload_100k);
    tcase_add_test(tc, boundaries);
    tcase_add_test(tc, expedited_frames);
    tcase_add_test(tc, block_download_lost_segment);
    tcase_add_test(tc, block_download_100k_lost_segment);
    tcase_add_test(tc, block_upload_100k_lost_segment);
    tcase_add_test(tc, crc_error);
    tcase_add_test(tc, client_abort_segmented);
    tcase_add_test(tc, client_abort_block);
    tcase_add_test(tc, client_abort_upload);
    tcase_add_test(tc, timeout);
    tcase_add_test(tc, replaced_by_new_request);
    tcase_add_test(tc, reset_ends_download);
    tcase_add_test(tc, size_too_big);
    tcase_add_test(tc, more_than_announced);
    tcase_add_test(tc, validation);
    tcase_add_test(tc, streamed_entry_without_streaming_code);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
