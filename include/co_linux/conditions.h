/* SPDX-License-Identifier: Apache-2.0 */
/* The CAN communication conditions the runtime reports to its devices, as EMCYs where CiA 301
 * table 21 has a code: frames lost (overrun), error passive, bus off; and the controller's error
 * warning level, which has none (an indicator's: CiA 303-3's ERR single flash). The bus says what
 * each condition is (`wanted`); the loop tells the devices when that differs from what they were
 * told (`reported`). */
#ifndef CO_LINUX_CONDITIONS_H
#define CO_LINUX_CONDITIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define CO_LINUX_EMCY_CAN_OVERRUN 0x8110 /* frames lost: TX queue full, controller overflow */
#define CO_LINUX_EMCY_CAN_PASSIVE 0x8120 /* CAN controller in error passive mode */
#define CO_LINUX_EMCY_BUS_OFF 0x8140     /* recovered from bus off (active while bus off) */
#define CO_LINUX_EMCY_NONE 0x0000        /* the warning level: no EMCY */

typedef enum co_linux_condition_kind {
    CO_LINUX_COND_OVERRUN,
    CO_LINUX_COND_PASSIVE,
    CO_LINUX_COND_BUS_OFF,
    /* An error counter of the controller at or over the warning limit (96, ISO 11898-1); also
     * while error passive, whose limit (128) is above it. */
    CO_LINUX_COND_WARNING,
    CO_LINUX_CONDITIONS
} co_linux_condition_kind_t;

typedef struct co_linux_condition {
    uint16_t emcy_code;
    bool wanted;   /* what the bus says */
    bool reported; /* what the devices were told */
} co_linux_condition_t;

typedef struct co_linux_conditions {
    co_linux_condition_t items[CO_LINUX_CONDITIONS];
    bool traffic_since_overrun;  /* a frame was read or written since the overrun began */
    unsigned long long bus_offs; /* times the controller went bus off since the loop opened */
} co_linux_conditions_t;

/* Every condition inactive and reported so. */
void co_linux_conditions_init(co_linux_conditions_t *c);

/* The bus says a condition began (active) or ended; a change is logged with the interface, and
 * each beginning of bus off is counted. */
void co_linux_conditions_set(co_linux_conditions_t *c, const char *iface,
                             co_linux_condition_kind_t which, bool active);

/* A controller that was down starts error active with empty queues (bus_offs is kept). */
void co_linux_conditions_restart(co_linux_conditions_t *c);

/* Ends a reported overrun once frames pass again and the transmit queue is empty (`queued`). */
void co_linux_conditions_end_overrun(co_linux_conditions_t *c, const char *iface, size_t queued);

/* True when `which` changed since the devices were told and may be told now; it then counts as
 * told. An overrun is held while the transmit queue is full (`queued` of `capacity`): its EMCY
 * would be the next frame dropped, and the master would never see it. */
bool co_linux_conditions_take(co_linux_conditions_t *c, co_linux_condition_kind_t which,
                              size_t queued, size_t capacity);

/* What the bus says of the condition with that EMCY code (false for an unknown code). */
bool co_linux_conditions_active(const co_linux_conditions_t *c, uint16_t emcy_code);
/* What the bus says of the warning level (the condition without an EMCY). */
bool co_linux_conditions_warning(const co_linux_conditions_t *c);

#endif
