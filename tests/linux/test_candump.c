/* SPDX-License-Identifier: Apache-2.0 */
/* The candump -L trace format: exact lines for data, RTR, 29-bit and error frames, and parsing
 * back what it writes; malformed lines are refused. */
#include "check_main.h"
#include "co_linux/candump.h"

#include <check.h>
#include <linux/can/error.h>
#include <stdlib.h>
#include <string.h>

static const struct timespec wall = {.tv_sec = 1700000000, .tv_nsec = 123456789};

static const char *format(const struct can_frame *f)
{
    static char line[CO_CANDUMP_LINE_MAX];
    size_t n = co_candump_format(line, sizeof line, &wall, "vcan0", f);
    ck_assert_uint_eq(n, strlen(line));
    return line;
}

START_TEST(formats_sdo_request)
{
    struct can_frame f = {.can_id = 0x604, .len = 8, .data = {0x40, 0x00, 0x10, 0x00}};
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 604#4000100000000000\n");
}
END_TEST

START_TEST(formats_rtr_with_and_without_dlc)
{
    struct can_frame f = {.can_id = 0x704 | CAN_RTR_FLAG, .len = 0};
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 704#R\n");
    f.len = 1;
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 704#R1\n");
}
END_TEST

START_TEST(formats_empty_extended_and_error_frames)
{
    struct can_frame f = {.can_id = 0x000, .len = 0};
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 000#\n");
    f = (struct can_frame){.can_id = 0x1ABCDEF0 | CAN_EFF_FLAG, .len = 2, .data = {0xA5, 0x0F}};
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 1ABCDEF0#A50F\n");
    f = (struct can_frame){.can_id = CAN_ERR_FLAG | 0x40, .len = 8};
    ck_assert_str_eq(format(&f), "(1700000000.123456) vcan0 20000040#0000000000000000\n");
}
END_TEST

START_TEST(formats_small_timestamps_zero_padded)
{
    struct timespec early = {.tv_sec = 12, .tv_nsec = 5000};
    struct can_frame f = {.can_id = 0x080, .len = 0};
    char line[CO_CANDUMP_LINE_MAX];
    co_candump_format(line, sizeof line, &early, "can1", &f);
    ck_assert_str_eq(line, "(0000000012.000005) can1 080#\n");
}
END_TEST

START_TEST(refuses_too_small_buffer)
{
    struct can_frame f = {.can_id = 0x604, .len = 8};
    char line[30];
    ck_assert_uint_eq(co_candump_format(line, sizeof line, &wall, "vcan0", &f), 0);
}
END_TEST

/* The longest line co_candump_parse reads back (19-digit seconds, a 15-character interface, an
 * error frame's 8 digits and 8 bytes) fits CO_CANDUMP_LINE_MAX: cotrace prints every line it
 * reads. */
START_TEST(formats_the_longest_line)
{
    struct timespec latest = {.tv_sec = 9223372036854775807LL, .tv_nsec = 999999999};
    struct can_frame f = {.can_id = CAN_ERR_FLAG | CAN_ERR_MASK, .len = 8};
    memset(f.data, 0xFF, sizeof f.data);
    char line[CO_CANDUMP_LINE_MAX];
    size_t n = co_candump_format(line, sizeof line, &latest, "abcdefghijklmno", &f);
    ck_assert_str_eq(line,
                     "(9223372036854775807.999999) abcdefghijklmno 3FFFFFFF#FFFFFFFFFFFFFFFF\n");
    ck_assert_uint_eq(n, sizeof line - 1);
    struct timespec ts;
    char iface[IFNAMSIZ];
    struct can_frame back;
    ck_assert(co_candump_parse(line, &ts, iface, &back));
    ck_assert_int_eq(ts.tv_sec, latest.tv_sec);
    ck_assert_str_eq(iface, "abcdefghijklmno");
    ck_assert_uint_eq(back.can_id, f.can_id);
}
END_TEST

START_TEST(parses_what_it_formats)
{
    const struct can_frame frames[] = {
        {.can_id = 0x604, .len = 8, .data = {0x2B, 0x3C, 0x20, 0x02, 0xE8, 0x03}},
        {.can_id = 0x704 | CAN_RTR_FLAG, .len = 1},
        {.can_id = 0x000, .len = 2, .data = {0x01, 0x04}},
        {.can_id = 0x12345678 | CAN_EFF_FLAG, .len = 3, .data = {1, 2, 3}},
        {.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL, .len = 8, .data = {0, 0x10}},
    };
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        struct timespec ts;
        char iface[IFNAMSIZ];
        struct can_frame back;
        ck_assert(co_candump_parse(format(&frames[i]), &ts, iface, &back));
        ck_assert_int_eq(ts.tv_sec, 1700000000);
        ck_assert_int_eq(ts.tv_nsec, 123456000);
        ck_assert_str_eq(iface, "vcan0");
        ck_assert_uint_eq(back.can_id, frames[i].can_id);
        ck_assert_uint_eq(back.len, frames[i].len);
        ck_assert_mem_eq(back.data, frames[i].data, frames[i].len);
    }
}
END_TEST

START_TEST(parses_lower_case_and_no_newline)
{
    struct timespec ts;
    char iface[IFNAMSIZ];
    struct can_frame f;
    ck_assert(co_candump_parse("(1.000001) can0 5fe#a0ff", &ts, iface, &f));
    ck_assert_uint_eq(f.can_id, 0x5FE);
    ck_assert_uint_eq(f.len, 2);
    ck_assert_uint_eq(f.data[0], 0xA0);
    ck_assert_uint_eq(f.data[1], 0xFF);
    ck_assert_int_eq(ts.tv_nsec, 1000);
}
END_TEST

/* canplayer and log2asc read any number of digits on either side of the point; the fraction is
 * a decimal fraction of a second, kept to the nanosecond (D-CANDUMP-FRACTION). */
START_TEST(parses_any_number_of_timestamp_digits)
{
    static const struct {
        const char *line;
        long long sec;
        long nsec;
    } cases[] = {
        {"(1.0) vcan0 604#00", 1, 0},
        {"(0.5) vcan0 604#00", 0, 500000000},
        {"(12.34567) vcan0 604#00", 12, 345670000},
        {"(1700000000.123456789) vcan0 604#00", 1700000000, 123456789},
        {"(1700000000.1234567891) vcan0 604#00", 1700000000, 123456789},
        {"(007.000001) vcan0 604#00", 7, 1000},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct timespec ts;
        char iface[IFNAMSIZ];
        struct can_frame f;
        ck_assert_msg(co_candump_parse(cases[i].line, &ts, iface, &f), "refused %s", cases[i].line);
        ck_assert_int_eq(ts.tv_sec, cases[i].sec);
        ck_assert_int_eq(ts.tv_nsec, cases[i].nsec);
    }
}
END_TEST

START_TEST(refuses_malformed_lines)
{
    static const char *const bad[] = {
        "",
        "604#00",
        "(1700000000.123456) vcan0 604",
        "(1700000000.) vcan0 604#00",                       /* no fraction digit */
        "(.123456) vcan0 604#00",                           /* no second digit */
        "(1700000000) vcan0 604#00",                        /* no point */
        "(99999999999999999999.0) vcan0 604#00",            /* seconds overflow */
        "(1700000000.123456)vcan0 604#00",                  /* no space */
        "(1700000000.123456) vcan0 6040#00",                /* 4-digit id */
        "(1700000000.123456) vcan0 804#00",                 /* above 0x7FF */
        "(1700000000.123456) vcan0 604#0",                  /* half a byte */
        "(1700000000.123456) vcan0 604#0G",                 /* not hex */
        "(1700000000.123456) vcan0 604#000102030405060708", /* 9 bytes */
        "(1700000000.123456) vcan0 704#RX",
        "(1700000000.123456) vcan0 E0000000#00", /* bits above the error flag */
        "(1700000000.123456) averyveryverylongname 604#00",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        struct timespec ts;
        char iface[IFNAMSIZ];
        struct can_frame f;
        ck_assert_msg(!co_candump_parse(bad[i], &ts, iface, &f), "accepted \"%s\"", bad[i]);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("candump");
    TCase *tc = tcase_create("candump");
    tcase_add_test(tc, formats_sdo_request);
    tcase_add_test(tc, formats_rtr_with_and_without_dlc);
    tcase_add_test(tc, formats_empty_extended_and_error_frames);
    tcase_add_test(tc, formats_small_timestamps_zero_padded);
    tcase_add_test(tc, refuses_too_small_buffer);
    tcase_add_test(tc, formats_the_longest_line);
    tcase_add_test(tc, parses_what_it_formats);
    tcase_add_test(tc, parses_lower_case_and_no_newline);
    tcase_add_test(tc, parses_any_number_of_timestamp_digits);
    tcase_add_test(tc, refuses_malformed_lines);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
