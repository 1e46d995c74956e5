/* What the drive's front panel shows: the 4-digit display (a state code, a fault code, or the
 * output frequency) and the two CANopen LEDs of the ATV312 manual's signalling table (RUN: the
 * NMT state; ERR: the worst communication error). Read-only views of a drive_t, for a person
 * testing a master (atv312d's control surface). Portable like the core. */
#ifndef DRIVE_PANEL_H
#define DRIVE_PANEL_H

#include "drive/drive.h"

/* The LED patterns of the manual ("Description of the various LED states"). */
typedef enum drive_led {
    DRIVE_LED_OFF,
    DRIVE_LED_SINGLE_FLASH, /* 200 ms on, 1 s off */
    DRIVE_LED_DOUBLE_FLASH, /* 200 ms on, 200 ms off, 200 ms on, 1 s off */
    DRIVE_LED_BLINKING,     /* 2.5 Hz: 200 ms on, 200 ms off */
    DRIVE_LED_ON
} drive_led_t;

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
/* "off", "single flash", "double flash", "blinking", "on". */
const char *drive_led_name(drive_led_t led);

#endif
