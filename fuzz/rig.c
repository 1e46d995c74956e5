/* SPDX-License-Identifier: Apache-2.0 */
#include "rig.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Deadlines handled one by one within a time step; a 1 ms heartbeat over a step of half an hour
 * would otherwise cost millions of calls per input. */
#define DEADLINES_PER_STEP 64
/* How long a reset node and a fresh node are run side by side: past the boot-up, the first
 * heartbeats and a motor ramp's first steps. */
#define COMPARE_US 3000000u
#define COMPARE_STEP_US 100000u

void rig_check(bool ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz invariant broken: %s\n", what);
        abort();
    }
}

/* The error register is what the active errors say: the generic bit and each error's own bits
 * while any is active, 0 when none is (CiA 301 7.5.2.2); the generic bit alone on a node with
 * CO_NODE_ERROR_REGISTER_GENERIC. */
static void check_error_register(const rig_t *rig)
{
    const co_emcy_t *emcy = &rig->drive.node.emcy;
    rig_check(emcy->active_count <= CO_CONFIG_EMCY_HISTORY, "more active errors than room");
    uint8_t want = emcy->active_count ? CO_ERR_REG_GENERIC : 0;
    for (uint8_t i = 0; i < emcy->active_count; i++) {
        rig_check(emcy->active[i].code != 0, "an active error with code 0");
        for (uint8_t j = 0; j < i; j++)
            rig_check(emcy->active[j].code != emcy->active[i].code, "an error active twice");
        want |= emcy->active[i].reg;
    }
    if (rig->drive.node.options & CO_NODE_ERROR_REGISTER_GENERIC)
        want &= CO_ERR_REG_GENERIC; /* the Altivars' 1001h is 0 or 1 (D-ERROR-REGISTER) */
    rig_check(co_od_value(&rig->drive.node, 0x1001, 0) == want,
              "1001h disagrees with the active errors");
}

static void on_send(void *user, const co_frame_t *frame)
{
    rig_t *rig = user;
    rig_check(frame->len <= 8, "a frame longer than 8 bytes");
    rig_check(frame->id <= 0x7FF && !(frame->flags & CO_FRAME_EFF), "a frame with a 29-bit id");
    if (rig->recorded < RIG_RECORD_MAX)
        rig->record[rig->recorded] = *frame;
    rig->recorded++;
}

/* The runtime processes again at once when the deadline is due: a second due deadline at the
 * same time would make it spin. */
static void process(rig_t *rig)
{
    co_time_t next = drive_process(&rig->drive, rig->now);
    if (next <= rig->now) {
        next = drive_process(&rig->drive, rig->now);
        rig_check(next > rig->now, "a deadline not in the future twice in a row");
    }
    rig->deadline = next;
    check_error_register(rig);
}

void rig_start(rig_t *rig, uint8_t node_id, const co_storage_t *storage, co_time_t now)
{
    memset(rig, 0, sizeof *rig);
    drive_config_t config = {
        .profile = &atv312_profile,
        .od_data = rig->od_data,
        .node_id = node_id,
        .send = on_send,
        .send_user = rig,
        .storage = storage,
    };
    rig_check(drive_init(&rig->drive, &config) == 0, "drive_init failed");
    rig->now = now;
    drive_start(&rig->drive, now);
    process(rig);
}

void rig_receive(rig_t *rig, const co_frame_t *frame)
{
    drive_receive(&rig->drive, frame, rig->now);
    process(rig);
}

void rig_advance(rig_t *rig, co_time_t us)
{
    co_time_t end = rig->now + us;
    for (int i = 0; i < DEADLINES_PER_STEP && rig->deadline <= end; i++) {
        rig->now = rig->deadline;
        process(rig);
    }
    rig->now = end;
    process(rig);
}

static void check_same(const rig_t *a, const rig_t *b, const char *when)
{
    char what[96];
    snprintf(what, sizeof what, "a reset node differs from a fresh one (%s)", when);
    rig_check(memcmp(a->od_data, b->od_data, sizeof a->od_data) == 0, what);
    rig_check(a->drive.node.nmt_state == b->drive.node.nmt_state, what);
    rig_check(a->drive.cia402.state == b->drive.cia402.state, what);
    rig_check(a->recorded == b->recorded, what);
    size_t n = a->recorded < RIG_RECORD_MAX ? a->recorded : RIG_RECORD_MAX;
    for (size_t i = 0; i < n; i++) {
        const co_frame_t *fa = &a->record[i], *fb = &b->record[i];
        rig_check(fa->id == fb->id && fa->len == fb->len && fa->flags == fb->flags &&
                      memcmp(fa->data, fb->data, fa->len) == 0,
                  what);
    }
}

void rig_check_reset(rig_t *rig, rig_t *fresh, const co_storage_t *fresh_storage)
{
    rig->recorded = 0;
    co_frame_t reset = {.id = 0x000, .len = 2, .data = {CO_NMT_CS_RESET_NODE, 0}};
    rig_receive(rig, &reset);
    rig_start(fresh, rig->drive.node.node_id, fresh_storage, rig->now);
    check_same(rig, fresh, "at the reset");
    for (co_time_t t = 0; t < COMPARE_US; t += COMPARE_STEP_US) {
        rig_advance(rig, COMPARE_STEP_US);
        rig_advance(fresh, COMPARE_STEP_US);
        check_same(rig, fresh, "after it");
    }
}
