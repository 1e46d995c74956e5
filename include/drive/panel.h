/* SPDX-License-Identifier: Apache-2.0 */
/* What the drive's front panel shows: the 4-digit display (a state code, a fault code, or the
 * output frequency) and the LEDs of the model's card: by default the two CANopen LEDs of the
 * ATV312 manual's signalling table (CiA 303-3 RUN: the NMT state; ERR: the worst communication
 * error), or those a model's profile names (the ATV58 card's OK and COM). Read-only views of a
 * drive_t, for a person testing a master (atv312d's control surface). Portable like the core. */
#ifndef DRIVE_PANEL_H
#define DRIVE_PANEL_H

#include "drive/drive.h"

/* The LED patterns of the manual ("Description of the various LED states"). */
typedef enum drive_led {
    DRIVE_LED_OFF,
    DRIVE_LED_SINGLE_FLASH, /* 200 ms on, 1 s off */
    DRIVE_LED_DOUBLE_FLASH, /* 200 ms on, 200 ms off, 200 ms on, 1 s off */
    DRIVE_LED_BLINKING,     /* 2.5 Hz: 200 ms on, 200 ms off */
    DRIVE_LED_FLASHING,     /* flashing at a rate the manual does not give (the ATV58 card's) */
    DRIVE_LED_ON
} drive_led_t;

/* One LED of a model's card: its name and colour as the manual prints them, and its pattern now
 * (a hook of the model, or of the drive layer for the CiA 303-3 pair). */
typedef struct drive_indicator {
    const char *name;   /* "RUN", "OK" */
    const char *colour; /* "green", "yellow" */
    drive_led_t (*pattern)(const drive_t *drive, co_time_t now);
} drive_indicator_t;

typedef struct drive_display {
    const char *code;   /* "nSt", "rdY", "FSt", a fault code; NULL: the output frequency */
    uint32_t decihertz; /* the output frequency, 0.1 Hz, when code is NULL */
} drive_display_t;

/* Fault: the latched fault's code; Switch on disabled: nSt (freewheel stop); Ready to switch on,
 * Switched on: rdY; Quick stop active: FSt; Operation enabled: the output frequency. */
drive_display_t drive_panel_display(const drive_t *drive);
/* RUN: Stopped single flash, Pre-operational blinking, Operational on, else off. */
drive_led_t drive_panel_run_led(const drive_t *drive);
/* ERR: bus off on; a heartbeat or life guarding event (the communication-loss fault latched)
 * double flash; a warning of the CAN controller (error passive, overrun) single flash; else off. */
drive_led_t drive_panel_err_led(const drive_t *drive);
/* The LEDs of the drive's card (the profile's, or RUN and ERR), count of them. */
const drive_indicator_t *drive_panel_indicators(const drive_t *drive, uint8_t *count);
/* "off", "single flash", "double flash", "blinking", "flashing", "on". */
const char *drive_led_name(drive_led_t led);

#endif
