/* SPDX-License-Identifier: Apache-2.0 */
/* The two LEDs of the VW3-A58308 card (its manual, section 1.4, "Signalling LEDs"), hooks of the
 * drive layer's panel (drive/panel.h): a green "OK", steady with no fault and flashing on
 * "Communication fault (CNF)" or "Internal failure (ILF)" ("Address 0", the third cause, cannot
 * happen: node-ids are 1..63); a yellow "COM", flashing while the card receives PDOs or SDOs and
 * off when it receives none. The manual gives no rate and no time after which "receiving" ends:
 * COM flashes for ATV58_COM_RECEIVING_US after each reception (docs/decisions.md, D-ATV58-LEDS). */
#include "atv58/atv58.h"

#include <string.h>

/* How long after a received PDO or SDO request the card still shows "receiving". */
#define ATV58_COM_RECEIVING_US 1000000u

/* Whether the latched fault is one the manual names for the flashing OK LED. A drive fault of
 * another code is not the card's: it is on the drive's display, and OK stays steady. */
static bool card_fault(const drive_t *drive)
{
    const drive_fault_def_t *fault = drive_fault_latched(drive);
    return fault != NULL && (strcmp(fault->code, "CnF") == 0 || strcmp(fault->code, "ILF") == 0);
}

static drive_led_t ok_pattern(const drive_t *drive, co_time_t now)
{
    (void)now;
    return card_fault(drive) ? DRIVE_LED_FLASHING : DRIVE_LED_ON;
}

static drive_led_t com_pattern(const drive_t *drive, co_time_t now)
{
    co_time_t last = drive_last_service_request(drive);
    bool receiving = last != CO_TIME_NEVER && now - last < ATV58_COM_RECEIVING_US;
    return receiving ? DRIVE_LED_FLASHING : DRIVE_LED_OFF;
}

const drive_indicator_t atv58_indicators[ATV58_INDICATORS] = {
    {"OK", "green", ok_pattern},
    {"COM", "yellow", com_pattern},
};
