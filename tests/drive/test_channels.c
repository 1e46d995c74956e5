/* SPDX-License-Identifier: Apache-2.0 */
/* Channels, stop type and frequencies on the minimal model: a command channel other than the
 * network is local control (bit 9 clear, the network's control word recorded and not obeyed), a
 * reference channel other than the network gives a zero reference, "not separate" makes the
 * command follow the reference's channel; the ramp stop bit stops as the stop type says; the
 * output frequency follows the motor; the frequency reference is 6042h in 0.1 Hz; auto-tuning. */
#include "check_main.h"
#include "minimal_model.h"

#define ABORT_STATE 0x08000022u

/* Operation enabled at 1500 rpm (ACC 3.0 s: after 3 s). */
static void run_at_speed(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

static uint32_t write_param(bench_t *b, uint8_t sub, uint16_t value)
{
    return bench_sdo_write(b, PARAMS, sub, value, 2);
}

START_TEST(local_command_channel_records_and_ignores_the_network)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    /* A configuration parameter: refused while the motor turns. */
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 1), ABORT_STATE);
    ck_assert_uint_eq(bench_read(&b, PARAMS, COMMAND_1), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0640);
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0440);
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    /* The channel at the drive runs it (the RUN key), remote stays clear. */
    ck_assert(drive_run_key(&b.drive, b.now));
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0427);
    /* The network's stop bits do not stop it either. */
    ck_assert_uint_eq(bench_command(&b, 0x000F | CW_FAST_STOP), 0x0427);
    drive_stop_key(&b.drive, b.now);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    /* Back to the network: Switch on disabled, remote, the network commands. */
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0) & ~(uint32_t)SW_STOP_KEY, 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
}
END_TEST

START_TEST(command_switch_selects_channel_2)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0440);
    ck_assert_uint_eq(write_param(&b, COMMAND_2, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

/* A reset node restores the channel parameters' defaults without writing them: the network
 * commands again (bit 9 set, the control word obeyed). */
START_TEST(reset_node_gives_the_command_back_to_the_network)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    ck_assert_uint_eq(bench_read(&b, PARAMS, COMMAND_1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

START_TEST(not_separate_command_follows_the_reference_channel)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 1), 0);
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 1), 0);
    /* The command channel parameters no longer count: the reference's channel is the network. */
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(write_param(&b, REFERENCE, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0440);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(write_param(&b, COMMAND_1, 0), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

START_TEST(local_reference_channel_gives_the_low_speed)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, REFERENCE, 1), 0);
    ck_assert_uint_eq(write_param(&b, LSP, 100), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    /* 10.0 Hz of 50.0 Hz at 1500 rpm nominal; 6042h stays as the network wrote it. */
    ck_assert_int_eq(bench_speed(&b), 300);
    ck_assert_uint_eq(bench_read(&b, 0x6042, 0), 1500);
}
END_TEST

/* Runs at 1500 rpm, sets the ramp stop bit; the speed 0.75 s later. */
static int16_t ramp_stop_speed(bench_t *b)
{
    run_at_speed(b);
    bench_command(b, 0x000F | CW_RAMP_STOP);
    bench_advance(b, 750000);
    /* Every stop type keeps the drive in Operation enabled. */
    ck_assert_uint_eq(bench_read(b, 0x6041, 0) & 0x006F, 0x0027);
    return bench_speed(b);
}

/* The same from the start with the stop type `type`. */
static int16_t speed_after_ramp_stop(bench_t *b, uint16_t type)
{
    bench_start(b);
    ck_assert_uint_eq(write_param(b, STOP_TYPE, type), 0);
    return ramp_stop_speed(b);
}

START_TEST(stop_type_ramp_stops_on_the_deceleration_ramp)
{
    bench_t b;
    ck_assert_int_eq(speed_after_ramp_stop(&b, DRIVE_STOP_RAMP), 1125);
}
END_TEST

START_TEST(stop_type_fast_stops_on_the_fast_ramp)
{
    bench_t b;
    ck_assert_int_eq(speed_after_ramp_stop(&b, DRIVE_STOP_FAST), 750);
    ck_assert_int_eq(speed_after_ramp_stop(&b, DRIVE_STOP_DC_INJECTION), 750);
}
END_TEST

START_TEST(stop_type_freewheel_cuts_the_output)
{
    bench_t b;
    ck_assert_int_eq(speed_after_ramp_stop(&b, DRIVE_STOP_FREEWHEEL), 0);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 0);
    /* Releasing the bit runs again on the ACC ramp. */
    bench_command(&b, 0x000F);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
}
END_TEST

/* The drive keeps the stop type's entry, not a copy of its value: every write of it counts at the
 * next ramp stop, and so does the default a reset node restores without a write. */
START_TEST(stop_type_follows_every_write_and_a_reset)
{
    bench_t b;
    ck_assert_int_eq(speed_after_ramp_stop(&b, DRIVE_STOP_FAST), 750);
    bench_advance(&b, 1000000);
    ck_assert_uint_eq(write_param(&b, STOP_TYPE, DRIVE_STOP_RAMP), 0);
    ck_assert_int_eq(ramp_stop_speed(&b), 1125);
    bench_advance(&b, 3000000);
    ck_assert_uint_eq(write_param(&b, STOP_TYPE, DRIVE_STOP_FREEWHEEL), 0);
    ck_assert_int_eq(ramp_stop_speed(&b), 0);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    ck_assert_uint_eq(bench_read(&b, PARAMS, STOP_TYPE), DRIVE_STOP_RAMP);
    ck_assert_int_eq(ramp_stop_speed(&b), 1125);
}
END_TEST

START_TEST(stop_type_is_a_configuration_parameter)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    ck_assert_uint_eq(write_param(&b, STOP_TYPE, DRIVE_STOP_FAST), ABORT_STATE);
    ck_assert_uint_eq(write_param(&b, STOP_TYPE, 4), 0x06090031);
    ck_assert_uint_eq(bench_read(&b, PARAMS, STOP_TYPE), DRIVE_STOP_RAMP);
}
END_TEST

START_TEST(output_frequency_follows_the_motor)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, FREQUENCY), 500);
    bench_command(&b, 0x000F | CW_REVERSE);
    bench_advance(&b, 6000000);
    ck_assert_int_eq(bench_speed(&b), -1500);
    ck_assert_int_eq((int16_t)bench_read(&b, OUTPUTS, FREQUENCY), -500);
    bench_command(&b, 0x0000);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, FREQUENCY), 0);
}
END_TEST

START_TEST(frequency_reference_is_6042_in_decihertz)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, FREQUENCY_REF, 250), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6042, 0), 750);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, (uint16_t)-1500, 2), 0);
    ck_assert_int_eq((int16_t)bench_read(&b, PARAMS, FREQUENCY_REF), -500);
    ck_assert_uint_eq(write_param(&b, FREQUENCY_REF, 5001), 0x06090031);
    ck_assert_int_eq((int16_t)bench_read(&b, 0x6042, 0), -1500);
    /* It drives the motor like 6042h. */
    ck_assert_uint_eq(write_param(&b, FREQUENCY_REF, 500), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
}
END_TEST

/* Auto-tuning: YES in Operation enabled with the motor standing runs the simulated tune, DONE
 * after DRIVE_AUTO_TUNE_TIME_US; refused elsewhere; DONE is not a command; leaving Operation
 * enabled ends it unfinished. */
START_TEST(auto_tune_runs_in_operation_enabled_and_reads_done)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, AUTO_TUNE, DRIVE_AUTO_TUNE_YES), ABORT_STATE);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    ck_assert_uint_eq(write_param(&b, AUTO_TUNE, DRIVE_AUTO_TUNE_DONE), 0x06090030);
    ck_assert_uint_eq(write_param(&b, AUTO_TUNE, DRIVE_AUTO_TUNE_YES), 0);
    ck_assert_uint_eq(b.deadline, b.now + DRIVE_AUTO_TUNE_TIME_US);
    bench_advance(&b, DRIVE_AUTO_TUNE_TIME_US - 1);
    ck_assert_uint_eq(bench_read(&b, PARAMS, AUTO_TUNE), DRIVE_AUTO_TUNE_YES);
    bench_advance(&b, 1);
    ck_assert_uint_eq(bench_read(&b, PARAMS, AUTO_TUNE), DRIVE_AUTO_TUNE_DONE);
    /* Again, interrupted by a shutdown. */
    ck_assert_uint_eq(write_param(&b, AUTO_TUNE, DRIVE_AUTO_TUNE_YES), 0);
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_read(&b, PARAMS, AUTO_TUNE), DRIVE_AUTO_TUNE_NO);
    bench_advance(&b, DRIVE_AUTO_TUNE_TIME_US);
    ck_assert_uint_eq(bench_read(&b, PARAMS, AUTO_TUNE), DRIVE_AUTO_TUNE_NO);
}
END_TEST

START_TEST(auto_tune_refused_while_the_motor_turns)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    ck_assert_uint_eq(write_param(&b, AUTO_TUNE, DRIVE_AUTO_TUNE_YES), ABORT_STATE);
    ck_assert_uint_eq(bench_read(&b, PARAMS, AUTO_TUNE), DRIVE_AUTO_TUNE_NO);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_channels");
    TCase *tc = tcase_create("channels");
    tcase_add_test(tc, local_command_channel_records_and_ignores_the_network);
    tcase_add_test(tc, command_switch_selects_channel_2);
    tcase_add_test(tc, reset_node_gives_the_command_back_to_the_network);
    tcase_add_test(tc, not_separate_command_follows_the_reference_channel);
    tcase_add_test(tc, local_reference_channel_gives_the_low_speed);
    tcase_add_test(tc, stop_type_ramp_stops_on_the_deceleration_ramp);
    tcase_add_test(tc, stop_type_fast_stops_on_the_fast_ramp);
    tcase_add_test(tc, stop_type_freewheel_cuts_the_output);
    tcase_add_test(tc, stop_type_follows_every_write_and_a_reset);
    tcase_add_test(tc, stop_type_is_a_configuration_parameter);
    tcase_add_test(tc, output_frequency_follows_the_motor);
    tcase_add_test(tc, frequency_reference_is_6042_in_decihertz);
    tcase_add_test(tc, auto_tune_runs_in_operation_enabled_and_reads_done);
    tcase_add_test(tc, auto_tune_refused_while_the_motor_turns);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
