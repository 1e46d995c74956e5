/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 303-3 indicators: which pattern the RUN (green) and the ERR (red) LED show for a node's
 * NMT state and error state, and whether a pattern is lit at a time the caller hands in (the core
 * reads no clock). A helper the application calls; no service calls it, so that a node without
 * LEDs does not link it. docs/indicators.md. */
#ifndef CO_INDICATORS_H
#define CO_INDICATORS_H

#include "co_nmt.h"
#include "co_types.h"

/* The patterns of CiA 303-3, its figures' timings (CO_LED_* below). */
typedef enum co_led {
    CO_LED_OFF,
    CO_LED_ON,
    CO_LED_FLICKERING,   /* 50 ms on, 50 ms off; the RUN and the ERR LED in turn */
    CO_LED_BLINKING,     /* 200 ms on, 200 ms off */
    CO_LED_SINGLE_FLASH, /* 200 ms on, 1000 ms off */
    CO_LED_DOUBLE_FLASH, /* 200 on, 200 off, 200 on, 1000 off */
    CO_LED_TRIPLE_FLASH,
    CO_LED_QUADRUPLE_FLASH
} co_led_t;

#define CO_LED_FLICKER_US 50000u /* one flicker phase, on or off */
#define CO_LED_BLINK_US 200000u  /* a blink's or a flash's on and off phases */
#define CO_LED_PAUSE_US 1000000u /* the pause closing a flash sequence */

/* What the LEDs show: the node's NMT state and the conditions CiA 303-3 names. */
typedef struct co_indicator_state {
    co_nmt_state_t nmt_state;
    bool lss;                 /* auto-baud or LSS services in progress: both LEDs flicker */
    bool download;            /* a program or firmware download: RUN triple flash */
    bool bus_off;             /* ERR on */
    bool event_timer_error;   /* an RPDO's event timer elapsed: ERR quadruple flash */
    bool sync_error;          /* no SYNC within the 1006h time-out: ERR triple flash */
    bool error_control;       /* a guarding or heartbeat event: ERR double flash */
    bool warning;             /* an error counter at or over the warning level: ERR single flash */
    bool configuration_error; /* ERR blinking */
} co_indicator_state_t;

/* RUN: flickering during LSS, triple flash during a download, else on Operational, blinking
 * Pre-operational, single flash Stopped, off in Initialisation. */
co_led_t co_indicator_run(const co_indicator_state_t *state);
/* ERR: flickering during LSS, else the most severe condition: on (bus off), quadruple, triple,
 * double, single flash, blinking, off. */
co_led_t co_indicator_err(const co_indicator_state_t *state);

/* Whether a LED showing `led` is lit at `now`. Every pattern runs from time 0, so that the two
 * LEDs of a node keep in step; the ERR LED (`err`) flickers when the RUN LED does not. */
bool co_led_lit(co_led_t led, bool err, co_time_t now);
/* When co_led_lit() changes next after `now`, for either LED (CO_TIME_NEVER for on and off):
 * the deadline of a main loop that sleeps. */
co_time_t co_led_next_change(co_led_t led, co_time_t now);

/* "off", "on", "flickering", "blinking", "single flash", "double flash", "triple flash",
 * "quadruple flash". */
const char *co_led_name(co_led_t led);

#endif
