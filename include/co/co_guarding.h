/* SPDX-License-Identifier: Apache-2.0 */
/* Node guarding and life guarding (CiA 301 section 7.2.8.3.1).
 *
 * A remote frame (DLC 0 or 1) on the guarding COB-ID is answered on the same CAN-ID with the NMT
 * state and a toggle bit (bit 7) that starts at 0 and alternates; only reset communication sets it
 * back to 0. The guarding COB-ID is 100Eh when the dictionary has that object (an 11-bit CAN-ID;
 * reset communication restores it like the rest of 1000h-1FFFh), else 0x700 + node-id. The first
 * request starts life guarding: when no request arrives within the life time (100Ch guard time x
 * 100Dh life time factor, ms; 0 = off), hooks->guarding(lost = true) is called once, and
 * hooks->guarding(lost = false) when requests come again. Writing 100Ch or 100Dh restarts the
 * life timer. While the heartbeat producer runs (1017h != 0) requests are ignored: no reply, no
 * life guarding: only one of the two protocols is active (docs/decisions.md,
 * D-HEARTBEAT-GUARDING). */
#ifndef CO_GUARDING_H
#define CO_GUARDING_H

#include "co_od.h"

typedef struct co_guarding {
    uint8_t toggle; /* 0x00 or 0x80: the bit of the next reply */
    bool started;   /* a request came since the reset or since heartbeat was switched off */
    bool lost;      /* the life guarding event was reported and no request came since */
    co_time_t deadline;
} co_guarding_t;

/* Reset communication: toggle back to 0, life guarding waits for the first request. */
void co_guarding_reset(co_node_t *node);
bool co_guarding_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_guarding_process(co_node_t *node, co_time_t now);
uint32_t co_guarding_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              size_t len);

/* Heartbeat took over (heartbeat.c, on a 1017h write): life guarding stops until the next
 * request after heartbeat is off. Inline: the heartbeat then calls nothing of guarding.c. */
static inline void co_guarding_stop(co_guarding_t *guarding)
{
    guarding->started = false;
    guarding->deadline = CO_TIME_NEVER;
}

#endif
