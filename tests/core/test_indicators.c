/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 303-3 indicators: the RUN and ERR patterns of every NMT state and error condition, and
 * each pattern's edges to the millisecond (200 ms on and off, 1000 ms pauses, 50 ms flicker),
 * co_led_next_change() agreeing with co_led_lit() at every millisecond. */
#include "check_main.h"
#include "co/co_indicators.h"

#include <stdio.h>

#define MS 1000u

/* The edges of `led` from `from` until before `until` (ms), "+0 -200 +1200": lit (+) or dark (-)
 * from that millisecond; each found with co_led_next_change() and checked against co_led_lit()
 * at every millisecond in between. */
static const char *edges(co_led_t led, bool err, unsigned from, unsigned until)
{
    static char text[256];
    size_t len = 0;
    co_time_t now = (co_time_t)from * MS;
    bool lit = co_led_lit(led, err, now);
    len += (size_t)snprintf(text + len, sizeof text - len, "%c%u", lit ? '+' : '-', from);
    while (now < (co_time_t)until * MS) {
        co_time_t next = co_led_next_change(led, now);
        for (co_time_t t = now; t < next && t < (co_time_t)until * MS; t += MS)
            ck_assert_int_eq(co_led_lit(led, err, t), lit);
        if (next >= (co_time_t)until * MS)
            break;
        ck_assert_int_ne(co_led_lit(led, err, next), lit);
        lit = !lit;
        now = next;
        len += (size_t)snprintf(text + len, sizeof text - len, " %c%u", lit ? '+' : '-',
                                (unsigned)(now / MS));
    }
    return text;
}

START_TEST(on_and_off_never_change)
{
    ck_assert_str_eq(edges(CO_LED_ON, false, 0, 5000), "+0");
    ck_assert_str_eq(edges(CO_LED_OFF, true, 0, 5000), "-0");
    ck_assert_uint_eq(co_led_next_change(CO_LED_ON, 123), CO_TIME_NEVER);
    ck_assert_uint_eq(co_led_next_change(CO_LED_OFF, 123), CO_TIME_NEVER);
}
END_TEST

START_TEST(blinking_200_ms_on_200_off)
{
    ck_assert_str_eq(edges(CO_LED_BLINKING, false, 0, 1200), "+0 -200 +400 -600 +800 -1000");
    ck_assert_str_eq(edges(CO_LED_BLINKING, true, 150, 500), "+150 -200 +400");
}
END_TEST

START_TEST(flashes_200_ms_then_a_1000_ms_pause)
{
    ck_assert_str_eq(edges(CO_LED_SINGLE_FLASH, false, 0, 2500), "+0 -200 +1200 -1400 +2400");
    ck_assert_str_eq(edges(CO_LED_DOUBLE_FLASH, true, 0, 3300),
                     "+0 -200 +400 -600 +1600 -1800 +2000 -2200 +3200");
    ck_assert_str_eq(edges(CO_LED_TRIPLE_FLASH, true, 0, 2100),
                     "+0 -200 +400 -600 +800 -1000 +2000");
    ck_assert_str_eq(edges(CO_LED_QUADRUPLE_FLASH, true, 0, 2500),
                     "+0 -200 +400 -600 +800 -1000 +1200 -1400 +2400");
    /* Mid-pause and mid-flash: the sequence runs from time 0, whenever the pattern began. */
    ck_assert_str_eq(edges(CO_LED_DOUBLE_FLASH, true, 700, 1700), "-700 +1600");
    ck_assert_str_eq(edges(CO_LED_SINGLE_FLASH, false, 1250, 1500), "+1250 -1400");
}
END_TEST

START_TEST(flickering_50_ms_in_turn)
{
    ck_assert_str_eq(edges(CO_LED_FLICKERING, false, 0, 200), "+0 -50 +100 -150");
    ck_assert_str_eq(edges(CO_LED_FLICKERING, true, 0, 200), "-0 +50 -100 +150");
}
END_TEST

START_TEST(run_led_from_the_nmt_state)
{
    co_indicator_state_t s = {.nmt_state = CO_NMT_INITIALISING};
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_OFF);
    s.nmt_state = CO_NMT_PRE_OPERATIONAL;
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_BLINKING);
    s.nmt_state = CO_NMT_OPERATIONAL;
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_ON);
    s.nmt_state = CO_NMT_STOPPED;
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_SINGLE_FLASH);
    s.bus_off = true; /* an error does not change the RUN LED */
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_SINGLE_FLASH);
    s.download = true;
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_TRIPLE_FLASH);
    s.lss = true;
    ck_assert_uint_eq(co_indicator_run(&s), CO_LED_FLICKERING);
}
END_TEST

START_TEST(err_led_shows_the_most_severe_error)
{
    co_indicator_state_t s = {.nmt_state = CO_NMT_OPERATIONAL};
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_OFF);
    s.configuration_error = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_BLINKING);
    s.warning = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_SINGLE_FLASH);
    s.error_control = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_DOUBLE_FLASH);
    s.sync_error = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_TRIPLE_FLASH);
    s.event_timer_error = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_QUADRUPLE_FLASH);
    s.bus_off = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_ON);
    s.lss = true;
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_FLICKERING);
    s = (co_indicator_state_t){.nmt_state = CO_NMT_STOPPED, .sync_error = true};
    ck_assert_uint_eq(co_indicator_err(&s), CO_LED_TRIPLE_FLASH);
}
END_TEST

START_TEST(names)
{
    ck_assert_str_eq(co_led_name(CO_LED_OFF), "off");
    ck_assert_str_eq(co_led_name(CO_LED_ON), "on");
    ck_assert_str_eq(co_led_name(CO_LED_FLICKERING), "flickering");
    ck_assert_str_eq(co_led_name(CO_LED_BLINKING), "blinking");
    ck_assert_str_eq(co_led_name(CO_LED_SINGLE_FLASH), "single flash");
    ck_assert_str_eq(co_led_name(CO_LED_DOUBLE_FLASH), "double flash");
    ck_assert_str_eq(co_led_name(CO_LED_TRIPLE_FLASH), "triple flash");
    ck_assert_str_eq(co_led_name(CO_LED_QUADRUPLE_FLASH), "quadruple flash");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("indicators");
    TCase *tc = tcase_create("indicators");
    tcase_add_test(tc, on_and_off_never_change);
    tcase_add_test(tc, blinking_200_ms_on_200_off);
    tcase_add_test(tc, flashes_200_ms_then_a_1000_ms_pause);
    tcase_add_test(tc, flickering_50_ms_in_turn);
    tcase_add_test(tc, run_led_from_the_nmt_state);
    tcase_add_test(tc, err_led_shows_the_most_severe_error);
    tcase_add_test(tc, names);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
