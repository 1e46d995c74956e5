/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV58 card's two LEDs as its manual prints them (section 1.4, "Signalling LEDs"): a green
 * "OK", steady with no fault, flashing on a communication fault (CNF) or an internal failure
 * (ILF); a yellow "COM", flashing while PDOs or SDOs are received, off when none is
 * (docs/decisions.md, D-ATV58-LEDS: flashing for 1 s after the last one). Not the CiA 303-3 RUN
 * and ERR pair of the Altivar 31/312. */
#include "atv58/atv58.h"
#include "check_main.h"
#include "drive/panel.h"
#include "drive_bench.h"

#include <string.h>

/* The pattern of the model's indicator `name` now. */
static drive_led_t led(const bench_t *b, const char *name)
{
    uint8_t count;
    const drive_indicator_t *indicators = drive_panel_indicators(&b->drive, &count);
    for (uint8_t i = 0; i < count; i++)
        if (strcmp(indicators[i].name, name) == 0)
            return indicators[i].pattern(&b->drive, b->now);
    ck_abort_msg("no indicator %s", name);
    return DRIVE_LED_OFF;
}

START_TEST(card_has_ok_and_com)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    uint8_t count;
    const drive_indicator_t *indicators = drive_panel_indicators(&b.drive, &count);
    ck_assert_uint_eq(count, 2);
    ck_assert_str_eq(indicators[0].name, "OK");
    ck_assert_str_eq(indicators[0].colour, "green");
    ck_assert_str_eq(indicators[1].name, "COM");
    ck_assert_str_eq(indicators[1].colour, "yellow");
    ck_assert_int_eq(led(&b, "OK"), DRIVE_LED_ON);
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_OFF);
}
END_TEST

/* COM flashes for 1 s after each SDO request or PDO received; NMT and guarding do not count. */
START_TEST(com_flashes_on_sdo_and_pdo)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    bench_advance(&b, 100000);
    bench_rx(&b, "000#0104000000000000");
    bench_expect(&b, "184#4006000000000000");
    bench_rx(&b, "704#R");
    bench_expect(&b, "704#0500000000000000");
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_OFF);
    bench_rx(&b, "604#400C100000000000");
    bench_expect(&b, "584#4B0C1000F4010000");
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_FLASHING);
    bench_advance(&b, 999999);
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_FLASHING);
    bench_advance(&b, 1);
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_OFF);
    bench_rx(&b, "204#0600000000000000");
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_FLASHING);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_OFF);
    bench_rx(&b, "205#0600000000000000"); /* another node's RPDO */
    ck_assert_int_eq(led(&b, "COM"), DRIVE_LED_OFF);
}
END_TEST

/* OK flashes while CnF (the life guarding time-out: guard time 500 ms x 2) or ILF is latched;
 * another fault of the drive leaves it steady (the card has no fault). */
START_TEST(ok_flashes_on_cnf_and_ilf)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    bench_rx(&b, "704#R");
    bench_expect(&b, "704#7F00000000000000");
    bench_advance(&b, 1000000);
    bench_expect(&b, "084#3081010000000000");
    ck_assert_str_eq(drive_fault_latched(&b.drive)->code, "CnF");
    ck_assert_int_eq(led(&b, "OK"), DRIVE_LED_FLASHING);

    bench_start_model(&b, &atv58_profile, NULL);
    drive_fault_inject(&b.drive, (uint8_t)drive_fault_find(&b.drive, "OHF"), b.now);
    ck_assert_int_eq(led(&b, "OK"), DRIVE_LED_ON);
    bench_start_model(&b, &atv58_profile, NULL);
    drive_fault_inject(&b.drive, (uint8_t)drive_fault_find(&b.drive, "ILF"), b.now);
    ck_assert_int_eq(led(&b, "OK"), DRIVE_LED_FLASHING);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv58_indicators");
    TCase *tc = tcase_create("indicators");
    tcase_add_test(tc, card_has_ok_and_com);
    tcase_add_test(tc, com_flashes_on_sdo_and_pdo);
    tcase_add_test(tc, ok_flashes_on_cnf_and_ilf);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
