/* SPDX-License-Identifier: Apache-2.0 */
/* co_frame_t <-> struct can_frame: the data bytes past the length (and all of a remote frame's)
 * arrive zero whatever the source holds there, the length is clamped to 8, the flags map. */
#include "check_main.h"
#include "co_linux/can_frame.h"

#include <check.h>

static const uint8_t garbage[8] = {0xA1, 0xB2, 0xC3, 0xD4, 0xE5, 0xF6, 0x17, 0x28};

START_TEST(to_can_keeps_len_bytes_and_zeroes_the_rest)
{
    for (uint8_t len = 0; len <= 8; len++) {
        co_frame_t in = {.id = 0x581, .len = len};
        memcpy(in.data, garbage, sizeof garbage);
        struct can_frame out;
        memset(&out, 0x55, sizeof out);
        co_linux_frame_to_can(&in, &out);
        ck_assert_uint_eq(out.can_id, 0x581);
        ck_assert_uint_eq(out.len, len);
        for (uint8_t i = 0; i < 8; i++)
            ck_assert_uint_eq(out.data[i], i < len ? garbage[i] : 0);
        ck_assert_uint_eq(out.__pad, 0);
        ck_assert_uint_eq(out.__res0, 0);
        ck_assert_uint_eq(out.len8_dlc, 0);
    }
}
END_TEST

START_TEST(from_can_keeps_len_bytes_and_zeroes_the_rest)
{
    for (uint8_t len = 0; len <= 8; len++) {
        struct can_frame in = {.can_id = 0x604, .len = len};
        memcpy(in.data, garbage, sizeof garbage);
        co_frame_t out;
        memset(&out, 0x55, sizeof out);
        co_linux_frame_from_can(&in, &out);
        ck_assert_uint_eq(out.id, 0x604);
        ck_assert_uint_eq(out.len, len);
        ck_assert_uint_eq(out.flags, 0);
        for (uint8_t i = 0; i < 8; i++)
            ck_assert_uint_eq(out.data[i], i < len ? garbage[i] : 0);
    }
}
END_TEST

START_TEST(remote_frames_carry_no_data)
{
    co_frame_t in = {.id = 0x704, .len = 1, .flags = CO_FRAME_RTR};
    memcpy(in.data, garbage, sizeof garbage);
    struct can_frame cf;
    co_linux_frame_to_can(&in, &cf);
    ck_assert_uint_eq(cf.can_id, 0x704 | CAN_RTR_FLAG);
    ck_assert_uint_eq(cf.len, 1);
    for (int i = 0; i < 8; i++)
        ck_assert_uint_eq(cf.data[i], 0);

    memcpy(cf.data, garbage, sizeof garbage);
    co_frame_t back;
    co_linux_frame_from_can(&cf, &back);
    ck_assert_uint_eq(back.id, 0x704);
    ck_assert_uint_eq(back.flags, CO_FRAME_RTR);
    ck_assert_uint_eq(back.len, 1);
    for (int i = 0; i < 8; i++)
        ck_assert_uint_eq(back.data[i], 0);
}
END_TEST

START_TEST(length_is_clamped_and_extended_ids_map)
{
    co_frame_t in = {.id = 0x1ABCDEF, .len = 15, .flags = CO_FRAME_EFF};
    memcpy(in.data, garbage, sizeof garbage);
    struct can_frame cf;
    co_linux_frame_to_can(&in, &cf);
    ck_assert_uint_eq(cf.can_id, 0x1ABCDEF | CAN_EFF_FLAG);
    ck_assert_uint_eq(cf.len, 8);
    ck_assert_mem_eq(cf.data, garbage, 8);

    cf.len = 12;
    co_frame_t back;
    co_linux_frame_from_can(&cf, &back);
    ck_assert_uint_eq(back.id, 0x1ABCDEF);
    ck_assert_uint_eq(back.flags, CO_FRAME_EFF);
    ck_assert_uint_eq(back.len, 8);
    ck_assert_mem_eq(back.data, garbage, 8);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("can_frame");
    TCase *tc = tcase_create("can_frame");
    tcase_add_test(tc, to_can_keeps_len_bytes_and_zeroes_the_rest);
    tcase_add_test(tc, from_can_keeps_len_bytes_and_zeroes_the_rest);
    tcase_add_test(tc, remote_frames_carry_no_data);
    tcase_add_test(tc, length_is_clamped_and_extended_ids_map);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
