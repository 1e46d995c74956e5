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

typedef struct co_sync {
    uint8_t counter;   /* of the last SYNC produced; 0 before the first one */
    co_time_t next;    /* next SYNC to produce, CO_TIME_NEVER when not producing */
    bool length_error; /* EMCY 0x8240 raised */
} co_sync_t;

/* Reset node and reset communication: the producer restarts, and the consumer's length error
 * ends with its EMCY 0x8240, so that the next wrong SYNC raises it again. */
void co_sync_reset(co_node_t *node);
bool co_sync_receive(co_node_t *node, const co_frame_t *frame);
/* Produces the SYNC when due; returns the next one (CO_TIME_NEVER when not producing). */
co_time_t co_sync_process(co_node_t *node, co_time_t now);
uint32_t co_sync_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len);

#endif
