/* SPDX-License-Identifier: Apache-2.0 */
/* The front panel on the minimal model: the display code of every state, the output frequency
 * while running, the latched fault's code; the RUN LED of every NMT state and the ERR LED of
 * every communication error of the ATV312 manual's signalling table. */
#include "check_main.h"
#include "drive/panel.h"
#include "minimal_model.h"

static const char *code(const bench_t *b)
{
    return drive_panel_display(&b->drive).code;
}

START_TEST(display_follows_the_state)
{
    bench_t b;
    bench_start(&b);
    ck_assert_str_eq(code(&b), "nSt");
    bench_command(&b, 0x0006);
    ck_assert_str_eq(code(&b), "rdY");
    bench_command(&b, 0x0007);
    ck_assert_str_eq(code(&b), "rdY");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 750, 2), 0);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    /* 750 rpm of a 1500 rpm, 50.0 Hz motor: 25.0 Hz. */
    drive_display_t display = drive_panel_display(&b.drive);
    ck_assert_ptr_null(display.code);
    ck_assert_uint_eq(display.decihertz, 250);
    bench_command(&b, 0x0002);
    ck_assert_str_eq(code(&b), "FSt");
    drive_fault_inject(&b.drive, FAULT_LOW, b.now);
    ck_assert_str_eq(code(&b), "LoW");
}
END_TEST

START_TEST(run_led_follows_nmt)
{
    bench_t b;
    bench_start(&b);
    ck_assert_int_eq(drive_panel_run_led(&b.drive), DRIVE_LED_BLINKING);
    bench_rx(&b, "000#0104");
    ck_assert_int_eq(drive_panel_run_led(&b.drive), DRIVE_LED_ON);
    bench_rx(&b, "000#0204");
    ck_assert_int_eq(drive_panel_run_led(&b.drive), DRIVE_LED_SINGLE_FLASH);
    ck_assert_str_eq(drive_led_name(DRIVE_LED_SINGLE_FLASH), "single flash");
}
END_TEST

START_TEST(err_led_shows_the_worst_error)
{
    bench_t b;
    bench_start(&b);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_OFF);
    drive_bus_event(&b.drive, 0x8120, true);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_SINGLE_FLASH);
    /* A heartbeat event: double flash while the communication-loss fault is latched. */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x1016, 1, 0x00010064, 4), 0);
    bench_rx(&b, "701#05");
    bench_advance(&b, 100000);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_DOUBLE_FLASH);
    drive_bus_event(&b.drive, 0x8140, true);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_ON);
    drive_bus_event(&b.drive, 0x8140, false);
    bench_command(&b, 0x0080);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_SINGLE_FLASH);
    drive_bus_event(&b.drive, 0x8120, false);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_OFF);
    /* Another fault is no communication error. */
    drive_fault_inject(&b.drive, FAULT_HOT, b.now);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_OFF);
}
END_TEST

/* CiA 303-3's single flash: an error counter at the warning level, which error passive is above;
 * frames lost (overrun) have no pattern, their EMCY tells the master (D-ERR-LED). */
START_TEST(err_led_single_flash_is_the_warning_level)
{
    bench_t b;
    bench_start(&b);
    drive_bus_warning(&b.drive, true);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_SINGLE_FLASH);
    bench_expect_none(&b); /* CiA 301 has no EMCY for the warning level */
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
    drive_bus_warning(&b.drive, false);
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_OFF);
    drive_bus_event(&b.drive, 0x8110, true);
    bench_expect(&b, "084#1081110000000000");
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_OFF);
    /* The warning level outlives a reset node, as the controller's state does. */
    drive_bus_warning(&b.drive, true);
    bench_rx(&b, "000#8104");
    ck_assert_int_eq(drive_panel_err_led(&b.drive), DRIVE_LED_SINGLE_FLASH);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_panel");
    TCase *tc = tcase_create("panel");
    tcase_add_test(tc, display_follows_the_state);
    tcase_add_test(tc, run_led_follows_nmt);
    tcase_add_test(tc, err_led_shows_the_worst_error);
    tcase_add_test(tc, err_led_single_flash_is_the_warning_level);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
