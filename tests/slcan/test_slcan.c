/* SPDX-License-Identifier: Apache-2.0 */
/* The serial-line CAN protocol, byte for byte: frames encoded to the exact lines Linux's slcan
 * driver writes and reads, lines decoded, commands answered, and every malformed line refused
 * without leaving a frame behind or disturbing the next line. */
#include "check_main.h"
#include "slcan/slcan.h"

#include <string.h>

/* Encodes frame and checks the exact line, CR included. */
static void assert_line(const co_frame_t *frame, const char *expected)
{
    char line[SLCAN_LINE_MAX];
    size_t n = slcan_encode(frame, line);
    ck_assert_uint_eq(n, strlen(expected));
    ck_assert_mem_eq(line, expected, n);
}

START_TEST(encode_standard_frames)
{
    assert_line(&(co_frame_t){.id = 0x604, .len = 8, .data = {0x40, 0x00, 0x10}},
                "t60484000100000000000\r");
    assert_line(&(co_frame_t){.id = 0x710, .len = 1, .data = {0x05}}, "t710105\r");
    assert_line(&(co_frame_t){.id = 0x080, .len = 0}, "t0800\r");
    assert_line(&(co_frame_t){.id = 0x7FF, .len = 2, .data = {0xCA, 0xFE}}, "t7FF2CAFE\r");
}
END_TEST

START_TEST(encode_remote_and_extended_frames)
{
    assert_line(&(co_frame_t){.id = 0x710, .len = 0, .flags = CO_FRAME_RTR}, "r7100\r");
    assert_line(&(co_frame_t){.id = 0x710, .len = 1, .flags = CO_FRAME_RTR, .data = {0xAA}},
                "r7101\r");
    assert_line(&(co_frame_t){.id = 0x1ABCDEF0, .len = 3, .flags = CO_FRAME_EFF, .data = {1, 2, 3}},
                "T1ABCDEF03010203\r");
    assert_line(&(co_frame_t){.id = 0x1FFFFFFF, .len = 8, .flags = CO_FRAME_EFF | CO_FRAME_RTR},
                "R1FFFFFFF8\r");
    co_frame_t longest = {.id = 0x1FFFFFFF, .len = 8, .flags = CO_FRAME_EFF};
    memset(longest.data, 0xFF, sizeof(longest.data));
    assert_line(&longest, "T1FFFFFFF8FFFFFFFFFFFFFFFF\r");
    ck_assert_uint_eq(strlen("T1FFFFFFF8FFFFFFFFFFFFFFFF\r"), SLCAN_LINE_MAX);
}
END_TEST

START_TEST(encode_refuses_what_the_protocol_cannot_carry)
{
    char line[SLCAN_LINE_MAX];
    memset(line, '#', sizeof(line));
    ck_assert_uint_eq(slcan_encode(&(co_frame_t){.id = 0x800, .len = 0}, line), 0);
    ck_assert_uint_eq(slcan_encode(&(co_frame_t){.id = 0x123, .len = 9}, line), 0);
    ck_assert_uint_eq(
        slcan_encode(&(co_frame_t){.id = 0x20000000, .len = 0, .flags = CO_FRAME_EFF}, line), 0);
    ck_assert_int_eq(line[0], '#'); /* nothing written */
}
END_TEST

static slcan_message_t decode(const char *line)
{
    return slcan_decode(line, strlen(line));
}

START_TEST(decode_frames)
{
    slcan_message_t m = decode("t60484000100000000000");
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x604);
    ck_assert_uint_eq(m.frame.len, 8);
    ck_assert_uint_eq(m.frame.flags, 0);
    ck_assert_mem_eq(m.frame.data, "\x40\x00\x10\x00\x00\x00\x00\x00", 8);

    m = decode("t0000");
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0);
    ck_assert_uint_eq(m.frame.len, 0);

    m = decode("t6012cafe"); /* hexadecimal of either case */
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x601);
    ck_assert_mem_eq(m.frame.data, "\xCA\xFE", 2);

    m = decode("r7100");
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x710);
    ck_assert_uint_eq(m.frame.len, 0);
    ck_assert_uint_eq(m.frame.flags, CO_FRAME_RTR);

    m = decode("T1ABCDEF03010203");
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x1ABCDEF0);
    ck_assert_uint_eq(m.frame.len, 3);
    ck_assert_uint_eq(m.frame.flags, CO_FRAME_EFF);
    ck_assert_mem_eq(m.frame.data, "\x01\x02\x03", 3);

    m = decode("R1FFFFFFF8");
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x1FFFFFFF);
    ck_assert_uint_eq(m.frame.len, 8);
    ck_assert_uint_eq(m.frame.flags, CO_FRAME_EFF | CO_FRAME_RTR);
}
END_TEST

START_TEST(decode_commands_and_their_answers)
{
    ck_assert_int_eq(decode("O").kind, SLCAN_OPEN);
    ck_assert_int_eq(decode("C").kind, SLCAN_CLOSE);
    slcan_message_t m = decode("S8");
    ck_assert_int_eq(m.kind, SLCAN_BITRATE);
    ck_assert_uint_eq(m.bitrate, 8);
    ck_assert_uint_eq(decode("S0").bitrate, 0);
    ck_assert_int_eq(decode("").kind, SLCAN_NOTHING);
    ck_assert_int_eq(slcan_answer(SLCAN_OPEN), '\r');
    ck_assert_int_eq(slcan_answer(SLCAN_CLOSE), '\r');
    ck_assert_int_eq(slcan_answer(SLCAN_BITRATE), '\r');
    ck_assert_int_eq(slcan_answer(SLCAN_INVALID), '\a');
    ck_assert_int_eq(slcan_answer(SLCAN_FRAME), 0);
    ck_assert_int_eq(slcan_answer(SLCAN_NOTHING), 0);
}
END_TEST

/* Every line here is one byte or digit away from a valid one. */
static const char *const malformed[] = {
    "t",                      /* no identifier */
    "t12",                    /* short identifier */
    "t123",                   /* no DLC */
    "t1239",                  /* DLC 9 */
    "t123A",                  /* DLC 10 */
    "t1231",                  /* one data byte missing */
    "t1231A",                 /* half a data byte */
    "t1231AAB",               /* one digit too many */
    "t12G0",                  /* not a hexadecimal digit in the identifier */
    "t1231AG",                /* nor in the data */
    "t800",                   /* 11-bit identifier over 7FFh (and no DLC) */
    "t8000",                  /* 11-bit identifier over 7FFh */
    "T200000000",             /* 29-bit identifier over 1FFFFFFFh */
    "T1234567",               /* short 29-bit identifier */
    "r71001",                 /* a remote frame carries no data */
    "t 230",                  /* a space */
    "O1",                     /* commands take no argument ... */
    "C ",                     /* ... */
    "S9",                     /* ... or a bit rate index of 0..8 */
    "S",                      /* ... */
    "S10",                    /* ... */
    "x",                      /* unknown command */
    "Z",                      /* an acknowledgement is no request */
    "t60484000100000000000F", /* too long by one digit */
};

START_TEST(malformed_lines_are_refused)
{
    for (size_t i = 0; i < sizeof(malformed) / sizeof(malformed[0]); i++) {
        slcan_message_t m = decode(malformed[i]);
        ck_assert_msg(m.kind == SLCAN_INVALID, "'%s' was not refused", malformed[i]);
        ck_assert_msg(m.frame.id == 0 && m.frame.len == 0 && m.frame.flags == 0,
                      "'%s' left a frame behind", malformed[i]);
        ck_assert_int_eq(slcan_answer(m.kind), '\a');
    }
}
END_TEST

/* Feeds text byte by byte; returns the message of the last byte and counts the others that were
 * not SLCAN_NOTHING. */
static slcan_message_t feed(slcan_reader_t *r, const char *text, int *earlier)
{
    slcan_message_t m = {.kind = SLCAN_NOTHING};
    *earlier = 0;
    for (size_t i = 0; text[i] != '\0'; i++) {
        if (m.kind != SLCAN_NOTHING)
            (*earlier)++;
        m = slcan_read(r, (uint8_t)text[i]);
    }
    return m;
}

START_TEST(reader_gathers_lines_byte_by_byte)
{
    slcan_reader_t r;
    slcan_reader_init(&r);
    int earlier;
    slcan_message_t m = feed(&r, "t7101", &earlier);
    ck_assert_int_eq(m.kind, SLCAN_NOTHING); /* no CR yet */
    m = feed(&r, "05\r", &earlier);
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x710);
    ck_assert_uint_eq(m.frame.data[0], 0x05);
    /* slcand -o -c -s8 writes these on start; the empty lines a host sends to flush are no-ops */
    ck_assert_int_eq(feed(&r, "C\r", &earlier).kind, SLCAN_CLOSE);
    ck_assert_int_eq(feed(&r, "S8\r", &earlier).kind, SLCAN_BITRATE);
    ck_assert_int_eq(feed(&r, "O\r", &earlier).kind, SLCAN_OPEN);
    ck_assert_int_eq(feed(&r, "\r\r", &earlier).kind, SLCAN_NOTHING);
    ck_assert_int_eq(earlier, 0);
}
END_TEST

START_TEST(reader_recovers_after_a_malformed_or_overlong_line)
{
    slcan_reader_t r;
    slcan_reader_init(&r);
    int earlier;
    ck_assert_int_eq(feed(&r, "t12G0\r", &earlier).kind, SLCAN_INVALID);
    slcan_message_t m = feed(&r, "t0801AA\r", &earlier);
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x080);
    ck_assert_uint_eq(m.frame.data[0], 0xAA);

    /* 40 digits: dropped up to its CR, once, however long; the next line is whole */
    m = feed(&r, "t6048400010000000000000000000000000000000000\r", &earlier);
    ck_assert_int_eq(m.kind, SLCAN_INVALID);
    ck_assert_int_eq(earlier, 0);
    m = feed(&r, "T1FFFFFFF8FFFFFFFFFFFFFFFFF\r", &earlier); /* one digit over the longest */
    ck_assert_int_eq(m.kind, SLCAN_INVALID);
    m = feed(&r, "t60484000100000000000\r", &earlier); /* 21 + CR: accepted */
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x604);
    m = feed(&r, "T1FFFFFFF8FFFFFFFFFFFFFFFF\r", &earlier); /* the longest line */
    ck_assert_int_eq(m.kind, SLCAN_FRAME);
    ck_assert_uint_eq(m.frame.id, 0x1FFFFFFF);
    ck_assert_uint_eq(m.frame.data[7], 0xFF);
}
END_TEST

START_TEST(every_frame_survives_a_round_trip)
{
    for (uint32_t id = 0; id <= 0x7FF; id += 0x7F) {
        for (uint8_t len = 0; len <= 8; len++) {
            for (uint8_t flags = 0; flags <= (CO_FRAME_RTR | CO_FRAME_EFF); flags++) {
                co_frame_t f = {
                    .id = flags & CO_FRAME_EFF ? id << 18 | id : id, .len = len, .flags = flags};
                if (!(flags & CO_FRAME_RTR))
                    for (uint8_t i = 0; i < len; i++)
                        f.data[i] = (uint8_t)(id + i * 37u);
                char line[SLCAN_LINE_MAX];
                size_t n = slcan_encode(&f, line);
                ck_assert_uint_gt(n, 0);
                ck_assert_int_eq(line[n - 1], '\r');
                slcan_message_t m = slcan_decode(line, n - 1);
                ck_assert_int_eq(m.kind, SLCAN_FRAME);
                ck_assert_mem_eq(&m.frame, &f, sizeof(f));
            }
        }
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("slcan");
    TCase *tc = tcase_create("slcan");
    tcase_add_test(tc, encode_standard_frames);
    tcase_add_test(tc, encode_remote_and_extended_frames);
    tcase_add_test(tc, encode_refuses_what_the_protocol_cannot_carry);
    tcase_add_test(tc, decode_frames);
    tcase_add_test(tc, decode_commands_and_their_answers);
    tcase_add_test(tc, malformed_lines_are_refused);
    tcase_add_test(tc, reader_gathers_lines_byte_by_byte);
    tcase_add_test(tc, reader_recovers_after_a_malformed_or_overlong_line);
    tcase_add_test(tc, every_frame_survives_a_round_trip);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
