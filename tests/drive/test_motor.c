/* SPDX-License-Identifier: Apache-2.0 */
/* The motor model of the drive layer: alone, ramps that do not depend on how often they are
 * sampled and the torque limit; on the minimal model, ramps with exact times, the reference
 * reached bit, the speed limits and their CiA 402 views, configuration parameters refused while
 * running, plausible current and torque, deadlines only while ramping. */
#include "check_main.h"
#include "minimal_model.h"

#include <stdlib.h>

/* The model's own ramp parameters: ACC 3.0 s, DEC 3.0 s, fast ramp 0.7 s, 1500 rpm nominal. */
static const drive_ramp_t ramp = {.acc = 30, .dec = 30, .fast_dec = 7, .nominal_rpm = 1500};

/* Sampled every 7 ms or once, a ramp is at the same speed at the same time: 1200 rpm at exactly
 * 2.4 s on ACC 3.0 s, and back to 0 on the fast ramp 0.56 s later. */
START_TEST(ramp_does_not_depend_on_sampling)
{
    drive_motor_t sampled, once;
    drive_motor_reset(&sampled, 0);
    drive_motor_reset(&once, 0);
    drive_motor_steer(&sampled, 1200, false, &ramp);
    drive_motor_steer(&once, 1200, false, &ramp);
    for (co_time_t t = 7000; t < 2400000; t += 7000)
        drive_motor_advance(&sampled, t);
    ck_assert(!drive_motor_at_target(&sampled));
    drive_motor_advance(&sampled, 2400000);
    drive_motor_advance(&once, 2400000);
    ck_assert_int_eq(drive_motor_rpm(&sampled), 1200);
    ck_assert(drive_motor_at_target(&sampled) && drive_motor_at_target(&once));
    ck_assert_int_eq(sampled.speed, once.speed);
    drive_motor_steer(&sampled, 0, true, &ramp);
    for (co_time_t t = 2407000; t < 2960000; t += 7000)
        drive_motor_advance(&sampled, t);
    ck_assert(drive_motor_running(&sampled));
    drive_motor_advance(&sampled, 2960000);
    ck_assert(drive_motor_stands(&sampled) && !drive_motor_running(&sampled));
}
END_TEST

/* The torque a ramp demands is limited to +/-150 %: ramps of 0.1 s would take 1000 %. Motoring
 * torque is positive whatever the direction, braking torque negative. */
START_TEST(torque_is_limited)
{
    const drive_ramp_t steep = {.acc = 1, .dec = 1, .fast_dec = 1, .nominal_rpm = 1500};
    drive_motor_t motor;
    drive_motor_reset(&motor, 0);
    drive_motor_steer(&motor, -1500, false, &steep);
    drive_motor_advance(&motor, 10000);
    ck_assert_int_eq(drive_motor_rpm(&motor), -150);
    ck_assert_int_eq(drive_motor_torque(&motor), 150);
    drive_motor_advance(&motor, 100000);
    drive_motor_steer(&motor, 0, false, &steep);
    drive_motor_advance(&motor, 110000);
    ck_assert_int_eq(drive_motor_rpm(&motor), -1350);
    ck_assert_int_eq(drive_motor_torque(&motor), -150);
}
END_TEST

static void enable(bench_t *b, int16_t reference)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, (uint16_t)reference, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
}

/* ACC = 3.0 s from 0 to nominal 1500 rpm: 1200 rpm is reached at exactly 2.4 s. */
START_TEST(ramp_reaches_the_reference_on_time)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER); /* idle: no wake-up */
    enable(&b, 1200);
    co_time_t start = b.now;
    ck_assert_uint_eq(b.deadline, start + 10000);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 500);
    ck_assert_uint_eq(bench_read(&b, 0x6043, 0), 500);
    bench_advance(&b, 1390000);
    ck_assert_int_eq(bench_speed(&b), 1195);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0227);
    ck_assert_uint_le(b.deadline - b.now, 10000);
    bench_advance(&b, 10000);
    ck_assert_uint_eq(b.now - start, 2400000);
    ck_assert_int_eq(bench_speed(&b), 1200);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
}
END_TEST

/* Deadlines fall every 10 ms while ramping, and exactly at the end of the ramp. */
START_TEST(ramp_deadlines)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 7, 2), 0); /* 0.7 s: 1500 rpm in 700 ms */
    enable(&b, 1000);                                             /* 466.67 ms */
    co_time_t start = b.now;
    unsigned wakeups = 0;
    while (b.deadline != CO_TIME_NEVER) {
        ck_assert_uint_le(b.deadline - b.now, 10000);
        bench_advance(&b, b.deadline - b.now);
        wakeups++;
    }
    ck_assert_uint_eq(b.now - start, 466667);
    ck_assert_uint_eq(wakeups, 47);
    ck_assert_int_eq(bench_speed(&b), 1000);
}
END_TEST

/* A new ACC applies from the moment it is written. */
START_TEST(ramp_time_change_mid_ramp)
{
    bench_t b;
    bench_start(&b);
    enable(&b, 1500);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 500);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 10, 2), 0); /* 1.0 s: 1500 rpm/s */
    bench_advance(&b, 600000);
    ck_assert_int_eq(bench_speed(&b), 1400);
    bench_advance(&b, 70000);
    ck_assert_int_eq(bench_speed(&b), 1500);
}
END_TEST

/* Reversing decelerates on DEC to 0, then accelerates on ACC. */
START_TEST(reversal_goes_through_zero)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, DEC, 15, 2), 0); /* DEC 1.5 s */
    enable(&b, 1500);
    bench_advance(&b, 3000000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, (uint16_t)-1500, 2), 0);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 0);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), -750);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REVERSE | 0x0227);
}
END_TEST

/* High speed 40.0 Hz = 1200 rpm clips the reference (status bit 11); low speed 10.0 Hz = 300 rpm
 * is the speed of a zero reference. 6046h shows both in rpm. */
START_TEST(speed_limits)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6046, 2), 1500);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, HSP, 400, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6046, 2), 1200);
    enable(&b, 1500);
    bench_advance(&b, 5000000);
    ck_assert_int_eq(bench_speed(&b), 1200);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0E27);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, LSP, 100, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6046, 1), 300);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 0, 2), 0);
    bench_advance(&b, 5000000);
    ck_assert_int_eq(bench_speed(&b), 300);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0E27);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 900, 2), 0);
    bench_advance(&b, 5000000);
    ck_assert_int_eq(bench_speed(&b), 900);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
}
END_TEST

/* The low speed may not exceed the high speed, through the parameters or their view 6046h; a
 * view refuses what its parameter's limits refuse (5000 = 500.0 Hz here). */
START_TEST(speed_limit_writes_are_checked)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, HSP, 400, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, LSP, 500, 2), CO_SDO_ABORT_MAX_LESS_MIN);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 1, 1500, 4), CO_SDO_ABORT_MAX_LESS_MIN);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, HSP, 5001, 2), CO_SDO_ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 2, 16000, 4), CO_SDO_ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_read(&b, PARAMS, HSP), 400);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 2, 900, 4), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, HSP), 300);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6046, 1, 600, 4), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, LSP), 200);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, HSP, 199, 2), CO_SDO_ABORT_MAX_LESS_MIN);
}
END_TEST

/* 6048h/6049h are the ramps as delta speed / delta time (nominal speed / ramp time); a view
 * refuses what its parameter's limits refuse (1..9999 here). */
START_TEST(acceleration_objects_are_views_of_the_ramps)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 500);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 1);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 2, 3, 2), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACC), 90);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6049, 1, 3000, 4), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, DEC), 5);
    ck_assert_uint_eq(bench_read(&b, 0x6049, 1), 3000);
    ck_assert_uint_eq(bench_read(&b, 0x6049, 2), 1);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 25, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 600);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 1);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 2, 60000, 2), CO_SDO_ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 2, 1000, 2), CO_SDO_ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 1, 0, 4), CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 1, 32767, 4), CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACC), 25);
}
END_TEST

/* A pair written term by term is the ramp the master meant, whatever ramp the first term gave on
 * the way: 700, then 3, from 500 / 1 is 700 rpm in 3 s, 6.4 s to the nominal speed (not 5000 / 7,
 * the fraction of the 2.1 s the first term gave, then 3: 0.9 s). The view reads back the pair
 * written while it stands for the ramp, the ramp's own fraction once the ramp is written. */
START_TEST(acceleration_pair_written_term_by_term)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 1, 700, 4), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACC), 21);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6048, 2, 3, 2), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACC), 64);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 700);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 3);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 30, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 1), 500);
    ck_assert_uint_eq(bench_read(&b, 0x6048, 2), 1);
}
END_TEST

/* Motor data (nominal speed, frequency, current) change only with the motor stopped, and send the
 * drive back to Switch on disabled; adjustment parameters (ACC) change any time. */
START_TEST(configuration_refused_while_running)
{
    bench_t b;
    bench_start(&b);
    enable(&b, 1500);
    bench_advance(&b, 1000000);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, NSP, 1450, 2), CO_SDO_ABORT_DATA_STATE);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, FRS, 600, 2), CO_SDO_ABORT_DATA_STATE);
    ck_assert_uint_eq(bench_read(&b, PARAMS, NSP), 1500);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 40, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0227);
    /* Halted: motor stopped, the change is accepted and locks the drive. */
    bench_command(&b, CW_RAMP_STOP | 0x000F);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, NSP, 1450, 2), CO_SDO_ABORT_DATA_STATE);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, NSP, 1450, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_read(&b, PARAMS, NSP), 1450);
    /* From Ready to switch on too. */
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, NCR, 52, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

/* Current (0.1 A) and torque (%) follow the ramps: nominal current 4.0 A. */
START_TEST(current_and_torque_are_plausible)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 0);
    enable(&b, 1500);
    bench_advance(&b, 1500000); /* 750 rpm, accelerating: 10 % load + 33 % */
    ck_assert_int_eq((int16_t)bench_read(&b, OUTPUTS, TORQUE), 43);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 24);
    bench_advance(&b, 1500000); /* steady at 1500 rpm: 20 % load */
    ck_assert_int_eq((int16_t)bench_read(&b, OUTPUTS, TORQUE), 20);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 17);
    bench_command(&b, CW_RAMP_STOP | 0x000F);
    bench_advance(&b, 1500000); /* decelerating: braking torque */
    ck_assert_int_eq((int16_t)bench_read(&b, OUTPUTS, TORQUE), 10 - 33);
    bench_advance(&b, 1500000); /* stopped, still enabled: magnetising current only */
    ck_assert_int_eq((int16_t)bench_read(&b, OUTPUTS, TORQUE), 0);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 12);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_motor");
    TCase *tc = tcase_create("motor");
    tcase_add_test(tc, ramp_does_not_depend_on_sampling);
    tcase_add_test(tc, torque_is_limited);
    tcase_add_test(tc, ramp_reaches_the_reference_on_time);
    tcase_add_test(tc, ramp_deadlines);
    tcase_add_test(tc, ramp_time_change_mid_ramp);
    tcase_add_test(tc, reversal_goes_through_zero);
    tcase_add_test(tc, speed_limits);
    tcase_add_test(tc, speed_limit_writes_are_checked);
    tcase_add_test(tc, acceleration_objects_are_views_of_the_ramps);
    tcase_add_test(tc, acceleration_pair_written_term_by_term);
    tcase_add_test(tc, configuration_refused_while_running);
    tcase_add_test(tc, current_and_torque_are_plausible);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
