/* SPDX-License-Identifier: Apache-2.0 */
#include "test_bus.h"

#include "test_od.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const uint16_t test_restricted_can_id[TEST_RESTRICTED_CAN_IDS] = {
    0x000, 0x001, 0x07F, 0x101, 0x180, 0x581, 0x5FF, 0x601,
    0x67F, 0x6E0, 0x6FF, 0x701, 0x77F, 0x780, 0x7FF};
const uint16_t test_free_can_id[TEST_FREE_CAN_IDS] = {0x080, 0x100, 0x181, 0x580,
                                                      0x600, 0x680, 0x6DF, 0x700};

static void bus_send(void *user, const co_frame_t *frame)
{
    test_bus_t *bus = user;
    ck_assert_msg(bus->count < TEST_BUS_FRAMES, "test bus overflow");
    bus->frame[bus->count] = *frame;
    bus->at[bus->count] = bus->now;
    bus->count++;
}

void test_node_start(test_node_t *t, uint8_t node_id, const co_app_hooks_t *hooks,
                     const co_storage_t *storage)
{
    test_node_start_od(t, &test_od, node_id, hooks, storage);
}

void test_node_start_od(test_node_t *t, const co_od_t *od, uint8_t node_id,
                        const co_app_hooks_t *hooks, const co_storage_t *storage)
{
    co_node_config_t config = {
        .node_id = node_id,
        .od = od,
        .hooks = hooks,
        .storage = storage,
    };
    test_node_start_config(t, &config);
}

void test_node_start_config(test_node_t *t, const co_node_config_t *config)
{
    memset(t, 0, sizeof(*t));
    ck_assert_uint_le(config->od->data_size, sizeof(t->data));
    co_node_config_t bus_config = *config;
    bus_config.od_data = t->data;
    bus_config.send = bus_send;
    bus_config.user = &t->bus;
    ck_assert_int_eq(co_node_init(&t->node, &bus_config), 0);
    co_node_start(&t->node, 0);
    t->bus.deadline = co_node_process(&t->node, 0);
    if (config->node_id == CO_LSS_NODE_ID_UNCONFIGURED) {
        test_expect_none(t); /* no node-id, no boot-up (CiA 305) */
        return;
    }
    bool padded = (config->options & CO_NODE_PAD_DLC8) != 0;
    char boot[32];
    snprintf(boot, sizeof(boot), "%03X#00%s", 0x700 + config->node_id,
             padded ? "00000000000000" : "");
    test_expect(t, boot);
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

co_frame_t test_frame(const char *text)
{
    co_frame_t f;
    memset(&f, 0, sizeof(f));
    char *end;
    f.id = (uint32_t)strtoul(text, &end, 16);
    ck_assert_msg(*end == '#', "bad frame text '%s'", text);
    end++;
    if (*end == 'R') {
        f.flags = CO_FRAME_RTR;
        f.len = end[1] ? (uint8_t)(end[1] - '0') : 0;
        return f;
    }
    while (*end) {
        if (*end == ' ' || *end == '.') {
            end++;
            continue;
        }
        int hi = hex_digit(end[0]);
        int lo = end[1] ? hex_digit(end[1]) : -1;
        ck_assert_msg(hi >= 0 && lo >= 0 && f.len < 8, "bad frame text '%s'", text);
        f.data[f.len++] = (uint8_t)(hi << 4 | lo);
        end += 2;
    }
    return f;
}

const char *test_format(const co_frame_t *frame, char *buf)
{
    int n = sprintf(buf, "%03X#", (unsigned)frame->id);
    if (frame->flags & CO_FRAME_RTR) {
        sprintf(buf + n, "R%u", frame->len);
        return buf;
    }
    for (uint8_t i = 0; i < frame->len; i++)
        n += sprintf(buf + n, "%02X", frame->data[i]);
    return buf;
}

void test_rx_frame(test_node_t *t, const co_frame_t *frame)
{
    co_node_receive(&t->node, frame, t->bus.now);
    t->bus.deadline = co_node_process(&t->node, t->bus.now);
}

void test_rx(test_node_t *t, const char *text)
{
    co_frame_t f = test_frame(text);
    test_rx_frame(t, &f);
}

void test_advance(test_node_t *t, co_time_t us)
{
    co_time_t target = t->bus.now + us;
    while (t->bus.deadline <= target) {
        if (t->bus.deadline > t->bus.now)
            t->bus.now = t->bus.deadline;
        co_time_t next = co_node_process(&t->node, t->bus.now);
        ck_assert_msg(next > t->bus.now, "deadline %llu does not advance past now %llu",
                      (unsigned long long)next, (unsigned long long)t->bus.now);
        t->bus.deadline = next;
    }
    t->bus.now = target;
}

co_time_t test_expect_at(test_node_t *t, const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(t->bus.next < t->bus.count, "%s:%d: expected %s, bus is quiet", file, line, want);
    const co_frame_t *g = &t->bus.frame[t->bus.next];
    test_format(g, got);
    ck_assert_msg(strcmp(want, got) == 0 && f.flags == g->flags, "%s:%d: expected %s, got %s", file,
                  line, want, got);
    return t->bus.at[t->bus.next++];
}

void test_expect_none_at(test_node_t *t, const char *file, int line)
{
    char got[32];
    if (t->bus.next < t->bus.count)
        ck_abort_msg("%s:%d: expected silence, got %s", file, line,
                     test_format(&t->bus.frame[t->bus.next], got));
}

void test_drain(test_node_t *t)
{
    t->bus.next = t->bus.count;
}

static uint32_t sdo_reply(test_node_t *t, uint32_t *value)
{
    uint32_t sdo_tx = 0x580u + t->node.node_id;
    ck_assert_msg(t->bus.next < t->bus.count, "no SDO response");
    const co_frame_t *g = &t->bus.frame[t->bus.next++];
    ck_assert_uint_eq(g->id, sdo_tx);
    ck_assert_uint_eq(g->len, 8);
    if (g->data[0] == 0x80)
        return co_get_u32(&g->data[4]);
    if (value != NULL)
        *value = co_get_u32(&g->data[4]);
    return 0;
}

uint32_t test_sdo_write(test_node_t *t, uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    co_frame_t f = {.id = 0x600u + t->node.node_id, .len = 8};
    f.data[0] = (uint8_t)(0x23 | ((4 - len) << 2));
    co_put_u16(&f.data[1], index);
    f.data[3] = sub;
    co_put_u32(&f.data[4], value);
    test_rx_frame(t, &f);
    return sdo_reply(t, NULL);
}

uint32_t test_sdo_read(test_node_t *t, uint16_t index, uint8_t sub, uint32_t *value)
{
    co_frame_t f = {.id = 0x600u + t->node.node_id, .len = 8};
    f.data[0] = 0x40;
    co_put_u16(&f.data[1], index);
    f.data[3] = sub;
    test_rx_frame(t, &f);
    return sdo_reply(t, value);
}

uint32_t test_write(test_node_t *t, uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    uint8_t data[4];
    co_put_u32(data, value);
    t->node.now = t->bus.now;
    uint32_t abort = co_od_write(&t->node, index, sub, data, len, CO_OD_ORIGIN_SDO);
    t->bus.deadline = co_node_process(&t->node, t->bus.now);
    return abort;
}
