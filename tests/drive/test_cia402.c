/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 402 / Drivecom power state machine and the stop types of the drive layer: every cell of
 * the command table on the state machine alone, then on the minimal model every command, every
 * status value, quick stop vs fast stop, freewheel, the profile's reverse and ramp stop bits, the
 * fault reset edge (the DeviceNet manual's status chart; docs/decisions.md, D-STATE-MACHINE). */
#include "check_main.h"
#include "minimal_model.h"

#include <stdlib.h>

/* Status words with bit 9 (remote) and bit 10 (reference reached, motor at its target). */
#define SW_SWITCH_ON_DISABLED 0x0640
#define SW_READY 0x0621
#define SW_SWITCHED_ON 0x0623
#define SW_ENABLED 0x0627
#define SW_QUICK_STOP 0x0607
#define SW_FAULT 0x0608

/* The command table (docs/atv312.md, "Power state machine") with the motor standing: the state
 * each of 0x0000, 0x0002, 0x0006, 0x0007 and 0x000F leads to from each state. */
START_TEST(every_cell_of_the_command_table)
{
    static const uint16_t commands[] = {0x0000, 0x0002, 0x0006, 0x0007, 0x000F};
    static const struct {
        cia402_state_t from;
        cia402_state_t to[5];
    } table[] = {
        {CIA402_SWITCH_ON_DISABLED,
         {CIA402_SWITCH_ON_DISABLED, CIA402_SWITCH_ON_DISABLED, CIA402_READY_TO_SWITCH_ON,
          CIA402_SWITCH_ON_DISABLED, CIA402_SWITCH_ON_DISABLED}},
        {CIA402_READY_TO_SWITCH_ON,
         {CIA402_SWITCH_ON_DISABLED, CIA402_SWITCH_ON_DISABLED, CIA402_READY_TO_SWITCH_ON,
          CIA402_SWITCHED_ON, CIA402_OPERATION_ENABLED}},
        {CIA402_SWITCHED_ON,
         {CIA402_SWITCH_ON_DISABLED, CIA402_SWITCH_ON_DISABLED, CIA402_READY_TO_SWITCH_ON,
          CIA402_SWITCHED_ON, CIA402_OPERATION_ENABLED}},
        {CIA402_OPERATION_ENABLED,
         {CIA402_SWITCH_ON_DISABLED, CIA402_QUICK_STOP_ACTIVE, CIA402_READY_TO_SWITCH_ON,
          CIA402_SWITCHED_ON, CIA402_OPERATION_ENABLED}},
        {CIA402_QUICK_STOP_ACTIVE,
         {CIA402_SWITCH_ON_DISABLED, CIA402_QUICK_STOP_ACTIVE, CIA402_QUICK_STOP_ACTIVE,
          CIA402_QUICK_STOP_ACTIVE, CIA402_QUICK_STOP_ACTIVE}},
        {CIA402_FAULT_REACTION_ACTIVE,
         {CIA402_FAULT_REACTION_ACTIVE, CIA402_FAULT_REACTION_ACTIVE, CIA402_FAULT_REACTION_ACTIVE,
          CIA402_FAULT_REACTION_ACTIVE, CIA402_FAULT_REACTION_ACTIVE}},
        {CIA402_FAULT, {CIA402_FAULT, CIA402_FAULT, CIA402_FAULT, CIA402_FAULT, CIA402_FAULT}},
    };
    for (size_t row = 0; row < sizeof table / sizeof table[0]; row++) {
        for (size_t col = 0; col < 5; col++) {
            cia402_state_machine_t sm = {.state = table[row].from, .control = 0};
            ck_assert(!cia402_command(&sm, commands[col], true));
            ck_assert_msg(sm.state == table[row].to[col], "%s, control %04X: %s, not %s",
                          cia402_state_name(table[row].from), commands[col],
                          cia402_state_name(sm.state), cia402_state_name(table[row].to[col]));
        }
    }
}
END_TEST

/* Transitions 13 and 14: a stopping reaction is Fault reaction active (0x000F, the output on)
 * until the motor stands, then Fault (0x0008); a reaction with nothing to stop is Fault at once.
 * Neither obeys a command, and a fault reset edge counts only in Fault. */
START_TEST(fault_reaction_active_ends_when_the_motor_stands)
{
    cia402_state_machine_t sm;
    cia402_reset(&sm);
    cia402_command(&sm, 0x000F, true);
    cia402_fault(&sm, true);
    ck_assert_uint_eq(cia402_status(&sm), 0x000F);
    ck_assert(cia402_drives_motor(&sm));
    ck_assert(cia402_faulted(&sm));
    ck_assert(!cia402_command(&sm, 0x0080, false));
    ck_assert_int_eq(sm.state, CIA402_FAULT_REACTION_ACTIVE);
    cia402_motor_stopped(&sm);
    ck_assert_int_eq(sm.state, CIA402_FAULT);
    ck_assert_uint_eq(cia402_status(&sm), 0x0008);
    ck_assert(!cia402_drives_motor(&sm));
    cia402_command(&sm, 0x0000, true);
    ck_assert(cia402_command(&sm, 0x0080, true));
    ck_assert_int_eq(sm.state, CIA402_SWITCH_ON_DISABLED);
    cia402_fault(&sm, false);
    ck_assert_int_eq(sm.state, CIA402_FAULT);
}
END_TEST

/* Disable operation (5) waits for the motor: Operation enabled until it stands. */
START_TEST(disable_operation_waits_for_the_motor)
{
    cia402_state_machine_t sm;
    cia402_reset(&sm);
    cia402_command(&sm, 0x0006, true);
    cia402_command(&sm, 0x000F, true);
    ck_assert(cia402_runs(&sm));
    cia402_command(&sm, 0x0007, false);
    ck_assert_int_eq(sm.state, CIA402_OPERATION_ENABLED);
    ck_assert(!cia402_runs(&sm) && cia402_drives_motor(&sm));
    cia402_motor_stopped(&sm);
    ck_assert_int_eq(sm.state, CIA402_SWITCHED_ON);
    ck_assert(!cia402_drives_motor(&sm));
    /* A standing motor in Operation enabled with an enable operation command stays enabled. */
    cia402_command(&sm, 0x000F, true);
    cia402_motor_stopped(&sm);
    ck_assert_int_eq(sm.state, CIA402_OPERATION_ENABLED);
}
END_TEST

START_TEST(boots_in_switch_on_disabled)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_SWITCH_ON_DISABLED);
    ck_assert_str_eq(drive_state_name(&b.drive), "Switch on disabled");
    /* Enable operation and switch on are not shutdown: nothing happens. */
    ck_assert_uint_eq(bench_command(&b, 0x000F), SW_SWITCH_ON_DISABLED);
    ck_assert_uint_eq(bench_command(&b, 0x0007), SW_SWITCH_ON_DISABLED);
}
END_TEST

typedef struct step {
    uint16_t control;
    uint16_t status;
} step_t;

static void run_steps(bench_t *b, const step_t *steps, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        uint16_t status = bench_command(b, steps[i].control);
        ck_assert_msg(status == steps[i].status,
                      "step %zu: control %04X gave status %04X, not %04X", i, steps[i].control,
                      status, steps[i].status);
    }
}

/* Transitions 2, 3, 4, 5, 6, 7 (disable voltage and quick stop), 10 (both), 8, 9. */
START_TEST(every_transition_of_the_command_table)
{
    bench_t b;
    bench_start(&b);
    const step_t steps[] = {
        {0x0006, SW_READY},              /* 2 shutdown */
        {0x0007, SW_SWITCHED_ON},        /* 3 switch on */
        {0x000F, SW_ENABLED},            /* 4 enable operation */
        {0x0007, SW_SWITCHED_ON},        /* 5 disable operation */
        {0x0006, SW_READY},              /* 6 shutdown */
        {0x0000, SW_SWITCH_ON_DISABLED}, /* 7 disable voltage */
        {0x0006, SW_READY},
        {0x0002, SW_SWITCH_ON_DISABLED}, /* 7 quick stop */
        {0x0006, SW_READY},
        {0x0007, SW_SWITCHED_ON},
        {0x0000, SW_SWITCH_ON_DISABLED}, /* 10 disable voltage */
        {0x0006, SW_READY},
        {0x0007, SW_SWITCHED_ON},
        {0x0002, SW_SWITCH_ON_DISABLED}, /* 10 quick stop */
        {0x0006, SW_READY},
        {0x000F, SW_ENABLED}, /* 3 then 4: the word is a level */
        {0x0006, SW_READY},   /* 8 shutdown */
        {0x000F, SW_ENABLED},
        {0x0000, SW_SWITCH_ON_DISABLED}, /* 9 disable voltage */
    };
    run_steps(&b, steps, sizeof(steps) / sizeof(steps[0]));
}
END_TEST

/* 11 then 12: quick stop locks until disable voltage; enable operation cannot restart it. */
START_TEST(quick_stop_locks_until_disable_voltage)
{
    bench_t b;
    bench_start(&b);
    const step_t steps[] = {
        {0x0006, SW_READY},      {0x000F, SW_ENABLED},    {0x0002, SW_QUICK_STOP}, /* 11 */
        {0x000F, SW_QUICK_STOP}, /* no transition 16 */
        {0x0006, SW_QUICK_STOP}, {0x0007, SW_QUICK_STOP}, {0x0000, SW_SWITCH_ON_DISABLED}, /* 12 */
        {0x0006, SW_READY},      {0x000F, SW_ENABLED},
    };
    run_steps(&b, steps, sizeof(steps) / sizeof(steps[0]));
    ck_assert_str_eq(drive_state_name(&b.drive), "Operation enabled");
}
END_TEST

/* Runs the motor at 1500 rpm (ACC 3.0 s, nominal 1500 rpm). */
static void run_at_nominal(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    ck_assert_uint_eq(bench_command(b, 0x000F), 0x0227); /* accelerating */
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
    ck_assert_uint_eq(bench_read(b, 0x6041, 0), SW_ENABLED);
}

static uint32_t motor_current(bench_t *b)
{
    return bench_read(b, OUTPUTS, CURRENT);
}

static uint32_t motor_torque(bench_t *b)
{
    return bench_read(b, OUTPUTS, TORQUE);
}

/* Quick stop: the profile's fast ramp, DEC / 2 = 1.5 s, then locked in Quick stop active with the
 * motor stopped. */
START_TEST(quick_stop_ramps_on_the_fast_ramp)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0002), 0x0207);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 750);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_QUICK_STOP);
    ck_assert_uint_eq(bench_command(&b, 0x000F), SW_QUICK_STOP);
    bench_advance(&b, 100000);
    ck_assert_int_eq(bench_speed(&b), 0);
}
END_TEST

/* Fast stop (the profile's fast stop bit): the same fast ramp, but the drive stays in Operation
 * enabled and a run command restarts it at once. */
START_TEST(fast_stop_stays_enabled)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, CW_FAST_STOP | 0x000F), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_ENABLED);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 500);
}
END_TEST

/* Shutdown (8) and disable voltage (9) from Operation enabled: freewheel, speed 0 at once. */
START_TEST(shutdown_and_disable_voltage_freewheel)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0006), SW_READY);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(motor_current(&b), 0);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0000), SW_SWITCH_ON_DISABLED);
    ck_assert_int_eq(bench_speed(&b), 0);
}
END_TEST

/* Frame for frame: in Operational, TPDO1 (status word, speed) goes out on every change; the
 * shutdown's frame already says Ready to switch on at 0 rpm, nothing in between. */
START_TEST(freewheel_is_one_frame)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    bench_rx(&b, "000#0104");
    bench_expect(&b, "184#2706DC05");
    bench_rx(&b, "204#06000000");
    bench_expect(&b, "184#21060000");
    bench_advance(&b, 1000000);
    bench_expect_none(&b);
}
END_TEST

/* Disable operation (5) stops on the DEC ramp (3.0 s): the drive stays in Operation enabled,
 * output on, while the motor decelerates (the DeviceNet manual's 0x0027 with "cmdd bit 3 = 0"),
 * and is Switched on, output off, once it stands. */
START_TEST(disable_operation_ramps_down)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0007), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0227);
    ck_assert_uint_ne(motor_current(&b), 0); /* current flows while it ramps */
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_SWITCHED_ON);
    ck_assert_uint_eq(motor_current(&b), 0);
    ck_assert_uint_eq(motor_torque(&b), 0);
}
END_TEST

/* Frame for frame: the ramp's last TPDO1 is Switched on at 0 rpm, exactly when the DEC ramp
 * ends; no frame shows Operation enabled at 0 rpm. */
START_TEST(disable_operation_ends_in_one_frame)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    bench_rx(&b, "000#0104");
    bench_expect(&b, "184#2706DC05");
    co_time_t start = b.now;
    bench_rx(&b, "204#07000000");
    bench_advance(&b, 4000000);
    ck_assert_uint_ge(b.count - b.next, 2);
    const co_frame_t *before = &b.frame[b.count - 2];
    ck_assert_uint_eq(co_get_u16(before->data), 0x0227);
    ck_assert_int_gt((int16_t)co_get_u16(before->data + 2), 0);
    b.next = b.count - 1;
    ck_assert_uint_eq(bench_expect(&b, "184#23060000"), start + 3000000);
}
END_TEST

/* Enable operation during the disable-operation ramp runs again at once. */
START_TEST(enable_operation_cancels_disable_operation)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0007), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_ENABLED);
}
END_TEST

/* ACC 0.5 s, DEC 4.0 s (fast ramp 2.0 s), running at 1500 rpm. */
static void run_with_slow_dec(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, PARAMS, ACC, 5, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, PARAMS, DEC, 40, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 500000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

/* Quick stop (11) then disable voltage (12) mid-ramp: the output is cut, the motor coasts (it
 * does not go on decelerating on DEC in Switch on disabled). */
START_TEST(disable_voltage_during_quick_stop_freewheels)
{
    bench_t b;
    bench_start(&b);
    run_with_slow_dec(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0002), 0x0207);
    bench_advance(&b, 20000);
    ck_assert_int_eq(bench_speed(&b), 1485); /* fast ramp: 750 rpm per second */
    ck_assert_uint_ne(motor_current(&b), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0000), SW_SWITCH_ON_DISABLED);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(motor_current(&b), 0);
    ck_assert_uint_eq(motor_torque(&b), 0);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_SWITCH_ON_DISABLED);
}
END_TEST

/* Disable operation (5) then disable voltage (9) mid-ramp: freewheel as well. */
START_TEST(disable_voltage_during_disable_operation_freewheels)
{
    bench_t b;
    bench_start(&b);
    run_with_slow_dec(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0007), 0x0227);
    bench_advance(&b, 400000);
    ck_assert_int_eq(bench_speed(&b), 1350); /* DEC: 375 rpm per second */
    ck_assert_uint_eq(bench_command(&b, 0x0000), SW_SWITCH_ON_DISABLED);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(motor_current(&b), 0);
}
END_TEST

/* The rule behind the two tests above, for every pair of commands given while the motor runs:
 * at every instant, a state other than Operation enabled and Quick stop active has speed,
 * current and torque 0. */
START_TEST(only_enabled_and_quick_stop_drive_the_motor)
{
    static const uint16_t commands[] = {0x0000, 0x0002, 0x0006,
                                        0x0007, 0x000F, CW_FAST_STOP | 0x000F};
    const size_t n = sizeof(commands) / sizeof(commands[0]);
    for (size_t first = 0; first < n; first++) {
        for (size_t second = 0; second < n; second++) {
            bench_t b;
            bench_start(&b);
            run_with_slow_dec(&b);
            bench_command(&b, commands[first]);
            bench_advance(&b, 200000);
            bench_command(&b, commands[second]);
            for (int sample = 0; sample < 24; sample++) {
                uint16_t state = bench_read(&b, 0x6041, 0) & CIA402_SW_STATE_MASK;
                int16_t speed = bench_speed(&b);
                uint32_t current = motor_current(&b);
                uint32_t torque = motor_torque(&b);
                if (state != 0x0027 && state != 0x0007)
                    ck_assert_msg(speed == 0 && current == 0 && torque == 0,
                                  "%04X then %04X, %d ms later: state %04X with %d rpm, current "
                                  "%u, torque %u",
                                  commands[first], commands[second], sample * 250, state, speed,
                                  current, torque);
                bench_advance(&b, 250000);
            }
        }
    }
}
END_TEST

/* The profile's reverse bit: negative speed and the profile's status bit (0x4227 ramping, 0x4627
 * at speed). */
START_TEST(reverse_bit)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    ck_assert_uint_eq(bench_command(&b, CW_REVERSE | 0x000F), SW_REVERSE | 0x0227);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), -1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_REVERSE | SW_ENABLED);
    /* A negative reference with the reverse bit runs forward. */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, (uint16_t)-600, 2), 0);
    bench_advance(&b, 5000000);
    ck_assert_int_eq(bench_speed(&b), 600);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_ENABLED);
}
END_TEST

/* The profile's ramp stop bit: DEC ramp to 0 in Operation enabled; releasing it runs again. */
START_TEST(ramp_stop_bit_halts_on_the_ramp)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    ck_assert_uint_eq(bench_command(&b, CW_RAMP_STOP | 0x000F), 0x0227);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 750);
    bench_advance(&b, 1500000);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_ENABLED);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
}
END_TEST

/* Loses the heartbeat of node 1 (1016h:01 = node 1, 100 ms). */
static void lose_heartbeat(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x1016, 1, 0x00010064, 4), 0);
    bench_rx(b, "701#05");
    bench_advance(b, 100000);
}

/* Fault reset acts on the 0 -> 1 edge of bit 7 only, whatever the other bits. */
START_TEST(fault_reset_on_the_rising_edge_only)
{
    bench_t b;
    bench_start(&b);
    run_at_nominal(&b);
    lose_heartbeat(&b);
    bench_expect(&b, "084#3081110000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault");
    const step_t locked[] = {{0x0006, SW_FAULT}, {0x000F, SW_FAULT}, {0x0000, SW_FAULT}};
    run_steps(&b, locked, 3);
    ck_assert_uint_eq(bench_command(&b, 0x0080), SW_SWITCH_ON_DISABLED); /* 15 */
    bench_expect(&b, "084#0000000000000000");
    /* A second fault: bit 7 still held is no edge. */
    bench_rx(&b, "701#05");
    bench_advance(&b, 100000);
    bench_expect(&b, "084#3081110000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), SW_FAULT);
    ck_assert_uint_eq(bench_command(&b, 0x0080), SW_FAULT);
    ck_assert_uint_eq(bench_command(&b, 0x0086), SW_FAULT);
    ck_assert_uint_eq(bench_command(&b, 0x0006), SW_FAULT);
    /* Edge with shutdown bits: reset (15) then shutdown (2). */
    ck_assert_uint_eq(bench_command(&b, 0x0086), SW_READY);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_cia402");
    TCase *tc = tcase_create("cia402");
    tcase_add_test(tc, every_cell_of_the_command_table);
    tcase_add_test(tc, fault_reaction_active_ends_when_the_motor_stands);
    tcase_add_test(tc, disable_operation_waits_for_the_motor);
    tcase_add_test(tc, boots_in_switch_on_disabled);
    tcase_add_test(tc, every_transition_of_the_command_table);
    tcase_add_test(tc, quick_stop_locks_until_disable_voltage);
    tcase_add_test(tc, quick_stop_ramps_on_the_fast_ramp);
    tcase_add_test(tc, fast_stop_stays_enabled);
    tcase_add_test(tc, shutdown_and_disable_voltage_freewheel);
    tcase_add_test(tc, freewheel_is_one_frame);
    tcase_add_test(tc, disable_operation_ramps_down);
    tcase_add_test(tc, disable_operation_ends_in_one_frame);
    tcase_add_test(tc, enable_operation_cancels_disable_operation);
    tcase_add_test(tc, disable_voltage_during_quick_stop_freewheels);
    tcase_add_test(tc, disable_voltage_during_disable_operation_freewheels);
    tcase_add_test(tc, only_enabled_and_quick_stop_drive_the_motor);
    tcase_add_test(tc, reverse_bit);
    tcase_add_test(tc, ramp_stop_bit_halts_on_the_ramp);
    tcase_add_test(tc, fault_reset_on_the_rising_edge_only);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
