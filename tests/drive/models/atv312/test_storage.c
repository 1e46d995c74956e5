/* SPDX-License-Identifier: Apache-2.0 */
/* What storage keeps of the drive (docs/decisions.md, D-STORE-PARAMETERS): parameters, never
 * process data; the values the CiA 402 views stand for; every stored value checked like an SDO
 * write. Reset node (000#8104) reloads the dictionary as a restart of the daemon does. */
#include "atv312_bench.h"
#include "check_main.h"
#include "memory_storage.h"
#include "test_bus.h"

static memory_storage_t mem;
static co_storage_t storage;
static bench_t b;

static void setup(void)
{
    memory_storage_init(&mem, &storage);
    bench_start_model(&b, &atv312_profile, &storage);
}

static void reset_node(void)
{
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
}

/* The frames: save all while running at 1200 rpm; after the reset the control word, CMD
 * and the reference are back at 0, and 0x0006, 0x0007, 0x000F never run the motor. */
/* ATV312 DeviceNet manual, "In access level L1 or L2": "At switch-on, the drive ... changes
 * automatically to the 'Operation enabled' state": a run command (CMD = 16#000F) starts it with no
 * status chart procedure. LAC = L1 stored, the drive switched on again: 0x0627 at once, and the
 * network's 000F with a reference runs the motor. A reset node is no switch-on. */
START_TEST(lac_l1_switches_on_in_operation_enabled)
{
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640); /* L3, the default */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 1, 1, 2), 0);
    bench_rx(&b, "604#2310100173617665");
    bench_expect(&b, "584#6010100100000000");
    bench_start_model(&b, &atv312_profile, &storage);
    ck_assert_uint_eq(bench_read(&b, 0x2036, 1), 1);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1200, 2), 0);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1200);
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

START_TEST(process_data_never_come_back_from_storage)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1200, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1200);
    bench_rx(&b, "604#2310100173617665");
    bench_expect(&b, "584#6010100100000000");
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2037, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2037, 5), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6042, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x0007);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0627);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* 1010h:03 saves the profile area: 6040h must not come back as 0x0006 while CMD reads 0. */
START_TEST(control_word_and_cmd_stay_one_word_across_a_save)
{
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 3, CO_STORE_SIGNATURE_SAVE, 4), 0);
    ck_assert_int_eq(memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6040, 0), 0);
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), bench_read(&b, 0x2037, 2));
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0);
}
END_TEST

/* 1010h:03 keeps what 6046h, 6048h and 6049h stand for (LSP/HSP, ACC, DEC). */
START_TEST(profile_save_keeps_what_the_views_stand_for)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 2, 1200, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 1, 1250, 4), 0); /* ACC 1.2 s */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6049, 2, 2, 2), 0);    /* DEC 6.0 s */
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 12);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 3), 60);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 3, CO_STORE_SIGNATURE_SAVE, 4), 0);
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6046, 2), 1200);
    ck_assert_uint_eq(bench_read(&b, 0x2001, 5), 400);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 12);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 3), 60);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* Save all, then 1011h:03 and reset: the views' defaults apply to what they stand for. */
START_TEST(profile_restore_restores_what_the_views_stand_for)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 2, 1200, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 1, 1250, 4), 0);
    bench_rx(&b, "604#2310100173617665");
    bench_expect(&b, "584#6010100100000000");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1011, 3, CO_STORE_SIGNATURE_LOAD, 4), 0);
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6046, 2), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x2001, 5), 500);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 30);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* Min above the default max: refused at first, applied once the max is (the values were valid
 * together when saved). */
START_TEST(values_valid_together_load_whatever_their_order)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 2, 1800, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 1, 1650, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 3, CO_STORE_SIGNATURE_SAVE, 4), 0);
    reset_node();
    ck_assert_uint_eq(bench_read(&b, 0x6046, 1), 1650);
    ck_assert_uint_eq(bench_read(&b, 0x6046, 2), 1800);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* A well-formed image holding NSP = 0 (limits 1..32767): refused and reported, NSP keeps its
 * default, and 6048h:02 = 1 (which divides by the ramp rate) is answered, not a crash. */
START_TEST(stored_value_outside_its_limits_is_skipped)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 2, 50, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 1, CO_STORE_SIGNATURE_SAVE, 4), 0);
    long nsp = memory_storage_record(&mem, CO_STORE_AREA_MANUFACTURER, 0x2042, 5);
    ck_assert_int_gt(nsp, 0);
    co_put_u16(mem.image[CO_STORE_AREA_MANUFACTURER] + nsp, 0);
    reset_node();
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2042, 5), CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(mem.refusals, 1);
    ck_assert_uint_eq(bench_read(&b, 0x2042, 5), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 50);
    bench_rx(&b, "604#2B48600201000000");
    bench_expect(&b, "584#6048600200000000");
}
END_TEST

/* Issue 22's image: NSP 4131 rpm and ACC 7.7 s, whose ramp 6048h reads, and 1010h:03 saves, as
 * 32726 / 61 (D-VIEW-LIMITS; 41310 / 77 before, over delta speed's HighLimit and refused at the
 * reset). NSP is not in that image: after the reset it is 1500 rpm again, and the image gives the
 * rate it holds, 536.5 rpm/s, ACC 2.8 s, its two terms applied one after the other. */
START_TEST(profile_image_of_a_ramp_beyond_its_limits)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2042, 5, 4131, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 2, 77, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 3, CO_STORE_SIGNATURE_SAVE, 4), 0);
    long speed = memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6048, 1);
    ck_assert_int_gt(speed, 0);
    ck_assert_uint_eq(co_get_u32(mem.image[CO_STORE_AREA_PROFILE] + speed), 32726);
    reset_node();
    ck_assert_uint_eq(mem.refusals, 0);
    ck_assert_uint_eq(bench_read(&b, 0x2042, 5), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 28);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 32726);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 61);
}
END_TEST

/* Two images that disagree on ACC: 1010h:01 saves NSP 4131 rpm with ACC 5.0 s, then 1010h:03 the
 * ramp of ACC 7.7 s. The later save wins: its pair, applied term by term over the ramp of 5.0 s
 * (the first term alone is 0.6 s), gives 7.7 s again. */
START_TEST(ramp_image_applied_term_by_term_over_another_ramp)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2042, 5, 4131, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 2, 50, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 1, CO_STORE_SIGNATURE_SAVE, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 2, 77, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 3, CO_STORE_SIGNATURE_SAVE, 4), 0);
    reset_node();
    ck_assert_uint_eq(mem.refusals, 0);
    ck_assert_uint_eq(bench_read(&b, 0x2042, 5), 4131);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 2), 77);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 32726);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 61);
}
END_TEST

/* Every byte of a drive_t not zeroed by its caller, before drive_init. */
#define PATTERN 0xA5u

/* Booted on stored values that settle the drive as they are applied, over memory that is not
 * zeroed (drive_init sets every field: issue 22), the drive sends what it sends over zeroes. */
START_TEST(stored_values_boot_a_drive_over_any_memory)
{
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 2, 50, 2), 0);   /* ACC 5.0 s */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 11, 101, 2), 0); /* rPS: LI1 */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1010, 1, CO_STORE_SIGNATURE_SAVE, 4), 0);
    static bench_t zeroed, patterned;
    bench_t *benches[] = {&zeroed, &patterned};
    for (size_t i = 0; i < 2; i++) {
        bench_t *run = benches[i];
        bench_start_model_over(run, &atv312_profile, &storage, i == 0 ? 0 : PATTERN);
        ck_assert_uint_eq(bench_read(run, 0x203C, 2), 50);
        ck_assert_uint_eq(bench_sdo_write(run, 0x6042, 0, 1500, 2), 0);
        bench_command(run, 0x0006);
        bench_command(run, 0x000F);
        bench_advance(run, 5000000);
        ck_assert_int_eq(bench_speed(run), 1500);
    }
    ck_assert_uint_eq(mem.refusals, 0);
    ck_assert_uint_eq(patterned.count, zeroed.count);
    for (size_t i = 0; i < zeroed.count; i++) {
        char want[32], got[32];
        ck_assert_str_eq(test_format(&patterned.frame[i], got),
                         test_format(&zeroed.frame[i], want));
        ck_assert_uint_eq(patterned.at[i], zeroed.at[i]);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_storage");
    TCase *tc = tcase_create("storage");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, process_data_never_come_back_from_storage);
    tcase_add_test(tc, lac_l1_switches_on_in_operation_enabled);
    tcase_add_test(tc, control_word_and_cmd_stay_one_word_across_a_save);
    tcase_add_test(tc, profile_save_keeps_what_the_views_stand_for);
    tcase_add_test(tc, profile_restore_restores_what_the_views_stand_for);
    tcase_add_test(tc, values_valid_together_load_whatever_their_order);
    tcase_add_test(tc, stored_value_outside_its_limits_is_skipped);
    tcase_add_test(tc, stored_values_boot_a_drive_over_any_memory);
    tcase_add_test(tc, profile_image_of_a_ramp_beyond_its_limits);
    tcase_add_test(tc, ramp_image_applied_term_by_term_over_another_ramp);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
