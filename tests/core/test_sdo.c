/* SPDX-License-Identifier: Apache-2.0 */
/* SDO server, frame by frame on the in-process bus with the test dictionary, node-id 4: expedited,
 * segmented and block transfers of every type in 2000h, every abort code a request can provoke,
 * the protocol timeout, client aborts, NMT states, short frames and the ATV312 manual's frames. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RX_ID 0x604u
#define TX_ID 0x584u

static test_node_t t;

static void setup(void)
{
    test_node_start(&t, 4, NULL, NULL);
}

static void frame_text(char *buf, uint32_t id, const uint8_t *data, size_t len)
{
    int n = sprintf(buf, "%03X#", (unsigned)id);
    for (size_t i = 0; i < len; i++)
        n += sprintf(buf + n, "%02X", data[i]);
}

static void rx8(const uint8_t p[8])
{
    char text[32];
    frame_text(text, RX_ID, p, 8);
    test_rx(&t, text);
}

#define expect8(p) expect8_at(p, __FILE__, __LINE__)
static void expect8_at(const uint8_t p[8], const char *file, int line)
{
    char text[32];
    frame_text(text, TX_ID, p, 8);
    test_expect_at(&t, text, file, line);
}

/* A client segment: command byte and up to 7 data bytes, padded with zeros. */
static void segment_frame(uint8_t p[8], uint8_t command, const uint8_t *data, size_t count)
{
    memset(p, 0, 8);
    p[0] = command;
    if (count > 0)
        memcpy(&p[1], data, count);
}

static void initiate_frame(uint8_t p[8], uint8_t command, uint16_t index, uint8_t sub,
                           uint32_t value)
{
    p[0] = command;
    co_put_u16(&p[1], index);
    p[3] = sub;
    co_put_u32(&p[4], value);
}

static size_t min7(size_t n)
{
    return n < 7 ? n : 7;
}

/* Segmented download (CiA 301 download initiate and segment protocols): initiate, then segments
 * with alternating toggle, the server confirming each one; the final confirmation is left for the
 * caller when `last_reply` is false (to check an abort instead). */
static void segmented_download(uint16_t index, uint8_t sub, const uint8_t *data, size_t len,
                               bool indicate, bool last_reply)
{
    uint8_t p[8], r[8];
    initiate_frame(p, indicate ? 0x21 : 0x20, index, sub, indicate ? (uint32_t)len : 0);
    rx8(p);
    initiate_frame(r, 0x60, index, sub, 0);
    expect8(r);
    uint8_t toggle = 0;
    size_t off = 0;
    for (;;) {
        size_t count = min7(len - off);
        bool last = off + count == len;
        segment_frame(p, (uint8_t)(toggle | ((7 - count) << 1) | (last ? 1 : 0)), data + off,
                      count);
        rx8(p);
        off += count;
        if (last && !last_reply)
            return;
        segment_frame(r, (uint8_t)(0x20 | toggle), NULL, 0);
        expect8(r);
        if (last)
            return;
        toggle ^= 0x10;
    }
}

static void segmented_upload(uint16_t index, uint8_t sub, const uint8_t *data, size_t len)
{
    uint8_t p[8], r[8];
    initiate_frame(p, 0x40, index, sub, 0);
    rx8(p);
    initiate_frame(r, 0x41, index, sub, (uint32_t)len);
    expect8(r);
    uint8_t toggle = 0;
    size_t off = 0;
    for (;;) {
        size_t count = min7(len - off);
        bool last = off + count == len;
        segment_frame(p, (uint8_t)(0x60 | toggle), NULL, 0);
        rx8(p);
        segment_frame(r, (uint8_t)(toggle | ((7 - count) << 1) | (last ? 1 : 0)), data + off,
                      count);
        expect8(r);
        off += count;
        if (last)
            return;
        toggle ^= 0x10;
    }
}

/* Block download (CiA 301 block download protocols). `blksizes` are the server's expected block
 * sizes: the initiate response's, then each acknowledge's. */
static void block_download(uint16_t index, uint8_t sub, const uint8_t *data, size_t len, bool crc,
                           const uint8_t *blksizes, size_t acks)
{
    uint8_t p[8], r[8];
    initiate_frame(p, crc ? 0xC6 : 0xC2, index, sub, (uint32_t)len);
    rx8(p);
    initiate_frame(r, crc ? 0xA4 : 0xA0, index, sub, blksizes[0]);
    expect8(r);
    size_t off = 0, k = 0, count = 0;
    bool last = false;
    while (!last) {
        uint8_t seqno = 0;
        while (seqno < blksizes[k] && !last) {
            count = min7(len - off);
            last = off + count == len;
            seqno++;
            segment_frame(p, (uint8_t)((last ? 0x80 : 0) | seqno), data + off, count);
            rx8(p);
            off += count;
        }
        k++;
        ck_assert_uint_le(k, acks);
        uint8_t ack[8] = {0xA2, seqno, blksizes[k]};
        expect8(ack);
    }
    ck_assert_uint_eq(k, acks);
    uint8_t end[8] = {(uint8_t)(0xC1 | ((7 - count) << 2))};
    if (crc)
        co_put_u16(&end[1], co_sdo_crc16(data, len));
    rx8(end);
    uint8_t done[8] = {0xA1};
    expect8(done);
}

/* Block upload with a constant client block size, every sub-block acknowledged in full. */
static void block_upload(uint16_t index, uint8_t sub, const uint8_t *data, size_t len, bool crc,
                         uint8_t blksize)
{
    uint8_t p[8] = {crc ? 0xA4 : 0xA0}, r[8];
    co_put_u16(&p[1], index);
    p[3] = sub;
    p[4] = blksize;
    p[5] = 0;
    p[6] = p[7] = 0;
    rx8(p);
    initiate_frame(r, crc ? 0xC6 : 0xC2, index, sub, (uint32_t)len);
    expect8(r);
    uint8_t start[8] = {0xA3};
    rx8(start);
    size_t off = 0, count = 0;
    bool last = false;
    while (!last) {
        uint8_t seqno = 0;
        while (seqno < blksize && !last) {
            count = min7(len - off);
            last = off + count == len;
            seqno++;
            segment_frame(r, (uint8_t)((last ? 0x80 : 0) | seqno), data + off, count);
            expect8(r);
            off += count;
        }
        test_expect_none(&t);
        uint8_t ack[8] = {0xA2, seqno, blksize};
        rx8(ack);
    }
    uint8_t end[8] = {(uint8_t)(0xC1 | ((7 - count) << 2))};
    if (crc)
        co_put_u16(&end[1], co_sdo_crc16(data, len));
    expect8(end);
    uint8_t done[8] = {0xA1};
    rx8(done);
    test_expect_none(&t);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
}

static const uint8_t *entry_bytes(uint16_t index, uint8_t sub)
{
    return co_od_bytes(&t.node, co_od_find(&test_od, index, sub));
}

static const char hello[] = "Hello, CANopen!"; /* 15 bytes */

/* ---- ATV312 manual (example frames T31-08..T31-15, docs/manuals.md) ---------------------- */

START_TEST(atv312_manual_frames)
{
    test_rx(&t, "604#2B3C2002E8030000");     /* T31-10 */
    test_expect(&t, "584#603C200200000000"); /* T31-11 */
    test_rx(&t, "604#403C200200000000");     /* T31-08 */
    test_expect(&t, "584#4B3C2002E8030000"); /* T31-09 */
    test_rx(&t, "604#2B0C1000F4010000");     /* T31-12 */
    test_expect(&t, "584#600C100000000000"); /* T31-13 */
    test_rx(&t, "604#2F0D100004000000");     /* T31-14 */
    test_expect(&t, "584#600D100000000000"); /* T31-15 */
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 2), 1000);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x100D, 0), 4);
    test_expect_none(&t);
}
END_TEST

/* ---- Expedited ---------------------------------------------------------------------------- */

START_TEST(expedited_read_every_fixed_type)
{
    co_od_set_value(&t.node, 0x2000, 0x01, -5);
    co_od_set_value(&t.node, 0x2000, 0x02, -2);
    co_od_set_value(&t.node, 0x2000, 0x03, 0x12345678);
    co_od_set_value(&t.node, 0x2000, 0x07, 0xDEADBEEF);
    co_od_set_value(&t.node, 0x2000, 0x09, 0x3F800000); /* 1.0f */
    co_od_set_value(&t.node, 0x2000, 0x0A, 1);
    co_od_set_value(&t.node, 0x2000, 0x0E, -100);
    static const char *const exchanges[][2] = {
        {"604#4000200000000000", "584#4F00200012000000"},
        {"604#4000200100000000", "584#4F002001FB000000"},
        {"604#4000200200000000", "584#4B002002FEFF0000"},
        {"604#4000200300000000", "584#4300200378563412"},
        {"604#4000200500000000", "584#4F00200532000000"},
        {"604#4000200600000000", "584#4B002006E8030000"},
        {"604#4000200700000000", "584#43002007EFBEADDE"},
        {"604#4000200900000000", "584#430020090000803F"},
        {"604#4000200A00000000", "584#4F00200A01000000"},
        {"604#4000200E00000000", "584#4B00200E9CFF0000"},
        {"604#4000200F00000000", "584#4B00200F00000000"},
        {"604#4000100000000000", "584#4300100092010100"},
        {"604#4000120100000000", "584#4300120104060000"},
        {"604#4000120200000000", "584#4300120284050000"},
    };
    for (size_t i = 0; i < sizeof(exchanges) / sizeof(exchanges[0]); i++) {
        test_rx(&t, exchanges[i][0]);
        test_expect(&t, exchanges[i][1]);
    }
    unsigned reads = test_od_hook_reads;
    test_rx(&t, "604#4000201000000000");
    test_expect(&t, "584#4B00201000000000");
    ck_assert_uint_eq(test_od_hook_reads, reads + 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(expedited_write_every_fixed_type)
{
    static const char *const exchanges[][3] = {
        {"604#2F002001FB000000", "584#6000200100000000", "584#4F002001FB000000"},
        {"604#2B002002FEFF0000", "584#6000200200000000", "584#4B002002FEFF0000"},
        {"604#2300200378563412", "584#6000200300000000", "584#4300200378563412"},
        {"604#2F002005C8000000", "584#6000200500000000", "584#4F002005C8000000"},
        {"604#2B00200688130000", "584#6000200600000000", "584#4B00200688130000"},
        {"604#23002007EFBEADDE", "584#6000200700000000", "584#43002007EFBEADDE"},
        {"604#230020090000803F", "584#6000200900000000", "584#430020090000803F"},
        {"604#2F00200A01000000", "584#6000200A00000000", "584#4F00200A01000000"},
        {"604#2B00200E9CFF0000", "584#6000200E00000000", "584#4B00200E9CFF0000"},
        {"604#2B00200F00000000", "584#6000200F00000000", "584#4B00200F00000000"},
    };
    for (size_t i = 0; i < sizeof(exchanges) / sizeof(exchanges[0]); i++) {
        test_rx(&t, exchanges[i][0]);
        test_expect(&t, exchanges[i][1]);
        char read[32] = "604#40";
        memcpy(read + 6, exchanges[i][0] + 6, 6);
        strcpy(read + 12, "00000000");
        test_rx(&t, read);
        test_expect(&t, exchanges[i][2]);
    }
    test_rx(&t, "604#2300200B04030201");
    test_expect(&t, "584#6000200B00000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x0B), 0x01020304);
    test_expect_none(&t);
}
END_TEST

/* A visible string takes 1..4 bytes expedited and reads back by its current length. */
START_TEST(expedited_strings_by_length)
{
    static const char *const exchanges[][3] = {
        {"604#2F00200C7A000000", "584#6000200C00000000", "584#4F00200C7A000000"},
        {"604#2B00200C78790000", "584#6000200C00000000", "584#4B00200C78790000"},
        {"604#2700200C61626300", "584#6000200C00000000", "584#4700200C61626300"},
        {"604#2300200C61626364", "584#6000200C00000000", "584#4300200C61626364"},
    };
    for (size_t i = 0; i < sizeof(exchanges) / sizeof(exchanges[0]); i++) {
        test_rx(&t, exchanges[i][0]);
        test_expect(&t, exchanges[i][1]);
        test_rx(&t, "604#4000200C00000000");
        test_expect(&t, exchanges[i][2]);
    }
    test_expect_none(&t);
}
END_TEST

/* e = 1, s = 0: a fixed type takes its own size from the four data bytes. */
START_TEST(expedited_without_size)
{
    test_rx(&t, "604#22002006E803AABB");
    test_expect(&t, "584#6000200600000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 1000);
    test_rx(&t, "604#22002001FF000000");
    test_expect(&t, "584#6000200100000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x01), -1);
    test_rx(&t, "604#2200200C41420000");
    test_expect(&t, "584#6000200C00000000");
    ck_assert_uint_eq(co_od_length(&t.node, co_od_find(&test_od, 0x2000, 0x0C)), 2);
    /* An 8-byte type cannot be carried by four bytes. */
    test_rx(&t, "604#2200200801020304");
    test_expect(&t, "584#8000200813000706");
    test_rx(&t, "604#2200201300000000");
    test_expect(&t, "584#8000201311000906");
    test_expect_none(&t);
}
END_TEST

/* ---- Abort codes of the dictionary --------------------------------------------------------- */

START_TEST(dictionary_abort_codes)
{
    static const char *const exchanges[][2] = {
        {"604#4004100000000000", "584#8004100000000206"}, /* no object */
        {"604#4000100100000000", "584#8000100111000906"}, /* no sub-index */
        {"604#4000200B00000000", "584#8000200B01000106"}, /* write-only */
        {"604#2300100000000000", "584#8000100002000106"}, /* read-only */
        {"604#2B00200300000000", "584#8000200313000706"}, /* too short */
        {"604#2300200601000000", "584#8000200612000706"}, /* too long */
        {"604#2F00200A02000000", "584#8000200A30000906"}, /* boolean 2 */
        {"604#2B00200689130000", "584#8000200631000906"}, /* 5001 > 5000 */
        {"604#2B00200663000000", "584#8000200632000906"}, /* 99 < 100 */
        {"604#2B00201001000000", "584#8000201021000008"}, /* hook: local control */
        {"604#2300120108060000", "584#8000120102000106"}, /* 1200h is read-only */
        {"604#2304100000000000", "584#8004100000000206"},
        {"604#400018FF00000000", "584#800018FF11000906"}, /* sub-index FFh: not supported */
    };
    for (size_t i = 0; i < sizeof(exchanges) / sizeof(exchanges[0]); i++) {
        test_rx(&t, exchanges[i][0]);
        test_expect(&t, exchanges[i][1]);
    }
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 1000);
    test_expect_none(&t);
}
END_TEST

START_TEST(unknown_command_specifier)
{
    test_rx(&t, "604#E000200000000000");
    test_expect(&t, "584#8000200001000405");
    /* A segment without a transfer: no multiplexer to report. */
    test_rx(&t, "604#6000000000000000");
    test_expect(&t, "584#8000000001000405");
    test_rx(&t, "604#00AABBCCDDEEFF00");
    test_expect(&t, "584#8000000001000405");
    test_rx(&t, "604#A300000000000000");
    test_expect(&t, "584#8000000001000405");
    test_rx(&t, "604#E0");
    test_expect(&t, "584#8000000001000405");
    test_expect_none(&t);
}
END_TEST

/* ---- Segmented ---------------------------------------------------------------------------- */

START_TEST(segmented_upload_device_name)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "604#6000000000000000");
    test_expect(&t, "584#0341545633313200");
    test_expect_none(&t);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
}
END_TEST

START_TEST(segmented_string_round_trip)
{
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#0048656C6C6F2C20");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "604#1043414E6F70656E");
    test_expect(&t, "584#3000000000000000");
    test_rx(&t, "604#0D21000000000000");
    test_expect(&t, "584#2000000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    test_rx(&t, "604#4000200C00000000");
    test_expect(&t, "584#4100200C0F000000");
    test_rx(&t, "604#60");
    test_expect(&t, "584#0048656C6C6F2C20");
    test_rx(&t, "604#70");
    test_expect(&t, "584#1043414E6F70656E");
    test_rx(&t, "604#60");
    test_expect(&t, "584#0D21000000000000");
    /* Size not indicated: 3 bytes, n = 4, c = 1. */
    test_rx(&t, "604#2000200C00000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#0978797A");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "604#4000200C00000000");
    test_expect(&t, "584#4700200C78797A00");
    test_expect_none(&t);
}
END_TEST

START_TEST(segmented_eight_byte_types)
{
    static const uint8_t subs[] = {0x04, 0x08, 0x11};
    for (size_t i = 0; i < sizeof(subs); i++) {
        char text[32];
        sprintf(text, "604#210020%02X08000000", subs[i]);
        test_rx(&t, text);
        sprintf(text, "584#600020%02X00000000", subs[i]);
        test_expect(&t, text);
        test_rx(&t, "604#0001020304050607");
        test_expect(&t, "584#2000000000000000");
        test_rx(&t, "604#1D08");
        test_expect(&t, "584#3000000000000000");
        ck_assert_int_eq(co_od_value(&t.node, 0x2000, subs[i]), 0x0807060504030201);
        sprintf(text, "604#400020%02X00000000", subs[i]);
        test_rx(&t, text);
        sprintf(text, "584#410020%02X08000000", subs[i]);
        test_expect(&t, text);
        test_rx(&t, "604#60");
        test_expect(&t, "584#0001020304050607");
        test_rx(&t, "604#70");
        test_expect(&t, "584#1D08000000000000");
    }
    test_expect_none(&t);
}
END_TEST

START_TEST(segmented_octet_string_and_big_string)
{
    uint8_t octets[200], text[1000];
    for (size_t i = 0; i < sizeof(octets); i++)
        octets[i] = (uint8_t)(i * 7 + 3);
    for (size_t i = 0; i < sizeof(text); i++)
        text[i] = (uint8_t)('A' + i % 26);
    segmented_download(0x2000, 0x0D, octets, sizeof(octets), true, true);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0D), octets, sizeof(octets));
    segmented_upload(0x2000, 0x0D, octets, sizeof(octets));
    segmented_download(0x2000, 0x12, text, sizeof(text), false, true);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x12), text, sizeof(text));
    segmented_upload(0x2000, 0x12, text, sizeof(text));
    /* An octet string must be written whole. */
    segmented_download(0x2000, 0x0D, octets, 199, true, false);
    test_expect(&t, "584#8000200D13000706");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0D), octets, sizeof(octets));
    test_expect_none(&t);
}
END_TEST

START_TEST(segmented_empty_string)
{
    test_rx(&t, "604#4000201200000000");
    test_expect(&t, "584#4100201200000000");
    test_rx(&t, "604#60");
    test_expect(&t, "584#0F00000000000000");
    test_expect_none(&t);
}
END_TEST

START_TEST(segmented_download_aborts)
{
    /* Toggle must start at 0. */
    test_rx(&t, "604#2100200C05000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#156162636465");
    test_expect(&t, "584#8000200C00000305");
    /* Then alternate. */
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#0048656C6C6F2C20");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "604#0043414E6F70656E");
    test_expect(&t, "584#8000200C00000305");
    /* More bytes than announced. */
    test_rx(&t, "604#2100200C05000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#03414243444546");
    test_expect(&t, "584#8000200C10000706");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "short", 6);
    /* Larger than the buffer, announced. */
    test_rx(&t, "604#2100201201040000");
    test_expect(&t, "584#8000201205000405");
    /* Target checks at initiate. */
    test_rx(&t, "604#2100100006000000");
    test_expect(&t, "584#8000100002000106");
    test_rx(&t, "604#2104100006000000");
    test_expect(&t, "584#8004100000000206");
    test_rx(&t, "604#2100201306000000");
    test_expect(&t, "584#8000201311000906");
    test_expect_none(&t);
}
END_TEST

/* Without a size, the buffer's end is found by the segment that overflows it. */
START_TEST(segmented_download_overflows_buffer)
{
    test_rx(&t, "604#2000201200000000");
    test_expect(&t, "584#6000201200000000");
    uint8_t p[8] = {0, 'a', 'b', 'c', 'd', 'e', 'f', 'g'};
    for (unsigned i = 0; i < CO_CONFIG_SDO_BUFFER / 7; i++) {
        p[0] = (uint8_t)((i & 1) << 4);
        rx8(p);
        uint8_t r[8] = {(uint8_t)(0x20 | p[0])};
        expect8(r);
    }
    p[0] = (uint8_t)(((CO_CONFIG_SDO_BUFFER / 7) & 1) << 4);
    rx8(p);
    test_expect(&t, "584#8000201205000405");
    test_expect_none(&t);
}
END_TEST

START_TEST(segmented_upload_toggle_and_unexpected)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "604#70");
    test_expect(&t, "584#8008100000000305");
    test_rx(&t, "604#4000200D00000000");
    test_expect(&t, "584#4100200DC8000000");
    test_rx(&t, "604#60");
    test_expect(&t, "584#0000000000000000");
    /* A download segment in an upload. */
    test_rx(&t, "604#1000000000000000");
    test_expect(&t, "584#8000200D01000405");
    test_rx(&t, "604#2100200C05000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000200C01000405");
    test_expect_none(&t);
}
END_TEST

/* The CCT's SDO 14/15, 20/21 and 24/25: 100Ch and 1017h written segmented, then by block without
 * and with CRC (2 bytes: one segment, n = 5). */
START_TEST(segmented_and_block_writes_of_error_control_objects)
{
    static const uint8_t blksizes[] = {127, 127};
    static const uint8_t guard_time[] = {0xF4, 0x01};    /* 500 ms */
    static const uint8_t producer_time[] = {0x64, 0x00}; /* 100 ms */
    static const uint8_t zero[] = {0, 0};
    segmented_download(0x100C, 0, guard_time, 2, true, true);
    segmented_download(0x1017, 0, producer_time, 2, true, true);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 100);
    block_download(0x100C, 0, zero, 2, false, blksizes, 1);
    block_download(0x1017, 0, zero, 2, false, blksizes, 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    block_download(0x100C, 0, guard_time, 2, true, blksizes, 1);
    block_download(0x1017, 0, producer_time, 2, true, blksizes, 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 100);
    test_expect_none(&t);
}
END_TEST

/* ---- Block download ----------------------------------------------------------------------- */

START_TEST(crc16_ccitt_check_values)
{
    ck_assert_uint_eq(co_sdo_crc16((const uint8_t *)"123456789", 9), 0x31C3);
    ck_assert_uint_eq(co_sdo_crc16((const uint8_t *)hello, 15), 0x1E0E);
    ck_assert_uint_eq(co_sdo_crc16(NULL, 0), 0);
}
END_TEST

START_TEST(block_download_with_crc)
{
    test_rx(&t, "604#C600200C0F000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0243414E6F70656E");
    test_expect_none(&t);
    test_rx(&t, "604#8321000000000000");
    test_expect(&t, "584#A2037F0000000000");
    test_rx(&t, "604#D90E1E0000000000");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_expect_none(&t);
}
END_TEST

START_TEST(block_download_without_crc)
{
    /* The client does not use the CRC: sc = 0, and the end request's CRC bytes are not checked. */
    test_rx(&t, "604#C200200C0F000000");
    test_expect(&t, "584#A000200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0243414E6F70656E");
    test_rx(&t, "604#8321000000000000");
    test_expect(&t, "584#A2037F0000000000");
    test_rx(&t, "604#D9FFFF");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    /* Neither size nor CRC. */
    test_rx(&t, "604#C000200C00000000");
    test_expect(&t, "584#A000200C7F000000");
    test_rx(&t, "604#8178797A00000000");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#D1");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "xyz", 4);
    test_expect_none(&t);
}
END_TEST

START_TEST(block_download_wrong_crc)
{
    test_rx(&t, "604#C600200C0F000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0243414E6F70656E");
    test_rx(&t, "604#8321000000000000");
    test_expect(&t, "584#A2037F0000000000");
    test_rx(&t, "604#D90F1E0000000000");
    test_expect(&t, "584#8000200C04000405");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "short", 6);
    test_expect_none(&t);
}
END_TEST

/* A segment out of sequence spoils the rest of its sub-block; the acknowledge names the last good
 * one and the client resends from the next, numbering from 1 again. */
START_TEST(block_download_wrong_seqno_is_resent)
{
    test_rx(&t, "604#C600200C0F000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0343414E6F70656E"); /* 2 was lost */
    test_rx(&t, "604#8321000000000000");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#0143414E6F70656E");
    test_rx(&t, "604#8221000000000000");
    test_expect(&t, "584#A2027F0000000000");
    test_rx(&t, "604#D90E1E0000000000");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    /* The very first segment lost: ackseq 0, everything again. */
    test_rx(&t, "604#C600200C03000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8261626300000000");
    test_expect(&t, "584#A2007F0000000000");
    test_rx(&t, "604#8161626300000000");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#D1D69D");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "abc", 4);
    test_expect_none(&t);
}
END_TEST

START_TEST(block_download_invalid_seqno)
{
    test_rx(&t, "604#C600200C0F000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0043414E6F70656E");
    test_expect(&t, "584#8000200C03000405");
    test_expect_none(&t);
}
END_TEST

/* 1000 bytes: 127 segments, then the buffer limits the block size to what it can still take. */
START_TEST(block_download_multi_subblock)
{
    uint8_t text[1000], octets[200];
    for (size_t i = 0; i < sizeof(text); i++)
        text[i] = (uint8_t)('a' + i % 26);
    for (size_t i = 0; i < sizeof(octets); i++)
        octets[i] = (uint8_t)(255 - i);
    static const uint8_t big[] = {127, 20, 4};
    block_download(0x2000, 0x12, text, sizeof(text), true, big, 2);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x12), text, sizeof(text));
    static const uint8_t small[] = {127, 118};
    block_download(0x2000, 0x0D, octets, sizeof(octets), false, small, 1);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0D), octets, sizeof(octets));
    test_expect_none(&t);
}
END_TEST

/* A segment numbered beyond the server's block size is invalid. */
START_TEST(block_download_seqno_beyond_blksize)
{
    test_rx(&t, "604#C400201200000000");
    test_expect(&t, "584#A40020127F000000");
    uint8_t p[8] = {0, 'a', 'b', 'c', 'd', 'e', 'f', 'g'};
    for (uint8_t seqno = 1; seqno <= 127; seqno++) {
        p[0] = seqno;
        rx8(p);
    }
    test_expect(&t, "584#A27F140000000000");
    p[0] = 21;
    rx8(p);
    test_expect(&t, "584#8000201203000405");
    test_expect_none(&t);
}
END_TEST

START_TEST(block_download_overflows_buffer)
{
    test_rx(&t, "604#C400201200000000");
    test_expect(&t, "584#A40020127F000000");
    uint8_t p[8] = {0, 'a', 'b', 'c', 'd', 'e', 'f', 'g'};
    for (uint8_t seqno = 1; seqno <= 127; seqno++) {
        p[0] = seqno;
        rx8(p);
    }
    test_expect(&t, "584#A27F140000000000");
    for (uint8_t seqno = 1; seqno <= 19; seqno++) {
        p[0] = seqno;
        rx8(p);
    }
    test_expect_none(&t);
    p[0] = 20; /* bytes 1022..1028 */
    rx8(p);
    test_expect(&t, "584#8000201205000405");
    /* The last segment may overhang the buffer with padding only... */
    test_rx(&t, "604#C400201200000000");
    test_expect(&t, "584#A40020127F000000");
    for (uint8_t seqno = 1; seqno <= 127; seqno++) {
        p[0] = seqno;
        rx8(p);
    }
    test_expect(&t, "584#A27F140000000000");
    for (uint8_t seqno = 1; seqno <= 19; seqno++) {
        p[0] = seqno;
        rx8(p);
    }
    p[0] = 0x80 | 20;
    rx8(p);
    test_expect(&t, "584#A214010000000000");
    /* ...but 1025 bytes of data do not fit. */
    test_rx(&t, "604#D10000");
    test_expect(&t, "584#8000201205000405");
    test_expect_none(&t);
}
END_TEST

START_TEST(block_download_initiate_aborts)
{
    test_rx(&t, "604#C600201201040000");
    test_expect(&t, "584#8000201205000405");
    test_rx(&t, "604#C600100004000000");
    test_expect(&t, "584#8000100002000106");
    test_rx(&t, "604#C604100004000000");
    test_expect(&t, "584#8004100000000206");
    /* The length rules of the entry apply at the end. */
    test_rx(&t, "604#C000200300000000");
    test_expect(&t, "584#A00020037F000000");
    test_rx(&t, "604#8101020304050607");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#C5");
    test_expect(&t, "584#8000200312000706");
    /* Announced 5, sent 6. */
    test_rx(&t, "604#C200200C05000000");
    test_expect(&t, "584#A000200C7F000000");
    test_rx(&t, "604#8141424344454600");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#C5");
    test_expect(&t, "584#8000200C10000706");
    test_expect_none(&t);
}
END_TEST

/* ---- Block upload ------------------------------------------------------------------------- */

START_TEST(block_upload_with_and_without_crc)
{
    test_rx(&t, "604#2100200C0F000000");
    test_drain(&t);
    test_rx(&t, "604#0048656C6C6F2C20");
    test_rx(&t, "604#1043414E6F70656E");
    test_rx(&t, "604#0D21000000000000");
    test_drain(&t);
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C0F000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#0148656C6C6F2C20");
    test_expect(&t, "584#0243414E6F70656E");
    test_expect(&t, "584#8321000000000000");
    test_expect_none(&t);
    test_rx(&t, "604#A2037F");
    test_expect(&t, "584#D90E1E0000000000");
    test_rx(&t, "604#A1");
    test_expect_none(&t);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    /* Without CRC: sc = 0 and the end carries zeros. */
    test_rx(&t, "604#A000200C7F000000");
    test_expect(&t, "584#C200200C0F000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#0148656C6C6F2C20");
    test_expect(&t, "584#0243414E6F70656E");
    test_expect(&t, "584#8321000000000000");
    test_rx(&t, "604#A2037F");
    test_expect(&t, "584#D900000000000000");
    test_rx(&t, "604#A1");
    test_expect_none(&t);
}
END_TEST

START_TEST(block_upload_small_blocks_and_resend)
{
    test_rx(&t, "604#2100200C0F000000");
    test_drain(&t);
    test_rx(&t, "604#0048656C6C6F2C20");
    test_rx(&t, "604#1043414E6F70656E");
    test_rx(&t, "604#0D21000000000000");
    test_drain(&t);
    test_rx(&t, "604#A400200C01000000");
    test_expect(&t, "584#C600200C0F000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#0148656C6C6F2C20");
    test_expect_none(&t);
    test_rx(&t, "604#A20102");
    test_expect(&t, "584#0143414E6F70656E");
    test_expect(&t, "584#8221000000000000");
    /* Segment 2 lost: the server resends it as segment 1 of the next sub-block. */
    test_rx(&t, "604#A20102");
    test_expect(&t, "584#8121000000000000");
    test_rx(&t, "604#A20102");
    test_expect(&t, "584#D90E1E0000000000");
    test_rx(&t, "604#A1");
    test_expect_none(&t);
}
END_TEST

START_TEST(block_upload_long_values)
{
    uint8_t text[1000], octets[200];
    for (size_t i = 0; i < sizeof(text); i++)
        text[i] = (uint8_t)('A' + i % 23);
    for (size_t i = 0; i < sizeof(octets); i++)
        octets[i] = (uint8_t)(i ^ 0x5A);
    memcpy(co_od_bytes(&t.node, co_od_find(&test_od, 0x2000, 0x12)), text, sizeof(text));
    memcpy(co_od_bytes(&t.node, co_od_find(&test_od, 0x2000, 0x0D)), octets, sizeof(octets));
    block_upload(0x2000, 0x12, text, sizeof(text), true, 100);
    block_upload(0x2000, 0x12, text, sizeof(text), false, 127);
    block_upload(0x2000, 0x0D, octets, sizeof(octets), true, 5);
    block_upload(0x1008, 0x00, (const uint8_t *)"ATV312", 6, true, 127);
    block_upload(0x1000, 0x00, (const uint8_t *)"\x92\x01\x01\x00", 4, true, 1);
}
END_TEST

START_TEST(block_upload_empty_string)
{
    test_rx(&t, "604#A40020127F000000");
    test_expect(&t, "584#C600201200000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8100000000000000");
    test_rx(&t, "604#A2017F");
    test_expect(&t, "584#DD00000000000000");
    test_rx(&t, "604#A1");
    test_expect_none(&t);
}
END_TEST

/* CiA 301: at or below the client's protocol switch threshold the server uses the plain upload. */
START_TEST(block_upload_protocol_switch)
{
    test_rx(&t, "604#A400200C7F050000");
    test_expect(&t, "584#4100200C05000000");
    test_rx(&t, "604#60");
    test_expect(&t, "584#0573686F72740000");
    test_rx(&t, "604#A40010007F040000");
    test_expect(&t, "584#4300100092010100");
    /* Above the threshold: block upload. */
    test_rx(&t, "604#A400200C7F040000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8173686F72740000");
    test_rx(&t, "604#A2017F");
    test_expect(&t, "584#C937C80000000000");
    test_rx(&t, "604#A1");
    test_expect_none(&t);
}
END_TEST

START_TEST(block_upload_aborts)
{
    test_rx(&t, "604#A400200C00000000");
    test_expect(&t, "584#8000200C02000405");
    test_rx(&t, "604#A400200C80000000");
    test_expect(&t, "584#8000200C02000405");
    test_rx(&t, "604#A400200B7F000000");
    test_expect(&t, "584#8000200B01000106");
    test_rx(&t, "604#A40010017F000000");
    test_expect(&t, "584#8000100111000906");
    /* Acknowledge with block size 0. */
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8173686F72740000");
    test_rx(&t, "604#A20100");
    test_expect(&t, "584#8000200C02000405");
    /* Acknowledge of a segment never sent. */
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8173686F72740000");
    test_rx(&t, "604#A2027F");
    test_expect(&t, "584#8000200C03000405");
    /* Acknowledge before start, end before acknowledge. */
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#A2017F");
    test_expect(&t, "584#8000200C01000405");
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8173686F72740000");
    test_rx(&t, "604#A1");
    test_expect(&t, "584#8000200C01000405");
    test_expect_none(&t);
}
END_TEST

/* The CCT's SDO 19 and 27 frames: 1000h by block upload without CRC (sc = 0, end with n = 3 and
 * no CRC), then an acknowledge of segment 128, which was never sent. */
START_TEST(block_upload_device_type_and_ackseq_128)
{
    test_rx(&t, "604#A000100014000000");
    test_expect(&t, "584#C200100004000000");
    test_rx(&t, "604#A300000000000000");
    test_expect(&t, "584#8192010100000000");
    test_rx(&t, "604#A201140000000000");
    test_expect(&t, "584#CD00000000000000");
    test_rx(&t, "604#A100000000000000");
    test_expect_none(&t);
    test_rx(&t, "604#A000100014000000");
    test_expect(&t, "584#C200100004000000");
    test_rx(&t, "604#A300000000000000");
    test_expect(&t, "584#8192010100000000");
    test_rx(&t, "604#A280140000000000");
    test_expect(&t, "584#8000100003000405");
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_expect_none(&t);
}
END_TEST

/* ---- Timeout ------------------------------------------------------------------------------ */

START_TEST(timeout_restarts_on_every_frame)
{
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), t.bus.now + 1000000);
    test_advance(&t, 900000);
    test_rx(&t, "604#0048656C6C6F2C20");
    test_expect(&t, "584#2000000000000000");
    test_advance(&t, 900000);
    test_rx(&t, "604#1043414E6F70656E");
    test_expect(&t, "584#3000000000000000");
    co_time_t last = t.bus.now;
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), last + 1000000);
    test_advance(&t, 999999);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "584#8000200C00000405"), last + 1000000);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "short", 6);
    test_rx(&t, "604#0D21000000000000");
    test_expect(&t, "584#8000000001000405");
    test_expect_none(&t);
}
END_TEST

START_TEST(timeout_settable_and_in_block_upload)
{
    co_sdo_set_timeout(&t.node, 250000);
    test_rx(&t, "604#A40010007F000000");
    test_expect(&t, "584#C600100004000000");
    test_advance(&t, 200000);
    test_rx(&t, "604#A3");
    test_expect(&t, "584#8192010100000000");
    co_time_t last = t.bus.now;
    test_advance(&t, 300000);
    ck_assert_uint_eq(test_expect(&t, "584#8000100000000405"), last + 250000);
    test_expect_none(&t);
    /* Idle: no deadline. */
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now + 10000000), CO_TIME_NEVER);
}
END_TEST

/* ---- Client abort, new requests, NMT ------------------------------------------------------- */

START_TEST(client_abort_returns_to_idle)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "604#8008100000000405");
    test_expect_none(&t);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000000001000405");
    /* In a block download sub-block too. */
    test_rx(&t, "604#C600200C0F000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#8000200C00000000");
    test_advance(&t, 2000000);
    test_expect_none(&t);
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "short", 6);
    /* An abort while idle is ignored. */
    test_rx(&t, "604#8000000000000000");
    test_expect_none(&t);
}
END_TEST

/* A new request replaces the transfer under way, without an abort for the old one. */
START_TEST(new_initiate_replaces_transfer)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "604#4000100000000000");
    test_expect(&t, "584#4300100092010100");
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000000001000405");
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C05000000");
    test_rx(&t, "604#C600200C03000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8178797A00000000");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#2F00200514000000");
    test_expect(&t, "584#6000200500000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 20);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_expect_none(&t);
}
END_TEST

START_TEST(no_sdo_when_stopped)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "000#0204");
    test_rx(&t, "604#60");
    test_rx(&t, "604#4000100000000000");
    test_advance(&t, 3000000);
    test_expect_none(&t);
    test_rx(&t, "000#0104");
    test_drain(&t); /* TPDOs of Operational */
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000000001000405");
    test_rx(&t, "604#4000100000000000");
    test_expect(&t, "584#4300100092010100");
    test_expect_none(&t);
}
END_TEST

START_TEST(state_change_and_reset_return_to_idle)
{
    test_rx(&t, "000#0104");
    test_drain(&t);
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "000#8004");
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000000001000405");
    test_expect_none(&t);
}
END_TEST

/* ---- Short and foreign frames -------------------------------------------------------------- */

START_TEST(short_frames)
{
    /* Ignored: RTR, empty, an initiate without index and sub-index. */
    test_rx(&t, "604#R");
    test_rx(&t, "604#");
    test_rx(&t, "604#400810");
    test_rx(&t, "603#4000100000000000");
    test_expect_none(&t);
    /* Enough for what the command says. */
    test_rx(&t, "604#40001000");
    test_expect(&t, "584#4300100092010100");
    test_rx(&t, "604#2F00200514");
    test_expect(&t, "584#6000200500000000");
    test_rx(&t, "604#2B00200688");
    test_expect(&t, "584#8000200601000405");
    test_rx(&t, "604#2F002005");
    test_expect(&t, "584#8000200501000405");
    test_rx(&t, "604#2200200614");
    test_expect(&t, "584#8000200601000405");
    test_rx(&t, "604#2100200C05");
    test_expect(&t, "584#8000200C01000405");
    test_rx(&t, "604#C600200C05");
    test_expect(&t, "584#8000200C01000405");
    test_rx(&t, "604#A400200C");
    test_expect(&t, "584#8000200C01000405");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 20);
    /* A download segment shorter than its n says. */
    test_rx(&t, "604#2100200C05000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#056162");
    test_expect(&t, "584#8000200C01000405");
    test_rx(&t, "604#2000200C");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#0B6162");
    test_expect(&t, "584#2000000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "ab", 3);
    test_expect_none(&t);
}
END_TEST

/* The server is idle: no answer, and no deadline left for a timeout abort. */
static void expect_idle(const char *state)
{
    test_expect_none(&t);
    ck_assert_msg(co_sdo_process(&t.node, t.bus.now) == CO_TIME_NEVER, "%s: transfer still open",
                  state);
}

/* A client abort of `len` bytes: 0x80, then the multiplexer and the code as far as they fit. */
static void client_abort(uint16_t index, uint8_t sub, size_t len)
{
    uint8_t p[8];
    char text[32];
    initiate_frame(p, 0x80, index, sub, CO_SDO_ABORT_GENERAL);
    frame_text(text, RX_ID, p, len);
    test_rx(&t, text);
}

/* docs/decisions.md, D-SDO-SHORT-ABORT: command byte 0x80 can only be an abort (unconfirmed), so
 * it ends any transfer silently whatever its DLC: the issue's frame first, then every DLC in every
 * state of the server. */
START_TEST(short_client_abort_ends_any_transfer_silently)
{
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "604#80081000");
    expect_idle("segmented upload, DLC 4");
    test_rx(&t, "604#60");
    test_expect(&t, "584#8000000001000405"); /* no transfer left to continue */
    for (size_t len = 1; len <= 8; len++) {
        client_abort(0x0000, 0, len);
        expect_idle("idle");
        test_rx(&t, "604#4008100000000000");
        test_expect(&t, "584#4108100006000000");
        client_abort(0x1008, 0, len);
        expect_idle("segmented upload");
        test_rx(&t, "604#2100200C05000000");
        test_expect(&t, "584#6000200C00000000");
        client_abort(0x2000, 0x0C, len);
        expect_idle("segmented download");
        test_rx(&t, "604#C600200C0F000000");
        test_expect(&t, "584#A400200C7F000000");
        test_rx(&t, "604#0148656C6C6F2C20");
        client_abort(0x2000, 0x0C, len);
        expect_idle("block download sub-block");
        test_rx(&t, "604#C400200C00000000");
        test_expect(&t, "584#A400200C7F000000");
        test_rx(&t, "604#8178797A00000000");
        test_expect(&t, "584#A2017F0000000000");
        client_abort(0x2000, 0x0C, len);
        expect_idle("block download end");
        test_rx(&t, "604#A400200C7F000000");
        test_expect(&t, "584#C600200C05000000");
        client_abort(0x2000, 0x0C, len);
        expect_idle("block upload start");
        test_rx(&t, "604#A400200C7F000000");
        test_expect(&t, "584#C600200C05000000");
        test_rx(&t, "604#A3");
        test_expect(&t, "584#8173686F72740000");
        client_abort(0x2000, 0x0C, len);
        expect_idle("block upload acknowledge");
        test_rx(&t, "604#A400200C7F000000");
        test_expect(&t, "584#C600200C05000000");
        test_rx(&t, "604#A3");
        test_expect(&t, "584#8173686F72740000");
        test_rx(&t, "604#A2017F");
        test_expect(&t, "584#C937C80000000000");
        client_abort(0x2000, 0x0C, len);
        expect_idle("block upload end");
    }
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), "short", 6);
    test_advance(&t, 2000000);
    test_expect_none(&t);
}
END_TEST

START_TEST(short_block_frames)
{
    /* A short final segment is enough when the end request's n agrees. */
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C6C6F2C20");
    test_rx(&t, "604#0243414E6F70656E");
    test_rx(&t, "604#8321");
    test_expect(&t, "584#A2037F0000000000");
    test_rx(&t, "604#D90E1E");
    test_expect(&t, "584#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    /* ... and not when it claims more data than the frame had. */
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8178");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#D5");
    test_expect(&t, "584#8000200C01000405");
    /* A short segment that is not the last. */
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#0148656C");
    test_expect(&t, "584#8000200C01000405");
    /* An end request without its CRC. */
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8178797A");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#D1");
    test_expect(&t, "584#8000200C01000405");
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8178797A");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#D1AF");
    test_expect(&t, "584#8000200C01000405");
    /* A segment where the end request belongs. */
    test_rx(&t, "604#C400200C00000000");
    test_expect(&t, "584#A400200C7F000000");
    test_rx(&t, "604#8178797A");
    test_expect(&t, "584#A2017F0000000000");
    test_rx(&t, "604#0178797A00000000");
    test_expect(&t, "584#8000200C01000405");
    /* A block upload acknowledge without its block size. */
    test_rx(&t, "604#A400200C7F");
    test_expect(&t, "584#C600200C0F000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#0148656C6C6F2C20");
    test_expect(&t, "584#0243414E6F70656E");
    test_expect(&t, "584#8321000000000000");
    test_rx(&t, "604#A201");
    test_expect(&t, "584#8000200C01000405");
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo");
    TCase *tc = tcase_create("sdo");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, atv312_manual_frames);
    tcase_add_test(tc, expedited_read_every_fixed_type);
    tcase_add_test(tc, expedited_write_every_fixed_type);
    tcase_add_test(tc, expedited_strings_by_length);
    tcase_add_test(tc, expedited_without_size);
    tcase_add_test(tc, dictionary_abort_codes);
    tcase_add_test(tc, unknown_command_specifier);
    tcase_add_test(tc, segmented_upload_device_name);
    tcase_add_test(tc, segmented_string_round_trip);
    tcase_add_test(tc, segmented_eight_byte_types);
    tcase_add_test(tc, segmented_octet_string_and_big_string);
    tcase_add_test(tc, segmented_empty_string);
    tcase_add_test(tc, segmented_download_aborts);
    tcase_add_test(tc, segmented_download_overflows_buffer);
    tcase_add_test(tc, segmented_upload_toggle_and_unexpected);
    tcase_add_test(tc, segmented_and_block_writes_of_error_control_objects);
    tcase_add_test(tc, crc16_ccitt_check_values);
    tcase_add_test(tc, block_download_with_crc);
    tcase_add_test(tc, block_download_without_crc);
    tcase_add_test(tc, block_download_wrong_crc);
    tcase_add_test(tc, block_download_wrong_seqno_is_resent);
    tcase_add_test(tc, block_download_invalid_seqno);
    tcase_add_test(tc, block_download_multi_subblock);
    tcase_add_test(tc, block_download_seqno_beyond_blksize);
    tcase_add_test(tc, block_download_overflows_buffer);
    tcase_add_test(tc, block_download_initiate_aborts);
    tcase_add_test(tc, block_upload_with_and_without_crc);
    tcase_add_test(tc, block_upload_small_blocks_and_resend);
    tcase_add_test(tc, block_upload_long_values);
    tcase_add_test(tc, block_upload_empty_string);
    tcase_add_test(tc, block_upload_protocol_switch);
    tcase_add_test(tc, block_upload_aborts);
    tcase_add_test(tc, block_upload_device_type_and_ackseq_128);
    tcase_add_test(tc, timeout_restarts_on_every_frame);
    tcase_add_test(tc, timeout_settable_and_in_block_upload);
    tcase_add_test(tc, client_abort_returns_to_idle);
    tcase_add_test(tc, new_initiate_replaces_transfer);
    tcase_add_test(tc, no_sdo_when_stopped);
    tcase_add_test(tc, state_change_and_reset_return_to_idle);
    tcase_add_test(tc, short_frames);
    tcase_add_test(tc, short_client_abort_ends_any_transfer_silently);
    tcase_add_test(tc, short_block_frames);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
