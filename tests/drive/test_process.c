/* SPDX-License-Identifier: Apache-2.0 */
/* drive_process works only when something changed (issue 10): a steady drive neither runs its
 * motor model nor touches its dictionary, a reset or a moving motor makes it settle. Observed by
 * changing the published status word behind the drive's back: a settle would publish it again. */
#include "check_main.h"
#include "minimal_model.h"

#define STATUS_SWITCH_ON_DISABLED 0x0640u /* remote, target reached */
#define FOREIGN_VALUE 0x1234

static void overwrite_status_word(bench_t *b)
{
    co_od_set_value(&b->drive.node, 0x6041, 0, FOREIGN_VALUE);
}

START_TEST(a_steady_drive_publishes_nothing_when_processed)
{
    bench_t b;
    bench_start(&b);
    overwrite_status_word(&b);
    bench_advance(&b, 1000000);
    bench_rx(&b, "000#0204"); /* an NMT command to another node: the core alone */
    ck_assert_int_eq(co_od_value(&b.drive.node, 0x6041, 0), FOREIGN_VALUE);
}
END_TEST

START_TEST(a_reset_settles_the_drive_on_the_restored_defaults)
{
    bench_t b;
    bench_start(&b);
    overwrite_status_word(&b);
    bench_rx(&b, "000#8204"); /* reset communication */
    bench_expect(&b, "704#00");
    ck_assert_uint_eq(co_od_value(&b.drive.node, 0x6041, 0), STATUS_SWITCH_ON_DISABLED);
    overwrite_status_word(&b);
    bench_rx(&b, "000#8104"); /* reset node */
    bench_expect(&b, "704#00");
    ck_assert_uint_eq(co_od_value(&b.drive.node, 0x6041, 0), STATUS_SWITCH_ON_DISABLED);
}
END_TEST

START_TEST(a_moving_motor_is_published_until_it_reaches_its_target)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x0007);
    bench_command(&b, 0x000F);
    /* ACC 3.0 s to 1500 rpm: 500 rpm after 1 s, every tick on the way published. */
    bench_advance(&b, 1000000);
    ck_assert_int_eq(co_od_value(&b.drive.node, 0x6044, 0), 500);
    overwrite_status_word(&b);
    bench_advance(&b, 10000);
    ck_assert_int_ne(co_od_value(&b.drive.node, 0x6041, 0), FOREIGN_VALUE);
    bench_advance(&b, 2000000);
    ck_assert_int_eq(co_od_value(&b.drive.node, 0x6044, 0), 1500);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
    overwrite_status_word(&b);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(co_od_value(&b.drive.node, 0x6041, 0), FOREIGN_VALUE);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_process");
    TCase *tc = tcase_create("drive_process");
    tcase_add_test(tc, a_steady_drive_publishes_nothing_when_processed);
    tcase_add_test(tc, a_reset_settles_the_drive_on_the_restored_defaults);
    tcase_add_test(tc, a_moving_motor_is_published_until_it_reaches_its_target);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
