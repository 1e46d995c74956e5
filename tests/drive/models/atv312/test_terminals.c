/* SPDX-License-Identifier: Apache-2.0 */
/* The terminals' run inputs, 2-wire control (docs/decisions.md, D-TERMINAL-RUN): while the
 * command comes from the terminals (CHCF = SEP with Cd1 = terminals, or CHCF = SIM with the
 * reference on an analogue input), LI1 switched on runs forward, LI2 in reverse, off stops on
 * the DEC ramp to Switch on disabled. The status word has bit 9 clear (local). */
#include "atv312_bench.h"
#include "check_main.h"

#define CHCF 0x2036, 2
#define FR1 0x2036, 14
#define CD1 0x2036, 24

static void input(bench_t *b, uint8_t n, bool on)
{
    ck_assert(drive_set_input(&b->drive, n, on, b->now));
    b->deadline = drive_process(&b->drive, b->now);
}

/* CHCF = SEP, Cd1 = terminals, the reference 6042h = 1500 rpm from the network (Fr1). */
static void terminals_command(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, CHCF, 2, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, CD1, 1, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_read(b, 0x6041, 0), 0x0440);
}

/* LI1 on: Operation enabled, the motor ramps to 1500 rpm (ETA 0x0427 there); off: the DEC ramp
 * (3.0 s), then Switch on disabled (0x0440). LI2 the same in reverse (0x8427). */
START_TEST(li1_forward_li2_reverse_in_2_wire_control)
{
    bench_t b;
    bench_start(&b);
    terminals_command(&b);
    input(&b, 1, true);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0427);
    input(&b, 1, false);
    bench_advance(&b, 2999000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0027);
    bench_advance(&b, 1000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    input(&b, 2, true);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), -1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x8427);
}
END_TEST

/* Both run inputs on stop the drive; the one left on needs a new change to on to run again. */
START_TEST(both_run_inputs_stop)
{
    bench_t b;
    bench_start(&b);
    terminals_command(&b);
    input(&b, 1, true);
    bench_advance(&b, 3000000);
    input(&b, 2, true);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    input(&b, 2, false);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    input(&b, 1, false);
    input(&b, 1, true);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 500);
}
END_TEST

/* An input that is no run input (LI3) leaves a run as it is: here the keypad's, with both run
 * inputs off. */
START_TEST(other_inputs_leave_the_run)
{
    bench_t b;
    bench_start(&b);
    terminals_command(&b);
    ck_assert(drive_run_key(&b.drive, b.now));
    bench_advance(&b, 3000000);
    input(&b, 3, true);
    input(&b, 3, false);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0427);
}
END_TEST

/* LI1 on before the terminals take the command starts nothing (a run needs the change), nor does
 * a run input in Fault; under network control the run inputs do nothing. */
START_TEST(a_run_needs_the_inputs_change)
{
    bench_t b;
    bench_start(&b);
    input(&b, 1, true);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    terminals_command(&b);
    bench_advance(&b, 1000000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    input(&b, 1, false);
    drive_fault_inject(&b.drive, (uint8_t)drive_fault_find(&b.drive, "OHF"), b.now);
    input(&b, 1, true);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0408);
}
END_TEST

/* CHCF = SIM with Fr1 = AI2: reference and command from the terminals, the Altivar's terminal
 * wiring: LI1 runs to AI2's speed, 5 V 750 rpm (6044h read frame for frame). */
START_TEST(terminals_with_an_analogue_reference)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, FR1, 2, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert(drive_set_analog(&b.drive, (uint8_t)drive_analog_find(&b.drive, "AI2"), 5000, b.now));
    input(&b, 1, true);
    bench_advance(&b, 2000000);
    const bench_exchange_t read[] = {
        {"6044h", "604#4044600000000000", 0, {"584#4B446000EE020000"}},
        {"6041h", "604#4041600000000000", 0, {"584#4B41600027040000"}},
    };
    bench_play(&b, read, 2);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_terminals");
    TCase *tc = tcase_create("terminals");
    tcase_add_test(tc, li1_forward_li2_reverse_in_2_wire_control);
    tcase_add_test(tc, both_run_inputs_stop);
    tcase_add_test(tc, other_inputs_leave_the_run);
    tcase_add_test(tc, a_run_needs_the_inputs_change);
    tcase_add_test(tc, terminals_with_an_analogue_reference);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
