/* SPDX-License-Identifier: Apache-2.0 */
/* The TIME service (CiA 301 7.2.6, time stamp object): 1012h COB-ID TIME, a node's consumer
 * (bit 31) and producer (bit 30), and the TIME_OF_DAY of its frame, milliseconds after midnight
 * and days since 1984-01-01 (its codec: co_time_of_day.h). The core reads no clock: the producer
 * sends the time of day the application hands in, the consumer hands the one received to the
 * application (its time_stamp hook). Selectable per node: a node gets the service with
 * co_node_config_t.time_stamp = &co_time_stamp, and a firmware that names neither it nor
 * co_time_stamp_send links none of it. docs/time.md. */
#ifndef CO_TIME_STAMP_H
#define CO_TIME_STAMP_H

#include "co_od.h"
#include "co_time_of_day.h"

/* 1012h bits (CiA 301 7.5.2.12, table "Description of TIME COB-ID entry"). */
#define CO_TIME_COBID_CONSUMER 0x80000000u
#define CO_TIME_COBID_PRODUCER 0x40000000u
#define CO_TIME_COBID_FRAME 0x20000000u /* 29-bit CAN-ID: refused, as for every COB-ID */
#define CO_TIME_COBID_CAN_ID 0x000007FFu

/* The consumer's and the 1012h rules' code, for co_node_config_t.time_stamp. */
typedef struct co_time_stamp_code {
    /* At each reset, after the defaults and the stored values are in place: 1012h into
     * co_node_t.time_cob_id. */
    void (*reset)(co_node_t *node);
    /* A TIME frame for this node (1012h bit 31, its CAN-ID): to the application; true when the
     * frame was the TIME's (a wrong length is consumed and ignored). */
    bool (*receive)(co_node_t *node, const co_frame_t *frame);
    /* The write rules of 1012h (co_node_t.parameter_write). */
    uint32_t (*od_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
} co_time_stamp_code_t;

extern const co_time_stamp_code_t co_time_stamp;

/* The producer: sends `time` on the 1012h CAN-ID when 1012h says produce (bit 30) and the node
 * is in Pre-operational or Operational; false (nothing sent) otherwise. When to send is the
 * application's (CiA 301 leaves the rate to it). */
bool co_time_stamp_send(co_node_t *node, const co_time_of_day_t *time);

#endif
