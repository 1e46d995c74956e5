/* SPDX-License-Identifier: Apache-2.0 */
/* PDO engine: RPDOs and TPDOs configured by 1400h/1600h/1800h/1A00h, their transmission types,
 * inhibit and event timers, SYNC start value, change-of-state detection and the CiA 301 dynamic
 * mapping procedure (CiA 301 section 7.2.2).
 *
 * The engine keeps a decoded copy of each PDO's parameters, re-read from the dictionary at every
 * reset and NMT state change and after every write of a PDO parameter through co_od_write(). */
#ifndef CO_PDO_H
#define CO_PDO_H

#include "co_config.h"
#include "co_od.h"

/* COB-ID bits of the PDO communication parameter, sub 1 (CiA 301 table 72). */
#define CO_PDO_COBID_INVALID CO_COB_ID_INVALID
#define CO_PDO_COBID_NO_RTR 0x40000000u
#define CO_PDO_COBID_FRAME 0x20000000u /* 29-bit CAN-ID */
#define CO_PDO_COBID_CAN_ID 0x000007FFu

/* Transmission types (CiA 301 tables 71 and 73). */
#define CO_PDO_TYPE_SYNC_ACYCLIC 0u
#define CO_PDO_TYPE_SYNC_MAX 240u
#define CO_PDO_TYPE_RTR_SYNC 252u
#define CO_PDO_TYPE_RTR_EVENT 253u
#define CO_PDO_TYPE_EVENT_MANUFACTURER 254u
#define CO_PDO_TYPE_EVENT_PROFILE 255u

/* The objects a PDO carries: one dictionary entry per mapping entry, NULL for a dummy entry
 * (an RPDO's data type index 0002h..0007h: the bytes are received and dropped). */
typedef struct co_pdo_map {
    const co_od_entry_t *entry[CO_CONFIG_PDO_MAP_MAX];
    uint8_t size[CO_CONFIG_PDO_MAP_MAX]; /* bytes of each entry in the frame */
    uint8_t count;
    uint8_t length; /* bytes of the whole PDO */
} co_pdo_map_t;

typedef struct co_rpdo {
    bool valid; /* present, COB-ID bit 31 clear and the mapping usable */
    uint16_t can_id;
    uint8_t type;
    uint32_t event_us; /* deadline monitoring period, 0 = off */
    co_pdo_map_t map;
    uint8_t buffer[8]; /* synchronous RPDO: received data kept until the next SYNC */
    bool buffered;
    co_time_t deadline;    /* deadline monitoring, CO_TIME_NEVER until the first reception */
    uint16_t length_error; /* EMCY code (0x8210 / 0x8220) raised by this RPDO's length, or 0 */
    bool timed_out;        /* EMCY 0x8250 raised by this RPDO */
} co_rpdo_t;

typedef struct co_tpdo {
    bool valid;
    bool rtr_allowed; /* COB-ID bit 30 clear */
    uint16_t can_id;
    uint8_t type;
    uint32_t inhibit_us;
    uint32_t event_us;
    uint8_t sync_start; /* 0 = not used */
    co_pdo_map_t map;
    uint8_t last[8];    /* data of the last transmission */
    bool sent;          /* `last` holds a transmission since the PDO (re)started */
    bool pending;       /* event-driven: a transmission waits for the end of the inhibit time */
    bool requested;     /* acyclic synchronous: the application asked for the next SYNC */
    bool sync_due;      /* synchronous: `sample` goes out in the SYNC window */
    bool sampled;       /* `sample` holds data taken at a SYNC */
    bool started;       /* cyclic synchronous: first transmission done (SYNC start value) */
    uint8_t sync_count; /* SYNCs since the last cyclic transmission */
    uint8_t sample[8];
    co_time_t inhibit_end;
    co_time_t event_due; /* CO_TIME_NEVER when the event timer is off */
} co_tpdo_t;

typedef struct co_pdo {
    co_rpdo_t rpdo[CO_CONFIG_RPDO_MAX];
    co_tpdo_t tpdo[CO_CONFIG_TPDO_MAX];
    co_time_t sync_at;   /* time of the last SYNC, start of the synchronous window (1007h) */
    uint32_t inhibit_ms; /* co_node_config_t.tpdo_inhibit_ms: TPDOs counting 18xxh:03 in ms */
} co_pdo_t;

/* Reset node and reset communication: co_pdo_restart(), and the RPDOs' errors end with their
 * EMCYs (0x8210, 0x8220, 0x8250), so that the next fault raises its EMCY again. */
void co_pdo_reset(co_node_t *node);
/* An NMT state change: re-reads every PDO's parameters and forgets all transmission state (timers,
 * pending requests, buffered data), so that the first transmission after entering Operational is
 * immediate. The RPDOs' errors and their EMCYs stay: the configuration they were detected with is
 * unchanged, and the next frame of the RPDO ends them. */
void co_pdo_restart(co_node_t *node);
/* An RPDO, or an RTR for a TPDO. Returns true when the frame belonged to a PDO. */
bool co_pdo_receive(co_node_t *node, const co_frame_t *frame);
/* Change-of-state detection, inhibit and event timers, synchronous transmissions, RPDO deadline
 * monitoring. Returns the next deadline (CO_TIME_NEVER when none). */
co_time_t co_pdo_process(co_node_t *node, co_time_t now);
/* CiA 301 parameter rules of 1400h..1BFFh; stores the value and reconfigures the PDO. */
uint32_t co_pdo_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
/* Called by the node for every SYNC received or produced (counter 0 when none). */
void co_pdo_sync(co_node_t *node, uint8_t counter);
/* Application request to transmit TPDO `pdo_number` (1..): an event-driven TPDO is sent as soon
 * as its inhibit time allows, an acyclic synchronous one at the next SYNC. */
void co_tpdo_request(co_node_t *node, uint16_t pdo_number);

#endif
