/* SPDX-License-Identifier: Apache-2.0 */
/* The drive never runs on the network's command without a live connection carrying it: every
 * way the connection that carried the commands ends (bus off with and without BOI, the interface
 * coming back, the explicit connection's watchdog or release, a UCMM connection's Close or
 * watchdog) while the drive runs on them is
 * CnF with COL's reaction (docs/decisions.md, D-DEVICENET-CONNECTION-END); a standing drive, or
 * one whose commands another live connection carries, keeps its state. The ATV312 behind its
 * card at MAC ID 25, the scanner at 1. */
#include "check_main.h"
#include "dn_drive_bench.h"

#include <stdio.h>

static dn_drive_bench_t b;

static void setup(void)
{
    memset(&b, 0, sizeof b);
    db_online(&b);
}

/* COL = 1 (the default) freewheels into Fault: CnF latched with code 1, 6041h Fault, and the
 * motor coasts to a stop. */
static void expect_cnf(void)
{
    ck_assert_ptr_nonnull(drive_fault_latched(&b.drive));
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CnF");
    ck_assert_int_eq(db_value(&b, 0x2022, 3), 1);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
    db_advance(&b, 10000000);
    ck_assert_int_eq(db_value(&b, 0x6044, 0), 0);
}

/* Operation enabled (6041h & 006Fh = 0027h), turning forward. */
static void expect_running(void)
{
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(db_value(&b, 0x6041, 0) & 0x006F, 0x0027);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_ENABLED);
    ck_assert_int_gt(db_value(&b, 0x6044, 0), 0);
}

/* The fuzzer's reproducer: explicit and polled allocated, an expected packet rate of 100 ms
 * (104 ms in use, a watchdog of 416 ms), one poll Run forward, NetCtrl and NetRef at 1200 rpm;
 * 50 ms later the drive runs. */
static void run_on_one_poll(void)
{
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_exchange(&b, "4CC#41100502096400", "4CB#41906800");
    db_exchange(&b, "4CD#6100B004", "3D9#74040000");
    db_advance(&b, 50000);
    expect_running();
}

START_TEST(bus_off_while_running_is_cnf)
{
    run_on_one_poll();
    drive_dn_bus_off(&b.dn, b.now);
    db_expect_none(&b); /* faulted off the bus: no check, no frame */
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node) & 0x0F00u, 0x0400u); /* major rec. */
    expect_cnf();
    db_expect_none(&b);
}
END_TEST

START_TEST(bus_off_with_boi_while_running_is_cnf)
{
    run_on_one_poll();
    db_exchange(&b, "4CC#011003010301", "4CB#0190"); /* BOI = 1 */
    drive_dn_bus_off(&b.dn, b.now);
    db_expect(&b, "4CF#00F30078563412"); /* on the bus again, no connection */
    expect_cnf();
    db_expect(&b, "4CF#00F30078563412");
    db_expect_none(&b);
}
END_TEST

/* In atv312d: an interface outage shorter than the I/O watchdog. */
START_TEST(interface_back_while_running_is_cnf)
{
    run_on_one_poll();
    drive_dn_restart(&b.dn, b.now);
    db_expect(&b, "4CF#00F30078563412");
    expect_cnf();
    db_expect(&b, "4CF#00F30078563412");
    db_expect_none(&b);
    /* Major recoverable fault, no I/O connection. */
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node), 0x0430);
}
END_TEST

/* A standing drive keeps its state through bus off and the interface coming back. */
START_TEST(bus_off_of_a_standing_drive_keeps_it)
{
    db_connected(&b);
    db_exchange(&b, "4CD#00000000", "3D9#F0030000"); /* Ready */
    drive_dn_bus_off(&b.dn, b.now);
    drive_dn_restart(&b.dn, b.now);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_READY);
}
END_TEST

/* Explicit connection only: NetRef and NetCtrl stay 1 (the network), the speed reference 1200
 * rpm and Run1 through the Control supervisor, the last request 50 ms ago. */
static void run_by_explicit_messages(const char *allocate)
{
    db_exchange(&b, allocate, "4CB#01CB00");
    db_exchange(&b, "4CC#01102A0108B004", "4CB#0190");
    db_exchange(&b, "4CC#011029010301", "4CB#0190");
    db_advance(&b, 50000);
    expect_running();
}

/* The explicit connection's watchdog, 2504 ms x 4 after the last request, deletes it (auto
 * delete): the commands it carried stop. */
START_TEST(explicit_watchdog_while_running_is_cnf)
{
    run_by_explicit_messages("4CE#014B03010101");
    db_advance(&b, 10015999 - 50000);
    expect_running();
    db_advance(&b, 1);
    expect_cnf();
}
END_TEST

START_TEST(explicit_release_while_running_is_cnf)
{
    run_by_explicit_messages("4CE#014B03010101");
    db_exchange(&b, "4CE#014C030101", "4CB#01CC");
    expect_cnf();
}
END_TEST

/* A connection the UCMM opened (group 3: 781h from MAC ID 1, answered on 759h; requests on 641h,
 * responses on 619h) runs the drive as instance 1 does: its Close or its watchdog while the drive
 * runs on its Sets is CnF; closing one that carried nothing, while instance 1's Sets run the
 * drive, leaves it running. */
static void run_by_ucmm_connection(void)
{
    db_exchange(&b, "781#194B0031", "759#01CB00100A00");
    db_exchange(&b, "641#19102A0108B004", "619#0190");
    db_exchange(&b, "641#191029010301", "619#0190");
    db_advance(&b, 50000);
    expect_running();
}

START_TEST(ucmm_close_while_running_is_cnf)
{
    run_by_ucmm_connection();
    db_exchange(&b, "781#194C0A00", "759#01CC");
    expect_cnf();
}
END_TEST

START_TEST(ucmm_watchdog_while_running_is_cnf)
{
    run_by_ucmm_connection();
    db_advance(&b, 10015999 - 50000);
    expect_running();
    db_advance(&b, 1);
    expect_cnf();
}
END_TEST

START_TEST(ucmm_close_of_a_connection_that_carried_nothing_keeps_running)
{
    db_exchange(&b, "781#194B0032", "759#01CB00200A00");
    db_exchange(&b, "681#190E2A0107", "619#018E0000");
    run_by_explicit_messages("4CE#014B03010101");
    db_exchange(&b, "781#194C0A00", "759#01CC");
    expect_running();
    /* Then the drive's commands come through a UCMM connection, and instance 1 goes: running. */
    db_exchange(&b, "781#194B0033", "759#01CB00300A00");
    db_exchange(&b, "6C1#191029010301", "619#0190");
    db_exchange(&b, "4CE#014C030101", "4CB#01CC");
    expect_running();
}
END_TEST

/* The output assembly's Set over a UCMM connection (instance 21, attribute 3: Run forward,
 * NetCtrl and NetRef at 1200 rpm, in two fragments) commands the drive as the Control
 * supervisor's Sets do: the connection's Close is CnF. */
START_TEST(ucmm_close_after_an_assembly_set_is_cnf)
{
    db_exchange(&b, "781#194B0031", "759#01CB00100A00");
    db_rx(&b, "641#9900100415036100");
    db_expect(&b, "619#81C000");
    db_rx(&b, "641#9981B004");
    db_expect(&b, "619#81C100");
    db_expect(&b, "619#0190");
    db_advance(&b, 50000);
    expect_running();
    db_exchange(&b, "781#194C0A00", "759#01CC");
    expect_cnf();
}
END_TEST

/* A Set of the transparent output assembly (100: 6040h, 6042h) over UCMM instance 10, in two
 * fragments (header, then the 4 bytes' last two): the commands ran through the card's
 * transparent path, not the ODVA one, and the connection's Close is CnF all the same. */
static void set_transparent_by_ucmm(uint16_t control, uint16_t speed, bool xid)
{
    char frame[32];
    unsigned header = xid ? 0xD9u : 0x99u, answer = xid ? 0xC1u : 0x81u;
    snprintf(frame, sizeof frame, "641#%02X00100464%02X%02X%02X", header, 3u, control & 0xFFu,
             control >> 8);
    db_rx(&b, frame);
    snprintf(frame, sizeof frame, "619#%02XC000", answer);
    db_expect(&b, frame);
    snprintf(frame, sizeof frame, "641#%02X81%02X%02X", header, speed & 0xFFu, speed >> 8);
    db_rx(&b, frame);
    snprintf(frame, sizeof frame, "619#%02XC100", answer);
    db_expect(&b, frame);
    snprintf(frame, sizeof frame, "619#%02X90", answer & 0x7Fu);
    db_expect(&b, frame);
}

START_TEST(ucmm_close_after_a_transparent_set_is_cnf)
{
    db_exchange(&b, "781#194B0031", "759#01CB00100A00");
    set_transparent_by_ucmm(0x0006, 300, false);
    set_transparent_by_ucmm(0x0007, 300, true);
    set_transparent_by_ucmm(0x000F, 300, false);
    db_advance(&b, 50000);
    expect_running();
    db_exchange(&b, "781#194C0A00", "759#01CC");
    expect_cnf();
}
END_TEST

/* A Set refused on instance 1 (Run1 = 2, "invalid attribute value") changes no command: the
 * UCMM connection whose Sets run the drive still carries them, and its Close is CnF. */
START_TEST(refused_set_elsewhere_leaves_the_commands_connection)
{
    run_by_ucmm_connection();
    db_exchange(&b, "4CE#014B03010101", "4CB#01CB00");
    db_exchange(&b, "4CC#011029010302", "4CB#019409FF");
    expect_running();
    db_exchange(&b, "781#194C0A00", "759#01CC");
    expect_cnf();
}
END_TEST

/* The polled connection allocated but still configuring carries nothing: bus off ends the
 * explicit connection the commands came on. */
START_TEST(bus_off_with_a_configuring_poll_is_cnf)
{
    run_by_explicit_messages("4CE#014B03010301");
    drive_dn_bus_off(&b.dn, b.now);
    expect_cnf();
}
END_TEST

/* A live polled connection carries the commands (each poll the whole of them): the explicit
 * connection's end takes nothing away, the drive runs on the polls. */
START_TEST(explicit_end_while_polls_carry_keeps_running)
{
    db_connected(&b);
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    for (int second = 1; second <= 12; second++) {
        db_advance(&b, 1000000);
        db_rx(&b, "4CD#0100B004");
        b.next = b.count;
    }
    ck_assert_int_eq(dn_node_connection_state(&b.dn.node, DN_CONN_EXPLICIT), DN_CONN_NON_EXISTENT);
    expect_running();
}
END_TEST

START_TEST(explicit_end_of_a_standing_drive_keeps_it)
{
    db_exchange(&b, "4CE#014B03010101", "4CB#01CB00");
    db_exchange(&b, "4CC#01102A0108B004", "4CB#0190");
    drive_dn_state_t before = drive_dn_state(&b.dn);
    db_advance(&b, 10016000);
    ck_assert_int_eq(dn_node_connection_state(&b.dn.node, DN_CONN_EXPLICIT), DN_CONN_NON_EXISTENT);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(drive_dn_state(&b.dn), before);
}
END_TEST

/* An Identity Reset restarts the drive first: it no longer runs when the connections end, and
 * comes back without a fault. */
START_TEST(identity_reset_while_running_is_no_fault)
{
    run_on_one_poll();
    db_rx(&b, "4CC#41050101");
    db_expect(&b, "4CB#4185");
    db_expect(&b, "4CF#00F30078563412");
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(db_value(&b, 0x2022, 3), 0);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0640); /* Switch on disabled */
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("drive_devicenet_connection_loss");
    TCase *tc = tcase_create("connection_loss");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, bus_off_while_running_is_cnf);
    tcase_add_test(tc, bus_off_with_boi_while_running_is_cnf);
    tcase_add_test(tc, interface_back_while_running_is_cnf);
    tcase_add_test(tc, bus_off_of_a_standing_drive_keeps_it);
    tcase_add_test(tc, explicit_watchdog_while_running_is_cnf);
    tcase_add_test(tc, explicit_release_while_running_is_cnf);
    tcase_add_test(tc, bus_off_with_a_configuring_poll_is_cnf);
    tcase_add_test(tc, explicit_end_while_polls_carry_keeps_running);
    tcase_add_test(tc, explicit_end_of_a_standing_drive_keeps_it);
    tcase_add_test(tc, identity_reset_while_running_is_no_fault);
    tcase_add_test(tc, ucmm_close_while_running_is_cnf);
    tcase_add_test(tc, ucmm_watchdog_while_running_is_cnf);
    tcase_add_test(tc, ucmm_close_of_a_connection_that_carried_nothing_keeps_running);
    tcase_add_test(tc, ucmm_close_after_an_assembly_set_is_cnf);
    tcase_add_test(tc, refused_set_elsewhere_leaves_the_commands_connection);
    tcase_add_test(tc, ucmm_close_after_a_transparent_set_is_cnf);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
