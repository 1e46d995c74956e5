/* SPDX-License-Identifier: Apache-2.0 */
/* The bench of the drive on DeviceNet: an ATV312 behind its DeviceNet adapter at MAC ID 25, the
 * frames it sends recorded with their times, a store in memory, time injected. A scanner at MAC
 * ID 1 allocates the explicit and polled connections (request 4CC, response 4CB, poll 4CD,
 * poll response 3D9). */
#ifndef DN_DRIVE_BENCH_H
#define DN_DRIVE_BENCH_H

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "test_bus.h"

#define DB_MAC 25u
#define DB_FRAMES 512

typedef struct dn_drive_bench {
    drive_t drive;
    uint8_t od_data[ATV312_OD_DATA_SIZE];
    drive_dn_t dn;
    co_time_t now, deadline;
    co_frame_t frame[DB_FRAMES];
    size_t count, next;
    dn_stored_t stored;
    int stores;
} dn_drive_bench_t;

static void db_send(void *user, const co_frame_t *frame)
{
    dn_drive_bench_t *b = user;
    ck_assert_uint_lt(b->count, DB_FRAMES);
    b->frame[b->count++] = *frame;
}

static bool db_store(void *user, const dn_stored_t *stored)
{
    dn_drive_bench_t *b = user;
    b->stored = *stored;
    b->stores++;
    return true;
}

/* Initialised and started at the bench's time with the stored selection b->stored. */
static inline void db_start(dn_drive_bench_t *b)
{
    drive_config_t dc = {.profile = atv312_devicenet_profile.drive,
                         .od_data = b->od_data,
                         .node_id = 1,
                         .send = drive_dn_drop_frame};
    ck_assert_int_eq(drive_init(&b->drive, &dc), 0);
    drive_dn_config_t c = {.drive = &b->drive,
                           .profile = &atv312_devicenet_profile,
                           .mac_id = DB_MAC,
                           .baud_rate = 2,
                           .serial_number = 0x12345678,
                           .stored = b->stored,
                           .send = db_send,
                           .user = b,
                           .store = db_store};
    ck_assert_int_eq(drive_dn_init(&b->dn, &c), 0);
    drive_dn_start(&b->dn, b->now);
    b->deadline = drive_dn_process(&b->dn, b->now);
}

static inline void db_advance(dn_drive_bench_t *b, co_time_t us)
{
    co_time_t target = b->now + us;
    while (b->deadline <= target) {
        if (b->deadline > b->now)
            b->now = b->deadline;
        co_time_t next = drive_dn_process(&b->dn, b->now);
        ck_assert_msg(next > b->now, "deadline does not advance");
        b->deadline = next;
    }
    b->now = target;
}

static inline void db_rx(dn_drive_bench_t *b, const char *text)
{
    co_frame_t f = test_frame(text);
    drive_dn_receive(&b->dn, &f, b->now);
    b->deadline = drive_dn_process(&b->dn, b->now);
}

static inline void db_expect_at(dn_drive_bench_t *b, const char *text, const char *file, int line)
{
    char got[32];
    ck_assert_msg(b->next < b->count, "%s:%d: expected %s, nothing sent", file, line, text);
    test_format(&b->frame[b->next++], got);
    ck_assert_msg(strcmp(got, text) == 0, "%s:%d: expected %s, got %s", file, line, text, got);
}

static inline void db_expect_none_at(dn_drive_bench_t *b, const char *file, int line)
{
    char got[32] = "";
    if (b->next < b->count)
        test_format(&b->frame[b->next], got);
    ck_assert_msg(b->next == b->count, "%s:%d: unexpected %s", file, line, got);
}

#define db_expect(b, text) db_expect_at((b), (text), __FILE__, __LINE__)
#define db_expect_none(b) db_expect_none_at((b), __FILE__, __LINE__)
#define db_exchange(b, request, response)                                                          \
    do {                                                                                           \
        db_rx((b), (request));                                                                     \
        db_expect((b), (response));                                                                \
        db_expect_none(b);                                                                         \
    } while (0)

/* Started, two quiet seconds of duplicate MAC ID check: online; its two requests consumed. */
static inline void db_online(dn_drive_bench_t *b)
{
    db_start(b);
    db_advance(b, 2000000);
    db_expect(b, "4CF#00F30078563412");
    db_expect(b, "4CF#00F30078563412");
    db_expect_none(b);
}

/* Explicit and polled connections allocated by MAC ID 1, the poll's expected packet rate 10 s
 * (a watchdog of 40 s): established. */
static inline void db_connected(dn_drive_bench_t *b)
{
    db_online(b);
    db_exchange(b, "4CE#014B03010301", "4CB#01CB00");
    db_exchange(b, "4CC#01100502091027", "4CB#01901027");
}

static inline int64_t db_value(dn_drive_bench_t *b, uint16_t index, uint8_t subindex)
{
    return co_od_value(&b->drive.node, index, subindex);
}

#endif
