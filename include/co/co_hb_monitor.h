/* SPDX-License-Identifier: Apache-2.0 */
/* The timer of one heartbeat consumer (CiA 301 7.2.8.3.2), the one rule of heartbeat consumption
 * that both sides share: a node's consumers (1016h, co_heartbeat.h, heartbeat.c) and the NMT
 * master's consumer of each slave (co_nmt_master.h, nmt_master.c). */
#ifndef CO_HB_MONITOR_H
#define CO_HB_MONITOR_H

#include "co_types.h"

/* The timer of one heartbeat consumer, shared by a node's consumers (1016h) and the NMT
 * master's (co_nmt_master.h): monitoring starts with the first frame from the producer, the loss
 * is due once when the consumer time passes without a frame, the next frame ends it. */
typedef struct co_hb_monitor {
    uint32_t time_us;   /* consumer time; 0 = not monitored */
    bool monitoring;    /* a frame was received since the consumer was configured */
    bool lost;          /* the loss was reported and no frame came since */
    co_time_t deadline; /* CO_TIME_NEVER before the first frame and while lost */
} co_hb_monitor_t;

/* Sets the consumer time (0 = off); monitoring waits for the next frame. The three functions are
 * inline: each has one caller in a node (heartbeat.c) and one in the NMT master (nmt_master.c),
 * where GCC folds them into the caller. */
static inline void co_hb_monitor_configure(co_hb_monitor_t *monitor, uint32_t time_us)
{
    monitor->time_us = time_us;
    monitor->monitoring = false;
    monitor->lost = false;
    monitor->deadline = CO_TIME_NEVER;
}

/* A heartbeat or boot-up frame from the producer at `now`: restarts the timer of a configured
 * consumer. True when it ends a loss (to report the producer resumed). */
static inline bool co_hb_monitor_alive(co_hb_monitor_t *monitor, co_time_t now)
{
    if (monitor->time_us == 0)
        return false;
    monitor->monitoring = true;
    monitor->deadline = now + monitor->time_us;
    bool resumed = monitor->lost;
    monitor->lost = false;
    return resumed;
}

/* True once, when the consumer time has passed at `now` (the loss to report). */
static inline bool co_hb_monitor_expired(co_hb_monitor_t *monitor, co_time_t now)
{
    if (now < monitor->deadline)
        return false;
    monitor->lost = true;
    monitor->deadline = CO_TIME_NEVER;
    return true;
}

#endif
