/* SPDX-License-Identifier: Apache-2.0 */
/* The log level of a DeviceNet card's LED change (leds.h). */
#include "atv312d/leds.h"

static bool green(dn_led_t led)
{
    return led == DN_LED_GREEN || led == DN_LED_FLASHING_GREEN;
}

co_log_level_t atv312d_led_change_level(dn_led_t from, dn_led_t to)
{
    if (to == DN_LED_RED || to == DN_LED_FLASHING_RED)
        return CO_LOG_WARN;
    if (green(from) && green(to))
        return CO_LOG_DEBUG;
    return CO_LOG_INFO;
}
