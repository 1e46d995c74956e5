/* SPDX-License-Identifier: Apache-2.0 */
/* The DeviceNet slave tests' bench (dn_bench.h). */
#include "dn_bench.h"

#include <string.h>

#include "test_bus.h" /* test_frame, test_format: candump text */

const dn_assembly_t bench_assemblies[BENCH_ASSEMBLIES] = {
    {20, 4, false}, {21, 4, false}, {70, 4, true}, {71, 4, true}, {100, 4, false}, {101, 4, true},
};

uint8_t *bench_assembly(dn_bench_t *b, uint16_t instance)
{
    for (size_t i = 0; i < BENCH_ASSEMBLIES; i++)
        if (bench_assemblies[i].instance == instance)
            return b->data[i];
    ck_abort_msg("no assembly %u", instance);
    return NULL;
}

static void on_send(void *user, const co_frame_t *frame)
{
    dn_bench_t *b = user;
    ck_assert_uint_lt(b->count, BENCH_FRAMES);
    b->at[b->count] = b->now;
    b->frame[b->count++] = *frame;
}

static void on_read(void *user, uint16_t instance, uint8_t *data)
{
    memcpy(data, bench_assembly(user, instance), 4);
}

static void on_write(void *user, uint16_t instance, const uint8_t *data)
{
    memcpy(bench_assembly(user, instance), data, 4);
}

static void on_event(void *user, dn_io_event_t event)
{
    dn_bench_t *b = user;
    ck_assert_uint_lt(b->event_count, BENCH_EVENTS);
    b->events[b->event_count++] = event;
}

static void on_connection_ended(void *user, uint8_t instance, dn_end_cause_t cause)
{
    dn_bench_t *b = user;
    ck_assert_uint_lt(b->end_count, BENCH_EVENTS);
    b->ends[b->end_count++] = (bench_end_t){instance, cause};
}

void bench_expect_ends_at(dn_bench_t *b, const bench_end_t *want, size_t count, const char *file,
                          int line)
{
    ck_assert_msg(b->end_count == count, "%s:%d: %zu connection ends, not %zu", file, line,
                  b->end_count, count);
    for (size_t i = 0; i < count; i++)
        ck_assert_msg(b->ends[i].instance == want[i].instance && b->ends[i].cause == want[i].cause,
                      "%s:%d: end %zu: instance %u cause %d, not instance %u cause %d", file, line,
                      i, b->ends[i].instance, b->ends[i].cause, want[i].instance, want[i].cause);
    b->end_count = 0;
}

static bool on_store(void *user, const dn_stored_t *stored)
{
    dn_bench_t *b = user;
    if (b->store_fails)
        return false;
    b->stored = *stored;
    b->stores++;
    return true;
}

static void on_reset(void *user, uint8_t type)
{
    dn_bench_t *b = user;
    b->reset_type = type;
}

/* Class 0x29 (a control supervisor's shape): class revision, Run1 (BOOL, Get/Set), State (Get),
 * and a Reset service. */
static const dn_attribute_t supervisor_attributes[] = {
    {0, 1, DN_GET, 0},
    {1, 3, DN_GET_SET, 1},
    {1, 6, DN_GET, 0},
};

static dn_status_t supervisor_handler(dn_node_t *node, const dn_object_t *object,
                                      const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    dn_bench_t *b = object->user;
    switch (request->service) {
    case DN_SVC_GET_ATTRIBUTE_SINGLE:
        if (request->instance == 0)
            dn_reply_u16(reply, 1);
        else if (request->attribute == 3)
            dn_reply_u8(reply, b->run1);
        else
            dn_reply_u8(reply, 3);
        return DN_OK;
    case DN_SVC_SET_ATTRIBUTE_SINGLE:
        if (request->data[0] > 1)
            return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
        b->run1 = request->data[0];
        return DN_OK;
    case DN_SVC_RESET:
        b->run1 = 0;
        return DN_OK;
    default:
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    }
}

/* Classes 0x70..0xA8, instance 1, attributes 1..200: only class 0x70's are kept here, the
 * others do not exist; the handler checks attribute and length itself. */
static dn_status_t parameters_handler(dn_node_t *node, const dn_object_t *object,
                                      const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    dn_bench_t *b = object->user;
    bool get = request->service == DN_SVC_GET_ATTRIBUTE_SINGLE;
    if (!get && request->service != DN_SVC_SET_ATTRIBUTE_SINGLE)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance != 1)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->class_id != 0x70 || request->attribute == 0 || request->attribute > 200)
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SUPPORTED);
    if (get) {
        dn_reply_u16(reply, b->param[request->attribute]);
        return DN_OK;
    }
    if (request->len != 2)
        return DN_ERROR(request->len < 2 ? DN_GS_NOT_ENOUGH_DATA : DN_GS_TOO_MUCH_DATA);
    b->param[request->attribute] = co_get_u16(request->data);
    return DN_OK;
}

void bench_init(dn_bench_t *b, uint8_t mac_id, dn_stored_t stored)
{
    memset(b, 0, sizeof(*b));
    b->reset_type = -1;
    b->deadline = CO_TIME_NEVER;
    b->app.user = b;
    b->app.send = on_send;
    b->app.read_assembly = on_read;
    b->app.write_assembly = on_write;
    b->app.io_event = on_event;
    b->app.connection_ended = on_connection_ended;
    b->app.store = on_store;
    b->app.reset = on_reset;
    b->app.stats = &b->stats;
    dn_object_t *objects = b->objects;
    objects[0] = (dn_object_t){DN_CLASS_CONTROL_SUPERVISOR,
                               DN_CLASS_CONTROL_SUPERVISOR,
                               1,
                               sizeof(supervisor_attributes) / sizeof(supervisor_attributes[0]),
                               supervisor_attributes,
                               supervisor_handler,
                               b};
    objects[1] = (dn_object_t){0x70, 0xA8, 1, 0, NULL, parameters_handler, b};
    dn_config_t *c = &b->config;
    c->mac_id = mac_id;
    c->baud_rate = 1;
    c->mac_switch = mac_id;
    c->baud_switch = 1;
    c->vendor_id = 0x00F3;
    c->device_type = 2;
    c->product_code = 6153;
    c->major_revision = 1;
    c->minor_revision = 2;
    c->serial_number = BENCH_SERIAL;
    c->product_name = "ATV312";
    c->assemblies = bench_assemblies;
    c->assembly_count = BENCH_ASSEMBLIES;
    c->default_consumed_assembly = 21;
    c->default_produced_assembly = 71;
    c->stored = stored;
    c->objects = objects;
    c->object_count = 2;
    c->app = &b->app;
    ck_assert_int_eq(dn_node_init(&b->node, c), DN_INIT_OK);
}

void bench_online(dn_bench_t *b, uint8_t mac_id)
{
    dn_stored_t none = {0, 0, false};
    bench_init(b, mac_id, none);
    dn_node_start(&b->node, b->now);
    b->deadline = dn_node_process(&b->node, b->now);
    bench_advance(b, 2 * DN_DUP_MAC_WAIT_US);
    ck_assert_int_eq(b->node.link, DN_LINK_ONLINE);
    ck_assert_uint_eq(b->count, 2);
    b->next = b->count;
}

void bench_rx(dn_bench_t *b, const char *text)
{
    co_frame_t f = test_frame(text);
    dn_node_receive(&b->node, &f, b->now);
    b->deadline = dn_node_process(&b->node, b->now);
}

void bench_advance(dn_bench_t *b, co_time_t us)
{
    co_time_t target = b->now + us;
    while (b->deadline <= target) {
        if (b->deadline > b->now)
            b->now = b->deadline;
        co_time_t next = dn_node_process(&b->node, b->now);
        ck_assert_msg(next > b->now, "deadline %llu does not advance past now %llu",
                      (unsigned long long)next, (unsigned long long)b->now);
        b->deadline = next;
    }
    b->now = target;
}

co_time_t bench_expect_at(dn_bench_t *b, const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(b->next < b->count, "%s:%d: expected %s, bus is quiet", file, line, want);
    test_format(&b->frame[b->next], got);
    ck_assert_msg(strcmp(want, got) == 0, "%s:%d: expected %s, got %s", file, line, want, got);
    return b->at[b->next++];
}

void bench_expect_none_at(dn_bench_t *b, const char *file, int line)
{
    char got[32];
    if (b->next < b->count)
        ck_abort_msg("%s:%d: expected silence, got %s", file, line,
                     test_format(&b->frame[b->next], got));
}

void bench_expect_stats_at(const dn_bench_t *b, dn_stats_t want, const char *file, int line)
{
    const dn_stats_t *s = &b->stats;
    ck_assert_msg(s->explicit_requests == want.explicit_requests &&
                      s->error_responses == want.error_responses &&
                      s->io_messages == want.io_messages && s->fragments == want.fragments &&
                      s->timeouts == want.timeouts,
                  "%s:%d: counted requests %u, errors %u, I/O %u, fragments %u, timeouts %u; "
                  "expected %u, %u, %u, %u, %u",
                  file, line, s->explicit_requests, s->error_responses, s->io_messages,
                  s->fragments, s->timeouts, want.explicit_requests, want.error_responses,
                  want.io_messages, want.fragments, want.timeouts);
}
