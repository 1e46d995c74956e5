/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's per-drive counters of the CANopen services a person testing a master looks at first:
 * the SDO requests a drive received, the SDO aborts and EMCYs it sent. They stand beside the
 * runtime's frame counts of the drive's device (co_linux_device_stats_t) in the control and
 * status surfaces. A frame's service is its COB-ID in the pre-defined connection set (CiA 301):
 * every model's SDO server (1200h) and EMCY (1014h) COB-IDs are read-only, so no frame reads the
 * dictionary, and counting is a comparison and an increment. */
#ifndef ATV312D_COUNTERS_H
#define ATV312D_COUNTERS_H

#include "co/co_types.h"

typedef struct atv312d_counters {
    unsigned long long sdo_requests; /* frames on the SDO server's request COB-ID, 0x600 + id */
    unsigned long long sdo_aborts;   /* abort transfer frames sent on 0x580 + id */
    unsigned long long emcy;         /* EMCY frames sent on 0x080 + id, error resets included */
} atv312d_counters_t;

/* The frame is an EMCY of the node (its COB-ID 0x080 + node_id). */
bool atv312d_is_emcy(uint8_t node_id, const co_frame_t *frame);
/* Counts a frame the drive `node_id` received. */
void atv312d_count_received(atv312d_counters_t *counters, uint8_t node_id, const co_frame_t *frame);
/* Counts a frame the drive `node_id` sent. */
void atv312d_count_sent(atv312d_counters_t *counters, uint8_t node_id, const co_frame_t *frame);

#endif
