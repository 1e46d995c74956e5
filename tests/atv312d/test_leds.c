/* SPDX-License-Identifier: Apache-2.0 */
/* The log level of every change of a DeviceNet card's MS or NS LED: warn to red and flashing red,
 * debug between green and flashing green (a scanner's allocations and releases), info else. */
#include "atv312d/leds.h"
#include "check_main.h"

#include <check.h>

START_TEST(every_change)
{
    static const dn_led_t leds[] = {DN_LED_OFF, DN_LED_GREEN, DN_LED_FLASHING_GREEN, DN_LED_RED,
                                    DN_LED_FLASHING_RED};
    /* want[from][to], in the order of leds[]. */
    static const co_log_level_t want[5][5] = {
        {CO_LOG_INFO, CO_LOG_INFO, CO_LOG_INFO, CO_LOG_WARN, CO_LOG_WARN},
        {CO_LOG_INFO, CO_LOG_DEBUG, CO_LOG_DEBUG, CO_LOG_WARN, CO_LOG_WARN},
        {CO_LOG_INFO, CO_LOG_DEBUG, CO_LOG_DEBUG, CO_LOG_WARN, CO_LOG_WARN},
        {CO_LOG_INFO, CO_LOG_INFO, CO_LOG_INFO, CO_LOG_WARN, CO_LOG_WARN},
        {CO_LOG_INFO, CO_LOG_INFO, CO_LOG_INFO, CO_LOG_WARN, CO_LOG_WARN},
    };
    for (int from = 0; from < 5; from++)
        for (int to = 0; to < 5; to++)
            ck_assert_msg(atv312d_led_change_level(leds[from], leds[to]) == want[from][to],
                          "LED %d -> %d", from, to);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("leds");
    TCase *tc = tcase_create("leds");
    tcase_add_test(tc, every_change);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
