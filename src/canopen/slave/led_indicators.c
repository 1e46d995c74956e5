/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 303-3 indicators (co_indicators.h). */
#include "co/co_indicators.h"

co_led_t co_indicator_run(const co_indicator_state_t *state)
{
    if (state->lss)
        return CO_LED_FLICKERING;
    if (state->download)
        return CO_LED_TRIPLE_FLASH;
    switch (state->nmt_state) {
    case CO_NMT_OPERATIONAL:
        return CO_LED_ON;
    case CO_NMT_PRE_OPERATIONAL:
        return CO_LED_BLINKING;
    case CO_NMT_STOPPED:
        return CO_LED_SINGLE_FLASH;
    case CO_NMT_INITIALISING:
        break;
    }
    return CO_LED_OFF;
}

/* CiA 303-3: where several errors are present the ERR LED shows the most severe one. */
co_led_t co_indicator_err(const co_indicator_state_t *state)
{
    if (state->lss)
        return CO_LED_FLICKERING;
    if (state->bus_off)
        return CO_LED_ON;
    if (state->event_timer_error)
        return CO_LED_QUADRUPLE_FLASH;
    if (state->sync_error)
        return CO_LED_TRIPLE_FLASH;
    if (state->error_control)
        return CO_LED_DOUBLE_FLASH;
    if (state->warning)
        return CO_LED_SINGLE_FLASH;
    if (state->configuration_error)
        return CO_LED_BLINKING;
    return CO_LED_OFF;
}

/* The number of flashes of a flash pattern, 0 for the others. */
static co_time_t flashes(co_led_t led)
{
    switch (led) {
    case CO_LED_SINGLE_FLASH:
        return 1;
    case CO_LED_DOUBLE_FLASH:
        return 2;
    case CO_LED_TRIPLE_FLASH:
        return 3;
    case CO_LED_QUADRUPLE_FLASH:
        return 4;
    case CO_LED_OFF:
    case CO_LED_ON:
    case CO_LED_FLICKERING:
    case CO_LED_BLINKING:
        break;
    }
    return 0;
}

/* A flash sequence: n flashes 200 ms on with 200 ms off between them, then the 1000 ms pause. */
static co_time_t flash_lit_span(co_time_t n)
{
    return (2 * n - 1) * CO_LED_BLINK_US;
}

static co_time_t flash_period(co_time_t n)
{
    return flash_lit_span(n) + CO_LED_PAUSE_US;
}

bool co_led_lit(co_led_t led, bool err, co_time_t now)
{
    switch (led) {
    case CO_LED_OFF:
        return false;
    case CO_LED_ON:
        return true;
    case CO_LED_FLICKERING:
        return (now / CO_LED_FLICKER_US) % 2 == (err ? 1u : 0u);
    case CO_LED_BLINKING:
        return (now / CO_LED_BLINK_US) % 2 == 0;
    case CO_LED_SINGLE_FLASH:
    case CO_LED_DOUBLE_FLASH:
    case CO_LED_TRIPLE_FLASH:
    case CO_LED_QUADRUPLE_FLASH:
        break;
    }
    co_time_t n = flashes(led);
    co_time_t at = now % flash_period(n);
    return at < flash_lit_span(n) && (at / CO_LED_BLINK_US) % 2 == 0;
}

/* The end of the phase of `length` that `now` is in. */
static co_time_t phase_end(co_time_t now, co_time_t length)
{
    return (now / length + 1) * length;
}

co_time_t co_led_next_change(co_led_t led, co_time_t now)
{
    switch (led) {
    case CO_LED_OFF:
    case CO_LED_ON:
        return CO_TIME_NEVER;
    case CO_LED_FLICKERING:
        return phase_end(now, CO_LED_FLICKER_US);
    case CO_LED_BLINKING:
        return phase_end(now, CO_LED_BLINK_US);
    case CO_LED_SINGLE_FLASH:
    case CO_LED_DOUBLE_FLASH:
    case CO_LED_TRIPLE_FLASH:
    case CO_LED_QUADRUPLE_FLASH:
        break;
    }
    co_time_t n = flashes(led);
    co_time_t at = now % flash_period(n);
    co_time_t start = now - at;
    if (at < flash_lit_span(n))
        return start + phase_end(at, CO_LED_BLINK_US);
    return start + flash_period(n);
}

const char *co_led_name(co_led_t led)
{
    switch (led) {
    case CO_LED_ON:
        return "on";
    case CO_LED_FLICKERING:
        return "flickering";
    case CO_LED_BLINKING:
        return "blinking";
    case CO_LED_SINGLE_FLASH:
        return "single flash";
    case CO_LED_DOUBLE_FLASH:
        return "double flash";
    case CO_LED_TRIPLE_FLASH:
        return "triple flash";
    case CO_LED_QUADRUPLE_FLASH:
        return "quadruple flash";
    case CO_LED_OFF:
        break;
    }
    return "off";
}
