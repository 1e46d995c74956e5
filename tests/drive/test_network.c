/* SPDX-License-Identifier: Apache-2.0 */
/* What the network does to the drive, on the minimal model: communication loss (heartbeat
 * consumer, life guarding) is the network fault with its EMCY, 603Fh and 1003h entry; CAN bus
 * events are emergencies only, raised again after a reset node while they last; reset node
 * restarts the drive. */
#include "check_main.h"
#include "minimal_model.h"

/* Heartbeat consumer timeout: the network fault, EMCY 0x8130 with register 0x11, 603Fh, 1003h,
 * freewheel; the fault reset sends the EMCY error reset. */
START_TEST(heartbeat_loss_is_a_network_fault)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1016, 1, 0x00010064, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_rx(&b, "701#05");
    bench_advance(&b, 90000);
    bench_rx(&b, "701#05");
    bench_advance(&b, 99999);
    bench_expect_none(&b);
    co_time_t lost = b.now + 1;
    bench_advance(&b, 1);
    ck_assert_uint_eq(bench_expect(&b, "084#3081110000000000"), lost);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x8130);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x11);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 0), 1);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 1), 0x8130);
    ck_assert_int_eq(b.drive.comm_loss.source, DRIVE_COMM_LOSS_HEARTBEAT);
    ck_assert_uint_eq(b.drive.comm_loss.node, 1);
    /* The producer coming back does not clear the latched fault. */
    bench_rx(&b, "701#05");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(b.drive.comm_loss.source, DRIVE_COMM_LOSS_HEARTBEAT);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    ck_assert_int_eq(b.drive.comm_loss.source, DRIVE_COMM_LOSS_NONE); /* the fault reset */
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
    bench_expect_none(&b);
}
END_TEST

/* Life guarding: guard time 100 ms x 3 without a guarding request faults the drive. */
START_TEST(life_guarding_loss_is_a_network_fault)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x100C, 0, 100, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x100D, 0, 3, 1), 0);
    bench_rx(&b, "704#R");
    bench_expect(&b, "704#7F");
    bench_advance(&b, 299999);
    bench_expect_none(&b);
    bench_advance(&b, 1);
    bench_expect(&b, "084#3081110000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_str_eq(drive_state_name(&b.drive), "Fault");
    ck_assert_int_eq(b.drive.comm_loss.source, DRIVE_COMM_LOSS_GUARDING);
    ck_assert_uint_eq(b.drive.comm_loss.node, 0);
    bench_rx(&b, "000#8104"); /* a reset node forgets it */
    ck_assert_int_eq(b.drive.comm_loss.source, DRIVE_COMM_LOSS_NONE);
}
END_TEST

/* CAN errors from the runtime raise and clear their EMCY without faulting the drive; the status
 * word's bit 7 (warning, the Altivars' "Alarm") is set while one lasts (D-STATUS-ALARM). */
START_TEST(bus_events_are_emergencies_only)
{
    bench_t b;
    bench_start(&b);
    drive_bus_event(&b.drive, 0x8120, true);
    bench_expect(&b, "084#2081110000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x06C0);
    drive_bus_event(&b.drive, 0x8120, false);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

/* A reset node empties the EMCY producer, not the bus: a condition that lasts is an error again
 * after the boot-up, and its end still sends the error reset; reset communication keeps it. */
START_TEST(bus_condition_outlives_reset_node)
{
    bench_t b;
    bench_start(&b);
    drive_bus_event(&b.drive, 0x8120, true);
    bench_expect(&b, "084#2081110000000000");
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    bench_expect(&b, "084#2081110000000000");
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x11);
    bench_rx(&b, "000#8204");
    bench_expect(&b, "704#00");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x11);
    drive_bus_event(&b.drive, 0x8120, false);
    bench_expect(&b, "084#0000000000000000");
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
}
END_TEST

/* Reset node restarts the drive: boot-up, Switch on disabled, motor stopped, defaults back. */
START_TEST(reset_node_resets_the_drive)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, PARAMS, ACC, 10, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 500000);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    ck_assert_str_eq(drive_state_name(&b.drive), "Switch on disabled");
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0);
    ck_assert_uint_eq(bench_read(&b, PARAMS, ACC), 30);
    ck_assert_uint_eq(b.deadline, CO_TIME_NEVER);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0640);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_network");
    TCase *tc = tcase_create("network");
    tcase_add_test(tc, heartbeat_loss_is_a_network_fault);
    tcase_add_test(tc, life_guarding_loss_is_a_network_fault);
    tcase_add_test(tc, bus_events_are_emergencies_only);
    tcase_add_test(tc, bus_condition_outlives_reset_node);
    tcase_add_test(tc, reset_node_resets_the_drive);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
