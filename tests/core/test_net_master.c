/* SPDX-License-Identifier: Apache-2.0 */
/* Network master against the project's own slave nodes (three nodes 4, 5, 6 on the test
 * dictionary) on an in-process bus that delivers every frame to every party in order, and can
 * disconnect a slave: the full boot of the PLC300's section 7.3 frame by frame, the status words
 * of its 5.6.3, an identity mismatch, a missing optional and a missing mandatory slave, a slave
 * that appears late and is retried after the others, heartbeat loss and the re-boot that
 * reconfigures the slave, the report-only reaction and the slave's return (also before its first
 * heartbeat, and while the start of all waits for it), no past deadline while a slave waits for
 * the SDO client, the last SDO error and EMCY, the process image in and out (also without
 * outputs), and the configuration checks. Every event in every step, frame by frame without
 * slave nodes: test_net_master_states.c. Time is injected; no sleeps. */
#include "check_main.h"
#include "co/co_net_master.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdio.h>
#include <string.h>

#define MS 1000u
#define LOG_MAX 4096u
#define SLAVES 3u
#define SDO_TIMEOUT_MS 50u
#define BOOT_TIME_MS 200u
#define RETRY_DELAY_MS 500u

typedef struct slave {
    co_node_t node;
    uint8_t data[4096];
    bool present; /* connected to the bus */
} slave_t;

static struct {
    co_frame_t log[LOG_MAX];
    size_t sender[LOG_MAX]; /* SLAVES for the master */
    co_time_t at[LOG_MAX];
    size_t count;
    size_t delivered;
    size_t next; /* first frame not yet checked by expect() */
    co_time_t now;
} bus;

static slave_t slaves[SLAVES]; /* node-ids 4, 5, 6 */
static co_net_master_t master;
static co_net_master_config_t config;
static co_net_slave_config_t table[SLAVES];
static co_net_slave_t state[SLAVES];
static co_net_event_t events[LOG_MAX];
static uint8_t event_step[LOG_MAX];     /* the slave's step when the event came */
static uint16_t event_status[LOG_MAX];  /* and its status word */
static uint8_t event_ec_error[LOG_MAX]; /* and its kind of error control failure */
static size_t event_count;

static const uint8_t heartbeat_100ms[] = {0x64, 0x00};
static const uint8_t u32_value[] = {0x78, 0x56, 0x34, 0x12};
static const co_net_write_t writes[] = {
    {0x1017, 0, heartbeat_100ms, sizeof(heartbeat_100ms)},
    {0x2000, 7, u32_value, sizeof(u32_value)},
};
static const uint8_t refused_value[] = {0x01, 0x00};
static const co_net_write_t refused_write[] = {{0x2000, 0x10, refused_value, 2}};

static uint8_t inputs[8];
static uint8_t outputs[8];
static const co_net_pdo_t input_pdos[] = {{4, 0x184, 2, 0}, {5, 0x185, 2, 2}};
static const co_net_pdo_t output_pdos[] = {{4, 0x204, 2, 0}, {5, 0x205, 2, 2}};

static void log_frame(size_t sender, const co_frame_t *frame)
{
    ck_assert_uint_lt(bus.count, LOG_MAX);
    bus.sender[bus.count] = sender;
    bus.at[bus.count] = bus.now;
    bus.log[bus.count++] = *frame;
}

static void slave_send(void *user, const co_frame_t *frame)
{
    slave_t *s = user;
    if (s->present)
        log_frame((size_t)(s - slaves), frame);
}

static void master_send(void *user, const co_frame_t *frame)
{
    ck_assert_ptr_eq(user, &bus);
    log_frame(SLAVES, frame);
}

static void on_event(void *user, const co_net_event_t *event)
{
    ck_assert_ptr_eq(user, &bus);
    ck_assert_uint_lt(event_count, LOG_MAX);
    const co_net_slave_t *s = co_net_master_slave(&master, event->node_id);
    event_step[event_count] = s == NULL ? 0xFF : s->step;
    event_status[event_count] = s == NULL ? 0 : s->status;
    event_ec_error[event_count] = s == NULL ? 0 : s->ec_error;
    events[event_count++] = *event;
}

/* Delivers every frame not yet delivered, and those they cause, to every connected party. */
static void pump(void)
{
    while (bus.delivered < bus.count) {
        size_t position = bus.delivered++;
        co_frame_t frame = bus.log[position];
        for (size_t i = 0; i < SLAVES; i++) {
            if (slaves[i].present) {
                co_node_receive(&slaves[i].node, &frame, bus.now);
                co_node_process(&slaves[i].node, bus.now);
            }
        }
        if (bus.sender[position] != SLAVES) {
            co_net_master_receive(&master, &frame, bus.now);
            co_net_master_process(&master, bus.now);
        }
    }
}

static co_time_t next_deadline(void)
{
    co_time_t next = co_net_master_process(&master, bus.now);
    pump();
    for (size_t i = 0; i < SLAVES; i++) {
        if (slaves[i].present)
            next = co_time_min(next, co_node_process(&slaves[i].node, bus.now));
    }
    pump();
    return next;
}

/* Advances time by `us`, running every party at each deadline on the way. */
static void advance(co_time_t us)
{
    co_time_t end = bus.now + us;
    for (;;) {
        co_time_t next = next_deadline();
        if (next > end)
            break;
        bus.now = next > bus.now ? next : bus.now;
    }
    bus.now = end;
    next_deadline();
}

static void start_slave(slave_t *s, uint8_t node_id)
{
    ck_assert_uint_le(test_od.data_size, sizeof(s->data));
    co_node_config_t node_config = {
        .node_id = node_id, .od = &test_od, .od_data = s->data, .send = slave_send, .user = s};
    ck_assert_int_eq(co_node_init(&s->node, &node_config), 0);
    s->present = true;
    co_node_start(&s->node, bus.now);
}

static co_net_slave_config_t plain_slave(uint8_t node_id)
{
    return (co_net_slave_config_t){
        .node_id = node_id,
        .check = CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR | CO_NET_CHECK_PRODUCT,
        .device_type = 0x00010192,
        .identity = {0x5F, 0x312, 0, 0},
        .writes = writes,
        .write_count = 2,
    };
}

static void setup(void)
{
    memset(&bus, 0, sizeof(bus));
    memset(inputs, 0, sizeof(inputs));
    memset(outputs, 0, sizeof(outputs));
    event_count = 0;
    for (uint8_t i = 0; i < SLAVES; i++) {
        start_slave(&slaves[i], (uint8_t)(4 + i));
        table[i] = plain_slave((uint8_t)(4 + i));
    }
    bus.delivered = bus.next = bus.count; /* the boot-ups of the power-on */
    config = (co_net_master_config_t){
        .send = master_send,
        .user = &bus,
        .event = on_event,
        .slaves = table,
        .slave_state = state,
        .slave_count = SLAVES,
        .sdo_timeout_ms = SDO_TIMEOUT_MS,
        .boot_time_ms = BOOT_TIME_MS,
        .retry_delay_ms = RETRY_DELAY_MS,
        .start = CO_NET_START_EACH,
        .reset_all = true,
        .inputs = input_pdos,
        .input_count = 2,
        .input_image = inputs,
        .input_size = sizeof(inputs),
        .outputs = output_pdos,
        .output_count = 2,
        .output_image = outputs,
        .output_size = sizeof(outputs),
    };
}

static void start_master(void)
{
    ck_assert(co_net_master_init(&master, &config));
    co_net_master_start(&master, bus.now);
    advance(0);
}

/* The slaves' heartbeats, guarding replies (not boot-ups) and TPDOs go on under the boot steps:
 * expect() passes over them. */
static bool slave_noise(size_t position)
{
    const co_frame_t *f = &bus.log[position];
    if (bus.sender[position] == SLAVES)
        return false;
    bool tpdo = f->id >= 0x181 && f->id <= 0x4FF;
    bool error_control = f->id > 0x700 && f->id <= 0x77F && f->len == 1 && f->data[0] != 0;
    return tpdo || error_control;
}

#define expect(text) expect_at(text, __FILE__, __LINE__)
static void expect_at(const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    while (bus.next < bus.count && slave_noise(bus.next))
        bus.next++;
    ck_assert_msg(bus.next < bus.count, "%s:%d: expected %s, bus is quiet", file, line, want);
    test_format(&bus.log[bus.next++], got);
    ck_assert_msg(strcmp(want, got) == 0, "%s:%d: expected %s, got %s", file, line, want, got);
}

/* Skips frames up to and including the next one equal to `text`. */
#define skip_to(text) skip_to_at(text, __FILE__, __LINE__)
static void skip_to_at(const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    while (bus.next < bus.count) {
        test_format(&bus.log[bus.next++], got);
        if (strcmp(want, got) == 0)
            return;
    }
    ck_abort_msg("%s:%d: %s never sent", file, line, want);
}

/* Whether `text` is sent among the unchecked frames (none are consumed). */
static bool sent_later(const char *text)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    for (size_t i = bus.next; i < bus.count; i++) {
        if (strcmp(want, test_format(&bus.log[i], got)) == 0)
            return true;
    }
    return false;
}

/* The boot of one slave after the request for its 1000h, frame by frame: 1000h, 1018h:01-02, the
 * two configuration writes, NMT start. */
static void expect_boot_after_request(uint8_t id)
{
    char f[64];
    snprintf(f, sizeof(f), "%03X#4300100092010100", 0x580 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#4018100100000000", 0x600 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#431810015F000000", 0x580 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#4018100200000000", 0x600 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#4318100212030000", 0x580 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#2B17100064000000", 0x600 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#6017100000000000", 0x580 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#2300200778563412", 0x600 + id);
    expect(f);
    snprintf(f, sizeof(f), "%03X#6000200700000000", 0x580 + id);
    expect(f);
    snprintf(f, sizeof(f), "000#01%02X", id);
    expect(f);
}

/* The same from the request for 1000h. */
static void expect_boot(uint8_t id)
{
    char f[64];
    snprintf(f, sizeof(f), "%03X#4000100000000000", 0x600 + id);
    expect(f);
    expect_boot_after_request(id);
}

static uint32_t slave_u32(uint8_t id, uint16_t index, uint8_t sub)
{
    const co_od_entry_t *entry;
    co_node_t *node = &slaves[id - 4].node;
    ck_assert_uint_eq(co_od_read_check(node, index, sub, &entry), 0);
    uint8_t b[4] = {0};
    memcpy(b, co_od_bytes(node, entry),
           co_od_length(node, entry) < 4 ? co_od_length(node, entry) : 4);
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

/* Two slave descriptions alike field by field: memory compares would read their padding, which
 * no assignment has to copy or set. */
static void assert_slave_config_eq(const co_net_slave_config_t *a, const co_net_slave_config_t *b)
{
    ck_assert_uint_eq(a->node_id, b->node_id);
    ck_assert_int_eq(a->mandatory, b->mandatory);
    ck_assert_uint_eq(a->check, b->check);
    ck_assert_uint_eq(a->device_type, b->device_type);
    for (size_t i = 0; i < CO_NET_IDENTITY_SUBS; i++)
        ck_assert_uint_eq(a->identity[i], b->identity[i]);
    ck_assert_ptr_eq(a->writes, b->writes);
    ck_assert_uint_eq(a->write_count, b->write_count);
    ck_assert_ptr_eq(a->concise_dcf, b->concise_dcf);
    ck_assert_uint_eq(a->concise_dcf_len, b->concise_dcf_len);
    ck_assert_uint_eq(a->heartbeat_ms, b->heartbeat_ms);
    ck_assert_uint_eq(a->guard_ms, b->guard_ms);
    ck_assert_uint_eq(a->life_time_factor, b->life_time_factor);
    ck_assert_int_eq(a->on_error, b->on_error);
}

START_TEST(full_boot_of_three_slaves)
{
    start_master();
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect_boot(5);
    expect_boot(6);
    for (uint8_t id = 4; id <= 6; id++) {
        ck_assert_uint_eq(co_net_master_slave_status(&master, id), 0x000F);
        ck_assert_uint_eq(co_net_master_slave(&master, id)->step, CO_NET_STEP_OPERATIONAL);
        ck_assert_uint_eq(slave_u32(id, 0x1017, 0), 100);
        ck_assert_uint_eq(slave_u32(id, 0x2000, 7), 0x12345678);
        ck_assert_uint_eq(slaves[id - 4].node.nmt_state, CO_NMT_OPERATIONAL);
    }
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
    ck_assert_uint_eq(master.last_sdo_error.node_id, 0);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 7), 0);
    ck_assert_ptr_null(co_net_master_slave(&master, 7));
}
END_TEST

/* Steps and status bits come out as events, in order. */
START_TEST(events_follow_the_steps)
{
    start_master();
    static const uint8_t steps[] = {CO_NET_STEP_WAIT_BOOT, CO_NET_STEP_DEVICE_TYPE,
                                    CO_NET_STEP_IDENTITY, CO_NET_STEP_DOWNLOAD,
                                    CO_NET_STEP_OPERATIONAL};
    static const uint16_t statuses[] = {0x01, 0x03, 0x07, 0x0F};
    size_t step = 0, status = 0;
    for (size_t e = 0; e < event_count; e++) {
        if (events[e].node_id != 4)
            continue;
        if (events[e].kind == CO_NET_EVENT_STEP) {
            ck_assert_uint_lt(step, sizeof(steps));
            ck_assert_uint_eq(event_step[e], steps[step++]);
        }
        if (events[e].kind == CO_NET_EVENT_STATUS) {
            ck_assert_uint_lt(status, 4);
            ck_assert_uint_eq(event_status[e], statuses[status++]);
        }
    }
    ck_assert_uint_eq(step, sizeof(steps));
    ck_assert_uint_eq(status, 4);
}
END_TEST

START_TEST(identity_mismatch_is_an_init_error)
{
    table[1].identity[1] = 0x999; /* node 5 is expected to be another product */
    start_master();
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect("605#4000100000000000");
    expect("585#4300100092010100");
    expect("605#4018100100000000");
    expect("585#431810015F000000");
    expect("605#4018100200000000");
    expect("585#4318100212030000");
    expect_boot(6); /* node 5 gets no configuration, no start */
    const co_net_slave_t *s = co_net_master_slave(&master, 5);
    ck_assert_uint_eq(s->status, CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(s->step, CO_NET_STEP_FAILED);
    ck_assert_uint_eq(s->failure, CO_NET_FAIL_IDENTITY);
    ck_assert_uint_eq(s->read_value, 0x312);
    ck_assert_uint_eq(co_net_master_status(&master),
                      CO_NET_MASTER_INIT_FINISHED | CO_NET_MASTER_INIT_ERROR);
    ck_assert_uint_eq(slaves[1].node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_str_eq(co_net_failure_text(s->failure), "identity mismatch");
    /* Retried after the retry delay: a reset communication, then the same mismatch. */
    advance(RETRY_DELAY_MS * MS);
    expect("000#8205");
    expect("705#00");
    expect("605#4000100000000000");
}
END_TEST

START_TEST(device_type_mismatch)
{
    table[2].device_type = 0x00020192;
    start_master();
    const co_net_slave_t *s = co_net_master_slave(&master, 6);
    ck_assert_uint_eq(s->status, CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(s->failure, CO_NET_FAIL_DEVICE_TYPE);
    ck_assert_uint_eq(s->read_value, 0x00010192);
    ck_assert(!sent_later("606#4018100100000000"));
}
END_TEST

/* CiA 302-2's error status of each identity check that fails, on node 5: the value expected is
 * one more than the slave's, the read of that sub is the last request to node 5, and the slave
 * gets no configuration. */
static const struct {
    uint16_t index; /* 1F84h..1F88h */
    uint8_t boot_error;
} identity_checks[] = {
    {CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION, 'C'},
    {CO_NET_IDX_VENDOR_IDENTIFICATION, 'D'},
    {CO_NET_IDX_PRODUCT_CODE, 'M'},
    {CO_NET_IDX_REVISION_NUMBER, 'N'},
    {CO_NET_IDX_SERIAL_NUMBER, 'O'},
};

START_TEST(identity_check_gives_its_boot_error)
{
    uint16_t index = identity_checks[_i].index;
    uint8_t sub = (uint8_t)(index - CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION);
    uint32_t actual = sub == 0 ? slave_u32(5, 0x1000, 0) : slave_u32(5, 0x1018, sub);
    table[1] = (co_net_slave_config_t){.node_id = 5, .writes = writes, .write_count = 2};
    ck_assert(co_net_slave_config_set_expected(&table[1], index, actual + 1));
    start_master();
    char request[32], answer[32];
    if (sub == 0) {
        snprintf(request, sizeof request, "605#4000100000000000");
        snprintf(answer, sizeof answer, "585#43001000%02X%02X%02X%02X", actual & 0xFF,
                 (actual >> 8) & 0xFF, (actual >> 16) & 0xFF, actual >> 24);
    } else {
        snprintf(request, sizeof request, "605#401810%02X00000000", sub);
        snprintf(answer, sizeof answer, "585#431810%02X%02X%02X%02X%02X", sub, actual & 0xFF,
                 (actual >> 8) & 0xFF, (actual >> 16) & 0xFF, actual >> 24);
    }
    skip_to(request);
    expect(answer);
    expect_boot(6); /* node 5's boot ends there */
    const co_net_slave_t *s = co_net_master_slave(&master, 5);
    ck_assert_uint_eq(s->step, CO_NET_STEP_FAILED);
    ck_assert_uint_eq(s->status, CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(s->read_value, actual);
    ck_assert_uint_eq(s->boot_error, identity_checks[_i].boot_error);
}
END_TEST

/* B: 1000h unanswered; J: a write of the configuration refused; none once a boot succeeds. */
START_TEST(boot_errors_of_a_silent_and_a_refusing_slave)
{
    slaves[2].present = false;
    table[1].writes = refused_write;
    table[1].write_count = 1;
    start_master();
    advance((BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->boot_error, CO_NET_BOOT_ERROR_B);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->boot_error, CO_NET_BOOT_ERROR_J);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->boot_error, CO_NET_BOOT_ERROR_NONE);
    ck_assert_str_eq(co_net_boot_error_text(CO_NET_BOOT_ERROR_B), "no answer to the read of 1000h");
    ck_assert_str_eq(co_net_boot_error_text(CO_NET_BOOT_ERROR_J), "configuration download failed");
    ck_assert_str_eq(co_net_boot_error_text(CO_NET_BOOT_ERROR_O),
                     "serial number differs from 1F88h");
    ck_assert_str_eq(co_net_boot_error_text(CO_NET_BOOT_ERROR_NONE), "none");
    ck_assert_str_eq(co_net_boot_error_text('Z'), "unknown boot error");
    /* Retried, node 6 keeps its boot error while it waits for its boot-up, as bit 4; it comes,
     * and the boot that succeeds clears it. */
    advance(RETRY_DELAY_MS * MS);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->step, CO_NET_STEP_WAIT_BOOT);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->boot_error, CO_NET_BOOT_ERROR_B);
    slaves[2].present = true;
    advance(BOOT_TIME_MS * MS);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->step, CO_NET_STEP_OPERATIONAL);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->boot_error, CO_NET_BOOT_ERROR_NONE);
}
END_TEST

/* 1F84h..1F88h are the table's check and values, 0 being no check. */
START_TEST(expected_identity_1f84_to_1f88_both_ways)
{
    co_net_slave_config_t slave = plain_slave(4);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F84), 0x00010192);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F85), 0x5F);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F86), 0x312);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F87), 0);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F88), 0);
    ck_assert(co_net_slave_config_set_expected(&slave, 0x1F88, 0x12345678));
    ck_assert_uint_eq(slave.check, CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR |
                                       CO_NET_CHECK_PRODUCT | CO_NET_CHECK_SERIAL);
    ck_assert_uint_eq(slave.identity[3], 0x12345678);
    ck_assert(co_net_slave_config_set_expected(&slave, 0x1F84, 0));
    ck_assert_uint_eq(slave.check,
                      CO_NET_CHECK_VENDOR | CO_NET_CHECK_PRODUCT | CO_NET_CHECK_SERIAL);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F84), 0);
    co_net_slave_config_t before = slave;
    ck_assert(!co_net_slave_config_set_expected(&slave, 0x1F83, 1));
    ck_assert(!co_net_slave_config_set_expected(&slave, 0x1F89, 1));
    assert_slave_config_eq(&slave, &before);
    ck_assert_uint_eq(co_net_slave_expected(&slave, 0x1F89), 0);
}
END_TEST

static size_t boot_time_events(void)
{
    size_t n = 0;
    for (size_t e = 0; e < event_count; e++)
        n += events[e].kind == CO_NET_EVENT_BOOT_TIME && events[e].node_id == 0;
    return n;
}

/* 1F89h: the mandatory node 6 is missing; at the boot time's end, not a microsecond before, the
 * application is told and status bit 7 set; the boot goes on, and bit 7 stays until a new start. */
START_TEST(boot_time_1f89_ends_before_a_mandatory_slave)
{
    config.boot_limit_ms = 1000;
    table[2].mandatory = true;
    slaves[2].present = false;
    start_master();
    advance(1000 * MS - 1);
    ck_assert_uint_eq(boot_time_events(), 0);
    ck_assert_uint_eq(co_net_master_status(&master) & CO_NET_MASTER_BOOT_TIME_OVER, 0);
    advance(1);
    ck_assert_uint_eq(boot_time_events(), 1);
    ck_assert_uint_eq(co_net_master_status(&master),
                      CO_NET_MASTER_INIT_FINISHED | CO_NET_MASTER_INIT_ERROR |
                          CO_NET_MASTER_MANDATORY_ERROR | CO_NET_MASTER_BOOT_TIME_OVER);
    slaves[2].present = true;
    advance(RETRY_DELAY_MS * MS);
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->step, CO_NET_STEP_OPERATIONAL);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F | CO_NET_MASTER_BOOT_TIME_OVER);
    ck_assert_uint_eq(boot_time_events(), 1);
    co_net_master_start(&master, bus.now);
    ck_assert_uint_eq(co_net_master_status(&master) & CO_NET_MASTER_BOOT_TIME_OVER, 0);
}
END_TEST

/* Every mandatory slave configured in time: nothing told, and no deadline of the boot time left
 * (the master's next deadline is the heartbeat consumer's, not 1F89h's). */
START_TEST(boot_time_1f89_met)
{
    config.boot_limit_ms = 1000;
    table[2].mandatory = true;
    start_master();
    ck_assert_uint_eq(co_net_master_slave(&master, 6)->step, CO_NET_STEP_OPERATIONAL);
    ck_assert_uint_eq(master.boot_limit, CO_TIME_NEVER);
    advance(2000 * MS);
    ck_assert_uint_eq(boot_time_events(), 0);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

/* 1F22h: node 5 configured from a concise DCF of the same two writes: the same frames. */
static uint8_t concise[64];

static size_t concise_of(const co_net_write_t *w, size_t count)
{
    size_t used = co_concise_dcf_begin(concise, sizeof concise);
    for (size_t k = 0; k < count; k++) {
        co_concise_dcf_entry_t e = {w[k].index, w[k].subindex, w[k].data, w[k].len};
        used = co_concise_dcf_add(concise, sizeof concise, used, &e);
        ck_assert_uint_ne(used, 0);
    }
    return used;
}

START_TEST(concise_dcf_1f22_configures_a_slave)
{
    table[1].writes = NULL;
    table[1].write_count = 0;
    table[1].concise_dcf = concise;
    table[1].concise_dcf_len = concise_of(writes, 2);
    start_master();
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect_boot(5);
    expect_boot(6);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(slave_u32(5, 0x2000, 7), 0x12345678);
}
END_TEST

/* An entry refused: the SDO error names it and its value, error J. */
START_TEST(concise_dcf_entry_refused)
{
    const co_net_write_t refused[] = {writes[0], refused_write[0]};
    table[1].writes = NULL;
    table[1].write_count = 0;
    table[1].concise_dcf = concise;
    table[1].concise_dcf_len = concise_of(refused, 2);
    start_master();
    skip_to("605#2B17100064000000");
    expect("585#6017100000000000");
    expect("605#2B00201001000000");
    expect("585#8000201021000008"); /* 0x08000021 */
    const co_net_slave_t *s = co_net_master_slave(&master, 5);
    ck_assert_uint_eq(s->step, CO_NET_STEP_FAILED);
    ck_assert_uint_eq(s->boot_error, CO_NET_BOOT_ERROR_J);
    ck_assert_uint_eq(master.last_sdo_error.index, 0x2000);
    ck_assert_uint_eq(master.last_sdo_error.subindex, 0x10);
    ck_assert_uint_eq(master.last_sdo_error.value, 1);
}
END_TEST

START_TEST(concise_dcf_checked_at_init)
{
    uint8_t broken[] = {0x01, 0x00, 0x00, 0x00, 0x17, 0x10, 0x00, 0x02, 0x00, 0x00, 0x00, 0x64};
    table[1].concise_dcf = broken;
    table[1].concise_dcf_len = sizeof broken; /* and writes too */
    ck_assert(!co_net_master_init(&master, &config));
    table[1].writes = NULL;
    table[1].write_count = 0;
    ck_assert(!co_net_master_init(&master, &config)); /* its value cut short */
    table[1].concise_dcf_len = concise_of(writes, 2);
    table[1].concise_dcf = concise;
    ck_assert(co_net_master_init(&master, &config));
}
END_TEST

/* 1F25h: "conf" to node 5 boots it again, configuration and all; to 128 every slave. */
START_TEST(configuration_request_1f25)
{
    ck_assert(!co_net_master_request_configuration(&master, 5, CO_NET_1F25_SIGNATURE, 0));
    start_master();
    skip_to("000#0106");
    size_t sent = bus.count;
    ck_assert(!co_net_master_request_configuration(&master, 5, 0x65766173, bus.now)); /* "save" */
    ck_assert(!co_net_master_request_configuration(&master, 7, CO_NET_1F25_SIGNATURE, bus.now));
    ck_assert(!co_net_master_request_configuration(&master, 0, CO_NET_1F25_SIGNATURE, bus.now));
    ck_assert_uint_eq(bus.count, sent);
    ck_assert(co_net_master_request_configuration(&master, 5, CO_NET_1F25_SIGNATURE, bus.now));
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->step, CO_NET_STEP_WAIT_BOOT);
    advance(0);
    expect("000#8205");
    expect("705#00");
    expect_boot(5);
    ck_assert(co_net_master_request_configuration(&master, CO_NET_1F25_ALL, CO_NET_1F25_SIGNATURE,
                                                  bus.now));
    advance(0);
    expect("000#8204");
    expect("000#8205");
    expect("000#8206");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect_boot(5);
    expect_boot(6);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
    co_net_master_disable(&master, bus.now);
    ck_assert(!co_net_master_request_configuration(&master, 5, CO_NET_1F25_SIGNATURE, bus.now));
}
END_TEST

/* The master's own objects: the table (each slave by its concise DCF) to the objects and back,
 * and a master configured from them boots the same frames. */
START_TEST(configuration_from_the_masters_objects)
{
    static co_net_objects_t objects;
    static co_net_slave_config_t from_objects[SLAVES];
    size_t len = concise_of(writes, 2);
    for (size_t i = 0; i < SLAVES; i++) {
        table[i].writes = NULL;
        table[i].write_count = 0;
        table[i].concise_dcf = concise;
        table[i].concise_dcf_len = len;
        table[i].heartbeat_ms = 0;
    }
    table[0].mandatory = true;
    table[1].guard_ms = 100;
    table[1].life_time_factor = 3;
    table[2].heartbeat_ms = 300;
    table[2].on_error = CO_NET_ON_ERROR_REPORT;
    config.on_mandatory_error = CO_NET_MANDATORY_STOP_ALL;
    config.boot_limit_ms = 2000;
    ck_assert(co_net_objects_from_config(&objects, &config));
    ck_assert_uint_eq(objects.nmt_startup, 0x41);
    ck_assert_uint_eq(objects.boot_time_ms, 2000);
    ck_assert_uint_eq(objects.slave_assignment[3], 0x0D);       /* node 4: slave, boot, mandatory */
    ck_assert_uint_eq(objects.slave_assignment[4], 0x00640305); /* node 5: guarding 100 ms x 3 */
    ck_assert_uint_eq(objects.slave_assignment[5], 0x01);       /* node 6: report */
    ck_assert_uint_eq(objects.slave_assignment[6], 0);
    ck_assert_uint_eq(objects.consumer_heartbeat_ms[5], 300);
    ck_assert_uint_eq(objects.expected[0][3], 0x00010192);
    ck_assert_uint_eq(objects.expected[2][4], 0x312);
    ck_assert_uint_eq(objects.expected[3][4], 0);
    ck_assert_ptr_eq(objects.concise_dcf[5], concise);
    ck_assert_uint_eq(objects.concise_dcf_len[5], len);

    co_net_master_config_t back = config;
    back.start = CO_NET_START_ALL;
    back.on_mandatory_error = CO_NET_MANDATORY_ALONE;
    back.boot_limit_ms = 0;
    ck_assert(!co_net_config_from_objects(&back, from_objects, 2, &objects)); /* no room */
    ck_assert(co_net_config_from_objects(&back, from_objects, SLAVES, &objects));
    ck_assert_uint_eq(back.slave_count, SLAVES);
    ck_assert_ptr_eq(back.slaves, from_objects);
    ck_assert_uint_eq(back.start, CO_NET_START_EACH);
    ck_assert_uint_eq(back.on_mandatory_error, CO_NET_MANDATORY_STOP_ALL);
    ck_assert_uint_eq(back.boot_limit_ms, 2000);
    for (size_t i = 0; i < SLAVES; i++)
        assert_slave_config_eq(&from_objects[i], &table[i]);

    /* Booted from its objects: the same frames as from the table (node 5's first guarding
     * request between its start and node 6's boot). */
    config = back;
    start_master();
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect_boot(5);
    expect("705#R1");
    expect_boot(6);

    /* What the objects cannot hold, or the master does not take. */
    config.slaves = table;
    table[0].writes = writes;
    table[0].write_count = 2;
    table[0].concise_dcf = NULL;
    ck_assert(!co_net_objects_from_config(&objects, &config));
    table[0] = from_objects[0];
    table[0].check |= CO_NET_CHECK_SERIAL; /* a serial number of 0 expected */
    ck_assert(!co_net_objects_from_config(&objects, &config));
    objects.slave_assignment[9] = 0x03; /* bit 1, reserved */
    ck_assert(!co_net_config_from_objects(&back, from_objects, SLAVES + 1, &objects));
    objects.slave_assignment[9] = 0;
    objects.nmt_startup = 0x04;
    ck_assert(!co_net_config_from_objects(&back, from_objects, SLAVES, &objects));
}
END_TEST

START_TEST(missing_optional_slave)
{
    slaves[2].present = false;
    start_master();
    advance((BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect_boot(4);
    expect_boot(5);
    /* Node 6 never booted: identified anyway when the boot time ends; the SDO times out. */
    expect("606#4000100000000000");
    ck_assert_uint_eq(bus.at[bus.next - 1], BOOT_TIME_MS * MS);
    expect("606#8000100000000405");
    ck_assert_uint_eq(bus.at[bus.next - 1], (BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    const co_net_slave_t *s = co_net_master_slave(&master, 6);
    ck_assert_uint_eq(s->status, CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(s->failure, CO_NET_FAIL_SDO);
    ck_assert_uint_eq(master.last_sdo_error.node_id, 6);
    ck_assert_uint_eq(master.last_sdo_error.index, 0x1000);
    ck_assert_uint_eq(master.last_sdo_error.subindex, 0);
    ck_assert_uint_eq(master.last_sdo_error.access, CO_NET_ACCESS_READ);
    ck_assert_uint_eq(master.last_sdo_error.abort_code, CO_SDO_ABORT_TIMEOUT);
    ck_assert_uint_eq(co_net_master_status(&master),
                      CO_NET_MASTER_INIT_FINISHED | CO_NET_MASTER_INIT_ERROR);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
}
END_TEST

START_TEST(mandatory_slave_missing_blocks_start_all)
{
    config.start = CO_NET_START_ALL;
    table[2].mandatory = true;
    slaves[2].present = false;
    start_master();
    advance((BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    ck_assert(!sent_later("000#0100"));
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x07);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_WAIT_START);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 6), CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(co_net_master_status(&master), CO_NET_MASTER_INIT_FINISHED |
                                                         CO_NET_MASTER_INIT_ERROR |
                                                         CO_NET_MASTER_MANDATORY_ERROR);
    /* The mandatory slave comes: its retry boots it, then all start at once. */
    slaves[2].present = true;
    advance(RETRY_DELAY_MS * MS);
    skip_to("000#8206");
    skip_to("706#00");
    skip_to("586#6000200700000000");
    expect("000#0100");
    for (uint8_t id = 4; id <= 6; id++)
        ck_assert_uint_eq(co_net_master_slave_status(&master, id), 0x0F);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

START_TEST(start_all_after_every_slave)
{
    config.start = CO_NET_START_ALL;
    start_master();
    skip_to("586#6000200700000000");
    expect("000#0100");
    ck_assert(!sent_later("000#0104"));
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
    bool started = false;
    for (size_t e = 0; e < event_count; e++)
        started |= events[e].kind == CO_NET_EVENT_STARTED;
    ck_assert(started);
}
END_TEST

START_TEST(slave_appearing_late_is_retried_after_the_others)
{
    config.boot_time_ms = 0; /* identified at once: node 4 first, while it is still away */
    slaves[0].present = false;
    start_master();
    advance(SDO_TIMEOUT_MS * MS);
    expect("000#8200");
    expect("604#4000100000000000");
    expect("705#00");
    expect("706#00");
    expect("604#8000100000000405");
    expect_boot(5);
    expect_boot(6);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(co_net_master_status(&master),
                      CO_NET_MASTER_INIT_FINISHED | CO_NET_MASTER_INIT_ERROR);
    slaves[0].present = true;
    advance(RETRY_DELAY_MS * MS);
    expect("000#8204");
    ck_assert_uint_eq(bus.at[bus.next - 1], (SDO_TIMEOUT_MS + RETRY_DELAY_MS) * MS);
    expect("604#4000100000000000");
    expect("704#00"); /* no boot time: the request went out before the boot-up came */
    expect_boot_after_request(4);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

START_TEST(sdo_abort_of_a_write_is_recorded)
{
    table[1].writes = refused_write;
    table[1].write_count = 1;
    start_master();
    /* Found, configuration refused (PLC300 5.6.3): contacted and init error together. */
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5),
                      CO_NET_SLAVE_CONTACTED | CO_NET_SLAVE_INIT_ERROR);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->step, CO_NET_STEP_FAILED);
    /* Every slave contacted, not every one configured. */
    ck_assert_uint_eq(co_net_master_status(&master), CO_NET_MASTER_ALL_CONTACTED |
                                                         CO_NET_MASTER_INIT_FINISHED |
                                                         CO_NET_MASTER_INIT_ERROR);
    ck_assert_uint_eq(master.last_sdo_error.node_id, 5);
    ck_assert_uint_eq(master.last_sdo_error.index, 0x2000);
    ck_assert_uint_eq(master.last_sdo_error.subindex, 0x10);
    ck_assert_uint_eq(master.last_sdo_error.access, CO_NET_ACCESS_WRITE);
    ck_assert_uint_eq(master.last_sdo_error.value, 1);
    ck_assert_uint_eq(master.last_sdo_error.abort_code, CO_SDO_ABORT_DATA_LOCAL);
}
END_TEST

START_TEST(heartbeat_loss_reboots_and_reconfigures)
{
    table[0].heartbeat_ms = 150;
    start_master();
    advance(1000 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    bus.next = bus.count;
    /* Node 4 disconnected: lost 150 ms after its last heartbeat, then reset. */
    slaves[0].present = false;
    advance(200 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), CO_NET_SLAVE_EC_ERROR);
    ck_assert_uint_eq(co_net_master_status(&master) & CO_NET_MASTER_EC_ERROR,
                      CO_NET_MASTER_EC_ERROR);
    skip_to("000#8104");
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_WAIT_BOOT);
    /* Its configuration is lost meanwhile; reconnected, it is identified and configured again. */
    const uint8_t zero[2] = {0};
    ck_assert_uint_eq(co_od_write(&slaves[0].node, 0x1017, 0, zero, 2, CO_OD_ORIGIN_SDO), 0);
    slaves[0].present = true;
    advance(BOOT_TIME_MS * MS);
    expect_boot(4);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(slave_u32(4, 0x1017, 0), 100);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
    advance(1000 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
}
END_TEST

/* CiA 301's consumer waits for the first heartbeat forever; a slave that dies right after its
 * configuration must still be seen lost, one consumer time after error control started. */
START_TEST(no_first_heartbeat_is_a_loss)
{
    table[0].heartbeat_ms = 150;
    start_master();
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    co_time_t started = bus.now;
    slaves[0].present = false; /* before its first heartbeat */
    bus.next = bus.count;
    advance(149 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    advance(1 * MS);
    expect("000#8104");
    ck_assert_uint_eq(bus.at[bus.next - 1], started + 150 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), CO_NET_SLAVE_EC_ERROR);
}
END_TEST

/* A new start while a slave's SDO transfer is under way: its answer is ignored and the network
 * boots again from the start. */
START_TEST(restart_during_a_transfer)
{
    slaves[0].present = false;
    config.boot_time_ms = 0;
    ck_assert(co_net_master_init(&master, &config));
    co_net_master_start(&master, bus.now);
    advance(0);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_DEVICE_TYPE);
    slaves[0].present = true;
    co_net_master_start(&master, bus.now);
    bus.next = bus.count;
    advance(SDO_TIMEOUT_MS * MS);
    for (uint8_t id = 4; id <= 6; id++)
        ck_assert_uint_eq(co_net_master_slave_status(&master, id), 0x0F);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

/* Issue 22, item 1: nodes 4 and 6 are absent; when the boot time ends, node 6 (next after node 5)
 * takes the SDO client and waits for an answer that does not come, and node 4 waits for the
 * client, which no time brings: the deadline is node 6's SDO timeout, not node 4's boot time
 * again and again. */
START_TEST(slave_waiting_for_the_client_asks_for_no_past_deadline)
{
    slaves[0].present = false;
    slaves[2].present = false;
    start_master();
    advance((BOOT_TIME_MS - 1) * MS);
    bus.next = bus.count;
    bus.now = BOOT_TIME_MS * MS;
    ck_assert_uint_eq(co_net_master_process(&master, bus.now),
                      (BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    expect("606#4000100000000000");
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_WAIT_BOOT);
    bus.now += 1 * MS;
    ck_assert_uint_eq(co_net_master_process(&master, bus.now),
                      (BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    /* Node 6's timeout hands the client to node 4. */
    bus.now = (BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS;
    ck_assert_uint_eq(co_net_master_process(&master, bus.now),
                      (BOOT_TIME_MS + 2 * SDO_TIMEOUT_MS) * MS);
    expect("606#8000100000000405");
    expect("604#4000100000000000");
}
END_TEST

/* Issue 22, item 3: the report reaction, no start by the master; node 4 goes away right after its
 * configuration, is lost for lack of its first heartbeat, comes back and beats in Pre-operational,
 * the state the master knew from its boot-up: it is running again. */
START_TEST(lost_without_a_first_heartbeat_resumes)
{
    config.start = CO_NET_START_NONE;
    table[0].heartbeat_ms = 150;
    table[0].on_error = CO_NET_ON_ERROR_REPORT;
    start_master();
    slaves[0].present = false;
    advance(150 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x2F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_LOST);
    slaves[0].present = true;
    advance(50 * MS); /* its next heartbeat, 704#7F, at 200 ms */
    ck_assert_uint_eq(slaves[0].node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_OPERATIONAL);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

/* Issue 22, item 4: start all, the report reaction; mandatory node 4, heard once, is silent while
 * it waits for the start: lost at 220 ms (0x27). It beats again at once, and waits for the start
 * again (0x07, not running without bit 3); the start of all goes out when node 6, absent, has had
 * its attempt. */
START_TEST(late_heartbeat_of_a_mandatory_slave_before_start_all)
{
    config.start = CO_NET_START_ALL;
    table[0].mandatory = true;
    table[0].heartbeat_ms = 120;
    table[0].on_error = CO_NET_ON_ERROR_REPORT;
    slaves[2].present = false;
    start_master();
    advance(100 * MS); /* node 4's first heartbeat */
    slaves[0].present = false;
    advance(120 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x27);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_LOST);
    slaves[0].present = true;
    advance(0); /* the heartbeat it owes */
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x07);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_WAIT_START);
    ck_assert(!sent_later("000#0100"));
    advance(30 * MS);
    skip_to("606#8000100000000405");
    expect("000#0100");
    ck_assert_uint_eq(bus.at[bus.next - 1], (BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(slaves[0].node.nmt_state, CO_NMT_OPERATIONAL);
}
END_TEST

START_TEST(unexpected_boot_up_reboots)
{
    start_master();
    bus.next = bus.count;
    co_node_start(&slaves[1].node, bus.now); /* node 5 restarted: defaults again */
    advance(0);
    expect("705#00");
    expect_boot(5);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
}
END_TEST

START_TEST(heartbeat_loss_only_reported)
{
    table[0].heartbeat_ms = 150;
    table[0].on_error = CO_NET_ON_ERROR_REPORT;
    start_master();
    advance(500 * MS);
    slaves[0].present = false;
    advance(200 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x2F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_LOST);
    ck_assert(!sent_later("000#8104"));
    slaves[0].present = true;
    advance(200 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_OPERATIONAL);
}
END_TEST

START_TEST(guarding_loss_reboots)
{
    static const uint8_t guard_100ms[] = {0x64, 0x00};
    static const uint8_t factor_3[] = {3};
    static const co_net_write_t guard_writes[] = {{0x100C, 0, guard_100ms, 2},
                                                  {0x100D, 0, factor_3, 1}};
    table[1].writes = guard_writes;
    table[1].write_count = 2;
    table[1].guard_ms = 100;
    table[1].life_time_factor = 3;
    start_master();
    advance(500 * MS);
    ck_assert(sent_later("705#R1"));
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    slaves[1].present = false;
    advance(400 * MS);
    skip_to("000#8105");
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), CO_NET_SLAVE_EC_ERROR);
}
END_TEST

/* Node 5 guarded every 100 ms, life time factor 3 (its 100Ch and 100Dh written by the boot). */
static void guard_node_5(co_net_on_error_t on_error)
{
    static const uint8_t guard_100ms[] = {0x64, 0x00};
    static const uint8_t factor_3[] = {3};
    static const co_net_write_t guard_writes[] = {{0x100C, 0, guard_100ms, 2},
                                                  {0x100D, 0, factor_3, 1}};
    table[1].writes = guard_writes;
    table[1].write_count = 2;
    table[1].guard_ms = 100;
    table[1].life_time_factor = 3;
    table[1].on_error = on_error;
}

/* The last STATUS event of node `id`: its kind of error control failure then. */
static uint8_t last_status_ec_error(uint8_t id)
{
    for (size_t k = event_count; k-- > 0;) {
        if (events[k].kind == CO_NET_EVENT_STATUS && events[k].node_id == id)
            return event_ec_error[k];
    }
    ck_abort_msg("no status event of node %u", id);
    return 0;
}

/* The PLC300's status bit 5 is one for both error controls; its %SB3180 (4, 5) and the slave's
 * record tell them apart. Node 5, guarded, stops answering: the master's requests go on, three
 * guard times pass without a reply, and the third missed request is the loss, a node guarding
 * error, then its reset. */
START_TEST(guarded_slave_silent_is_a_node_guarding_error)
{
    guard_node_5(CO_NET_ON_ERROR_REBOOT);
    start_master();
    advance(500 * MS);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_EC_ENABLED);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->ec_error, CO_NET_EC_ERROR_NONE);
    slaves[1].present = false;
    bus.next = bus.count;
    advance(400 * MS);
    expect("705#R1"); /* answered before node 5 went silent: the last one not missed */
    co_time_t first = bus.at[bus.next - 1];
    expect("705#R1");
    ck_assert_uint_eq(bus.at[bus.next - 1], first + 100 * MS);
    expect("705#R1");
    ck_assert_uint_eq(bus.at[bus.next - 1], first + 200 * MS);
    expect("000#8105");
    ck_assert_uint_eq(bus.at[bus.next - 1], first + 300 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), CO_NET_SLAVE_EC_ERROR);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->ec_error, CO_NET_EC_ERROR_GUARDING);
    ck_assert_uint_eq(last_status_ec_error(5), CO_NET_EC_ERROR_GUARDING);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_GUARDING_ERROR);
    ck_assert_str_eq(co_net_protocol_state_text(co_net_master_protocol_state(&master)),
                     "node guarding error");
    /* Back, booted again: bit 5 and its kind cleared together. */
    slaves[1].present = true;
    advance(BOOT_TIME_MS * MS + 100 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->ec_error, CO_NET_EC_ERROR_NONE);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_EC_ENABLED);
}
END_TEST

/* Node 4 produces a heartbeat every 100 ms, the master consumes it for 150 ms: silent after a
 * heartbeat, it is lost exactly 150 ms later, a heartbeat error, then reset; the master never
 * sent it a guarding request. */
START_TEST(heartbeat_producer_silent_is_a_heartbeat_error)
{
    table[0].heartbeat_ms = 150;
    start_master();
    advance(500 * MS);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_EC_ENABLED);
    co_time_t last_beat = 0;
    for (size_t k = 0; k < bus.count; k++) {
        if (bus.sender[k] == 0 && bus.log[k].id == 0x704 && bus.log[k].len == 1 &&
            bus.log[k].data[0] == CO_NMT_OPERATIONAL)
            last_beat = bus.at[k];
    }
    ck_assert_uint_eq(last_beat, bus.now); /* on the 100 ms grid: it just beat */
    slaves[0].present = false;
    bus.next = bus.count;
    advance(149 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    for (size_t k = bus.next; k < bus.count; k++)
        ck_assert_uint_ne(bus.sender[k], SLAVES); /* the master is silent until the loss */
    advance(1 * MS);
    expect("000#8104");
    ck_assert_uint_eq(bus.at[bus.next - 1], last_beat + 150 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), CO_NET_SLAVE_EC_ERROR);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->ec_error, CO_NET_EC_ERROR_HEARTBEAT);
    ck_assert_uint_eq(last_status_ec_error(4), CO_NET_EC_ERROR_HEARTBEAT);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_HEARTBEAT_ERROR);
    ck_assert_str_eq(co_net_protocol_state_text(co_net_master_protocol_state(&master)),
                     "heartbeat error");
    for (size_t k = 0; k < bus.count; k++)
        ck_assert(!(bus.sender[k] == SLAVES && bus.log[k].id == 0x704 &&
                    (bus.log[k].flags & CO_FRAME_RTR) != 0));
}
END_TEST

/* Both at once, reported only: the protocol state gives the first slave of the table with bit 5
 * (node 4's heartbeat error), then node 5's node guarding error once node 4 is heard again, then
 * error control enabled; disabled (bit 15) before anything else. */
START_TEST(protocol_state_gives_the_first_slave_in_error)
{
    table[0].heartbeat_ms = 150;
    table[0].on_error = CO_NET_ON_ERROR_REPORT;
    guard_node_5(CO_NET_ON_ERROR_REPORT);
    ck_assert(co_net_master_init(&master, &config));
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_ENABLED);
    co_net_master_start(&master, bus.now);
    advance(500 * MS);
    slaves[0].present = false;
    slaves[1].present = false;
    advance(500 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x2F);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x2F);
    ck_assert_uint_eq(co_net_master_slave(&master, 5)->ec_error, CO_NET_EC_ERROR_GUARDING);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_HEARTBEAT_ERROR);
    slaves[0].present = true;
    advance(100 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->ec_error, CO_NET_EC_ERROR_NONE);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_GUARDING_ERROR);
    slaves[1].present = true;
    advance(100 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_EC_ENABLED);
    co_net_master_set_bus(&master, CO_NET_MASTER_BUS_OFF);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_DISABLED);
    co_net_master_set_bus(&master, 0);
    co_net_master_disable(&master, bus.now);
    ck_assert_uint_eq(co_net_master_protocol_state(&master), CO_NET_PROTOCOL_DISABLED);
}
END_TEST

/* CiA 302-2's 1F80h both ways: the bits this master takes, bit 3 before bit 1 and bit 6 before
 * bit 4, and the values it refuses (no NMT master, bit 2, bit 5, a reserved bit). */
START_TEST(nmt_startup_1f80_both_ways)
{
    static const struct {
        uint32_t value;
        co_net_start_t start;
        co_net_mandatory_error_t on_error;
        uint32_t back;
    } taken[] = {
        {0x01, CO_NET_START_EACH, CO_NET_MANDATORY_ALONE, 0x01},
        {0x03, CO_NET_START_ALL, CO_NET_MANDATORY_ALONE, 0x03},
        {0x09, CO_NET_START_NONE, CO_NET_MANDATORY_ALONE, 0x09},
        {0x0B, CO_NET_START_NONE, CO_NET_MANDATORY_ALONE, 0x09},
        {0x11, CO_NET_START_EACH, CO_NET_MANDATORY_RESET_ALL, 0x11},
        {0x41, CO_NET_START_EACH, CO_NET_MANDATORY_STOP_ALL, 0x41},
        {0x53, CO_NET_START_ALL, CO_NET_MANDATORY_STOP_ALL, 0x43},
    };
    for (size_t k = 0; k < sizeof taken / sizeof taken[0]; k++) {
        config.start = CO_NET_START_EACH;
        config.on_mandatory_error = CO_NET_MANDATORY_ALONE;
        ck_assert(co_net_master_config_from_1f80(&config, taken[k].value));
        ck_assert_uint_eq(config.start, taken[k].start);
        ck_assert_uint_eq(config.on_mandatory_error, taken[k].on_error);
        ck_assert_uint_eq(co_net_master_1f80(&config), taken[k].back);
    }
    static const uint32_t refused[] = {0x00, 0x02, 0x05, 0x21, 0x81, 0x80000001};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        ck_assert(!co_net_master_config_from_1f80(&config, refused[k]));
        ck_assert_uint_eq(config.start, CO_NET_START_ALL); /* untouched */
    }
    config.on_mandatory_error = (co_net_mandatory_error_t)3;
    ck_assert(!co_net_master_init(&master, &config));
}
END_TEST

/* CiA 302-2's 1F81h both ways: node 5 guarded 100 ms x 3, mandatory, rebooted on a loss is
 * 0x0064030D; the bits this master does not take are refused, the record left as it was. */
START_TEST(slave_assignment_1f81_both_ways)
{
    co_net_slave_config_t s = plain_slave(5);
    ck_assert_uint_eq(co_net_slave_1f81(&s), 0x05);
    ck_assert(co_net_slave_config_from_1f81(&s, 0x0064030D));
    ck_assert(s.mandatory);
    ck_assert_uint_eq(s.on_error, CO_NET_ON_ERROR_REBOOT);
    ck_assert_uint_eq(s.guard_ms, 100);
    ck_assert_uint_eq(s.life_time_factor, 3);
    ck_assert_uint_eq(co_net_slave_1f81(&s), 0x0064030D);
    ck_assert(co_net_slave_config_from_1f81(&s, 0x01));
    ck_assert(!s.mandatory);
    ck_assert_uint_eq(s.on_error, CO_NET_ON_ERROR_REPORT);
    ck_assert_uint_eq(s.guard_ms, 0);
    ck_assert_uint_eq(co_net_slave_1f81(&s), 0x01);
    static const uint32_t refused[] = {0x00, 0x0C, 0x03, 0x11, 0x21, 0x41, 0x81};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        ck_assert(!co_net_slave_config_from_1f81(&s, refused[k]));
        ck_assert_uint_eq(co_net_slave_1f81(&s), 0x01);
    }
}
END_TEST

/* 1F80h bit 6: mandatory node 4's heartbeat stops; the master stops all nodes (000#0200) at the
 * loss, node 4 is lost without a reset, the master is Stopped too (heartbeat 04h, no SYNC, no
 * output PDO) until the application starts all nodes. Node 5 stopped meanwhile. */
START_TEST(mandatory_loss_stops_all_nodes)
{
    config.on_mandatory_error = CO_NET_MANDATORY_STOP_ALL;
    config.node_id = 1;
    config.heartbeat_ms = 100;
    config.sync_period_us = 50 * MS;
    table[0].mandatory = true;
    table[0].heartbeat_ms = 150;
    table[0].on_error = CO_NET_ON_ERROR_REBOOT; /* the network's reaction comes first */
    start_master();
    advance(500 * MS);
    slaves[0].present = false;
    bus.next = bus.count;
    advance(150 * MS);
    skip_to("000#0200");
    co_time_t stopped = bus.at[bus.next - 1];
    ck_assert(!sent_later("000#8104"));
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x2F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_LOST);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->ec_error, CO_NET_EC_ERROR_HEARTBEAT);
    ck_assert_uint_eq(slaves[1].node.nmt_state, CO_NMT_STOPPED);
    ck_assert(master.stopped_all);
    advance(300 * MS);
    for (size_t k = bus.next; k < bus.count; k++) {
        if (bus.sender[k] != SLAVES || bus.at[k] <= stopped)
            continue;
        ck_assert_uint_ne(bus.log[k].id, 0x080);                     /* no SYNC */
        ck_assert(bus.log[k].id != 0x205 && bus.log[k].id != 0x204); /* no PDO */
        if (bus.log[k].id == 0x701)
            ck_assert_uint_eq(bus.log[k].data[0], CO_NMT_STOPPED);
    }
    ck_assert(sent_later("701#04"));
    ck_assert(co_net_master_write_output(&master, 2, (const uint8_t[]){1, 2}, 2));
    bus.next = bus.count;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_START, 0, 500, bus.now));
    advance(100 * MS);
    expect("000#0100");
    ck_assert(!master.stopped_all);
    ck_assert(sent_later("701#05"));
    ck_assert(sent_later("080#"));
    ck_assert(sent_later("205#0102"));
    ck_assert_uint_eq(slaves[1].node.nmt_state, CO_NMT_OPERATIONAL);
}
END_TEST

/* 1F80h bit 4: the mandatory slave's loss resets every node (000#8100) and the master boots the
 * network again; node 4 keeps bit 5 until its own boot succeeds. An optional slave's loss is
 * its own (node 5: reset node alone). */
START_TEST(mandatory_loss_resets_all_nodes)
{
    config.on_mandatory_error = CO_NET_MANDATORY_RESET_ALL;
    table[0].mandatory = true;
    table[0].heartbeat_ms = 150;
    table[1].heartbeat_ms = 150;
    start_master();
    advance(500 * MS);
    slaves[1].present = false;
    bus.next = bus.count;
    advance(150 * MS);
    skip_to("000#8105");
    ck_assert(!sent_later("000#8100"));
    slaves[1].present = true;
    advance(BOOT_TIME_MS * MS + 100 * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    slaves[0].present = false;
    bus.next = bus.count;
    advance(150 * MS);
    skip_to("000#8100");
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), CO_NET_SLAVE_EC_ERROR);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, CO_NET_STEP_WAIT_BOOT);
    expect("705#00"); /* nodes 5 and 6 reset by the broadcast: their boot-ups at once */
    expect("706#00");
    expect_boot(5); /* and their boot again, configuration and start included */
    expect_boot(6);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 6), 0x0F);
    slaves[0].present = true;
    co_node_start(&slaves[0].node, bus.now);
    advance(BOOT_TIME_MS * MS);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

START_TEST(emcy_is_recorded)
{
    start_master();
    co_frame_t emcy = test_frame("085#3081110102030405");
    ck_assert(co_net_master_receive(&master, &emcy, bus.now));
    ck_assert_uint_eq(master.last_emcy.node_id, 5);
    ck_assert_uint_eq(master.last_emcy.code, 0x8130);
    ck_assert_uint_eq(master.last_emcy.reg, 0x11);
    ck_assert_mem_eq(master.last_emcy.msef, "\x01\x02\x03\x04\x05", 5);
    ck_assert_uint_eq(events[event_count - 1].kind, CO_NET_EVENT_EMCY);
    /* A short EMCY, or one of a node not in the table, changes nothing. */
    co_frame_t short_emcy = test_frame("084#1000");
    co_net_master_receive(&master, &short_emcy, bus.now);
    co_frame_t other = test_frame("087#0010010000000000");
    ck_assert(!co_net_master_receive(&master, &other, bus.now));
    ck_assert_uint_eq(master.last_emcy.node_id, 5);
    ck_assert_uint_eq(master.last_emcy.code, 0x8130);
}
END_TEST

START_TEST(process_image_in)
{
    start_master();
    bus.next = bus.count;
    advance(100 * MS); /* TPDO1 (6041h) by its event timer */
    co_frame_t tpdo = test_frame("184#3412");
    co_net_master_receive(&master, &tpdo, bus.now);
    ck_assert_mem_eq(inputs, "\x34\x12\x00\x00", 4);
    ck_assert_uint_eq(events[event_count - 1].kind, CO_NET_EVENT_INPUT);
    ck_assert_uint_eq(events[event_count - 1].pdo, 0);
    co_frame_t tpdo5 = test_frame("185#7856");
    co_net_master_receive(&master, &tpdo5, bus.now);
    ck_assert_mem_eq(inputs, "\x34\x12\x78\x56", 4);
    /* Shorter than mapped: not used. */
    co_frame_t short_pdo = test_frame("184#01");
    ck_assert(!co_net_master_receive(&master, &short_pdo, bus.now));
    ck_assert_mem_eq(inputs, "\x34\x12\x78\x56", 4);
}
END_TEST

START_TEST(process_image_out_on_change)
{
    start_master();
    bus.next = bus.count;
    ck_assert(co_net_master_write_output(&master, 0, (const uint8_t *)"\x0F\x00", 2));
    expect("204#0F00");
    pump();
    ck_assert_uint_eq(slave_u32(4, 0x6040, 0), 0x000F);
    /* The same value again: nothing; one byte of PDO 2: only that PDO. */
    ck_assert(co_net_master_write_output(&master, 0, (const uint8_t *)"\x0F\x00", 2));
    ck_assert(co_net_master_write_output(&master, 3, (const uint8_t *)"\x01", 1));
    expect("205#0001");
    /* Across both PDOs. */
    ck_assert(co_net_master_write_output(&master, 1, (const uint8_t *)"\x02\x03", 2));
    expect("204#0F02");
    expect("205#0301");
    ck_assert(!co_net_master_write_output(&master, 7, (const uint8_t *)"\x01\x02", 2));
    ck_assert(!co_net_master_write_output(&master, 9, (const uint8_t *)"\x01", 0));
    ck_assert_mem_eq(outputs, "\x0F\x02\x03\x01\x00\x00\x00\x00", 8);
}
END_TEST

START_TEST(process_image_out_not_to_a_failed_slave)
{
    slaves[0].present = false;
    start_master();
    advance((BOOT_TIME_MS + SDO_TIMEOUT_MS) * MS);
    bus.next = bus.count;
    ck_assert(co_net_master_write_output(&master, 0, (const uint8_t *)"\x06\x00", 2));
    ck_assert(!sent_later("204#0600"));
    ck_assert_mem_eq(outputs, "\x06\x00", 2);
}
END_TEST

/* Issue 22, item 5: a master without outputs has no image to write to; the write is refused, not
 * a copy to a null pointer. An image size without an image is refused at init. */
START_TEST(process_image_out_without_outputs)
{
    config.outputs = NULL;
    config.output_count = 0;
    config.output_image = NULL;
    config.output_size = 0;
    start_master();
    bus.next = bus.count;
    ck_assert(!co_net_master_write_output(&master, 0, (const uint8_t *)"\x01", 0));
    ck_assert(!co_net_master_write_output(&master, 0, (const uint8_t *)"\x01", 1));
    ck_assert(!sent_later("204#01"));
    config.output_size = 8;
    ck_assert(!co_net_master_init(&master, &config));
    config.output_size = 0;
    config.input_count = 0;
    config.input_image = NULL;
    config.input_size = 2;
    ck_assert(!co_net_master_init(&master, &config));
}
END_TEST

START_TEST(process_image_out_on_sync)
{
    config.sync_period_us = 10 * MS;
    start_master();
    ck_assert(co_net_master_write_output(&master, 0, (const uint8_t *)"\x0F\x00", 2));
    bus.next = bus.count;
    co_time_t from = bus.now;
    advance(10 * MS);
    expect("080#");
    expect("204#0F00");
    expect("205#0000");
    ck_assert_uint_eq(bus.now - from, 10 * MS);
}
END_TEST

START_TEST(configuration_is_checked)
{
    co_net_master_config_t good = config;
    ck_assert(co_net_master_init(&master, &good));
    config.sdo_timeout_ms = 4;
    ck_assert(!co_net_master_init(&master, &config));
    config.sdo_timeout_ms = 5001;
    ck_assert(!co_net_master_init(&master, &config));
    config = good;
    config.send = NULL;
    ck_assert(!co_net_master_init(&master, &config));
    config = good;
    config.slave_count = 0;
    ck_assert(!co_net_master_init(&master, &config));
    config = good;
    table[1].node_id = 4;
    ck_assert(!co_net_master_init(&master, &config));
    table[1].node_id = 128;
    ck_assert(!co_net_master_init(&master, &config));
    table[1].node_id = 5;
    static const co_net_pdo_t restricted[] = {{4, 0x604, 2, 0}};
    config.outputs = restricted;
    config.output_count = 1;
    ck_assert(!co_net_master_init(&master, &config));
    static const co_net_pdo_t outside[] = {{4, 0x204, 2, 7}};
    config.outputs = outside;
    ck_assert(!co_net_master_init(&master, &config));
    static const co_net_pdo_t unknown_node[] = {{9, 0x209, 2, 0}};
    config.outputs = unknown_node;
    ck_assert(!co_net_master_init(&master, &config));
    static const co_net_pdo_t too_long[] = {{4, 0x204, 9, 0}};
    config.outputs = too_long;
    ck_assert(!co_net_master_init(&master, &config));
    config = good;
    static const co_net_write_t no_data[] = {{0x1017, 0, NULL, 2}};
    table[0].writes = no_data;
    table[0].write_count = 1;
    ck_assert(!co_net_master_init(&master, &config));
}
END_TEST

START_TEST(texts)
{
    ck_assert_str_eq(co_net_step_text(CO_NET_STEP_WAIT_BOOT), "wait boot-up");
    ck_assert_str_eq(co_net_step_text(CO_NET_STEP_OPERATIONAL), "operational");
    ck_assert_str_eq(co_net_step_text((co_net_step_t)99), "unknown step");
    ck_assert_str_eq(co_net_failure_text(CO_NET_FAIL_SDO), "SDO error");
    ck_assert_str_eq(co_net_failure_text((co_net_failure_t)99), "unknown failure");
    ck_assert_str_eq(co_net_ec_error_text(CO_NET_EC_ERROR_NONE), "none");
    ck_assert_str_eq(co_net_ec_error_text(CO_NET_EC_ERROR_GUARDING), "node guarding error");
    ck_assert_str_eq(co_net_ec_error_text((co_net_ec_error_t)9), "unknown error control error");
    ck_assert_str_eq(co_net_protocol_state_text(CO_NET_PROTOCOL_DISABLED), "disabled");
    ck_assert_str_eq(co_net_protocol_state_text(CO_NET_PROTOCOL_ENABLED), "CANopen enabled");
    ck_assert_str_eq(co_net_protocol_state_text(CO_NET_PROTOCOL_EC_ENABLED),
                     "error control enabled");
    ck_assert_str_eq(co_net_protocol_state_text(1), "reserved");
    /* The PLC300's baud rate codes (%CB3055). */
    static const uint32_t bit_s[] = {1000000, 0, 500000, 250000, 125000, 100000, 50000, 20000, 0};
    for (uint8_t code = 0; code < sizeof bit_s / sizeof bit_s[0]; code++)
        ck_assert_uint_eq(co_net_bit_rate(code), bit_s[code]);
    ck_assert_uint_eq(co_net_bit_rate(CO_NET_BIT_RATE_1M), 1000000);
    ck_assert_uint_eq(co_net_bit_rate(CO_NET_BIT_RATE_20K), 20000);
    ck_assert_uint_eq(co_net_bit_rate(255), 0);
}
END_TEST

/* The times (ms from `from`) of the master's frames equal to `text` among those logged. */
static size_t master_frame_times(const char *text, co_time_t from, co_time_t *ms, size_t max)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    size_t n = 0;
    for (size_t i = 0; i < bus.count && n < max; i++) {
        if (bus.sender[i] == SLAVES && strcmp(want, test_format(&bus.log[i], got)) == 0)
            ms[n++] = (bus.at[i] - from) / MS;
    }
    return n;
}

/* How many frames the master sent from position `from` of the log on. */
static size_t master_frames_since(size_t from)
{
    size_t n = 0;
    for (size_t i = from; i < bus.count; i++)
        n += bus.sender[i] == SLAVES;
    return n;
}

/* The PLC300's own heartbeat (its 1017h): 700h + its node-id, Operational, from the start on the
 * grid of its producer time, so that slaves consuming it (1016h) supervise the master. */
START_TEST(master_heartbeat_on_its_grid)
{
    config.node_id = 1;
    config.heartbeat_ms = 50;
    start_master();
    expect("000#8200");
    expect("701#05");
    co_time_t from = bus.now;
    ck_assert_uint_eq(co_net_master_process(&master, bus.now), from + 50 * MS);
    advance(200 * MS);
    co_time_t at[8];
    ck_assert_uint_eq(master_frame_times("701#05", from, at, 8), 5);
    for (size_t k = 0; k < 5; k++)
        ck_assert_uint_eq(at[k], 50 * k);
    /* Woken late, it beats once and keeps the period from then on. */
    bus.now += 130 * MS;
    size_t before = bus.count;
    co_net_master_process(&master, bus.now);
    ck_assert_uint_eq(master_frames_since(before), 1);
    ck_assert_uint_eq(co_net_master_process(&master, bus.now), bus.now + 50 * MS);
}
END_TEST

START_TEST(master_heartbeat_needs_a_node_id_of_its_own)
{
    config.heartbeat_ms = 50;
    ck_assert(!co_net_master_init(&master, &config)); /* node-id 0 */
    config.node_id = 128;
    ck_assert(!co_net_master_init(&master, &config));
    config.node_id = 5; /* a slave's */
    ck_assert(!co_net_master_init(&master, &config));
    config.node_id = 127;
    ck_assert(co_net_master_init(&master, &config));
    config.heartbeat_ms = 0;
    config.node_id = 5; /* no heartbeat: the node-id is not used */
    ck_assert(co_net_master_init(&master, &config));
}
END_TEST

/* Disabling communication (the PLC300's DisableComm): no frame out, none taken, the status words
 * and the last SDO error and EMCY cleared, bit 15 set; enabling boots the network again. */
START_TEST(disable_stops_every_frame_and_enable_boots_again)
{
    config.node_id = 1;
    config.heartbeat_ms = 50;
    config.sync_period_us = 20 * MS;
    for (size_t i = 0; i < SLAVES; i++)
        table[i].heartbeat_ms = 150;
    start_master();
    advance(100 * MS);
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
    master.last_sdo_error.node_id = 4;
    co_net_master_disable(&master, bus.now);
    ck_assert_uint_eq(co_net_master_status(&master), CO_NET_MASTER_DISABLED);
    ck_assert_uint_eq(master.last_sdo_error.node_id, 0);
    for (uint8_t id = 4; id <= 6; id++) {
        ck_assert_uint_eq(co_net_master_slave_status(&master, id), 0);
        ck_assert_uint_eq(co_net_master_slave(&master, id)->step, CO_NET_STEP_IDLE);
    }
    ck_assert_uint_eq(co_net_master_process(&master, bus.now), CO_TIME_NEVER);
    size_t before = bus.count;
    advance(1000 * MS); /* the slaves beat on, heard by nobody */
    ck_assert_uint_eq(master_frames_since(before), 0);
    ck_assert_uint_gt(bus.count, before);
    ck_assert_uint_eq(co_net_master_status(&master), CO_NET_MASTER_DISABLED);
    ck_assert(!co_net_master_nmt(&master, CO_NMT_CS_START, 4, 100, bus.now));
    bus.next = bus.count;
    co_net_master_enable(&master, bus.now);
    advance(0);
    expect("000#8200");
    expect("701#05");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
}
END_TEST

/* Bits 13 and 14 as the runtime tells the controller's state; either sets bit 15 too (the
 * PLC300's CommDisabled "also on loss of CAN interface power or bus-off"). */
START_TEST(bus_off_and_bus_power_bits)
{
    start_master();
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
    co_net_master_set_bus(&master, CO_NET_MASTER_BUS_OFF);
    ck_assert_uint_eq(co_net_master_status(&master), 0xA00F);
    co_net_master_set_bus(&master, CO_NET_MASTER_NO_BUS_POWER);
    ck_assert_uint_eq(co_net_master_status(&master), 0xC00F);
    co_net_master_set_bus(&master, 0xFFFF);
    ck_assert_uint_eq(co_net_master_status(&master), 0xE00F);
    co_net_master_set_bus(&master, 0);
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
}
END_TEST

static size_t nmt_done_events(void)
{
    size_t n = 0;
    for (size_t e = 0; e < event_count; e++)
        n += events[e].kind == CO_NET_EVENT_NMT_DONE;
    return n;
}

/* An NMT command of the application, confirmed by the state the node reports next: here its
 * heartbeat (the master does not consume it, so it also asks once by a guarding request, which
 * a node producing heartbeats does not answer). Status bit 8 flips with each command. */
START_TEST(nmt_command_confirmed_by_the_next_heartbeat)
{
    start_master();
    bus.next = bus.count;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_STOP, 5, 500, bus.now));
    ck_assert(!co_net_master_nmt(&master, CO_NMT_CS_START, 5, 500, bus.now)); /* one at a time */
    ck_assert_uint_eq(co_net_master_status(&master), 0x010F);
    expect("000#0205");
    expect("705#R1");
    ck_assert(co_net_master_nmt_awaited(&master, 5));
    advance(99 * MS);
    ck_assert(co_net_master_nmt_awaited(&master, 5));
    advance(1 * MS); /* the slave's next heartbeat (1017h = 100 ms) */
    ck_assert(!co_net_master_nmt_awaited(&master, 5));
    ck_assert_uint_eq(nmt_done_events(), 1);
    ck_assert(!master.nmt_request.pending);
    ck_assert_uint_eq(slaves[1].node.nmt_state, CO_NMT_STOPPED);
    /* To all: every slave of the table confirms; bit 8 flips back. */
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_ENTER_PRE_OPERATIONAL, 0, 500, bus.now));
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
    expect("000#8000");
    expect("704#R1");
    expect("705#R1");
    expect("706#R1");
    advance(100 * MS);
    ck_assert_uint_eq(nmt_done_events(), 2);
    for (uint8_t id = 4; id <= 6; id++)
        ck_assert(!co_net_master_nmt_awaited(&master, id));
}
END_TEST

/* A node that produces no heartbeat confirms by its reply to the guarding request (its toggle
 * bit set aside), at once. */
START_TEST(nmt_command_confirmed_by_a_guarding_reply)
{
    for (size_t i = 0; i < SLAVES; i++) {
        table[i].writes = &writes[1]; /* no 1017h: the slaves send no heartbeat */
        table[i].write_count = 1;
    }
    start_master();
    bus.next = bus.count;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_ENTER_PRE_OPERATIONAL, 6, 500, bus.now));
    advance(0);
    expect("000#8006");
    expect("706#R1");
    ck_assert(sent_later("706#7F")); /* the reply: Pre-operational */
    ck_assert_uint_eq(nmt_done_events(), 1);
    ck_assert(!co_net_master_nmt_awaited(&master, 6));
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_START, 6, 500, bus.now));
    advance(0);
    expect("000#0106");
    expect("706#R1");
    ck_assert(sent_later("706#85")); /* Operational, toggle bit set */
    ck_assert_uint_eq(nmt_done_events(), 2);
}
END_TEST

/* A node that never answers is still awaited when the deadline ends the command, exactly then;
 * a node the master consumes the heartbeat of is not asked by a guarding request. */
START_TEST(nmt_command_unconfirmed_at_its_deadline)
{
    for (size_t i = 0; i < SLAVES; i++)
        table[i].heartbeat_ms = 150;
    start_master();
    bus.next = bus.count;
    co_time_t from = bus.now;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_START, 9, 300, bus.now));
    expect("000#0109");
    expect("709#R1");
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_STOP, 4, 300, bus.now) == false);
    advance(299 * MS);
    ck_assert_uint_eq(nmt_done_events(), 0);
    ck_assert_uint_le(co_net_master_process(&master, bus.now), from + 300 * MS);
    advance(1 * MS);
    ck_assert_uint_eq(nmt_done_events(), 1);
    ck_assert(co_net_master_nmt_awaited(&master, 9));
    bus.next = bus.count;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_STOP, 4, 300, bus.now));
    expect("000#0204");
    ck_assert(!sent_later("704#R1"));
    ck_assert(!co_net_master_nmt(&master, 0x03, 4, 300, bus.now)); /* no such command here */
    ck_assert(!co_net_master_nmt(&master, CO_NMT_CS_START, 128, 300, bus.now));
}
END_TEST

/* A reset is confirmed by the node's boot-up, after which the master boots the slave again. */
START_TEST(nmt_reset_confirmed_by_the_boot_up)
{
    start_master();
    bus.next = bus.count;
    ck_assert(co_net_master_nmt(&master, CO_NMT_CS_RESET_NODE, 4, 300, bus.now));
    advance(0);
    expect("000#8104");
    expect("704#00");
    ck_assert_uint_eq(nmt_done_events(), 1);
    ck_assert(!co_net_master_nmt_awaited(&master, 4));
    expect_boot(4);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x000F);
}
END_TEST

static struct {
    co_net_request_t request;
    co_sdo_client_result_t result;
    size_t count;
} done_log[8];
static size_t done_count;

static void request_done(void *user, const co_net_request_t *request,
                         const co_sdo_client_result_t *result)
{
    ck_assert_ptr_eq(user, &bus);
    ck_assert_uint_lt(done_count, 8);
    done_log[done_count].request = *request;
    done_log[done_count].result = *result;
    done_log[done_count++].count = bus.count;
}

/* SDO requests of the application wait for the master's own client until the boot of the slaves
 * that are ready leaves it free, and run one at a time in the order asked; an abort is the last
 * SDO error; the queue holds CO_NET_REQUEST_MAX. */
START_TEST(sdo_requests_queued_behind_the_boot)
{
    static uint8_t vendor[4], abort_buf[4];
    static uint8_t value[] = {0x44, 0x33, 0x22, 0x11};
    done_count = 0;
    ck_assert(co_net_master_init(&master, &config));
    co_net_request_t read = {.node_id = 4,
                             .index = 0x1018,
                             .subindex = 1,
                             .data = vendor,
                             .len = sizeof vendor,
                             .done = request_done,
                             .user = &bus};
    co_net_request_t write = {.node_id = 5,
                              .index = 0x2000,
                              .subindex = 7,
                              .write = true,
                              .data = value,
                              .len = sizeof value,
                              .done = request_done,
                              .user = &bus};
    co_net_request_t missing = read;
    missing.index = 0x1234;
    missing.subindex = 0;
    missing.data = abort_buf;
    ck_assert(co_net_master_sdo(&master, &read, bus.now));
    ck_assert(co_net_master_sdo(&master, &write, bus.now));
    ck_assert(co_net_master_sdo(&master, &missing, bus.now));
    ck_assert(co_net_master_sdo(&master, &read, bus.now));
    ck_assert(!co_net_master_sdo(&master, &read, bus.now)); /* full */
    co_net_master_start(&master, bus.now);
    advance(0);
    expect("000#8200");
    expect("704#00");
    expect("705#00");
    expect("706#00");
    expect_boot(4);
    expect_boot(5);
    expect_boot(6);
    expect("604#4018100100000000");
    expect("584#431810015F000000");
    expect("605#2300200744332211");
    expect("585#6000200700000000");
    expect("604#4034120000000000");
    expect("584#8034120000000206");
    expect("604#4018100100000000");
    expect("584#431810015F000000");
    ck_assert_uint_eq(done_count, 4);
    ck_assert_uint_eq(done_log[0].result.status, CO_SDO_CLIENT_OK);
    ck_assert_mem_eq(vendor, "\x5F\x00\x00\x00", 4);
    ck_assert(done_log[1].request.write);
    ck_assert_uint_eq(done_log[1].result.status, CO_SDO_CLIENT_OK);
    ck_assert_uint_eq(slave_u32(5, 0x2000, 7), 0x11223344);
    ck_assert_uint_eq(done_log[2].result.status, CO_SDO_CLIENT_SERVER_ABORT);
    ck_assert_uint_eq(done_log[2].result.abort_code, 0x06020000);
    ck_assert_uint_eq(master.last_sdo_error.node_id, 4);
    ck_assert_uint_eq(master.last_sdo_error.index, 0x1234);
    ck_assert_uint_eq(master.last_sdo_error.access, CO_NET_ACCESS_READ);
    ck_assert_uint_eq(master.last_sdo_error.abort_code, 0x06020000);
    ck_assert_uint_eq(co_net_master_status(&master), 0x000F);
}
END_TEST

/* Disabling the master ends the request under way and those queued with 0x05040000, no frame. */
START_TEST(disable_ends_the_sdo_requests)
{
    static uint8_t buf[4];
    done_count = 0;
    start_master();
    slaves[0].present = false; /* node 4 does not answer */
    co_net_request_t read = {.node_id = 4,
                             .index = 0x1018,
                             .subindex = 1,
                             .data = buf,
                             .len = sizeof buf,
                             .done = request_done,
                             .user = &bus};
    ck_assert(co_net_master_sdo(&master, &read, bus.now));
    ck_assert(co_net_master_sdo(&master, &read, bus.now));
    bus.next = bus.count;
    advance(0);
    expect("604#4018100100000000");
    size_t before = bus.count;
    co_net_master_disable(&master, bus.now);
    ck_assert_uint_eq(master_frames_since(before), 0);
    ck_assert_uint_eq(done_count, 2);
    for (size_t k = 0; k < 2; k++) {
        ck_assert_uint_eq(done_log[k].result.status, CO_SDO_CLIENT_CLIENT_ABORT);
        ck_assert_uint_eq(done_log[k].result.abort_code, 0x05040000);
    }
    ck_assert(!co_net_master_sdo(&master, &read, bus.now));
}
END_TEST

static Suite *net_master_suite(void)
{
    Suite *s = suite_create("net_master");
    TCase *tc = tcase_create("net_master");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, full_boot_of_three_slaves);
    tcase_add_test(tc, events_follow_the_steps);
    tcase_add_test(tc, identity_mismatch_is_an_init_error);
    tcase_add_test(tc, device_type_mismatch);
    tcase_add_loop_test(tc, identity_check_gives_its_boot_error, 0,
                        (int)(sizeof identity_checks / sizeof identity_checks[0]));
    tcase_add_test(tc, boot_errors_of_a_silent_and_a_refusing_slave);
    tcase_add_test(tc, expected_identity_1f84_to_1f88_both_ways);
    tcase_add_test(tc, boot_time_1f89_ends_before_a_mandatory_slave);
    tcase_add_test(tc, boot_time_1f89_met);
    tcase_add_test(tc, concise_dcf_1f22_configures_a_slave);
    tcase_add_test(tc, concise_dcf_entry_refused);
    tcase_add_test(tc, concise_dcf_checked_at_init);
    tcase_add_test(tc, configuration_request_1f25);
    tcase_add_test(tc, configuration_from_the_masters_objects);
    tcase_add_test(tc, missing_optional_slave);
    tcase_add_test(tc, mandatory_slave_missing_blocks_start_all);
    tcase_add_test(tc, start_all_after_every_slave);
    tcase_add_test(tc, slave_appearing_late_is_retried_after_the_others);
    tcase_add_test(tc, sdo_abort_of_a_write_is_recorded);
    tcase_add_test(tc, heartbeat_loss_reboots_and_reconfigures);
    tcase_add_test(tc, no_first_heartbeat_is_a_loss);
    tcase_add_test(tc, restart_during_a_transfer);
    tcase_add_test(tc, slave_waiting_for_the_client_asks_for_no_past_deadline);
    tcase_add_test(tc, lost_without_a_first_heartbeat_resumes);
    tcase_add_test(tc, late_heartbeat_of_a_mandatory_slave_before_start_all);
    tcase_add_test(tc, unexpected_boot_up_reboots);
    tcase_add_test(tc, heartbeat_loss_only_reported);
    tcase_add_test(tc, guarding_loss_reboots);
    tcase_add_test(tc, guarded_slave_silent_is_a_node_guarding_error);
    tcase_add_test(tc, heartbeat_producer_silent_is_a_heartbeat_error);
    tcase_add_test(tc, protocol_state_gives_the_first_slave_in_error);
    tcase_add_test(tc, nmt_startup_1f80_both_ways);
    tcase_add_test(tc, slave_assignment_1f81_both_ways);
    tcase_add_test(tc, mandatory_loss_stops_all_nodes);
    tcase_add_test(tc, mandatory_loss_resets_all_nodes);
    tcase_add_test(tc, emcy_is_recorded);
    tcase_add_test(tc, process_image_in);
    tcase_add_test(tc, process_image_out_on_change);
    tcase_add_test(tc, process_image_out_not_to_a_failed_slave);
    tcase_add_test(tc, process_image_out_without_outputs);
    tcase_add_test(tc, process_image_out_on_sync);
    tcase_add_test(tc, configuration_is_checked);
    tcase_add_test(tc, texts);
    tcase_add_test(tc, master_heartbeat_on_its_grid);
    tcase_add_test(tc, master_heartbeat_needs_a_node_id_of_its_own);
    tcase_add_test(tc, disable_stops_every_frame_and_enable_boots_again);
    tcase_add_test(tc, bus_off_and_bus_power_bits);
    tcase_add_test(tc, nmt_command_confirmed_by_the_next_heartbeat);
    tcase_add_test(tc, nmt_command_confirmed_by_a_guarding_reply);
    tcase_add_test(tc, nmt_command_unconfirmed_at_its_deadline);
    tcase_add_test(tc, nmt_reset_confirmed_by_the_boot_up);
    tcase_add_test(tc, sdo_requests_queued_behind_the_boot);
    tcase_add_test(tc, disable_ends_the_sdo_requests);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(net_master_suite());
}
