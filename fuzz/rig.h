/* SPDX-License-Identifier: Apache-2.0 */
/* The fuzzing rig: one ATV312 drive (the real dictionary and profile) driven the way the Linux
 * runtime drives it, frame by frame and deadline by deadline, with the invariants of issue 10
 * checked as it runs. A broken invariant prints what broke and aborts, so libFuzzer keeps the
 * input as a crash like any sanitizer report. */
#ifndef FUZZ_RIG_H
#define FUZZ_RIG_H

#include "atv312/atv312.h"

/* The first frames sent since the start or the reset, compared between a reset node and a fresh
 * one. */
#define RIG_RECORD_MAX 64

typedef struct rig {
    drive_t drive;
    uint8_t od_data[ATV312_OD_DATA_SIZE];
    co_time_t now;
    co_time_t deadline; /* returned by the last drive_process */
    co_frame_t record[RIG_RECORD_MAX];
    size_t recorded; /* frames sent, even those past RIG_RECORD_MAX */
} rig_t;

/* Aborts with the message when ok is false. */
void rig_check(bool ok, const char *what);

/* Boots the drive with this node-id and storage (or NULL) at time `now`. */
void rig_start(rig_t *rig, uint8_t node_id, const co_storage_t *storage, co_time_t now);
/* Delivers a frame now, then processes, as the runtime does after every frame. */
void rig_receive(rig_t *rig, const co_frame_t *frame);
/* Advances time by `us`, processing at the deadlines on the way (a bounded number of them: past
 * that the rig wakes up late, as a loaded machine does) and at the end. */
void rig_advance(rig_t *rig, co_time_t us);
/* Sends the drive an NMT reset node and checks that it then equals a drive booted fresh at the
 * same time on `fresh_storage` (holding what the drive's own storage holds): same dictionary,
 * same NMT and CiA 402 states, the same frames over the next seconds. `fresh` is scratch space. */
void rig_check_reset(rig_t *rig, rig_t *fresh, const co_storage_t *fresh_storage);

#endif
