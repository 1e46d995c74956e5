/* SPDX-License-Identifier: Apache-2.0 */
/* An SDO download whose indicated size is not the object's, on every model of the table
 * (models.c): CiA 301 7.2.4.3.17, shorter 0x06070013, longer 0x06070012, frame for frame, as a PLC
 * sends it with a Size# of 1..4 bytes (the PLC300 manual's CO_SDOWrite block: "Size of the
 * accessed data in bytes - 1 to 4"; its NOTE: the quantity "is compatible with the size of the
 * variable"). The object is 100Ch, the guard time, UNSIGNED16 and writable on every model. An
 * expedited write with the size indicated and a segmented one with the size announced are refused
 * alike; a longer expedited write whose extra bytes are 0 is taken (D-ATV312-LONG-EXPEDITED).
 * The ATV58 answers in its card's layout (D-ATV58-OPTIONS: error code in byte 6, class in byte 7,
 * 1/6 for every refusal of an object's access, 3/5 for a segmented initiate, which it does not
 * support) and pads every frame to 8 bytes. */
#include "check_main.h"
#include "drive/models/models.h"
#include "drive_bench.h"

static const drive_model_t *model_named(const char *name)
{
    const drive_model_t *model = drive_model_find(name);
    ck_assert_ptr_nonnull(model);
    return model;
}

static void exchange(bench_t *b, const char *request, const char *answer)
{
    bench_rx(b, request);
    bench_expect(b, answer);
    bench_expect_none(b);
}

/* Size# into the UNSIGNED16 100Ch: 1 byte (0x2F), shorter; 3 bytes (0x27) and 4 bytes (0x23) with
 * a non-zero extra byte, longer; 4 bytes zero-extended (0x23), taken; then its 2 bytes (0x2B); and
 * 2 bytes into the UNSIGNED32 COB-ID of TPDO1 (1800h:01), shorter (read-only on the ATV58: refused
 * as such, in the same 1/6). */
static void expedited_sizes(bench_t *b, const char *short_abort, const char *long_abort,
                            const char *cob_id_short_abort)
{
    uint32_t guard_time = bench_read(b, 0x100C, 0);
    exchange(b, "604#2F0C1000F4000000", short_abort);
    exchange(b, "604#270C1000F4010100", long_abort);
    exchange(b, "604#230C1000F4010001", long_abort);
    ck_assert_uint_eq(bench_read(b, 0x100C, 0), guard_time);
    exchange(b, "604#230C1000F4010000", "584#600C100000000000");
    ck_assert_uint_eq(bench_read(b, 0x100C, 0), 500);
    exchange(b, "604#2B0C1000E8030000", "584#600C100000000000");
    ck_assert_uint_eq(bench_read(b, 0x100C, 0), 1000);
    exchange(b, "604#2B00180184010000", cob_id_short_abort);
    ck_assert_uint_eq(bench_read(b, 0x1800, 1), 0x184);
}

START_TEST(atv312_family_refuses_a_size_not_the_objects)
{
    static const char *const names[] = {"atv312", "atv31", "atv31-v1.1"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        bench_t b;
        bench_start_model(&b, model_named(names[i])->profile, NULL);
        expedited_sizes(&b, "584#800C100013000706", "584#800C100012000706", "584#8000180113000706");
        /* Segmented, 1 byte announced and sent: refused once complete. */
        exchange(&b, "604#210C100001000000", "584#600C100000000000");
        exchange(&b, "604#0D05000000000000", "584#800C100013000706");
        /* Segmented, 4 bytes announced and sent, the last two not 0: too long. */
        exchange(&b, "604#210C100004000000", "584#600C100000000000");
        exchange(&b, "604#0700000101000000", "584#800C100012000706");
        ck_assert_uint_eq(bench_read(&b, 0x100C, 0), 1000);
    }
}
END_TEST

START_TEST(atv58_refuses_a_size_not_the_objects_in_its_layout)
{
    bench_t b;
    bench_start_model(&b, model_named("atv58")->profile, NULL);
    expedited_sizes(&b, "584#800C100000000106", "584#800C100000000106", "584#8000180100000106");
    exchange(&b, "604#210C100001000000", "584#800C100000000305");
    ck_assert_uint_eq(bench_read(&b, 0x100C, 0), 1000);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("models_sdo_size");
    TCase *tc = tcase_create("size");
    tcase_add_test(tc, atv312_family_refuses_a_size_not_the_objects);
    tcase_add_test(tc, atv58_refuses_a_size_not_the_objects_in_its_layout);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
