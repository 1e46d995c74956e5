/* SPDX-License-Identifier: Apache-2.0 */
/* The ODVA AC drive profile on the drive's Drivecom profile (Altivar 312 DeviceNet manual, "Run/
 * Stop event triggers", "DRIVECOM status to State translation"), through the default assemblies
 * 21 (consumed) and 71 (produced): the worked example run forward at 1200 rpm, the Run/Stop
 * table row by row, the stop, the fault reset, NetCtrl/NetRef on C212/C213. */
#include "check_main.h"
#include "dn_drive_bench.h"

static dn_drive_bench_t b;

static void setup(void)
{
    memset(&b, 0, sizeof b);
    db_connected(&b);
}

/* 1200 rpm = 04B0h; the ramp: ACC 3.0 s from 0 to 1500 rpm, so 2.4 s. */
START_TEST(run_forward_at_1200_rpm)
{
    /* Run1 = 0: Stop, Shutdown: Ready (state 3), Ready, CtrlFromNet, RefFromNet, and AtReference:
     * 6041h bit 10, the standing motor is at its zero reference. */
    db_exchange(&b, "4CD#00000000", "3D9#F0030000");
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x0006);
    /* Run1 0 -> 1 at 1200 rpm: Shutdown, Switch on, Enable operation: Enabled, Running1. */
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x000F);
    ck_assert_int_eq(db_value(&b, 0x6042, 0), 1200);
    db_advance(&b, 2400000);
    db_exchange(&b, "4CD#0100B004", "3D9#F404B004");   /* AtReference */
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0627); /* the manual's "forward, speed reached" */
}
END_TEST

START_TEST(run_reverse_negates_the_reference)
{
    db_exchange(&b, "4CD#0200B004", "3D9#74040000"); /* Run2 0 -> 1 */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x000F);
    ck_assert_int_eq(db_value(&b, 0x6042, 0), -1200);
    db_advance(&b, 2400000);
    /* Running2 is always 0: the reverse is the negative actual speed, FB50h. */
    db_exchange(&b, "4CD#0200B004", "3D9#F40450FB");
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x8627);
}
END_TEST

/* One row of the Run/Stop table: from Run1/Run2 `from` to `to` (bit 0 Run1, bit 1 Run2), the
 * control word and the reference sign after it. */
static void row(uint8_t from, uint8_t to, uint16_t control, int16_t reference)
{
    char poll[32];
    snprintf(poll, sizeof poll, "4CD#%02X006400", from);
    db_rx(&b, poll);
    snprintf(poll, sizeof poll, "4CD#%02X006400", to);
    db_rx(&b, poll);
    b.next = b.count;
    ck_assert_int_eq(db_value(&b, 0x6040, 0), control);
    ck_assert_int_eq(db_value(&b, 0x6042, 0), reference);
}

START_TEST(run_stop_table_row_by_row)
{
    row(0x00, 0x01, 0x000F, 100);  /* 0 -> 1, 0: Run1 */
    row(0x01, 0x00, 0x0007, 100);  /* 0, 0: Stop (Disable operation in Operation enabled) */
    row(0x00, 0x02, 0x000F, -100); /* 0, 0 -> 1: Run2 */
    row(0x02, 0x03, 0x000F, -100); /* 1, 1: no action, the last command still valid */
    row(0x03, 0x02, 0x000F, -100); /* 1 -> 0, 1: Run2 */
    row(0x03, 0x01, 0x000F, 100);  /* 1, 1 -> 0: Run1 */
    row(0x00, 0x03, 0x0007, 100);  /* 0 -> 1, 0 -> 1: no action after the stop */
}
END_TEST

/* Stop in Operation enabled: Disable operation, the ramp (Stopping: Operation enabled with bit 3
 * at 0), then Switched on (Ready), then Shutdown at the next Stop. */
START_TEST(stop_ramps_through_stopping_to_ready)
{
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    db_advance(&b, 2400000);
    db_exchange(&b, "4CD#0000B004", "3D9#7405B004"); /* Stopping, Running1, ramping */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x0007);
    db_advance(&b, 1000000);
    db_rx(&b, "4CD#0000B004");
    b.next = b.count;
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_STOPPING);
    db_advance(&b, 2000000);
    db_exchange(&b, "4CD#0000B004", "3D9#F0030000");
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x0006);
}
END_TEST

START_TEST(fault_and_fault_reset)
{
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    int ohf = drive_fault_find(&b.drive, "OHF");
    drive_fault_inject(&b.drive, (uint8_t)ohf, b.now);
    drive_fault_remove_cause(&b.drive, (uint8_t)ohf, b.now);
    db_advance(&b, 3000000);
    /* Faulted (latched), CtrlFromNet, RefFromNet, AtReference (standing); state 7. */
    db_exchange(&b, "4CD#0100B004", "3D9#E1070000");
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node) & DN_STATUS_MAJOR_RECOVERABLE,
                      DN_STATUS_MAJOR_RECOVERABLE);
    /* FaultRst 0 -> 1: control word bit 7 edge; the drive stays stopped until a new Run. */
    db_exchange(&b, "4CD#0500B004", "3D9#E0020000");
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node) & DN_STATUS_MAJOR_RECOVERABLE, 0);
    db_exchange(&b, "4CD#0000B004", "3D9#F0030000");
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
}
END_TEST

/* COF behind the DeviceNet card (the manual's "Communication fault management": "The
 * communication card is not working properly: ... (COF)"), as the daemon's control surface
 * injects it: the drive freewheels into Fault with 603Fh 7520h, the scanner sees Faulted and the
 * Identity's major recoverable fault; the fault reset is refused while the card does not work,
 * taken once it does; the network fault code (CnF, 2022:03) stays 0. */
START_TEST(cof_is_the_card_not_working)
{
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    db_advance(&b, 2400000);
    int cof = drive_fault_find(&b.drive, "COF");
    ck_assert_int_eq(cof, 1);
    drive_fault_inject(&b.drive, (uint8_t)cof, b.now);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "COF");
    ck_assert_int_eq(db_value(&b, 0x603F, 0), 0x7520);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(db_value(&b, 0x2022, 3), 0);
    db_exchange(&b, "4CD#0100B004", "3D9#E1070000"); /* Faulted, state 7 */
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node) & DN_STATUS_MAJOR_RECOVERABLE,
                      DN_STATUS_MAJOR_RECOVERABLE);
    db_advance(&b, 10000000);
    db_exchange(&b, "4CD#0500B004", "3D9#E1070000"); /* FaultRst: refused, the cause is there */
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "COF");
    drive_fault_remove_cause(&b.drive, (uint8_t)cof, b.now);
    db_exchange(&b, "4CD#0000B004", "3D9#E1070000");
    db_exchange(&b, "4CD#0400B004", "3D9#F0030000");
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
}
END_TEST

/* The manual's configuration for 21/71: CHCF separate, Cd1 the network, Cd2 the terminals, CCS
 * C212; Fr1 the network, Fr2 AI2, rFC C213. NetCtrl 0 asks for local control (bit 12 at 1,
 * channel 2), NetRef 0 for the local reference (bit 13 at 1). */
START_TEST(net_ctrl_and_net_ref_switch_the_channels)
{
    db_exchange(&b, "4CC#01108B01020200", "4CB#0190"); /* CHCF 8401 = 2 */
    db_exchange(&b, "4CC#01108B0116D400", "4CB#0190"); /* CCS 8421 = 212 (C212) */
    db_exchange(&b, "4CC#01108B010CD500", "4CB#0190"); /* rFC 8411 = 213 (C213) */
    db_exchange(&b, "4CD#60000000", "3D9#F0030000");   /* NetCtrl, NetRef: the network */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x0006);
    db_exchange(&b, "4CD#00000000", "3D9#80020000"); /* both local: bits 12, 13 */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x3006);
    db_exchange(&b, "4CD#20000000", "3D9#B0030000"); /* control from the network: Ready */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x2006);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("drive_devicenet_odva");
    TCase *tc = tcase_create("odva");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, run_forward_at_1200_rpm);
    tcase_add_test(tc, run_reverse_negates_the_reference);
    tcase_add_test(tc, run_stop_table_row_by_row);
    tcase_add_test(tc, stop_ramps_through_stopping_to_ready);
    tcase_add_test(tc, fault_and_fault_reset);
    tcase_add_test(tc, cof_is_the_card_not_working);
    tcase_add_test(tc, net_ctrl_and_net_ref_switch_the_channels);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
