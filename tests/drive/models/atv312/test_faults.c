/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV312's faults: every code of its table faults the drive with the EMCY code of the
 * manuals (the ATV58 table, the manuals' only one), 603Fh, ETA 2002h:02, 1001h and 1003h, and is
 * reset by its class: the mains undervoltage USF by itself, OHF by a fault reset once the cause
 * is gone, OCF only by a reset node; the communication loss is COF, as the CANopen manual names
 * the life guarding fault, follows COL (ignore, freewheel, ramp or fast stop) and latches the
 * network fault code CnF. Every fault freewheels (the project's choice where the manuals give no
 * stop) but COF with COL = 2 or 3. */
#include "atv312_bench.h"
#include "check_main.h"
#include "drive/panel.h"

/* Code, EMCY frame of node 4 (code, 1001h), reset class. */
static const struct {
    const char *code;
    const char *emcy;
    drive_fault_reset_t reset;
} expected[] = {
    {"COF", "084#3081010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"ILF", "084#2075010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"SLF", "084#1075010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"OCF", "084#1023010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"SCF", "084#2023010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"OSF", "084#1031010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"USF", "084#2031010000000000", DRIVE_FAULT_RESET_AUTOMATIC},
    {"PHF", "084#3031010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"ObF", "084#1033010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"OPF", "084#1033010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"OHF", "084#1042010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"OtF", "084#1043010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"OLF", "084#0010010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"SOF", "084#0010010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"CrF", "084#0010010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"EEF", "084#2055010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"InF", "084#0061010000000000", DRIVE_FAULT_RESET_POWER_CYCLE},
    {"CFF", "084#0063010000000000", DRIVE_FAULT_RESET_AUTOMATIC},
    {"CFI", "084#0063010000000000", DRIVE_FAULT_RESET_AUTOMATIC},
    {"LFF", "084#0073010000000000", DRIVE_FAULT_RESET_COMMAND},
    {"EPF", "084#0090010000000000", DRIVE_FAULT_RESET_COMMAND},
};

#define EXPECTED_COUNT (sizeof expected / sizeof expected[0])

static uint8_t find(bench_t *b, const char *code)
{
    int index = drive_fault_find(&b->drive, code);
    ck_assert_int_ge(index, 0);
    return (uint8_t)index;
}

static void inject(bench_t *b, const char *code)
{
    drive_fault_inject(&b->drive, find(b, code), b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

static void remove_cause(bench_t *b, const char *code)
{
    drive_fault_remove_cause(&b->drive, find(b, code), b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

START_TEST(table_is_the_manuals)
{
    ck_assert_uint_eq(atv312_family_faults.count, EXPECTED_COUNT);
    ck_assert_str_eq(atv312_family_faults.faults[atv312_family_faults.communication_loss].code,
                     "COF");
}
END_TEST

/* Each fault on a fresh drive running at 1500 rpm: EMCY, freewheel (speed and current 0, Fault
 * at once), 603Fh, 1001h, 1003h, ETA. */
START_TEST(every_fault_reports)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    const drive_fault_def_t *def = &atv312_family_faults.faults[_i];
    ck_assert_str_eq(def->code, expected[_i].code);
    ck_assert_int_eq(def->reset, expected[_i].reset);
    inject(&b, expected[_i].code);
    bench_expect(&b, expected[_i].emcy);
    bench_expect_none(&b);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 4), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0608);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), def->emcy_code);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x01); /* "=1 (error)" */
    ck_assert_uint_eq(bench_read(&b, 0x1003, 0), 1);
    ck_assert_uint_eq(bench_read(&b, 0x1003, 1), def->emcy_code);
}
END_TEST

/* Mains undervoltage: USF while the mains is low, gone by itself when it returns. */
START_TEST(undervoltage_resets_itself)
{
    bench_t b;
    bench_start(&b);
    inject(&b, "usf");
    bench_expect(&b, "084#2031010000000000");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    remove_cause(&b, "USF");
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

START_TEST(overheating_needs_cause_gone_then_reset)
{
    bench_t b;
    bench_start(&b);
    inject(&b, "OHF");
    bench_expect(&b, "084#1042010000000000");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0608);
    bench_expect_none(&b);
    remove_cause(&b, "OHF");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
}
END_TEST

START_TEST(overcurrent_needs_power_cycle)
{
    bench_t b;
    bench_start(&b);
    inject(&b, "OCF");
    bench_expect(&b, "084#1023010000000000");
    remove_cause(&b, "OCF");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    bench_expect_none(&b);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

/* CFF and CFI share EMCY 6300h: one active error for both (CiA 301 keeps one per code), so CFI
 * sends no EMCY of its own, and the code stays active until the last of them ends. */
START_TEST(shared_emcy_code_ends_with_its_last_fault)
{
    bench_t b;
    bench_start(&b);
    inject(&b, "CFF");
    bench_expect(&b, "084#0063010000000000");
    inject(&b, "CFI");
    bench_expect_none(&b);
    remove_cause(&b, "CFF");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x6300);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x01);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CFI");
    remove_cause(&b, "CFI");
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
}
END_TEST

/* ObF and OPF share 3310h, reset by command: one reset ends both, with one error reset EMCY. */
START_TEST(shared_emcy_code_reset_together)
{
    bench_t b;
    bench_start(&b);
    inject(&b, "ObF");
    inject(&b, "OPF");
    bench_expect(&b, "084#1033010000000000");
    bench_expect_none(&b);
    remove_cause(&b, "ObF");
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0608);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0x01);
    remove_cause(&b, "OPF");
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0608);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
}
END_TEST

/* Heartbeat consumer 100 ms on node 1, running at 1500 rpm, then the producer stops: the loss
 * comes 100 ms after its last heartbeat. */
static void lose_heartbeat(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x1016, 1, 0x00010064, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_rx(b, "701#05");
    bench_advance(b, 3000000);
}

/* COL = 1 (the default): the communication loss is the COF fault, on the display too ("the drive
 * will display COF", the CANopen manual's life guarding); 2022:03 (CnF) latches the time out until
 * a reset node, also across the fault reset. */
START_TEST(communication_loss_faults_by_default)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x2022, 2), 1);
    ck_assert_uint_eq(bench_read(&b, 0x2022, 3), 0);
    lose_heartbeat(&b);
    bench_expect(&b, "084#3081010000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "COF");
    ck_assert_str_eq(drive_panel_display(&b.drive).code, "COF");
    ck_assert_uint_eq(bench_read(&b, 0x2022, 3), 1);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x2022, 3), 1);
    bench_rx(&b, "000#8104");
    bench_expect(&b, "704#00");
    ck_assert_uint_eq(bench_read(&b, 0x2022, 3), 0);
}
END_TEST

/* COL = 0: the drive ignores the loss and keeps running; the CnF code still says it happened. */
START_TEST(communication_loss_ignored_with_col_0)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2022, 2, 0, 2), 0);
    lose_heartbeat(&b);
    bench_expect_none(&b);
    ck_assert_int_eq(bench_speed(&b), 1500);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0627);
    ck_assert_uint_eq(bench_read(&b, 0x2022, 3), 1);
}
END_TEST

/* Running at 1500 rpm with COL = `col` and a heartbeat consumer of 100 ms on node 1 whose
 * producer then stops: the loss 100 ms after its last heartbeat, the COF EMCY. */
static void lose_heartbeat_at_speed(bench_t *b, uint16_t col)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x2022, 2, col, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x1016, 1, 0x00010064, 4), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
    bench_rx(b, "701#05");
    bench_advance(b, 100000);
    bench_expect(b, "084#3081010000000000");
    bench_expect_none(b);
}

/* ETA and its copy 2002:02: Fault reaction active (0x000F) with remote, not at the reference. */
static void expect_status(bench_t *b, uint16_t status)
{
    ck_assert_uint_eq(bench_read(b, 0x6041, 0), status);
    ck_assert_uint_eq(bench_read(b, 0x2002, 2), status);
}

/* COL = 2: COF stops on the DEC ramp (3.0 s from 1500 rpm) in Fault reaction active, the output
 * on, then the drive is in Fault. */
START_TEST(communication_loss_ramp_stop_with_col_2)
{
    bench_t b;
    bench_start(&b);
    lose_heartbeat_at_speed(&b, 2);
    expect_status(&b, 0x020F);
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 1125);
    ck_assert_uint_gt(bench_read(&b, 0x2002, 4), 0);
    expect_status(&b, 0x020F);
    bench_advance(&b, 2249000);
    expect_status(&b, 0x020F);
    bench_advance(&b, 1000);
    expect_status(&b, 0x0608);
    ck_assert_int_eq(bench_speed(&b), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 4), 0);
    ck_assert_uint_eq(bench_read(&b, 0x603F, 0), 0x8130);
    ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
    bench_expect(&b, "084#0000000000000000");
}
END_TEST

/* COL = 3: COF stops on the fast ramp, DEC / 4 = 0.7 s (in 0.1 s, rounded down) from 1500
 * rpm. */
START_TEST(communication_loss_fast_stop_with_col_3)
{
    bench_t b;
    bench_start(&b);
    lose_heartbeat_at_speed(&b, 3);
    bench_advance(&b, 350000);
    ck_assert_int_eq(bench_speed(&b), 750);
    expect_status(&b, 0x020F);
    bench_advance(&b, 349000);
    expect_status(&b, 0x020F);
    bench_advance(&b, 1000);
    expect_status(&b, 0x0608);
}
END_TEST

/* An injected COF stops as COL says too (atv312d's control surface injects it). */
START_TEST(injected_communication_loss_follows_col)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2022, 2, 2, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    inject(&b, "COF");
    bench_expect(&b, "084#3081010000000000");
    expect_status(&b, 0x020F);
    bench_advance(&b, 3000000);
    expect_status(&b, 0x0608);
}
END_TEST

/* COL is a configuration parameter with the values 0 to 3; CnF is read-only. */
START_TEST(col_is_a_configuration_parameter)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2022, 2, 4, 2), 0x06090031);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2022, 3, 0, 2), 0x06010002);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2022, 2, 0, 2), 0x08000022);
    ck_assert_uint_eq(bench_read(&b, 0x2022, 2), 1);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_faults");
    TCase *tc = tcase_create("faults");
    tcase_add_test(tc, table_is_the_manuals);
    tcase_add_loop_test(tc, every_fault_reports, 0, EXPECTED_COUNT);
    tcase_add_test(tc, undervoltage_resets_itself);
    tcase_add_test(tc, overheating_needs_cause_gone_then_reset);
    tcase_add_test(tc, overcurrent_needs_power_cycle);
    tcase_add_test(tc, shared_emcy_code_ends_with_its_last_fault);
    tcase_add_test(tc, shared_emcy_code_reset_together);
    tcase_add_test(tc, communication_loss_faults_by_default);
    tcase_add_test(tc, communication_loss_ignored_with_col_0);
    tcase_add_test(tc, communication_loss_ramp_stop_with_col_2);
    tcase_add_test(tc, communication_loss_fast_stop_with_col_3);
    tcase_add_test(tc, injected_communication_loss_follows_col);
    tcase_add_test(tc, col_is_a_configuration_parameter);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
