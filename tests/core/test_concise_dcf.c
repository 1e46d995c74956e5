/* SPDX-License-Identifier: Apache-2.0 */
/* The concise DCF (CiA 302-3): the exact bytes written, read back entry by entry, and every way
 * a buffer fails to be one (short headers, an entry past the end, a size of 0, bytes after the
 * last entry), none read past its length. */
#include "check_main.h"
#include "co/co_concise_dcf.h"

#include <string.h>

static const uint8_t heartbeat[] = {0x64, 0x00};
static const uint8_t value32[] = {0x78, 0x56, 0x34, 0x12};
/* 1017h = 100, 2000h:07 = 12345678h, as the bytes CiA 302-3 lays out. */
static const uint8_t two_entries[] = {0x02, 0x00, 0x00, 0x00, 0x17, 0x10, 0x00, 0x02,
                                      0x00, 0x00, 0x00, 0x64, 0x00, 0x00, 0x20, 0x07,
                                      0x04, 0x00, 0x00, 0x00, 0x78, 0x56, 0x34, 0x12};

START_TEST(written_byte_by_byte)
{
    uint8_t buf[64];
    size_t used = co_concise_dcf_begin(buf, sizeof buf);
    ck_assert_uint_eq(used, 4);
    co_concise_dcf_entry_t a = {0x1017, 0, heartbeat, sizeof heartbeat};
    co_concise_dcf_entry_t b = {0x2000, 7, value32, sizeof value32};
    used = co_concise_dcf_add(buf, sizeof buf, used, &a);
    ck_assert_uint_eq(used, 13);
    used = co_concise_dcf_add(buf, sizeof buf, used, &b);
    ck_assert_uint_eq(used, sizeof two_entries);
    ck_assert_mem_eq(buf, two_entries, sizeof two_entries);
    /* No room: 0 and nothing changed; an entry without bytes is none. */
    ck_assert_uint_eq(co_concise_dcf_add(buf, used + 10, used, &b), 0);
    ck_assert_mem_eq(buf, two_entries, sizeof two_entries);
    co_concise_dcf_entry_t empty = {0x2000, 8, value32, 0};
    ck_assert_uint_eq(co_concise_dcf_add(buf, sizeof buf, used, &empty), 0);
    ck_assert_uint_eq(co_concise_dcf_begin(buf, 3), 0);
}
END_TEST

START_TEST(read_entry_by_entry)
{
    uint32_t count = 0;
    ck_assert(co_concise_dcf_valid(two_entries, sizeof two_entries, &count));
    ck_assert_uint_eq(count, 2);
    size_t pos = CO_CONCISE_DCF_HEADER;
    co_concise_dcf_entry_t e;
    ck_assert(co_concise_dcf_next(two_entries, sizeof two_entries, &pos, &e));
    ck_assert_uint_eq(e.index, 0x1017);
    ck_assert_uint_eq(e.subindex, 0);
    ck_assert_uint_eq(e.len, 2);
    ck_assert_ptr_eq(e.data, two_entries + 11);
    ck_assert(co_concise_dcf_next(two_entries, sizeof two_entries, &pos, &e));
    ck_assert_uint_eq(e.index, 0x2000);
    ck_assert_uint_eq(e.subindex, 7);
    ck_assert_uint_eq(e.len, 4);
    ck_assert_mem_eq(e.data, value32, 4);
    ck_assert_uint_eq(pos, sizeof two_entries);
    ck_assert(!co_concise_dcf_next(two_entries, sizeof two_entries, &pos, &e));
    const uint8_t none[] = {0, 0, 0, 0};
    ck_assert(co_concise_dcf_valid(none, sizeof none, &count));
    ck_assert_uint_eq(count, 0);
}
END_TEST

START_TEST(what_is_not_one)
{
    uint8_t buf[sizeof two_entries + 1];
    memcpy(buf, two_entries, sizeof two_entries);
    ck_assert(!co_concise_dcf_valid(NULL, 4, NULL));
    ck_assert(!co_concise_dcf_valid(buf, 3, NULL));                      /* no count */
    ck_assert(!co_concise_dcf_valid(buf, sizeof two_entries - 1, NULL)); /* last byte missing */
    ck_assert(!co_concise_dcf_valid(buf, 10, NULL));                     /* a header cut */
    buf[sizeof two_entries] = 0;
    ck_assert(!co_concise_dcf_valid(buf, sizeof buf, NULL)); /* a byte after the last entry */
    buf[0] = 3;
    ck_assert(!co_concise_dcf_valid(buf, sizeof buf, NULL)); /* a third entry that is not there */
    buf[0] = 2;
    buf[7] = 0; /* the first entry's size 0 */
    ck_assert(!co_concise_dcf_valid(buf, sizeof two_entries, NULL));
    buf[7] = 0x02;
    buf[10] = 0x80; /* a size of 2^31 + 2 */
    ck_assert(!co_concise_dcf_valid(buf, sizeof two_entries, NULL));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("concise_dcf");
    TCase *tc = tcase_create("concise_dcf");
    tcase_add_test(tc, written_byte_by_byte);
    tcase_add_test(tc, read_entry_by_entry);
    tcase_add_test(tc, what_is_not_one);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
