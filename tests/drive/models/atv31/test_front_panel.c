/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV31's front panel (the ATV31...A of its manual's front view): the STOP/RESET key, "used to
 * stop the motor and to reset the current faults", resets a fault whose cause is gone, as the
 * fault reset edge would; the ATV312, whose manual gives its STOP key no reset, stays in Fault. */
#include "atv31/atv31.h"
#include "atv312/atv312.h"
#include "check_main.h"
#include "drive_bench.h"

static uint8_t fault_index(bench_t *b, const char *code)
{
    int index = drive_fault_find(&b->drive, code);
    ck_assert_int_ge(index, 0);
    return (uint8_t)index;
}

/* Running at 1500 rpm, then OHF (drive overheating, reset by command): EMCY, Fault. */
static void overheat_at_speed(bench_t *b, const drive_profile_t *profile)
{
    bench_start_model(b, profile, NULL);
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    drive_fault_inject(&b->drive, fault_index(b, "OHF"), b->now);
    b->deadline = drive_process(&b->drive, b->now);
    bench_expect(b, "084#1042010000000000");
    ck_assert_uint_eq(bench_read(b, 0x6041, 0), 0x0608);
}

static void stop_key(bench_t *b)
{
    drive_stop_key(&b->drive, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

/* While the cause lasts the key stops (bit 14) and resets nothing; once it is gone the key ends
 * the fault: Switch on disabled with the STOP key's bit (0x4640), the EMCY error reset, 603Fh 0.
 * The network then runs the drive again through the status chart. */
START_TEST(stop_reset_key_resets_a_fault_whose_cause_is_gone)
{
    bench_t b;
    overheat_at_speed(&b, &atv31_profile);
    stop_key(&b);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x4608);
    drive_fault_remove_cause(&b.drive, fault_index(&b, "OHF"), b.now);
    b.deadline = drive_process(&b.drive, b.now);
    bench_expect_none(&b);
    stop_key(&b);
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x4640);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
}
END_TEST

/* A fault only a power cycle ends (OCF) is not reset by the key either. */
START_TEST(stop_reset_key_does_not_end_a_power_cycle_fault)
{
    bench_t b;
    bench_start_model(&b, &atv31_profile, NULL);
    uint8_t ocf = fault_index(&b, "OCF");
    drive_fault_inject(&b.drive, ocf, b.now);
    b.deadline = drive_process(&b.drive, b.now);
    bench_expect(&b, "084#1023010000000000");
    drive_fault_remove_cause(&b.drive, ocf, b.now);
    stop_key(&b);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x4608);
}
END_TEST

/* The ATV312's manual gives its STOP key no reset: the drive stays in Fault. */
START_TEST(atv312_stop_key_resets_no_fault)
{
    bench_t b;
    overheat_at_speed(&b, &atv312_profile);
    drive_fault_remove_cause(&b.drive, fault_index(&b, "OHF"), b.now);
    stop_key(&b);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x4608);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "OHF");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv31_front_panel");
    TCase *tc = tcase_create("stop_reset_key");
    tcase_add_test(tc, stop_reset_key_resets_a_fault_whose_cause_is_gone);
    tcase_add_test(tc, stop_reset_key_does_not_end_a_power_cycle_fault);
    tcase_add_test(tc, atv312_stop_key_resets_no_fault);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
