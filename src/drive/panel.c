/* SPDX-License-Identifier: Apache-2.0 */
/* The front panel's display and LEDs (include/drive/panel.h), derived from the drive's state. */
#include "drive/panel.h"

#include "co/co_emcy.h"
#include "drive/drive_floors.h"

drive_display_t drive_panel_display(const drive_t *drive)
{
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    if (fault)
        return (drive_display_t){.code = fault->code};
    switch (drive->cia402.state) {
    case CIA402_SWITCH_ON_DISABLED:
        return (drive_display_t){.code = "nSt"};
    case CIA402_READY_TO_SWITCH_ON:
    case CIA402_SWITCHED_ON:
        return (drive_display_t){.code = "rdY"};
    case CIA402_QUICK_STOP_ACTIVE:
        return (drive_display_t){.code = "FSt"};
    case CIA402_OPERATION_ENABLED:
    case CIA402_FAULT_REACTION_ACTIVE:
    case CIA402_FAULT:
        break;
    }
    int32_t rpm = drive_motor_rpm(&drive->motor);
    uint32_t speed = (uint32_t)(rpm < 0 ? -rpm : rpm);
    return (drive_display_t){.decihertz = drive_rpm_to_frequency(drive, speed)};
}

drive_led_t drive_panel_run_led(const drive_t *drive)
{
    switch (drive->node.nmt_state) {
    case CO_NMT_STOPPED:
        return DRIVE_LED_SINGLE_FLASH;
    case CO_NMT_PRE_OPERATIONAL:
        return DRIVE_LED_BLINKING;
    case CO_NMT_OPERATIONAL:
        return DRIVE_LED_ON;
    case CO_NMT_INITIALISING:
        break;
    }
    return DRIVE_LED_OFF;
}

static bool bus_condition(const drive_t *drive, uint16_t emcy_code)
{
    for (uint8_t i = 0; i < drive->bus_event_count; i++) {
        if (drive->bus_events[i] == emcy_code)
            return true;
    }
    return false;
}

/* CiA 303-3's ERR, as the Altivar 31 and 312 manuals' signalling tables list it: on while bus off,
 * double flash for an error control event (the latched communication-loss fault), single flash
 * while the controller is at its warning level (error passive is above it). Lost frames
 * (overrun) have no pattern: their EMCY tells the master (docs/decisions.md, D-ERR-LED). */
drive_led_t drive_panel_err_led(const drive_t *drive)
{
    uint32_t communication_loss = (uint32_t)1u << drive->profile->faults->communication_loss;
    if (bus_condition(drive, CO_EMCY_BUS_OFF))
        return DRIVE_LED_ON;
    if (drive->faults_active & communication_loss)
        return DRIVE_LED_DOUBLE_FLASH;
    if (drive->can_warning || bus_condition(drive, CO_EMCY_CAN_PASSIVE))
        return DRIVE_LED_SINGLE_FLASH;
    return DRIVE_LED_OFF;
}

static drive_led_t run_pattern(const drive_t *drive, co_time_t now)
{
    (void)now;
    return drive_panel_run_led(drive);
}

static drive_led_t err_pattern(const drive_t *drive, co_time_t now)
{
    (void)now;
    return drive_panel_err_led(drive);
}

/* CiA 303-3's pair, which the Altivar 31 and 312 manuals' signalling tables follow. */
static const drive_indicator_t cia303_indicators[] = {
    {"RUN", "green", run_pattern},
    {"ERR", "red", err_pattern},
};

const drive_indicator_t *drive_panel_indicators(const drive_t *drive, uint8_t *count)
{
    if (drive->profile->indicators != NULL) {
        *count = drive->profile->indicator_count;
        return drive->profile->indicators;
    }
    *count = sizeof cia303_indicators / sizeof cia303_indicators[0];
    return cia303_indicators;
}

const char *drive_led_name(drive_led_t led)
{
    switch (led) {
    case DRIVE_LED_SINGLE_FLASH:
        return "single flash";
    case DRIVE_LED_DOUBLE_FLASH:
        return "double flash";
    case DRIVE_LED_BLINKING:
        return "blinking";
    case DRIVE_LED_FLASHING:
        return "flashing";
    case DRIVE_LED_ON:
        return "on";
    case DRIVE_LED_OFF:
        break;
    }
    return "off";
}
