/* SPDX-License-Identifier: Apache-2.0 */
/* NMT master: exact command frames, node states from boot-up, heartbeat and guarding frames, the
 * heartbeat consumer of 127 nodes (lost exactly at the consumer time, resumed; the first heartbeat
 * awaited from the consumer's start), node guarding
 * (requests on the guard time grid, toggle check, loss after the life time, reset of the toggle),
 * random frames that must leave every state valid, the standalone SYNC producer (counter wrap,
 * exact times, no drift), and the master against the project's own slave node on the in-process
 * bus. Time is injected; no sleeps. */
#include "check_main.h"
#include "co/co_nmt_master.h"
#include "test_bus.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MS 1000u
#define SENT_MAX 4096
#define EVENTS_MAX 512

static co_nmt_master_t master;
static co_time_t now;
static co_time_t master_deadline;

/* Frames the master sent, with their times. */
static co_frame_t sent[SENT_MAX];
static co_time_t sent_at[SENT_MAX];
static size_t sent_count;
static size_t sent_next;

static struct {
    co_nmt_master_event_t event;
    co_time_t at;
} events[EVENTS_MAX];
static size_t event_count;
static size_t events_checked; /* by expect_event */

/* The slave node of the bus tests; the master's frames reach it while `linked`. */
static test_node_t slave;
static bool linked;
static size_t slave_forwarded; /* the slave's frames already delivered to the master */

static void master_send(void *user, const co_frame_t *frame)
{
    (void)user;
    ck_assert_uint_lt(sent_count, SENT_MAX);
    sent[sent_count] = *frame;
    sent_at[sent_count] = now;
    sent_count++;
    if (linked)
        test_rx_frame(&slave, frame);
}

static void on_event(void *user, const co_nmt_master_event_t *event)
{
    (void)user;
    ck_assert_uint_lt(event_count, EVENTS_MAX);
    events[event_count].event = *event;
    events[event_count].at = now;
    event_count++;
}

static void setup(void)
{
    now = 0;
    sent_count = sent_next = event_count = events_checked = 0;
    linked = false;
    co_nmt_master_config_t config = {.send = master_send, .event = on_event};
    ck_assert(co_nmt_master_init(&master, &config));
    master_deadline = co_nmt_master_process(&master, now);
}

#define expect_sent(text) expect_sent_at(text, __FILE__, __LINE__)
static co_time_t expect_sent_at(const char *text, const char *file, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(sent_next < sent_count, "%s:%d: expected %s, the master sent nothing", file, line,
                  want);
    const co_frame_t *g = &sent[sent_next];
    test_format(g, got);
    ck_assert_msg(strcmp(want, got) == 0 && f.flags == g->flags, "%s:%d: expected %s, got %s", file,
                  line, want, got);
    return sent_at[sent_next++];
}

#define expect_sent_none() ck_assert_uint_eq(sent_next, sent_count)

#define expect_event(kind, id, old, state) expect_event_at(kind, id, old, state, __LINE__)
static co_time_t expect_event_at(co_nmt_master_event_kind_t kind, uint8_t node_id, uint8_t old,
                                 uint8_t state, int line)
{
    ck_assert_msg(events_checked < event_count, "line %d: no event", line);
    const co_nmt_master_event_t *e = &events[events_checked].event;
    ck_assert_msg(e->kind == kind && e->node_id == node_id && e->old_state == old &&
                      e->state == state,
                  "line %d: event %d node %u %02X -> %02X, expected %d node %u %02X -> %02X", line,
                  e->kind, e->node_id, e->old_state, e->state, kind, node_id, old, state);
    return events[events_checked++].at;
}

static bool rx(const char *text)
{
    co_frame_t f = test_frame(text);
    bool consumed = co_nmt_master_receive(&master, &f, now);
    master_deadline = co_nmt_master_process(&master, now);
    return consumed;
}

/* Delivers the slave's new frames to the master. */
static void forward_slave_frames(void)
{
    while (slave_forwarded < slave.bus.count) {
        co_nmt_master_receive(&master, &slave.bus.frame[slave_forwarded++], now);
        master_deadline = co_nmt_master_process(&master, now);
    }
}

/* Advances time by `us`, running the master (and the linked slave) at every deadline. */
static void advance(co_time_t us)
{
    co_time_t target = now + us;
    for (;;) {
        co_time_t next = master_deadline;
        if (linked)
            next = co_time_min(next, slave.bus.deadline);
        if (next > target)
            break;
        if (next > now)
            now = next;
        slave.bus.now = now;
        master_deadline = co_nmt_master_process(&master, now);
        ck_assert_uint_gt(master_deadline, now);
        if (linked) {
            slave.bus.deadline = co_node_process(&slave.node, now);
            forward_slave_frames();
        }
    }
    now = target;
    slave.bus.now = now;
}

/* Runs the master now, as a runtime does after a change. */
static void process(void)
{
    master_deadline = co_nmt_master_process(&master, now);
    if (linked)
        forward_slave_frames();
}

static void command(uint8_t cs, uint8_t node_id)
{
    ck_assert(co_nmt_master_command(&master, cs, node_id));
    if (linked)
        forward_slave_frames();
}

START_TEST(init_needs_a_send_callback)
{
    co_nmt_master_t m;
    co_nmt_master_config_t config = {.send = NULL};
    ck_assert(!co_nmt_master_init(&m, &config));
    ck_assert(!co_nmt_master_init(&m, NULL));
    ck_assert_uint_eq(master_deadline, CO_TIME_NEVER);
    for (uint8_t id = 1; id <= 127; id++)
        ck_assert_uint_eq(co_nmt_master_state(&master, id), CO_NMT_MASTER_STATE_UNKNOWN);
    ck_assert_uint_eq(co_nmt_master_state(&master, 0), CO_NMT_MASTER_STATE_UNKNOWN);
    ck_assert_uint_eq(co_nmt_master_state(&master, 128), CO_NMT_MASTER_STATE_UNKNOWN);
}
END_TEST

START_TEST(commands_to_one_node_and_to_all)
{
    command(CO_NMT_CS_START, 5);
    command(CO_NMT_CS_STOP, 127);
    command(CO_NMT_CS_ENTER_PRE_OPERATIONAL, 1);
    command(CO_NMT_CS_RESET_NODE, 0x22);
    command(CO_NMT_CS_RESET_COMMUNICATION, CO_NMT_MASTER_ALL_NODES);
    command(CO_NMT_CS_START, CO_NMT_MASTER_ALL_NODES);
    expect_sent("000#0105");
    expect_sent("000#027F");
    expect_sent("000#8001");
    expect_sent("000#8122");
    expect_sent("000#8200");
    expect_sent("000#0100");
    expect_sent_none();
}
END_TEST

START_TEST(bad_commands_send_nothing)
{
    ck_assert(!co_nmt_master_command(&master, 0x03, 5)); /* the ATV58's own command 3 */
    ck_assert(!co_nmt_master_command(&master, 0x00, 5));
    ck_assert(!co_nmt_master_command(&master, 0x83, 5));
    ck_assert(!co_nmt_master_command(&master, CO_NMT_CS_START, 128));
    ck_assert(!co_nmt_master_command(&master, CO_NMT_CS_START, 255));
    expect_sent_none();
}
END_TEST

START_TEST(state_from_boot_up_then_heartbeats)
{
    ck_assert(rx("705#00"));
    expect_event(CO_NMT_MASTER_BOOT_UP, 5, CO_NMT_MASTER_STATE_UNKNOWN, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(co_nmt_master_state(&master, 5), CO_NMT_PRE_OPERATIONAL);
    ck_assert(rx("705#7F"));
    ck_assert_uint_eq(event_count, 1); /* no change */
    ck_assert(rx("705#05"));
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 5, CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL);
    ck_assert(rx("705#05"));
    ck_assert(rx("705#04"));
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 5, CO_NMT_OPERATIONAL, CO_NMT_STOPPED);
    ck_assert(rx("705#00"));
    expect_event(CO_NMT_MASTER_BOOT_UP, 5, CO_NMT_STOPPED, CO_NMT_PRE_OPERATIONAL);
    ck_assert(rx("77F#05"));
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 127, CO_NMT_MASTER_STATE_UNKNOWN, CO_NMT_OPERATIONAL);
    ck_assert_uint_eq(event_count, 5);
    ck_assert_uint_eq(co_nmt_master_state(&master, 6), CO_NMT_MASTER_STATE_UNKNOWN);
    expect_sent_none();
}
END_TEST

START_TEST(foreign_and_malformed_frames_ignored)
{
    ck_assert(rx("705#7F"));
    size_t before = event_count;
    ck_assert(!rx("705#33"));   /* not a CiA 301 state */
    ck_assert(!rx("705#80"));   /* a toggle bit on Initialising */
    ck_assert(!rx("705#0500")); /* 2 bytes */
    ck_assert(!rx("705#"));
    ck_assert(!rx("705#R1"));
    ck_assert(!rx("700#05")); /* node-id 0 */
    ck_assert(!rx("780#05"));
    ck_assert(!rx("605#05"));
    co_frame_t extended = test_frame("705#05");
    extended.flags = CO_FRAME_EFF;
    ck_assert(!co_nmt_master_receive(&master, &extended, now));
    ck_assert_uint_eq(event_count, before);
    ck_assert_uint_eq(co_nmt_master_state(&master, 5), CO_NMT_PRE_OPERATIONAL);
}
END_TEST

START_TEST(heartbeat_lost_exactly_at_consumer_time)
{
    ck_assert(co_nmt_master_heartbeat(&master, 5, 150));
    master_deadline = co_nmt_master_process(&master, now);
    advance(10000 * MS); /* not monitored before the first heartbeat */
    ck_assert_uint_eq(master_deadline, CO_TIME_NEVER);
    ck_assert_uint_eq(event_count, 0);
    ck_assert(rx("705#7F"));
    co_time_t beat = now;
    ck_assert_uint_eq(master_deadline, beat + 150 * MS);
    ck_assert_uint_eq(co_nmt_master_process(&master, beat + 150 * MS - 1), beat + 150 * MS);
    ck_assert_uint_eq(event_count, 1); /* only the state change */
    ck_assert(!co_nmt_master_lost(&master, 5));
    now = beat + 150 * MS;
    ck_assert_uint_eq(co_nmt_master_process(&master, now), CO_TIME_NEVER);
    ck_assert_uint_eq(event_count, 2);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 5, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(expect_event(CO_NMT_MASTER_HEARTBEAT_LOST, 5, CO_NMT_PRE_OPERATIONAL,
                                   CO_NMT_PRE_OPERATIONAL),
                      beat + 150 * MS);
    ck_assert(co_nmt_master_lost(&master, 5));
    advance(1000 * MS); /* reported once */
    ck_assert_uint_eq(event_count, 2);
    ck_assert(rx("705#05"));
    expect_event(CO_NMT_MASTER_RESUMED, 5, CO_NMT_PRE_OPERATIONAL, CO_NMT_PRE_OPERATIONAL);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 5, CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL);
    ck_assert(!co_nmt_master_lost(&master, 5));
    ck_assert_uint_eq(master_deadline, now + 150 * MS);
    expect_sent_none();
}
END_TEST

/* A master that has just set a node's producer time awaits its first heartbeat from then: none
 * is a loss exactly one consumer time later, and the late first heartbeat resumes the node. */
START_TEST(awaited_heartbeat_lost_without_a_first_one)
{
    now = 1000 * MS;
    ck_assert(co_nmt_master_await_heartbeat(&master, 5, 150, now));
    master_deadline = co_nmt_master_process(&master, now);
    ck_assert_uint_eq(master_deadline, now + 150 * MS);
    advance(150 * MS - 1);
    ck_assert_uint_eq(event_count, 0);
    ck_assert(!co_nmt_master_lost(&master, 5));
    advance(1);
    ck_assert_uint_eq(expect_event(CO_NMT_MASTER_HEARTBEAT_LOST, 5, CO_NMT_MASTER_STATE_UNKNOWN,
                                   CO_NMT_MASTER_STATE_UNKNOWN),
                      1150 * MS);
    ck_assert(co_nmt_master_lost(&master, 5));
    ck_assert_uint_eq(master_deadline, CO_TIME_NEVER);
    advance(1000 * MS);
    ck_assert(rx("705#7F"));
    expect_event(CO_NMT_MASTER_RESUMED, 5, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_MASTER_STATE_UNKNOWN);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 5, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_PRE_OPERATIONAL);
    ck_assert(!co_nmt_master_lost(&master, 5));
    ck_assert_uint_eq(master_deadline, now + 150 * MS);
    /* Refused where co_nmt_master_heartbeat is; time 0 stops the consumer. */
    ck_assert(!co_nmt_master_await_heartbeat(&master, 0, 150, now));
    ck_assert(!co_nmt_master_await_heartbeat(&master, 128, 150, now));
    ck_assert(co_nmt_master_guard(&master, 6, 100, 3, now));
    ck_assert(!co_nmt_master_await_heartbeat(&master, 6, 150, now));
    ck_assert(co_nmt_master_guard(&master, 6, 0, 0, now));
    ck_assert(co_nmt_master_await_heartbeat(&master, 5, 0, now));
    ck_assert_uint_eq(co_nmt_master_process(&master, now), CO_TIME_NEVER);
    ck_assert_uint_eq(event_count, events_checked);
    expect_sent_none();
}
END_TEST

START_TEST(heartbeat_rearmed_by_each_frame_and_boot_up)
{
    ck_assert(co_nmt_master_heartbeat(&master, 9, 100));
    ck_assert(rx("709#05"));
    for (int i = 0; i < 20; i++) {
        advance(99 * MS);
        ck_assert(rx("709#05"));
    }
    advance(60 * MS);
    ck_assert(rx("709#00")); /* a boot-up is a sign of life */
    advance(99999);
    ck_assert(!co_nmt_master_lost(&master, 9));
    advance(1);
    ck_assert(co_nmt_master_lost(&master, 9));
    ck_assert_uint_eq(event_count, 3);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 9, CO_NMT_MASTER_STATE_UNKNOWN, CO_NMT_OPERATIONAL);
    expect_event(CO_NMT_MASTER_BOOT_UP, 9, CO_NMT_OPERATIONAL, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(expect_event(CO_NMT_MASTER_HEARTBEAT_LOST, 9, CO_NMT_PRE_OPERATIONAL,
                                   CO_NMT_PRE_OPERATIONAL),
                      20 * 99 * MS + 60 * MS + 100 * MS);
    /* Consumer time 0 stops monitoring; a new time waits for the next frame again. */
    ck_assert(co_nmt_master_heartbeat(&master, 9, 0));
    ck_assert(!co_nmt_master_lost(&master, 9));
    ck_assert(rx("709#7F"));
    ck_assert_uint_eq(master_deadline, CO_TIME_NEVER);
}
END_TEST

START_TEST(heartbeat_of_127_producers_one_lost)
{
    char text[16];
    for (uint8_t id = 1; id <= 127; id++)
        ck_assert(co_nmt_master_heartbeat(&master, id, 50));
    for (uint8_t id = 1; id <= 127; id++) {
        snprintf(text, sizeof(text), "%03X#05", 0x700 + id);
        ck_assert(rx(text));
    }
    ck_assert_uint_eq(event_count, 127); /* unknown -> operational, each */
    event_count = 0;
    for (int period = 1; period <= 10; period++) {
        advance(40 * MS);
        for (uint8_t id = 1; id <= 127; id++) {
            snprintf(text, sizeof(text), "%03X#05", 0x700 + id);
            if (id != 42)
                ck_assert(rx(text));
        }
    }
    ck_assert_uint_eq(event_count, 1);
    ck_assert_uint_eq(events[0].event.kind, CO_NMT_MASTER_HEARTBEAT_LOST);
    ck_assert_uint_eq(events[0].event.node_id, 42);
    ck_assert_uint_eq(events[0].at, 50 * MS);
    for (uint8_t id = 1; id <= 127; id++)
        ck_assert(co_nmt_master_lost(&master, id) == (id == 42));
    ck_assert_uint_eq(master_deadline, now + 50 * MS);
}
END_TEST

START_TEST(one_error_control_protocol_per_node)
{
    ck_assert(co_nmt_master_heartbeat(&master, 3, 100));
    ck_assert(!co_nmt_master_guard(&master, 3, 100, 3, now));
    ck_assert(co_nmt_master_guard(&master, 4, 100, 3, now));
    ck_assert(!co_nmt_master_heartbeat(&master, 4, 100));
    ck_assert(!co_nmt_master_heartbeat(&master, 0, 100));
    ck_assert(!co_nmt_master_heartbeat(&master, 128, 100));
    ck_assert(!co_nmt_master_guard(&master, 0, 100, 3, now));
    ck_assert(!co_nmt_master_guard(&master, 128, 100, 3, now));
    /* Switched off, the other protocol may be chosen. */
    ck_assert(co_nmt_master_guard(&master, 4, 0, 3, now));
    ck_assert(co_nmt_master_heartbeat(&master, 4, 100));
    ck_assert(co_nmt_master_heartbeat(&master, 3, 0));
    ck_assert(co_nmt_master_guard(&master, 3, 100, 3, now));
}
END_TEST

/* Guards node 3 from `now` and checks the first request goes out at once. */
static void guard_node_3(uint16_t guard_ms, uint8_t factor)
{
    ck_assert(co_nmt_master_guard(&master, 3, guard_ms, factor, now));
    master_deadline = co_nmt_master_process(&master, now);
    ck_assert_uint_eq(expect_sent("703#R1"), now);
    ck_assert_uint_eq(master_deadline, now + guard_ms * MS);
}

START_TEST(guarding_requests_on_the_guard_time_grid)
{
    advance(7 * MS);
    guard_node_3(100, 3);
    for (int k = 1; k <= 50; k++) {
        ck_assert(rx(k % 2 ? "703#7F" : "703#FF")); /* toggle 0, 1, 0, ... */
        advance(100 * MS);
        ck_assert_uint_eq(expect_sent("703#R1"), 7 * MS + (co_time_t)k * 100 * MS);
    }
    expect_sent_none();
    ck_assert_uint_eq(event_count, 1);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 3, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_PRE_OPERATIONAL);
    ck_assert(!co_nmt_master_lost(&master, 3));
    /* The state comes from the replies. */
    ck_assert(rx("703#05"));
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 3, CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL);
}
END_TEST

START_TEST(guarding_requests_stay_on_the_grid_when_called_late)
{
    guard_node_3(100, 3);
    for (co_time_t k = 1; k <= 20; k++) {
        ck_assert(rx(k % 2 ? "703#7F" : "703#FF"));
        now = k * 100 * MS + 700; /* the runtime's timer fired 700 us late */
        ck_assert_uint_eq(co_nmt_master_process(&master, now), (k + 1) * 100 * MS);
        ck_assert_uint_eq(expect_sent("703#R1"), now);
    }
    expect_sent_none();
    ck_assert(!co_nmt_master_lost(&master, 3));
}
END_TEST

START_TEST(guarding_lost_after_life_time_without_replies)
{
    guard_node_3(100, 3);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    expect_sent("703#R1"); /* at 100 ms: never answered */
    advance(300 * MS - 1);
    ck_assert_uint_eq(event_count, 1); /* the state change only */
    ck_assert(!co_nmt_master_lost(&master, 3));
    advance(1);
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(events[1].event.kind, CO_NMT_MASTER_GUARDING_LOST);
    ck_assert_uint_eq(events[1].event.state, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(events[1].at, 400 * MS); /* life time after the unanswered request */
    /* Requests go on, the loss is reported once; the right toggle resumes the node. */
    advance(1000 * MS);
    ck_assert_uint_eq(sent_count, 1 + 4 + 10);
    ck_assert_uint_eq(event_count, 2);
    ck_assert(rx("703#7F")); /* the same toggle as the last reply: not a reply */
    ck_assert_uint_eq(event_count, 2);
    ck_assert(rx("703#FF"));
    ck_assert_uint_eq(event_count, 3);
    ck_assert_uint_eq(events[2].event.kind, CO_NMT_MASTER_RESUMED);
    ck_assert(!co_nmt_master_lost(&master, 3));
}
END_TEST

START_TEST(guarding_wrong_toggle_counts_as_no_reply)
{
    guard_node_3(100, 2);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    /* A slave that stopped toggling: every reply after the first one is wrong. */
    for (int k = 0; k < 2; k++) {
        ck_assert(rx("703#7F"));
        advance(100 * MS);
    }
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(events[1].event.kind, CO_NMT_MASTER_GUARDING_LOST);
    ck_assert_uint_eq(events[1].at, 300 * MS);
    /* A wrong reply neither resumes the node nor changes its state. */
    ck_assert(rx("703#05"));
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(co_nmt_master_state(&master, 3), CO_NMT_PRE_OPERATIONAL);
    ck_assert(co_nmt_master_lost(&master, 3));
}
END_TEST

START_TEST(guarding_one_wrong_toggle_within_life_time_is_tolerated)
{
    guard_node_3(100, 2);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    ck_assert(rx("703#05")); /* toggle 0 again: ignored, state stays */
    ck_assert_uint_eq(co_nmt_master_state(&master, 3), CO_NMT_PRE_OPERATIONAL);
    advance(100 * MS);
    ck_assert(rx("703#FF")); /* the slave's next toggle is checked against the opposite bit */
    for (int k = 0; k < 10; k++) {
        advance(100 * MS);
        ck_assert(rx(k % 2 ? "703#FF" : "703#7F"));
    }
    ck_assert_uint_eq(event_count, 1);
    ck_assert(!co_nmt_master_lost(&master, 3));
}
END_TEST

START_TEST(reset_communication_restarts_the_toggle)
{
    guard_node_3(100, 2);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    /* The next valid toggle is 1; after a reset of the node it is 0 again. */
    command(CO_NMT_CS_RESET_COMMUNICATION, 3);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    command(CO_NMT_CS_RESET_NODE, CO_NMT_MASTER_ALL_NODES);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    /* The boot-up restarts it too. */
    ck_assert(rx("703#00"));
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    ck_assert_uint_eq(event_count, 2);
    ck_assert(!co_nmt_master_lost(&master, 3));
    /* A reset of another node leaves it alone: 0 is now the wrong toggle. */
    command(CO_NMT_CS_RESET_COMMUNICATION, 4);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    ck_assert(rx("703#7F"));
    advance(100 * MS);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 3, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_PRE_OPERATIONAL);
    expect_event(CO_NMT_MASTER_BOOT_UP, 3, CO_NMT_PRE_OPERATIONAL, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(expect_event(CO_NMT_MASTER_GUARDING_LOST, 3, CO_NMT_PRE_OPERATIONAL,
                                   CO_NMT_PRE_OPERATIONAL),
                      600 * MS);
    const char *frames[] = {"703#R1", "000#8203", "703#R1", "000#8100", "703#R1",
                            "703#R1", "000#8204", "703#R1", "703#R1"};
    const unsigned at_ms[] = {100, 100, 200, 200, 300, 400, 400, 500, 600};
    for (size_t i = 0; i < sizeof(frames) / sizeof(frames[0]); i++)
        ck_assert_uint_eq(expect_sent(frames[i]), at_ms[i] * MS);
    expect_sent_none();
}
END_TEST

START_TEST(guarding_off_sends_nothing)
{
    guard_node_3(100, 3);
    ck_assert(co_nmt_master_guard(&master, 3, 0, 3, now));
    master_deadline = co_nmt_master_process(&master, now);
    ck_assert_uint_eq(master_deadline, CO_TIME_NEVER);
    advance(10000 * MS);
    expect_sent_none();
    ck_assert(co_nmt_master_guard(&master, 3, 100, 0, now));
    ck_assert_uint_eq(co_nmt_master_process(&master, now), CO_TIME_NEVER);
    expect_sent_none();
}
END_TEST

/* xorshift32: the same sequence every run. */
static uint32_t random_next(uint32_t *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    return *state;
}

static bool state_is_known_or_unknown(uint8_t state)
{
    return state == CO_NMT_MASTER_STATE_UNKNOWN || state == CO_NMT_STOPPED ||
           state == CO_NMT_OPERATIONAL || state == CO_NMT_PRE_OPERATIONAL;
}

START_TEST(random_frames_never_corrupt_the_states)
{
    for (uint8_t id = 1; id <= 4; id++) {
        ck_assert(co_nmt_master_heartbeat(&master, id, 20));
        ck_assert(co_nmt_master_guard(&master, (uint8_t)(id + 4), 10, 2, now));
    }
    uint32_t seed = 0x12345678u;
    size_t requests = 0;
    unsigned kinds[CO_NMT_MASTER_RESUMED + 1] = {0};
    static const uint8_t states[] = {0x00, 0x04, 0x05, 0x7F};
    for (int i = 0; i < 5000; i++) {
        /* Frames on 700h-7FFh for the 8 nodes watched and others, mostly 1 byte, half of them with
         * a state byte and a random toggle bit, some RTR or 29-bit, at random intervals. */
        co_frame_t f = {.len = 1};
        bool watched = random_next(&seed) % 2;
        f.id = 0x700u + (watched ? 1 + random_next(&seed) % 8 : random_next(&seed) % 0x100);
        if (random_next(&seed) % 4 == 0)
            f.len = (uint8_t)(random_next(&seed) % 16);
        if (random_next(&seed) % 8 == 0)
            f.flags = (uint8_t)(random_next(&seed) % 4);
        for (int b = 0; b < 8; b++)
            f.data[b] = (uint8_t)random_next(&seed);
        if (random_next(&seed) % 2) {
            uint8_t state = states[random_next(&seed) % 4];
            f.data[0] = (uint8_t)(state | (random_next(&seed) % 2) << 7);
        }
        now += random_next(&seed) % 30000;
        co_nmt_master_receive(&master, &f, now);
        master_deadline = co_nmt_master_process(&master, now);
        ck_assert_uint_gt(master_deadline, now);
        requests += sent_count;
        sent_count = sent_next = 0;
        for (size_t e = 0; e < event_count; e++)
            kinds[events[e].event.kind]++;
        event_count = 0;
    }
    for (unsigned id = 0; id <= 255; id++)
        ck_assert(state_is_known_or_unknown(co_nmt_master_state(&master, (uint8_t)id)));
    ck_assert_uint_gt(requests, 1000);
    for (int kind = CO_NMT_MASTER_BOOT_UP; kind <= CO_NMT_MASTER_RESUMED; kind++)
        ck_assert_msg(kinds[kind] > 10, "event %d: %u", kind, kinds[kind]);
}
END_TEST

/* The SYNC producer a master program runs without a node. */
static co_sync_producer_t sync;

static size_t sync_run_until(co_time_t target, co_frame_t *frames, co_time_t *at, size_t max)
{
    size_t n = 0;
    while (sync.next <= target) {
        co_time_t t = sync.next;
        ck_assert(!co_sync_producer_take(&sync, t - 1, &frames[n]));
        ck_assert(co_sync_producer_take(&sync, t, &frames[n]));
        ck_assert_uint_lt(n, max);
        at[n++] = t;
    }
    return n;
}

START_TEST(sync_producer_parameters)
{
    ck_assert(!co_sync_producer_init(&sync, 0x080, 0, 0));
    ck_assert(!co_sync_producer_init(&sync, 0x080, 1000, 1));
    ck_assert(!co_sync_producer_init(&sync, 0x080, 1000, 241));
    ck_assert(!co_sync_producer_init(&sync, 0x800, 1000, 0));
    for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++)
        ck_assert(!co_sync_producer_init(&sync, test_restricted_can_id[i], 1000, 0));
    for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++)
        ck_assert(co_sync_producer_init(&sync, test_free_can_id[i], 1000, 0));
    ck_assert(co_sync_producer_init(&sync, 0x080, 1000, 2));
    ck_assert(co_sync_producer_init(&sync, 0x080, 1000, 240));
    ck_assert_uint_eq(sync.next, CO_TIME_NEVER); /* stopped until started */
    co_frame_t f;
    ck_assert(!co_sync_producer_take(&sync, 1000000, &f));
}
END_TEST

START_TEST(sync_producer_counter_wraps_at_overflow)
{
    ck_assert(co_sync_producer_init(&sync, 0x080, 10 * MS, 3));
    co_sync_producer_start(&sync, 5 * MS);
    co_frame_t f[8];
    co_time_t at[8];
    ck_assert_uint_eq(sync_run_until(45 * MS, f, at, 8), 4);
    const char *want[] = {"080#01", "080#02", "080#03", "080#01"};
    char got[32];
    for (int k = 0; k < 4; k++) {
        ck_assert_str_eq(test_format(&f[k], got), want[k]);
        ck_assert_uint_eq(at[k], 5 * MS + (co_time_t)(k + 1) * 10 * MS);
    }
    /* A restart begins a new grid and the counter at 1 again. */
    co_sync_producer_start(&sync, 47 * MS);
    ck_assert_uint_eq(sync_run_until(57 * MS, f, at, 8), 1);
    ck_assert_str_eq(test_format(&f[0], got), "080#01");
    ck_assert_uint_eq(at[0], 57 * MS);
    co_sync_producer_stop(&sync);
    ck_assert_uint_eq(sync.next, CO_TIME_NEVER);
}
END_TEST

START_TEST(sync_producer_without_counter_on_its_cob_id)
{
    ck_assert(co_sync_producer_init(&sync, 0x0C0, 2500, 0));
    co_sync_producer_start(&sync, 0);
    co_frame_t f[4];
    co_time_t at[4];
    ck_assert_uint_eq(sync_run_until(7500, f, at, 4), 3);
    char got[32];
    for (int k = 0; k < 3; k++) {
        ck_assert_str_eq(test_format(&f[k], got), "0C0#");
        ck_assert_uint_eq(at[k], (co_time_t)(k + 1) * 2500);
    }
}
END_TEST

START_TEST(sync_producer_does_not_drift_over_1000_periods)
{
    /* An odd period, and each call a little late (as a runtime's timer is): the schedule stays on
     * start + k x period, it is never rebuilt from the late call. */
    const co_time_t start = 123457, period = 3333;
    ck_assert(co_sync_producer_init(&sync, 0x080, period, 240));
    co_sync_producer_start(&sync, start);
    co_frame_t f;
    for (co_time_t k = 1; k <= 1000; k++) {
        co_time_t due = start + k * period;
        ck_assert_uint_eq(sync.next, due);
        ck_assert(!co_sync_producer_take(&sync, due - 1, &f));
        ck_assert(co_sync_producer_take(&sync, due + k % 500, &f));
        ck_assert_uint_eq(f.len, 1);
        ck_assert_uint_eq(f.data[0], (k - 1) % 240 + 1);
        ck_assert(!co_sync_producer_take(&sync, due + k % 500, &f)); /* one per period */
    }
    ck_assert_uint_eq(sync.next, start + 1001 * period);
}
END_TEST

START_TEST(sync_producer_late_by_periods_sends_one)
{
    ck_assert(co_sync_producer_init(&sync, 0x080, 10 * MS, 0));
    co_sync_producer_start(&sync, 0);
    co_frame_t f;
    ck_assert(co_sync_producer_take(&sync, 55 * MS, &f));
    ck_assert(!co_sync_producer_take(&sync, 55 * MS, &f));
    ck_assert_uint_eq(sync.next, 65 * MS);
}
END_TEST

/* The slave node on the in-process bus, linked to the master. */
static void link_slave(uint8_t node_id, const co_app_hooks_t *hooks)
{
    test_node_start(&slave, node_id, hooks, NULL);
    slave_forwarded = slave.bus.count; /* the boot-up went out before the master listened */
    linked = true;
}

START_TEST(master_boots_the_project_slave)
{
    link_slave(4, NULL);
    ck_assert(co_nmt_master_heartbeat(&master, 4, 150));
    command(CO_NMT_CS_RESET_COMMUNICATION, 4);
    expect_event(CO_NMT_MASTER_BOOT_UP, 4, CO_NMT_MASTER_STATE_UNKNOWN, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(co_nmt_master_state(&master, 4), CO_NMT_PRE_OPERATIONAL);
    /* The configuration an SDO client would download: heartbeat producer 100 ms. */
    ck_assert_uint_eq(test_write(&slave, 0x1017, 0, 100, 2), 0);
    command(CO_NMT_CS_START, 4);
    ck_assert_uint_eq(slave.node.nmt_state, CO_NMT_OPERATIONAL);
    advance(100 * MS);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 4, CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL);
    advance(1000 * MS);
    ck_assert_uint_eq(event_count, 2);
    ck_assert_uint_eq(co_nmt_master_state(&master, 4), CO_NMT_OPERATIONAL);
    command(CO_NMT_CS_STOP, CO_NMT_MASTER_ALL_NODES);
    advance(100 * MS);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 4, CO_NMT_OPERATIONAL, CO_NMT_STOPPED);
    /* The slave goes silent: lost exactly one consumer time after its last heartbeat. */
    co_time_t last = slave.bus.at[slave.bus.count - 1];
    linked = false;
    advance(200 * MS);
    ck_assert_uint_eq(expect_event(CO_NMT_MASTER_HEARTBEAT_LOST, 4, CO_NMT_STOPPED, CO_NMT_STOPPED),
                      last + 150 * MS);
}
END_TEST

static unsigned slave_life_guarding_losses;

static void on_slave_guarding(co_node_t *node, bool lost)
{
    (void)node;
    if (lost)
        slave_life_guarding_losses++;
}

START_TEST(master_guards_the_project_slave)
{
    static const co_app_hooks_t hooks = {.guarding = on_slave_guarding};
    slave_life_guarding_losses = 0;
    link_slave(4, &hooks);
    ck_assert_uint_eq(test_write(&slave, 0x100C, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&slave, 0x100D, 0, 3, 1), 0);
    ck_assert(co_nmt_master_guard(&master, 4, 100, 3, now));
    process();
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 4, CO_NMT_MASTER_STATE_UNKNOWN,
                 CO_NMT_PRE_OPERATIONAL);
    command(CO_NMT_CS_START, 4);
    advance(2000 * MS);
    expect_event(CO_NMT_MASTER_STATE_CHANGED, 4, CO_NMT_PRE_OPERATIONAL, CO_NMT_OPERATIONAL);
    /* A reset communication on the way: the slave's toggle restarts at 0, so does the master's. */
    command(CO_NMT_CS_RESET_COMMUNICATION, 4);
    expect_event(CO_NMT_MASTER_BOOT_UP, 4, CO_NMT_OPERATIONAL, CO_NMT_PRE_OPERATIONAL);
    ck_assert_uint_eq(test_write(&slave, 0x100C, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&slave, 0x100D, 0, 3, 1), 0);
    advance(2000 * MS);
    ck_assert_uint_eq(event_count, 3);
    ck_assert_uint_eq(slave_life_guarding_losses, 0);
    /* Two commands, and one request per guard time from 0 to 4000 ms. */
    ck_assert_uint_eq(sent_count, 2 + 41);
    /* The master stops guarding: the slave's life guarding fires after its life time. */
    ck_assert(co_nmt_master_guard(&master, 4, 0, 0, now));
    process();
    advance(1000 * MS);
    ck_assert_uint_eq(slave_life_guarding_losses, 1);
    ck_assert_uint_eq(event_count, 3);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("nmt_master");
    TCase *tc = tcase_create("nmt_master");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, init_needs_a_send_callback);
    tcase_add_test(tc, commands_to_one_node_and_to_all);
    tcase_add_test(tc, bad_commands_send_nothing);
    tcase_add_test(tc, state_from_boot_up_then_heartbeats);
    tcase_add_test(tc, foreign_and_malformed_frames_ignored);
    tcase_add_test(tc, heartbeat_lost_exactly_at_consumer_time);
    tcase_add_test(tc, awaited_heartbeat_lost_without_a_first_one);
    tcase_add_test(tc, heartbeat_rearmed_by_each_frame_and_boot_up);
    tcase_add_test(tc, heartbeat_of_127_producers_one_lost);
    tcase_add_test(tc, one_error_control_protocol_per_node);
    tcase_add_test(tc, guarding_requests_on_the_guard_time_grid);
    tcase_add_test(tc, guarding_requests_stay_on_the_grid_when_called_late);
    tcase_add_test(tc, guarding_lost_after_life_time_without_replies);
    tcase_add_test(tc, guarding_wrong_toggle_counts_as_no_reply);
    tcase_add_test(tc, guarding_one_wrong_toggle_within_life_time_is_tolerated);
    tcase_add_test(tc, reset_communication_restarts_the_toggle);
    tcase_add_test(tc, guarding_off_sends_nothing);
    tcase_add_test(tc, random_frames_never_corrupt_the_states);
    tcase_add_test(tc, sync_producer_parameters);
    tcase_add_test(tc, sync_producer_counter_wraps_at_overflow);
    tcase_add_test(tc, sync_producer_without_counter_on_its_cob_id);
    tcase_add_test(tc, sync_producer_does_not_drift_over_1000_periods);
    tcase_add_test(tc, sync_producer_late_by_periods_sends_one);
    tcase_add_test(tc, master_boots_the_project_slave);
    tcase_add_test(tc, master_guards_the_project_slave);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
