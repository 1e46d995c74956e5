/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's faults on the minimal model's table (one fault of each reset class, one of each
 * reaction): injection faults the drive with its EMCY, 603Fh, 1001h and 1003h entry and the stop
 * of its reaction (freewheel at once; a ramp or fast stop in Fault reaction active, then Fault);
 * a fault reset is refused while the cause is present and accepted once it is gone; an automatic
 * fault ends with its cause; a power-cycle fault ends only with a reset node. */
#include "check_main.h"
#include "minimal_model.h"

static void inject(bench_t *b, uint8_t fault)
{
    drive_fault_inject(&b->drive, fault, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

static void remove_cause(bench_t *b, uint8_t fault)
{
    drive_fault_remove_cause(&b->drive, fault, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

/* Operation enabled at 1500 rpm (ACC 3.0 s: after 3 s). */
static void run_at_speed(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

START_TEST(injected_fault_stops_and_reports)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    inject(&b, FAULT_HOT);
    /* 0x4210, error register generic + temperature. */
    bench_expect(&b, "084#1042090000000000");
    bench_expect_none(&b);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault");
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x4210);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x09);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 0), 1);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 1), 0x4210);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "HoT");
    /* Injected again while active: nothing new. */
    inject(&b, FAULT_HOT);
    bench_expect_none(&b);
    /* Run commands do nothing in Fault. */
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0608);
}
END_TEST

START_TEST(reset_refused_while_cause_present)
{
    bench_t b;
    bench_start(&b);
    inject(&b, FAULT_HOT);
    bench_expect(&b, "084#1042090000000000");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x4210);
    remove_cause(&b, FAULT_HOT);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    /* Bit 7 is still 1 from the refused reset: no edge, no reset. */
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0608);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    /* The drive runs again. */
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_command(&b, 0x000F) & 0x006F, 0x0027);
}
END_TEST

START_TEST(automatic_fault_ends_with_its_cause)
{
    bench_t b;
    bench_start(&b);
    inject(&b, FAULT_LOW);
    bench_expect(&b, "084#2031050000000000");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    bench_expect_none(&b);
    remove_cause(&b, FAULT_LOW);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 1), 0x3120);
}
END_TEST

START_TEST(power_cycle_fault_ends_with_reset_node_only)
{
    bench_t b;
    bench_start(&b);
    inject(&b, FAULT_CPU);
    bench_expect(&b, "084#0061010000000000");
    /* A reset node with the cause present: boot-up, then the fault again. */
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    bench_expect(&b, "084#0061010000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    remove_cause(&b, FAULT_CPU);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    bench_expect_none(&b);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
}
END_TEST

/* Two faults: two EMCYs, the first stays in 603Fh; the automatic one ending leaves the other
 * latched (no error reset while it is active); one reset ends the rest. */
START_TEST(second_fault_while_in_fault)
{
    bench_t b;
    bench_start(&b);
    inject(&b, FAULT_HOT);
    bench_expect(&b, "084#1042090000000000");
    inject(&b, FAULT_LOW);
    bench_expect(&b, "084#20310D0000000000");
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x4210);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x0D);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 1), 0x3120);
    remove_cause(&b, FAULT_LOW);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x09);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    remove_cause(&b, FAULT_HOT);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
}
END_TEST

/* The automatic fault that ends first hands 603Fh to the fault still active. */
START_TEST(latched_code_follows_remaining_fault)
{
    bench_t b;
    bench_start(&b);
    inject(&b, FAULT_LOW);
    inject(&b, FAULT_HOT);
    bench_expect(&b, "084#2031050000000000");
    bench_expect(&b, "084#10420D0000000000");
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x3120);
    remove_cause(&b, FAULT_LOW);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x4210);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "HoT");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
}
END_TEST

/* A bus condition and a fault may report one EMCY code (the runtime reports any code it is given):
 * the code is one active error for both, cleared when the last of them ends, whichever it is. */
START_TEST(bus_condition_and_fault_share_a_code)
{
    bench_t b;
    bench_start(&b);
    drive_bus_event(&b.drive, 0x8130, true);
    bench_expect(&b, "084#3081110000000000");
    inject(&b, FAULT_NET);
    bench_expect_none(&b);
    drive_bus_event(&b.drive, 0x8130, false);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x11);
    drive_bus_event(&b.drive, 0x8130, true);
    remove_cause(&b, FAULT_NET);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x06C0); /* the bus condition: a warning */
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x11);
    drive_bus_event(&b.drive, 0x8130, false);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
}
END_TEST

/* The communication loss is the table's entry, wherever it is. */
START_TEST(communication_loss_is_the_tables_entry)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x100C, 0, 100, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x100D, 0, 1, 1), 0);
    bench_rx(&b, "704#R");
    bench_expect(&b, "704#7F");
    bench_advance(&b, 100000);
    bench_expect(&b, "084#3081110000000000");
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "NeT");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
}
END_TEST

/* Status words while a fault's ramp runs: Fault reaction active (0x000F) with remote, the
 * reference not reached; then Fault. */
#define SW_REACTION 0x020F
#define SW_FAULT 0x0608

/* A ramp stop reaction: Fault reaction active with the output on while the motor stops on the
 * DEC ramp (3.0 s from 1500 rpm), the control word recorded and not obeyed (not even a fault
 * reset edge), then Fault the instant the motor stands (transition 14). */
START_TEST(ramp_reaction_stops_on_the_deceleration_ramp_then_faults)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    inject(&b, FAULT_EXT);
    bench_expect(&b, "084#0090010000000000");
    bench_expect_none(&b);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault reaction active");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REACTION);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x9000);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "ExT");
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 1125);
    ck_assert_uint_gt(bench_read(&b, OUTPUTS, CURRENT), 0);
    ck_assert_uint_eq(bench_command(&b, 0x000F), SW_REACTION);
    ck_assert_uint_eq(bench_command(&b, 0x0080), SW_REACTION);
    bench_expect_none(&b);
    bench_advance(&b, 2249000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REACTION);
    bench_advance(&b, 1000);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 0);
    bench_expect_none(&b);
    /* Bit 7 was set during the reaction: a new edge resets, once the cause is gone. */
    remove_cause(&b, FAULT_EXT);
    ck_assert_uint_eq(bench_command(&b, 0x0080), SW_FAULT);
    ck_assert_uint_eq(bench_command(&b, 0x0000), SW_FAULT);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
}
END_TEST

/* A fast stop reaction: the fast ramp, DEC / 2 = 1.5 s from 1500 rpm. */
START_TEST(fast_reaction_stops_on_the_fast_ramp_then_faults)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    inject(&b, FAULT_FAN);
    bench_expect(&b, "084#1043090000000000");
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 750);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REACTION);
    bench_advance(&b, 749000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REACTION);
    bench_advance(&b, 1000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    ck_assert_int_eq(bench_speed(&b), 0);
}
END_TEST

/* Nothing to stop: a motor standing in Operation enabled, or a drive that drives no motor, goes
 * to Fault at once. */
START_TEST(ramp_reaction_of_a_standing_motor_is_fault_at_once)
{
    bench_t b;
    bench_start(&b);
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0627);
    inject(&b, FAULT_EXT);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    bench_start(&b);
    inject(&b, FAULT_FAN);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
}
END_TEST

/* A freewheel fault during a reaction cuts the output at once: Fault. */
START_TEST(freewheel_fault_cuts_a_running_reaction)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    inject(&b, FAULT_EXT);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 1125);
    inject(&b, FAULT_HOT);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, OUTPUTS, CURRENT), 0);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x9000);
}
END_TEST

/* A ramp reaction never slows a stop already on the fast ramp (here a quick stop): 1000 rpm/s
 * on, not the DEC ramp's 500. */
START_TEST(ramp_reaction_keeps_a_running_fast_ramp)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0002), 0x0207);
    bench_advance(&b, 375000);
    ck_assert_int_eq(bench_speed(&b), 1125);
    inject(&b, FAULT_EXT);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REACTION);
    bench_advance(&b, 375000);
    ck_assert_int_eq(bench_speed(&b), 750);
    bench_advance(&b, 750000);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
}
END_TEST

/* An automatic fault whose cause goes during its reaction ends it: Switch on disabled, which
 * drives nothing (the motor coasts), and the EMCY error reset. */
START_TEST(automatic_fault_ending_during_its_reaction)
{
    bench_t b;
    bench_start(&b);
    run_at_speed(&b);
    inject(&b, FAULT_FAN);
    bench_expect(&b, "084#1043090000000000");
    bench_advance(&b, 750000);
    remove_cause(&b, FAULT_FAN);
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_int_eq(bench_speed(&b), 0);
}
END_TEST

START_TEST(faults_found_by_code_without_case)
{
    bench_t b;
    bench_start(&b);
    ck_assert_int_eq(drive_fault_find(&b.drive, "hot"), FAULT_HOT);
    ck_assert_int_eq(drive_fault_find(&b.drive, "CPU"), FAULT_CPU);
    ck_assert_int_eq(drive_fault_find(&b.drive, "HO"), -1);
    ck_assert_int_eq(drive_fault_find(&b.drive, "HOTT"), -1);
    ck_assert_int_eq(drive_fault_find(&b.drive, ""), -1);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert(!drive_fault_cause_present(&b.drive, FAULT_HOT));
}
END_TEST

/* A profile without a fault table is refused at init. */
START_TEST(profile_without_faults_is_refused)
{
    drive_profile_t profile = minimal_profile;
    drive_fault_table_t empty = {.faults = NULL, .count = 0};
    static uint8_t od_data[BENCH_OD_DATA_MAX];
    drive_t drive;
    drive_config_t config = {.profile = &profile, .od_data = od_data, .node_id = 4, .send = NULL};
    profile.faults = NULL;
    ck_assert_int_eq(drive_init(&drive, &config), DRIVE_INIT_BAD_FAULTS);
    profile.faults = &empty;
    ck_assert_int_eq(drive_init(&drive, &config), DRIVE_INIT_BAD_FAULTS);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_faults");
    TCase *tc = tcase_create("faults");
    tcase_add_test(tc, injected_fault_stops_and_reports);
    tcase_add_test(tc, reset_refused_while_cause_present);
    tcase_add_test(tc, automatic_fault_ends_with_its_cause);
    tcase_add_test(tc, power_cycle_fault_ends_with_reset_node_only);
    tcase_add_test(tc, second_fault_while_in_fault);
    tcase_add_test(tc, latched_code_follows_remaining_fault);
    tcase_add_test(tc, bus_condition_and_fault_share_a_code);
    tcase_add_test(tc, communication_loss_is_the_tables_entry);
    tcase_add_test(tc, ramp_reaction_stops_on_the_deceleration_ramp_then_faults);
    tcase_add_test(tc, fast_reaction_stops_on_the_fast_ramp_then_faults);
    tcase_add_test(tc, ramp_reaction_of_a_standing_motor_is_fault_at_once);
    tcase_add_test(tc, freewheel_fault_cuts_a_running_reaction);
    tcase_add_test(tc, ramp_reaction_keeps_a_running_fast_ramp);
    tcase_add_test(tc, automatic_fault_ending_during_its_reaction);
    tcase_add_test(tc, faults_found_by_code_without_case);
    tcase_add_test(tc, profile_without_faults_is_refused);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
