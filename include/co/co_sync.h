/* SPDX-License-Identifier: Apache-2.0 */
/* SYNC consumer and producer: 1005h COB-ID (bit 30 = produce), 1006h period, 1007h window and the
 * 1019h counter (CiA 301 section 7.2.5). */
#ifndef CO_SYNC_H
#define CO_SYNC_H

#include "co_od.h"

/* 1005h bits (CiA 301 7.5.2.5). */
#define CO_SYNC_COBID_PRODUCER 0x40000000u
#define CO_SYNC_COBID_FRAME 0x20000000u /* 29-bit CAN-ID */
#define CO_SYNC_COBID_CAN_ID 0x000007FFu

/* 1019h: 0 (no counter) or 2..240 (CiA 301 7.5.2.41). */
#define CO_SYNC_OVERFLOW_MIN 2u
#define CO_SYNC_OVERFLOW_MAX 240u

/* A SYNC producer: its frame, counter and schedule. A node's producer (1005h bit 30) keeps one in
 * its co_sync_t and fills it from the dictionary; a master program that has no node runs one on
 * its own (docs/nmt-master.md). The schedule stays on the grid start + k x period (next += period
 * at each SYNC); a caller later than a whole period gets one SYNC, not a burst, and the grid
 * restarts from that call. */
typedef struct co_sync_producer {
    uint32_t can_id;    /* 11-bit CAN-ID (080h by default) */
    uint32_t period_us; /* 1006h: communication cycle period */
    uint8_t overflow;   /* 1019h: 0 = no counter byte, else 2..240 */
    uint8_t counter;    /* of the last SYNC produced; 0 before the first one */
    co_time_t next;     /* next SYNC to produce, CO_TIME_NEVER when not producing */
} co_sync_producer_t;

/* Configures a stopped producer. False (and nothing changed) for a CAN-ID above 7FFh or a
 * CiA 301 7.3.5 restricted one, a period of 0 or an overflow of 1 or above 240. */
bool co_sync_producer_init(co_sync_producer_t *producer, uint32_t can_id, uint32_t period_us,
                           uint8_t overflow);
/* Starts (or restarts) production: the counter restarts at 1, the first SYNC is due one period
 * after `start`. */
void co_sync_producer_start(co_sync_producer_t *producer, co_time_t start);
/* Inline: a node's SYNC consumer stops its producer on every write of 1005h or 1006h, and a
 * firmware without the producer (sync_producer.c) must not link that file for it. */
static inline void co_sync_producer_stop(co_sync_producer_t *producer)
{
    producer->next = CO_TIME_NEVER;
}
/* When a SYNC is due at `now`: fills `frame` with it, advances the counter and the schedule and
 * returns true. The next one is due at producer->next. */
bool co_sync_producer_take(co_sync_producer_t *producer, co_time_t now, co_frame_t *frame);

typedef struct co_sync {
    co_sync_producer_t producer; /* fed from 1005h, 1006h, 1019h */
    /* Where the consumer and the producer hand each SYNC, with its counter (0 when none):
     * co_sync_event, which co_node_init sets. A pointer, so that the SYNC service calls no PDO
     * function: the node, which owns both, connects them. */
    void (*deliver)(co_node_t *node, uint8_t counter);
    /* 1005h, 1006h, 1007h and 1019h as the dictionary holds them (0 when absent), reloaded by
     * co_sync_init, co_sync_reset and every write of one of them through co_od_write. */
    uint32_t cob_id;
    uint32_t period_us;
    uint32_t window_us;
    uint8_t overflow;
    bool length_error; /* EMCY 0x8240 raised */
    /* The consumer's time-out: no SYNC within 1.5 x 1006h of the last one, EMCY 0x8100 (CiA 301
     * 7.5.2.6; docs/decisions.md, D-SYNC-TIMEOUT). Watched from the first SYNC received after a
     * reset, a 1005h/1006h write or a return to Pre-operational, in Pre-operational and
     * Operational; CO_TIME_NEVER when not watched. */
    co_time_t timeout_at;
    bool timeout_error; /* EMCY 0x8100 raised, until the next SYNC or a reset */
} co_sync_t;

/* Loads the node's SYNC parameters from its dictionary (co_node_init). */
void co_sync_init(co_node_t *node);
/* 1019h (synchronous counter overflow value) and 1007h (synchronous window length, us), for the
 * PDO engine. */
uint8_t co_sync_overflow(const co_node_t *node);
uint32_t co_sync_window_us(const co_node_t *node);

/* Reset node and reset communication: the parameters are reloaded, the producer restarts, and the
 * consumer's length error ends with its EMCY 0x8240, so that the next wrong SYNC raises it again.
 */
void co_sync_reset(co_node_t *node);
bool co_sync_receive(co_node_t *node, const co_frame_t *frame);
/* Produces the SYNC when due, through the dictionary's co_od_t.sync_producer, and watches the
 * consumer's time-out; returns the earlier of the next SYNC and the time-out (CO_TIME_NEVER when
 * neither). */
co_time_t co_sync_process(co_node_t *node, co_time_t now);
/* The node's producer (sync_producer.c), for co_od_t.sync_producer: produces the SYNC when
 * 1005h bit 30 and 1006h say so, in Pre-operational and Operational. */
co_time_t co_sync_produce(co_node_t *node, co_time_t now);
/* A SYNC received or produced: to the PDO engine, then to the application's sync hook. The node's
 * (node.c), which the consumer and the producer reach through co_sync_t.deliver. */
void co_sync_event(co_node_t *node, uint8_t counter);
uint32_t co_sync_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len);

#endif
