/* SPDX-License-Identifier: Apache-2.0 */
/* The process image as the PLC300 manual's network markers (CANopen communication manual, 5.4
 * and 7.2): every address of its tables and the ones around them, the three sizes over the same
 * bytes, least significant first, and values that do not fit. */
#include "check_main.h"
#include "co/co_image_address.h"

#include <string.h>

static co_image_address_t parsed(const char *text)
{
    co_image_address_t a = {CO_IMAGE_OUTPUT, 0, 0xFFFF};
    ck_assert_msg(co_image_address_parse(text, &a), "%s refused", text);
    return a;
}

START_TEST(the_manuals_addresses)
{
    /* Table 5.4's first and last rows of each area and size. */
    co_image_address_t a = parsed("%IB2000");
    ck_assert_int_eq(a.area, CO_IMAGE_INPUT);
    ck_assert_uint_eq(a.size, 1);
    ck_assert_uint_eq(a.offset, 0);
    a = parsed("%IB2511");
    ck_assert_uint_eq(a.offset, 511);
    a = parsed("%IW2510");
    ck_assert_uint_eq(a.size, 2);
    ck_assert_uint_eq(a.offset, 510);
    a = parsed("%ID2508");
    ck_assert_uint_eq(a.size, 4);
    ck_assert_uint_eq(a.offset, 508);
    a = parsed("%QB2001");
    ck_assert_int_eq(a.area, CO_IMAGE_OUTPUT);
    ck_assert_uint_eq(a.offset, 1);
    a = parsed("%QW2002");
    ck_assert_uint_eq(a.size, 2);
    ck_assert_uint_eq(a.offset, 2);
    a = parsed("%qd2004");
    ck_assert_int_eq(a.area, CO_IMAGE_OUTPUT);
    ck_assert_uint_eq(a.size, 4);
    ck_assert_uint_eq(a.offset, 4);
}
END_TEST

START_TEST(what_is_not_an_address)
{
    static const char *const refused[] = {
        "",        "%",        "IB2000",   "%XB2000",  "%IX2000",  "%IB",         "%IB1999",
        "%IB2512", "%IW2511",  "%IW2512",  "%IW2001",  "%ID2002",  "%ID2510",     "%ID2512",
        "%IB-200", "%IB 2000", "%IB2000 ", "%IB02000", "%IB2000x", "%IB99999999", "% QW2510",
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        co_image_address_t a = {CO_IMAGE_OUTPUT, 7, 0xABCD};
        ck_assert_msg(!co_image_address_parse(refused[i], &a), "%s taken", refused[i]);
        ck_assert_uint_eq(a.size, 7); /* untouched */
        ck_assert_uint_eq(a.offset, 0xABCD);
    }
    ck_assert(!co_image_address_parse(NULL, &(co_image_address_t){0}));
}
END_TEST

START_TEST(byte_word_double_word_share_the_bytes)
{
    uint8_t image[CO_IMAGE_ADDRESS_IMAGE_SIZE];
    memset(image, 0, sizeof image);
    image[4] = 0x78;
    image[5] = 0x56;
    image[6] = 0x34;
    image[7] = 0x12;
    image[511] = 0xE7;
    co_image_address_t a = parsed("%ID2004");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0x12345678u);
    a = parsed("%IW2004");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0x5678u);
    a = parsed("%IW2006");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0x1234u);
    a = parsed("%IB2005");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0x56u);
    a = parsed("%IB2511");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0xE7u);
    a = parsed("%IW2510");
    ck_assert_uint_eq(co_image_address_get(image, &a), 0xE700u);
}
END_TEST

START_TEST(bytes_of_a_value)
{
    uint8_t bytes[4] = {0xAA, 0xAA, 0xAA, 0xAA};
    co_image_address_t a = parsed("%QW2000");
    ck_assert(co_image_address_bytes(&a, 1200, bytes));
    ck_assert_mem_eq(bytes, ((const uint8_t[]){0xB0, 0x04, 0xAA, 0xAA}), 4);
    ck_assert(!co_image_address_bytes(&a, 0x10000, bytes));
    ck_assert_mem_eq(bytes, ((const uint8_t[]){0xB0, 0x04, 0xAA, 0xAA}), 4);
    a = parsed("%QB2003");
    ck_assert(co_image_address_bytes(&a, 255, bytes));
    ck_assert_uint_eq(bytes[0], 0xFF);
    ck_assert_uint_eq(bytes[1], 0x04);
    ck_assert(!co_image_address_bytes(&a, 256, bytes));
    a = parsed("%QD2508");
    ck_assert(co_image_address_bytes(&a, 0xFFFFFFFFu, bytes));
    ck_assert_mem_eq(bytes, ((const uint8_t[]){0xFF, 0xFF, 0xFF, 0xFF}), 4);
    ck_assert(co_image_address_bytes(&a, 0x01020304u, bytes));
    ck_assert_mem_eq(bytes, ((const uint8_t[]){0x04, 0x03, 0x02, 0x01}), 4);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("image_address");
    TCase *tc = tcase_create("image_address");
    tcase_add_test(tc, the_manuals_addresses);
    tcase_add_test(tc, what_is_not_an_address);
    tcase_add_test(tc, byte_word_double_word_share_the_bytes);
    tcase_add_test(tc, bytes_of_a_value);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
