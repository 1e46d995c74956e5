/* SPDX-License-Identifier: Apache-2.0 */
/* The analogue inputs as reference channels, on the real dictionaries: the ATV312's AI2 (+/-10 V)
 * and AI3 (X-Y mA between CrL3 and CrH3, 2010:03/04) of its option card, the ATV31's AI1 (0-10 V)
 * and its front panel's potentiometer AIP (Fr = 7). With Fr1 on an input (CHCF = SEP, Cd1 =
 * CANopen, so that the network commands), the speed runs from LSP at the bottom of the input's
 * range to HSP at its top: read frame for frame by SDO (6044h), and on TPDO6 while it follows. */
#include "atv31/atv31.h"
#include "atv312_bench.h"
#include "check_main.h"

#define FR1 0x2036, 14
#define CHCF_SEPARATE 2

static uint8_t input(bench_t *b, const char *name)
{
    int index = drive_analog_find(&b->drive, name);
    ck_assert_int_ge(index, 0);
    return (uint8_t)index;
}

static void set_analog(bench_t *b, const char *name, int32_t value)
{
    ck_assert(drive_set_analog(&b->drive, input(b, name), value, b->now));
    b->deadline = drive_process(&b->drive, b->now);
}

/* The network commands (CHCF = SEP, Cd1 = CANopen by default), Fr1 = `channel`; the drive runs. */
static void run_on_channel(bench_t *b, uint16_t channel)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x2036, 2, CHCF_SEPARATE, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, FR1, channel, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
}

/* The SDO read of 6044h, frame for frame, after the ramp (4.0 s: a reversal from -375 to 1500
 * rpm takes 3.75 s). */
static void expect_speed(bench_t *b, const char *answer)
{
    bench_advance(b, 4000000);
    const bench_exchange_t read[] = {{"6044h", "604#4044600000000000", 0, {answer}}};
    bench_play(b, read, 1);
}

/* AI2 at 5 V: half the range, 750 rpm; at -2.5 V a quarter in reverse, -375 rpm (ETA 0x8627);
 * at 10 V HSP. With LSP = 10 Hz, 5 V is 300 + 1200 / 2 = 900 rpm. */
START_TEST(ai2_bipolar_voltage_gives_the_speed_and_direction)
{
    bench_t b;
    bench_start(&b);
    run_on_channel(&b, 2);
    set_analog(&b, "AI2", 5000);
    expect_speed(&b, "584#4B446000EE020000");
    set_analog(&b, "AI2", -2500);
    expect_speed(&b, "584#4B44600089FE0000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x8627);
    set_analog(&b, "ai2", 10000);
    expect_speed(&b, "584#4B446000DC050000");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2001, 6, 100, 2), 0);
    set_analog(&b, "AI2", 5000);
    expect_speed(&b, "584#4B44600084030000");
}
END_TEST

/* AI3 between CrL3 = 4 mA and CrH3 = 20 mA (the defaults): 12 mA is 750 rpm, 20 mA 1500, 2 mA
 * (below CrL3) LSP, 0; with CrL3 = 0, 12 mA is 900 rpm; with CrH3 not above CrL3, LSP. */
START_TEST(ai3_current_between_crl3_and_crh3)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x2010, 3), 40);
    ck_assert_uint_eq(bench_read(&b, 0x2010, 4), 200);
    run_on_channel(&b, 3);
    set_analog(&b, "AI3", 12000);
    expect_speed(&b, "584#4B446000EE020000");
    set_analog(&b, "AI3", 20000);
    expect_speed(&b, "584#4B446000DC050000");
    set_analog(&b, "AI3", 2000);
    expect_speed(&b, "584#4B44600000000000");
    bench_command(&b, 0x0000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2010, 3, 0, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    set_analog(&b, "AI3", 12000);
    expect_speed(&b, "584#4B44600084030000");
    bench_command(&b, 0x0000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2010, 3, 200, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    expect_speed(&b, "584#4B44600000000000");
}
END_TEST

/* CrL3 and CrH3 are configuration parameters: refused while the motor turns. */
START_TEST(crl3_crh3_are_configuration_parameters)
{
    bench_t b;
    bench_start(&b);
    run_on_channel(&b, 3);
    set_analog(&b, "AI3", 20000);
    bench_advance(&b, 1000000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2010, 4, 100, 2), 0x08000022);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2010, 3, 201, 2), 0x06090031);
}
END_TEST

/* The card has no AI1: Fr1 = AI1 is a zero reference (LSP), and the input cannot be set. Values
 * outside an input's range are refused and change nothing. */
START_TEST(inputs_and_ranges_the_model_has)
{
    bench_t b;
    bench_start(&b);
    ck_assert_int_eq(drive_analog_find(&b.drive, "AI1"), -1);
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AI2"), 10001, b.now));
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AI2"), -10001, b.now));
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AI3"), -1, b.now));
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AI3"), 20001, b.now));
    ck_assert_int_eq(drive_analog(&b.drive, input(&b, "AI2")), 0);
    set_analog(&b, "AI2", 10000);
    run_on_channel(&b, 1);
    expect_speed(&b, "584#4B44600000000000");
}
END_TEST

/* A running drive follows its input: TPDO6 (ETAD, RFRD) ramps from 750 to 1500 rpm on ACC (3.0 s
 * for 1500 rpm: 1.5 s), the last frame at the speed. The input outlives a reset node. */
/* A lost 4-20 mA loop (AI3 at 0 mA) while the drive runs on it at 1500 rpm: the input's bottom,
 * LSP (0 rpm by default, 300 rpm at LSP = 10 Hz), and no fault. The ATV312 DeviceNet manual names
 * (LFF) [Fallback speed] only as its example of the terminal's notation ("Drive terminal
 * displays"), with no address, range, default or trigger: no fallback speed is built
 * (docs/decisions.md, D-ATV312-LFF). */
START_TEST(lost_loop_is_the_bottom_of_the_range)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2001, 6, 100, 2), 0); /* LSP 10.0 Hz */
    run_on_channel(&b, 3);
    set_analog(&b, "AI3", 20000);
    expect_speed(&b, "584#4B446000DC050000");
    set_analog(&b, "AI3", 0);
    expect_speed(&b, "584#4B4460002C010000");
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
}
END_TEST

START_TEST(running_drive_follows_the_input)
{
    bench_t b;
    bench_start(&b);
    run_on_channel(&b, 2);
    set_analog(&b, "AI2", 5000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1805, 1, 0x284, 4), 0);
    bench_operational(&b);
    bench_advance(&b, 3000000);
    b.next = b.count;
    set_analog(&b, "AI2", 10000);
    bench_advance(&b, 1490000);
    ck_assert_int_lt(bench_speed(&b), 1500);
    bench_advance(&b, 10000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    const co_frame_t *last = &b.frame[b.count - 1];
    ck_assert_uint_eq(last->id, 0x284);
    ck_assert_mem_eq(last->data, "\x27\x06\xDC\x05", 4);
    bench_rx(&b, "000#8104");
    ck_assert_int_eq(drive_analog(&b.drive, input(&b, "AI2")), 10000);
}
END_TEST

/* The ATV31's potentiometer (Fr1 = 7, AIP): 50 % is 750 rpm; its AI1 (0-10 V) at 2.5 V 375. */
START_TEST(atv31_potentiometer_and_ai1)
{
    bench_t b;
    bench_start_model(&b, &atv31_profile, NULL);
    run_on_channel(&b, 7);
    set_analog(&b, "AIP", 500);
    expect_speed(&b, "584#4B446000EE020000");
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AIP"), 1001, b.now));
    bench_command(&b, 0x0000);
    ck_assert_uint_eq(bench_sdo_write(&b, FR1, 1, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    set_analog(&b, "AI1", 2500);
    expect_speed(&b, "584#4B44600077010000");
    ck_assert(!drive_set_analog(&b.drive, input(&b, "AI1"), -1, b.now));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_analog");
    TCase *tc = tcase_create("analog");
    tcase_add_test(tc, ai2_bipolar_voltage_gives_the_speed_and_direction);
    tcase_add_test(tc, ai3_current_between_crl3_and_crh3);
    tcase_add_test(tc, lost_loop_is_the_bottom_of_the_range);
    tcase_add_test(tc, crl3_crh3_are_configuration_parameters);
    tcase_add_test(tc, inputs_and_ranges_the_model_has);
    tcase_add_test(tc, running_drive_follows_the_input);
    tcase_add_test(tc, atv31_potentiometer_and_ai1);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
