/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's CIP classes on the ATV312: Motor data 0x28, Control supervisor 0x29, AC/DC drive
 * 0x2A attribute by attribute with their refusals; the application objects by the manual's
 * address formula (read, write, refusals with their CIP codes); the assemblies 20/70 and 100/101
 * byte for byte after a stored selection and a restart; the I/O timeout as CnF and its reset;
 * the polled connection released while the drive runs as CnF too, not while it stands; the LEDs
 * and their start-up test at power-up and Identity Reset only.
 */
#include "check_main.h"
#include "dn_drive_bench.h"

static dn_drive_bench_t b;

static void setup(void)
{
    memset(&b, 0, sizeof b);
    db_connected(&b);
}

START_TEST(motor_data)
{
    db_exchange(&b, "4CC#010E280001", "4CB#018E0100");
    db_exchange(&b, "4CC#010E280103", "4CB#018E07");   /* squirrel cage induction motor */
    db_exchange(&b, "4CC#010E280106", "4CB#018E2800"); /* NCR 4.0 A in 100 mA */
    db_exchange(&b, "4CC#010E280107", "4CB#018E9001"); /* 400 V */
    db_exchange(&b, "4CC#0110280106 2D00", "4CB#0190");
    ck_assert_int_eq(db_value(&b, 0x2042, 4), 45);
    db_exchange(&b, "4CC#011028010300", "4CB#019409FF");    /* another motor type */
    db_exchange(&b, "4CC#0110280106 0000", "4CB#019409FF"); /* below NCR's limit */
    db_exchange(&b, "4CC#010E280102", "4CB#019414FF");
    db_exchange(&b, "4CC#0110280106 2D", "4CB#019413FF");
}
END_TEST

/* RatedVoltage is Get/Set (the manual's Motor data object, instance attribute 7, [V]): the drive's
 * UnS (2042:02, ADL 9601, also class 91h attribute 2), 100..500 V, a configuration parameter
 * refused while the motor runs (0x10) and taken back to Switch on disabled after. */
START_TEST(rated_voltage_is_uns)
{
    db_exchange(&b, "4CC#0110280107E600", "4CB#0190"); /* 230 V */
    ck_assert_int_eq(db_value(&b, 0x2042, 2), 230);
    db_exchange(&b, "4CC#010E280107", "4CB#018EE600");
    db_exchange(&b, "4CC#010E910102", "4CB#018EE600");
    db_exchange(&b, "4CC#01109101029001", "4CB#0190"); /* 400 V by its address */
    db_exchange(&b, "4CC#010E280107", "4CB#018E9001");
    db_exchange(&b, "4CC#0110280107F501", "4CB#019409FF"); /* 501 V */
    db_exchange(&b, "4CC#01102801076300", "4CB#019409FF"); /* 99 V */
    db_exchange(&b, "4CC#0110280107E6", "4CB#019413FF");
    ck_assert_int_eq(db_value(&b, 0x2042, 2), 400);
    db_exchange(&b, "4CC#01102A0108B004", "4CB#0190"); /* 1200 rpm */
    db_exchange(&b, "4CC#011029010301", "4CB#0190");   /* Run1 */
    db_advance(&b, 100000);
    db_exchange(&b, "4CC#0110280107E600", "4CB#019410FF");
    ck_assert_int_eq(db_value(&b, 0x2042, 2), 400);
    db_exchange(&b, "4CC#011029010300", "4CB#0190"); /* Run1 off: on its ramp to 0 */
    db_advance(&b, 3000000);
    db_exchange(&b, "4CC#0110280107E600", "4CB#0190");
    ck_assert_int_eq(db_value(&b, 0x6041, 0) & 0x006F, 0x0040); /* Switch on disabled */
}
END_TEST

START_TEST(control_supervisor)
{
    db_exchange(&b, "4CC#010E290001", "4CB#018E0100");
    db_exchange(&b, "4CC#010E290106", "4CB#018E02"); /* Not_Ready: Switch on disabled */
    db_exchange(&b, "4CC#011029010501", "4CB#0190");
    db_exchange(&b, "4CC#011029010301", "4CB#0190"); /* Run1 */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x000F);
    static const char *const gets[][2] = {
        {"4CC#010E290103", "4CB#018E01"}, {"4CC#010E290104", "4CB#018E00"},
        {"4CC#010E290105", "4CB#018E01"}, {"4CC#010E290106", "4CB#018E04"},
        {"4CC#010E290107", "4CB#018E01"}, {"4CC#010E290108", "4CB#018E00"},
        {"4CC#010E290109", "4CB#018E01"}, {"4CC#010E29010A", "4CB#018E00"},
        {"4CC#010E29010B", "4CB#018E00"}, {"4CC#010E29010C", "4CB#018E00"},
        {"4CC#010E29010F", "4CB#018E01"},
    };
    for (size_t i = 0; i < sizeof gets / sizeof gets[0]; i++)
        db_exchange(&b, gets[i][0], gets[i][1]);
    db_exchange(&b, "4CC#011029010302", "4CB#019409FF"); /* a BOOL of 2 */
    db_exchange(&b, "4CC#011029010601", "4CB#01940EFF");
    db_exchange(&b, "4CC#010E29010D", "4CB#019414FF");
    db_exchange(&b, "4CC#01052901", "4CB#0185"); /* Reset: stopped, the motor stood */
    ck_assert_int_eq(db_value(&b, 0x6040, 0), 0x0006);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_READY);
    db_exchange(&b, "4CC#01052900", "4CB#019408FF");
}
END_TEST

START_TEST(ac_dc_drive)
{
    db_exchange(&b, "4CC#010E2A0001", "4CB#019408FF"); /* no class attribute */
    db_exchange(&b, "4CC#01102A0108B004", "4CB#0190");
    ck_assert_int_eq(db_value(&b, 0x6042, 0), 1200);
    db_exchange(&b, "4CC#010E2A0103", "4CB#018E01"); /* standing at 0 until a run */
    db_exchange(&b, "4CC#010E2A0104", "4CB#018E01");
    db_exchange(&b, "4CC#010E2A0106", "4CB#018E00");
    db_exchange(&b, "4CC#010E2A0107", "4CB#018E0000");
    db_exchange(&b, "4CC#010E2A0108", "4CB#018EB004");
    db_exchange(&b, "4CC#010E2A011D", "4CB#018E01");
    db_exchange(&b, "4CC#011029010301", "4CB#0190");
    db_advance(&b, 2400000);
    db_exchange(&b, "4CC#010E2A0107", "4CB#018EB004");
    db_exchange(&b, "4CC#01102A0107B004", "4CB#01940EFF");
    db_exchange(&b, "4CC#01102A0108B0", "4CB#019413FF");
    db_exchange(&b, "4CC#010E2A0105", "4CB#019414FF");
}
END_TEST

/* Two rows of the manual's tables ("Supported CIP objects": the AC/DC drive object's instance
 * attributes, NetRef 0x2A attribute 4; the Control supervisor's, Run2 0x29 attribute 4), two
 * attributes: they share an attribute number, not a value.
 * The manual's explicit recipe (NetRef = 1, SpeedRef 300, Run1 = 1) runs forward: 6044h +300 rpm,
 * status 0627h. NetRef back to 0 leaves Run1 and Run2 as they were, and the drive running. */
START_TEST(net_ref_leaves_run2_alone)
{
    db_exchange(&b, "4CC#01102A010401", "4CB#0190");
    db_exchange(&b, "4CC#010E290104", "4CB#018E00");
    db_exchange(&b, "4CC#01102A01082C01", "4CB#0190");
    db_exchange(&b, "4CC#011029010301", "4CB#0190");
    db_advance(&b, 2400000);
    ck_assert_int_eq(db_value(&b, 0x6042, 0), 300);
    ck_assert_int_eq(db_value(&b, 0x6044, 0), 300);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0627);
    db_exchange(&b, "4CC#010E2A0107", "4CB#018E2C01");
    db_exchange(&b, "4CC#01102A010400", "4CB#0190");
    db_exchange(&b, "4CC#010E2A0104", "4CB#018E00");
    db_exchange(&b, "4CC#010E290104", "4CB#018E00");
    db_exchange(&b, "4CC#010E290103", "4CB#018E01");
    ck_assert_int_eq(db_value(&b, 0x6044, 0), 300);
    db_exchange(&b, "4CC#01102A010402", "4CB#019409FF"); /* a BOOL of 2 */
}
END_TEST

/* Class ((ADL - 3000) / 200) + 70h, attribute ADL mod 200 + 1, instance 1. */
START_TEST(application_objects_by_address)
{
    db_exchange(&b, "4CC#010E700001", "4CB#018E0100");
    db_exchange(&b, "4CC#010E700169", "4CB#018EF401"); /* HSP 3104: 50.0 Hz */
    db_exchange(&b, "4CC#010E8E0102", "4CB#018E1E00"); /* ACC 9001: 3.0 s */
    db_exchange(&b, "4CC#01108E01023200", "4CB#0190"); /* ACC = 5.0 s */
    ck_assert_int_eq(db_value(&b, 0x203C, 2), 50);
    db_exchange(&b, "4CC#01108E01030A00", "4CB#0190"); /* DEC 9002 = 1.0 s */
    ck_assert_int_eq(db_value(&b, 0x203C, 3), 10);
    db_exchange(&b, "4CC#010E8B0102", "4CB#018E0100");      /* CHCF 8401 */
    db_exchange(&b, "4CC#01108E01020000", "4CB#019409FF");  /* ACC 0: below its limit */
    db_exchange(&b, "4CC#01107001698913", "4CB#019409FF");  /* HSP 500.1 Hz */
    db_exchange(&b, "4CC#010E700102", "4CB#019414FF");      /* 3001: no parameter */
    db_exchange(&b, "4CC#010E7001C9", "4CB#019414FF");      /* attribute 201 */
    db_exchange(&b, "4CC#011071010200 00", "4CB#01940EFF"); /* ETA 3201 is read-only */
    db_exchange(&b, "4CC#01108E010232", "4CB#019413FF");
    db_exchange(&b, "4CC#010E700201", "4CB#019416FF");
}
END_TEST

/* The manual's "Explicit Messaging" examples, as printed: ADL 3 000 is 16#70/01/01, 3 100 is
 * 16#70/01/65, 3 201 is 16#71/01/02. The first two name no parameter of the drive: attribute not
 * supported; the third is ETA (docs/decisions.md, D-DEVICENET-ADL-EXAMPLES). */
START_TEST(the_manuals_address_examples)
{
    db_exchange(&b, "4CC#010E700101", "4CB#019414FF");
    db_exchange(&b, "4CC#010E700165", "4CB#019414FF");
    db_exchange(&b, "4CC#010E710102", "4CB#018E4006");
    ck_assert_int_eq(db_value(&b, 0x2002, 2), 0x0640);
}
END_TEST

START_TEST(io_timeout_is_cnf_and_the_scanner_resets_it)
{
    db_exchange(&b, "4CC#01100502096000", "4CB#01906000"); /* 96 ms: a watchdog of 384 ms */
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_GREEN);
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
    db_advance(&b, 384000);
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_FLASHING_RED);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
    ck_assert_int_eq(db_value(&b, 0x2022, 3), 1); /* CnF: time out */
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CnF");
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node),
                      0x0421);                             /* owned, faulted I/O, major rec. */
    db_exchange(&b, "4CC#01100502096000", "4CB#01906000"); /* established again */
    db_exchange(&b, "4CD#0400B004", "3D9#F0030000");       /* FaultRst, then Stop: Ready */
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
}
END_TEST

/* Run1 at 1200 rpm on the polled connection, at the reference 2.4 s later. */
static void run_at_1200_rpm(void)
{
    db_exchange(&b, "4CD#0100B004", "3D9#74040000");
    db_advance(&b, 2400000);
    db_exchange(&b, "4CD#0100B004", "3D9#F404B004");
}

/* The scanner releases the polled connection while the drive runs on its commands: the data stop
 * as after a timeout, and it is the same CnF with COL's reaction (docs/decisions.md,
 * D-DEVICENET-CONNECTION-END); COL = 1 (the default) freewheels into Fault at once. The explicit
 * connection stays: NS green, the Identity owned, without I/O, major recoverable fault. */
START_TEST(release_while_running_is_cnf)
{
    run_at_1200_rpm();
    db_exchange(&b, "4CE#014C030102", "4CB#01CC");
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CnF");
    ck_assert_int_eq(db_value(&b, 0x2022, 3), 1); /* CnF: time out */
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_GREEN);
    ck_assert_uint_eq(dn_node_identity_status(&b.dn.node), 0x0431);
    db_rx(&b, "4CD#0100B004"); /* no polled connection: ignored */
    db_expect_none(&b);
    /* Allocated again, the scanner resets the fault. */
    db_exchange(&b, "4CE#014B03010201", "4CB#01CB00");
    db_exchange(&b, "4CC#01100502091027", "4CB#01901027");
    db_exchange(&b, "4CD#0400B004", "3D9#F0030000"); /* FaultRst, then Stop: Ready */
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
}
END_TEST

/* With COL = 2 (2022:02, ADL 6401: class 81h attribute 2) the released drive stops on its DEC
 * ramp (3.0 s from 1500 rpm) in Fault reaction active, the supervisor Stopping, then Faulted. */
START_TEST(release_while_running_stops_as_col_says)
{
    db_exchange(&b, "4CC#011081010202 00", "4CB#0190");
    run_at_1200_rpm();
    db_exchange(&b, "4CE#014C030102", "4CB#01CC");
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x020F);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_STOPPING);
    db_advance(&b, 2399999);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_STOPPING);
    db_advance(&b, 1);
    ck_assert_int_eq(db_value(&b, 0x6044, 0), 0);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
}
END_TEST

/* A drive standing (Ready) or already stopping (Run1 off, on its ramp) is released as it is: the
 * scanner ended its session, nothing runs that the network could no longer stop. */
START_TEST(release_of_a_standing_or_stopping_drive_keeps_it)
{
    db_exchange(&b, "4CD#00000000", "3D9#F0030000"); /* Stop: Ready */
    db_exchange(&b, "4CE#014C030102", "4CB#01CC");
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_READY);
    db_exchange(&b, "4CE#014B03010201", "4CB#01CB00");
    db_exchange(&b, "4CC#01100502091027", "4CB#01901027");
    run_at_1200_rpm();
    db_exchange(&b, "4CD#0000B004", "3D9#7405B004"); /* Run1 off: Stopping */
    db_exchange(&b, "4CE#014C030102", "4CB#01CC");
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    db_advance(&b, 2400000);
    ck_assert_int_eq(db_value(&b, 0x6044, 0), 0);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_READY);
}
END_TEST

START_TEST(leds_before_and_after_the_check)
{
    memset(&b, 0, sizeof b);
    db_start(&b);
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_OFF);
    db_advance(&b, 2000000);
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_FLASHING_GREEN);
}
END_TEST

/* MS flashing green, the manual's "Needs commissioning due to configuration missing, incomplete
 * or incorrect": a transfer with CMI bit 15 (8504: class 8Bh attribute 69h) leaves LSP (3105:
 * class 70h attribute 6Ah) above HSP, bit 15 back to 0 is CFI; a consistent LSP ends it. */
START_TEST(ms_flashes_green_while_the_configuration_is_incorrect)
{
    db_exchange(&b, "4CC#01108B01690080", "4CB#0190");
    db_exchange(&b, "4CC#011070016A5802", "4CB#0190"); /* LSP 60.0 Hz */
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
    db_exchange(&b, "4CC#01108B01690000", "4CB#0190");
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CFI");
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_FLASHING_GREEN);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
    db_exchange(&b, "4CC#011070016A6400", "4CB#0190"); /* LSP 10.0 Hz */
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
}
END_TEST

/* The manual's "Drive behaviour at first Power on": CFF [Incorrect config.] until the restore
 * (FCS = InI). The drive does not start in it (D-DEVICENET-FIRST-POWER-ON); the control surface
 * makes it and ends it as the restore would: 603Fh 6300h, Fault, MS flashing green ("needs
 * commissioning"), then Switch on disabled and MS green as soon as its cause is gone. */
START_TEST(cff_is_made_and_ended_as_at_first_power_on)
{
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
    int cff = drive_fault_find(&b.drive, "CFF");
    ck_assert_int_ge(cff, 0);
    drive_fault_inject(&b.drive, (uint8_t)cff, b.now);
    b.deadline = drive_dn_process(&b.dn, b.now); /* as the daemon after a control command */
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CFF");
    ck_assert_int_eq(db_value(&b, 0x603F, 0), 0x6300);
    ck_assert_int_eq(db_value(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_FLASHING_GREEN);
    ck_assert_int_eq(drive_dn_state(&b.dn), DRIVE_DN_FAULTED);
    drive_fault_remove_cause(&b.drive, (uint8_t)cff, b.now);
    b.deadline = drive_dn_process(&b.dn, b.now);
    ck_assert_ptr_null(drive_fault_latched(&b.drive));
    ck_assert_int_eq(db_value(&b, 0x6041, 0) & 0x006F, 0x0040);
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), DN_LED_GREEN);
}
END_TEST

/* The manual's LED test runs "during start-up": at power-up and at an Identity Reset of either
 * type, which CIP's Reset service defines as a power cycle (type 1 after the out-of-box values);
 * not when the card goes on the bus again after bus off with BOI or an interface outage, which are
 * no power-up (docs/decisions.md, D-DEVICENET-LEDS). 0.25 s into the test MS is red. */
static void expect_led_test(bool running)
{
    b.next = b.count;
    b.deadline = drive_dn_process(&b.dn, b.now);
    db_advance(&b, 250000);
    ck_assert_int_eq(dn_node_ms_led(&b.dn.node), running ? DN_LED_RED : DN_LED_GREEN);
    ck_assert_int_eq(dn_node_ns_led(&b.dn.node), DN_LED_OFF);
    db_advance(&b, 2000000);
    ck_assert_int_eq(b.dn.node.link, DN_LINK_ONLINE);
    b.next = b.count;
}

START_TEST(led_test_at_power_up_and_identity_reset_only)
{
    memset(&b, 0, sizeof b);
    db_start(&b);
    expect_led_test(true);
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_exchange(&b, "4CC#011003010301", "4CB#0190"); /* BOI = 1 */
    drive_dn_bus_off(&b.dn, b.now);
    expect_led_test(false);
    drive_dn_restart(&b.dn, b.now);
    expect_led_test(false);
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_rx(&b, "4CC#01050101"); /* type 0 */
    db_expect(&b, "4CB#0185");
    expect_led_test(true);
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_rx(&b, "4CC#0105010101"); /* type 1 */
    db_expect(&b, "4CB#0185");
    expect_led_test(true);
}
END_TEST

/* Connection class attributes 100 and 101: stored, used after the restart an Identity Reset is. */
START_TEST(stored_selection_after_a_reset)
{
    db_exchange(&b, "4CC#01100500641400", "4CB#0190"); /* consumed 20 */
    db_exchange(&b, "4CC#01100500654600", "4CB#0190"); /* produced 70 */
    ck_assert_uint_eq(b.stored.consumed_assembly, 20);
    ck_assert_uint_eq(b.stored.produced_assembly, 70);
    db_exchange(&b, "4CD#0100B004", "3D9#74040000"); /* still 21/71 until the restart */
    db_rx(&b, "4CC#01050101");
    db_expect(&b, "4CB#0185");
    db_expect(&b, "4CF#00F30078563412");
    db_advance(&b, 2000000);
    db_expect(&b, "4CF#00F30078563412");
    db_expect_none(&b);
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_exchange(&b, "4CC#01100502091027", "4CB#01901027");
    db_exchange(&b, "4CD#0100B004", "3D9#04000000");   /* 70: Running1 */
    db_exchange(&b, "4CC#01100500646400", "4CB#0190"); /* consumed 100 */
    db_exchange(&b, "4CC#01100500656500", "4CB#0190"); /* produced 101 */
    db_rx(&b, "4CC#01050101");
    b.next = b.count;
    db_advance(&b, 2000000);
    b.next = b.count;
    db_exchange(&b, "4CE#014B03010301", "4CB#01CB00");
    db_exchange(&b, "4CC#01100502091027", "4CB#01901027");
    /* 6040h and 6042h as they are: Shutdown, Switch on, Enable operation at 1200 rpm. */
    db_exchange(&b, "4CD#0600B004", "3D9#21060000");
    db_exchange(&b, "4CD#0700B004", "3D9#23060000");
    db_exchange(&b, "4CD#0F00B004", "3D9#27020000");
    db_advance(&b, 2400000);
    db_exchange(&b, "4CD#0F00B004", "3D9#2706B004"); /* 0627h, 1200 rpm */
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("drive_devicenet_objects");
    TCase *tc = tcase_create("objects");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, motor_data);
    tcase_add_test(tc, rated_voltage_is_uns);
    tcase_add_test(tc, control_supervisor);
    tcase_add_test(tc, ac_dc_drive);
    tcase_add_test(tc, net_ref_leaves_run2_alone);
    tcase_add_test(tc, application_objects_by_address);
    tcase_add_test(tc, the_manuals_address_examples);
    tcase_add_test(tc, io_timeout_is_cnf_and_the_scanner_resets_it);
    tcase_add_test(tc, release_while_running_is_cnf);
    tcase_add_test(tc, release_while_running_stops_as_col_says);
    tcase_add_test(tc, release_of_a_standing_or_stopping_drive_keeps_it);
    tcase_add_test(tc, leds_before_and_after_the_check);
    tcase_add_test(tc, ms_flashes_green_while_the_configuration_is_incorrect);
    tcase_add_test(tc, cff_is_made_and_ended_as_at_first_power_on);
    tcase_add_test(tc, stored_selection_after_a_reset);
    tcase_add_test(tc, led_test_at_power_up_and_identity_reset_only);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
