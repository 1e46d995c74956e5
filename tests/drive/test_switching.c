/* SPDX-License-Identifier: Apache-2.0 */
/* Switching sources, the second ramp and the access level on the minimal model: a switch on a
 * control word bit or a logic input selects channel 2 while it is 1, live; an assigned bit loses
 * its profile meaning; the ramp switch selects the second ramp pair; below the full access level
 * the separate mode and bit sources are refused (0x06040043), the network has priority and a run
 * command needs no status chart procedure. */
#include "check_main.h"
#include "minimal_model.h"

#define ABORT_RANGE 0x06090030u
#define ABORT_INCOMPATIBLE 0x06040043u
#define NETWORK_BIT(bit) DRIVE_SOURCE_NETWORK_BIT(bit)
#define COMMAND_BIT(bit) DRIVE_SOURCE_COMMAND_BIT(bit)
#define INPUT(n) DRIVE_SOURCE_INPUT(n)

static uint32_t write_param(bench_t *b, uint8_t sub, uint16_t value)
{
    return bench_sdo_write(b, PARAMS, sub, value, 2);
}

/* Operation enabled at 1500 rpm (ACC 3.0 s) with the control word `run`. */
static void run_at_speed(bench_t *b, uint16_t run)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(b, 0x0006), 0x0621);
    bench_command(b, run);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

START_TEST(network_bit_switches_the_command_channel_live)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, NETWORK_BIT(12)), 0);
    run_at_speed(&b, 0x000F);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
    /* Bit 12 at 1: channel 2 (local), a freewheel stop to Switch on disabled, bit 9 clear. */
    ck_assert_uint_eq(bench_command(&b, 0x000F | 0x1000), 0x0440);
    bench_advance(&b, 100000);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, TORQUE), 0);
    /* The bit is read from the network's word while the channel at the drive commands. */
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_command(&b, 0x000F) & CIA402_SW_STATE_MASK, 0x0027);
}
END_TEST

/* Bit 12 is the minimal model's fast stop; assigned to a switch it no longer stops. */
START_TEST(assigned_bit_loses_its_profile_meaning)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, COMMAND_2, 0), 0);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, NETWORK_BIT(12)), 0);
    run_at_speed(&b, 0x000F);
    ck_assert_uint_eq(bench_command(&b, 0x000F | CW_FAST_STOP), 0x0627);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    /* Unassigned, the same word stops on the fast ramp (DEC / 2: 1.5 s). */
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0640);
    bench_advance(&b, 4000000);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, 0), 0);
    run_at_speed(&b, 0x000F);
    bench_command(&b, 0x000F | CW_FAST_STOP);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 750);
}
END_TEST

/* A Cd bit reads the active channel's word: the network's while it commands. */
START_TEST(command_bit_follows_the_active_channel)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, REFERENCE_SELECT, COMMAND_BIT(15)), 0);
    run_at_speed(&b, 0x000F);
    /* Bit 15 (the minimal model's reverse, now assigned): reference channel 2, the low speed 0. */
    bench_command(&b, 0x800F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
}
END_TEST

START_TEST(logic_input_switches_the_reference_channel)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, REFERENCE_SELECT, INPUT(2)), 0);
    run_at_speed(&b, 0x000F);
    ck_assert(drive_set_input(&b.drive, 2, true, b.now));
    ck_assert(drive_input(&b.drive, 2));
    ck_assert(!drive_input(&b.drive, 1));
    /* Channel 2 is local: the low speed (0), on the DEC ramp, still Operation enabled. */
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1000);
    bench_advance(&b, 2000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
    ck_assert(drive_set_input(&b.drive, 2, false, b.now));
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
}
END_TEST

START_TEST(switch_values_outside_the_model_are_refused)
{
    bench_t b;
    bench_start(&b);
    ck_assert(!drive_set_input(&b.drive, INPUTS + 1, true, b.now));
    ck_assert(!drive_set_input(&b.drive, 0, true, b.now));
    ck_assert_uint_eq(write_param(&b, REFERENCE_SELECT, INPUT(INPUTS + 1)), ABORT_RANGE);
    ck_assert_uint_eq(write_param(&b, REFERENCE_SELECT, INPUT(0)), ABORT_RANGE);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, 2), ABORT_RANGE);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, NETWORK_BIT(10)), ABORT_RANGE);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, NETWORK_BIT(16)), ABORT_RANGE);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, 1), ABORT_RANGE);
    ck_assert_uint_eq(bench_read(&b, PARAMS, COMMAND_SELECT), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, RAMP_SWITCH), 0);
}
END_TEST

/* ACC_2 = DEC_2 = 1.0 s instead of 3.0 s while the ramp switch's bit (15, the minimal model's
 * reverse: assigned, it no longer reverses) is 1. */
START_TEST(ramp_switch_selects_the_second_ramps)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, NETWORK_BIT(15)), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x800F);
    bench_advance(&b, 500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    bench_advance(&b, 500000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    /* Bit 15 clear: DEC, 3.0 s. */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 0, 2), 0);
    bench_command(&b, 0x000F);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1000);
    /* Set again mid-ramp: dE2 from here, 1000 rpm in 0.667 s. */
    bench_command(&b, 0x800F);
    bench_advance(&b, 500000);
    ck_assert_int_eq(bench_speed(&b), 250);
}
END_TEST

START_TEST(ramp_switch_on_a_logic_input)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, INPUT(1)), 0);
    ck_assert(drive_set_input(&b.drive, 1, true, b.now));
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    /* Input off: DEC. The fast stop divides the deceleration of the pair in use. */
    ck_assert(drive_set_input(&b.drive, 1, false, b.now));
    bench_command(&b, 0x000F | CW_FAST_STOP);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 750);
}
END_TEST

START_TEST(basic_access_refuses_separate_mode_and_bit_sources)
{
    bench_t b;
    bench_start(&b);
    /* The minimal model's default is the separate mode: the level may not drop below it. */
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 1), 0);
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), 0);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 0), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(&b, COMMAND_SELECT, NETWORK_BIT(12)), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, COMMAND_BIT(15)), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, INPUT(1)), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, CHANNEL_MODE), 1);
    ck_assert_uint_eq(bench_read(&b, PARAMS, COMMAND_SELECT), 0);
    /* Back to the full level: allowed, and then the level may not drop while a bit is assigned. */
    ck_assert_uint_eq(write_param(&b, ACCESS, 1), 0);
    ck_assert_uint_eq(write_param(&b, RAMP_SWITCH, COMMAND_BIT(15)), 0);
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACCESS), 1);
}
END_TEST

/* Below the full level the network has priority over the channel parameters, and 0x000F runs
 * the drive from Switch on disabled. */
START_TEST(basic_access_gives_the_network_priority_and_runs_directly)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 1), 0);
    ck_assert_uint_eq(write_param(&b, REFERENCE, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(&b, 0x000F) & CIA402_SW_STATE_MASK, 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    /* The other commands keep their transitions. */
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0007), 0x0640);
}
END_TEST

/* The I/O mode: bit 0 runs from Switch on disabled, 0 stops on the DEC ramp to Switched on;
 * bits 11-15 keep their meaning (bit 15 reverses); the other CiA 402 bits do not count. */
START_TEST(io_mode_reads_bit_0_as_the_run_command)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0001) & CIA402_SW_STATE_MASK, 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    bench_advance(&b, 1500000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0623);
    ck_assert_uint_eq(bench_command(&b, 0x8001) & CIA402_SW_STATE_MASK, 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), -1500);
    /* The I/O mode has separate channels: refused below the full access level. */
    ck_assert_uint_eq(bench_command(&b, 0x0000) & CIA402_SW_STATE_MASK, 0x0027);
    bench_advance(&b, 3000000);
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), ABORT_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 1), 0);
    ck_assert_uint_eq(write_param(&b, ACCESS, 0), 0);
    ck_assert_uint_eq(write_param(&b, CHANNEL_MODE, 2), ABORT_INCOMPATIBLE);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_switching");
    TCase *tc = tcase_create("switching");
    tcase_add_test(tc, network_bit_switches_the_command_channel_live);
    tcase_add_test(tc, assigned_bit_loses_its_profile_meaning);
    tcase_add_test(tc, command_bit_follows_the_active_channel);
    tcase_add_test(tc, logic_input_switches_the_reference_channel);
    tcase_add_test(tc, switch_values_outside_the_model_are_refused);
    tcase_add_test(tc, ramp_switch_selects_the_second_ramps);
    tcase_add_test(tc, ramp_switch_on_a_logic_input);
    tcase_add_test(tc, basic_access_refuses_separate_mode_and_bit_sources);
    tcase_add_test(tc, basic_access_gives_the_network_priority_and_runs_directly);
    tcase_add_test(tc, io_mode_reads_bit_0_as_the_run_command);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
