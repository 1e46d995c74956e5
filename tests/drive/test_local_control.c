/* SPDX-License-Identifier: Apache-2.0 */
/* At the drive, on the minimal model: the keypad's STOP key (a freewheel stop under network
 * control, the profile's status bit until the next run command), forced local control (status
 * word bit 9 = 0, the network's control word ignored, the RUN and STOP keys run the drive), and
 * an extra load on the motor (torque and current follow). */
#include "check_main.h"
#include "minimal_model.h"

/* Operation enabled at 1500 rpm (ACC 3.0 s: after 3 s). */
static void run_at_speed(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

static void settle(bench_t *b)
{
    b->deadline = drive_process(&b->drive, b->now);
}

START_TEST(stop_key_under_network_control_is_a_freewheel_stop)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    drive_stop_key(&b.drive, b.now);
    settle(&b);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640 | SW_STOP_KEY);
    /* The level 0x000F does not restart it; disable voltage keeps the bit. */
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0640 | SW_STOP_KEY);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0640 | SW_STOP_KEY);
    /* The master's next run sequence clears it. */
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_command(&b, 0x000F) & 0x006F, 0x0027);
}
END_TEST

START_TEST(forced_local_control_ignores_the_network)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    drive_set_local(&b.drive, true, b.now);
    settle(&b);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0440);
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0x000F);
    /* The RUN key runs to 6042h on the ACC ramp. */
    ck_assert(drive_run_key(&b.drive, b.now));
    settle(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0427);
    /* The STOP key stops on the DEC ramp (3.0 s), then Switch on disabled. */
    drive_stop_key(&b.drive, b.now);
    settle(&b);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0027 | SW_STOP_KEY);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440 | SW_STOP_KEY);
    /* Back to network control: Switch on disabled, remote, the network's commands work. */
    drive_set_local(&b.drive, false, b.now);
    settle(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640 | SW_STOP_KEY);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_command(&b, 0x000F) & 0x006F, 0x0027);
}
END_TEST

START_TEST(run_key_only_under_local_control_without_fault)
{
    bench_t b;
    bench_start(&b);
    ck_assert(!drive_run_key(&b.drive, b.now));
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    drive_set_local(&b.drive, true, b.now);
    drive_fault_inject(&b.drive, FAULT_HOT, b.now);
    settle(&b);
    bench_expect(&b, "084#1042090000000000");
    ck_assert(!drive_run_key(&b.drive, b.now));
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0408);
    /* Leaving local control keeps the fault latched. */
    drive_set_local(&b.drive, false, b.now);
    settle(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
}
END_TEST

START_TEST(load_raises_torque_and_current_while_turning)
{
    bench_t b;
    bench_start(&b);
    drive_set_load(&b.drive, 50, b.now);
    settle(&b);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, TORQUE), 0);
    run_at_speed(&b);
    /* 20 % fan-like load at nominal speed plus 50 %: 70 %; 4.0 A x (30 % + 70 % x 70 %). */
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, TORQUE), 70);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 31);
    drive_set_load(&b.drive, 0, b.now);
    settle(&b);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, TORQUE), 20);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 17);
    /* The load outlives a reset node. */
    drive_set_load(&b.drive, 100, b.now);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    run_at_speed(&b);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, TORQUE), 120);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_local");
    TCase *tc = tcase_create("local");
    tcase_add_test(tc, stop_key_under_network_control_is_a_freewheel_stop);
    tcase_add_test(tc, forced_local_control_ignores_the_network);
    tcase_add_test(tc, run_key_only_under_local_control_without_fault);
    tcase_add_test(tc, load_raises_torque_and_current_while_turning);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
