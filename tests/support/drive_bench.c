/* SPDX-License-Identifier: Apache-2.0 */
#include "drive_bench.h"

#include "test_bus.h"

#include <stdio.h>
#include <string.h>

static void bench_send(void *user, const co_frame_t *frame)
{
    bench_t *b = user;
    ck_assert_msg(b->count < BENCH_FRAMES, "bench frame buffer full");
    b->frame[b->count] = *frame;
    b->at[b->count] = b->now;
    b->count++;
}

void bench_start_model(bench_t *b, const drive_profile_t *profile, const co_storage_t *storage)
{
    bench_start_model_over(b, profile, storage, 0);
}

static void start_drive(bench_t *b, const drive_profile_t *profile, const co_storage_t *storage,
                        uint8_t node_id, uint8_t fill)
{
    memset(b, 0, sizeof(*b));
    memset(&b->drive, fill, sizeof b->drive);
    ck_assert_uint_le(profile->od->data_size, sizeof b->od_data);
    drive_config_t config = {
        .profile = profile,
        .od_data = b->od_data,
        .node_id = node_id,
        .send = bench_send,
        .send_user = b,
        .storage = storage,
    };
    ck_assert_int_eq(drive_init(&b->drive, &config), 0);
    drive_start(&b->drive, 0);
    b->deadline = drive_process(&b->drive, 0);
}

void bench_start_can_off(bench_t *b, const drive_profile_t *profile)
{
    start_drive(b, profile, NULL, 0, 0);
}

void bench_start_model_over(bench_t *b, const drive_profile_t *profile, const co_storage_t *storage,
                            uint8_t fill)
{
    start_drive(b, profile, storage, BENCH_NODE_ID, fill);
    bool padded = (profile->node_options & CO_NODE_PAD_DLC8) != 0;
    bench_expect(b, padded ? "704#0000000000000000" : "704#00");
}

void bench_rx(bench_t *b, const char *text)
{
    co_frame_t frame = test_frame(text);
    drive_receive(&b->drive, &frame, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

void bench_advance(bench_t *b, co_time_t us)
{
    co_time_t end = b->now + us;
    while (b->deadline <= end) {
        ck_assert_msg(b->deadline >= b->now, "deadline in the past");
        b->now = b->deadline;
        b->deadline = drive_process(&b->drive, b->now);
    }
    b->now = end;
    b->deadline = drive_process(&b->drive, b->now);
}

co_time_t bench_expect_at(bench_t *b, const char *text, const char *file, int line)
{
    char got[32];
    ck_assert_msg(b->next < b->count, "%s:%d: expected %s, nothing sent", file, line, text);
    const co_frame_t *f = &b->frame[b->next];
    co_frame_t want = test_frame(text);
    test_format(f, got);
    ck_assert_msg(f->id == want.id && f->len == want.len && f->flags == want.flags &&
                      memcmp(f->data, want.data, f->len) == 0,
                  "%s:%d: expected %s, got %s", file, line, text, got);
    return b->at[b->next++];
}

void bench_expect_none_at(bench_t *b, const char *file, int line)
{
    char got[32];
    if (b->next < b->count)
        ck_abort_msg("%s:%d: unexpected frame %s", file, line,
                     test_format(&b->frame[b->next], got));
}

/* Takes the SDO answer out of the recorded frames; frames sent around it (an EMCY the request
 * caused, a TPDO) stay for bench_expect. */
static co_frame_t sdo_answer(bench_t *b)
{
    for (size_t i = b->next; i < b->count; i++) {
        if (b->frame[i].id != CO_CAN_ID_SDO_TX + BENCH_NODE_ID)
            continue;
        co_frame_t answer = b->frame[i];
        memmove(&b->frame[i], &b->frame[i + 1], (b->count - i - 1) * sizeof(b->frame[0]));
        memmove(&b->at[i], &b->at[i + 1], (b->count - i - 1) * sizeof(b->at[0]));
        b->count--;
        return answer;
    }
    ck_abort_msg("no SDO answer");
    return (co_frame_t){0};
}

static void sdo_request(bench_t *b, uint8_t command, uint16_t index, uint8_t sub, uint32_t value)
{
    co_frame_t f = {.id = CO_CAN_ID_SDO_RX + BENCH_NODE_ID, .len = 8};
    f.data[0] = command;
    co_put_u16(&f.data[1], index);
    f.data[3] = sub;
    co_put_u32(&f.data[4], value);
    drive_receive(&b->drive, &f, b->now);
    b->deadline = drive_process(&b->drive, b->now);
}

uint32_t bench_sdo_write(bench_t *b, uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    sdo_request(b, (uint8_t)(0x23 | ((4 - len) << 2)), index, sub, value);
    co_frame_t f = sdo_answer(b);
    if (f.data[0] == 0x80)
        return co_get_u32(&f.data[4]);
    ck_assert_uint_eq(f.data[0], 0x60);
    return 0;
}

uint32_t bench_sdo_read(bench_t *b, uint16_t index, uint8_t sub, uint32_t *value)
{
    sdo_request(b, 0x40, index, sub, 0);
    co_frame_t f = sdo_answer(b);
    if (f.data[0] == 0x80)
        return co_get_u32(&f.data[4]);
    ck_assert_msg((f.data[0] & 0xF3) == 0x43, "not an expedited upload: %02X", f.data[0]);
    *value = co_get_u32(&f.data[4]);
    return 0;
}

uint32_t bench_read(bench_t *b, uint16_t index, uint8_t sub)
{
    uint32_t value = 0;
    uint32_t abort = bench_sdo_read(b, index, sub, &value);
    ck_assert_msg(abort == 0, "read %04X:%02X aborted %08X", index, sub, abort);
    return value;
}

uint16_t bench_command(bench_t *b, uint16_t control)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6040, 0, control, 2), 0);
    return (uint16_t)bench_read(b, 0x6041, 0);
}

int16_t bench_speed(bench_t *b)
{
    return (int16_t)bench_read(b, 0x6044, 0);
}

void bench_play(bench_t *b, const bench_exchange_t *session, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        const bench_exchange_t *x = &session[i];
        if (x->rx)
            bench_rx(b, x->rx);
        bench_advance(b, x->advance_us);
        for (size_t k = 0; k < 3 && x->expect[k]; k++)
            bench_expect_at(b, x->expect[k], x->vector, (int)i);
        bench_expect_none_at(b, x->vector, (int)i);
    }
}
