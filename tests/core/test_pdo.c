/* SPDX-License-Identifier: Apache-2.0 */
/* PDO engine: ATV312 manual vectors T31-02..T31-07, transmission types, inhibit and event timers,
 * SYNC start value, RTR, the dynamic mapping procedure and every abort of it, RPDO length and
 * deadline emergencies, NMT gating. Frame-exact on the in-process bus, with injected time. */
#include "check_main.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdlib.h>

#define MS 1000u

static test_node_t t;
static unsigned rpdo_calls;
static uint16_t rpdo_last;
static unsigned pdo_writes;

static void on_rpdo(co_node_t *node, uint16_t number)
{
    (void)node;
    rpdo_calls++;
    rpdo_last = number;
}

static void on_written(co_node_t *node, const co_od_entry_t *entry, co_od_origin_t origin)
{
    (void)node;
    (void)entry;
    if (origin == CO_OD_ORIGIN_PDO)
        pdo_writes++;
}

static const co_app_hooks_t hooks = {.rpdo = on_rpdo, .od_written = on_written};

/* A parameter write with every check of the SDO path, at the bus's current time. */
static uint32_t write_param(uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    uint8_t data[4];
    co_put_u32(data, value);
    t.node.now = t.bus.now;
    uint32_t abort = co_od_write(&t.node, index, sub, data, len, CO_OD_ORIGIN_SDO);
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    return abort;
}

/* The application changed mapped data and runs the node, as co_node.h asks. */
static void app_set(uint16_t index, uint8_t sub, int64_t value)
{
    ck_assert(co_od_set_value(&t.node, index, sub, value));
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

static void start_od(const co_od_t *od)
{
    rpdo_calls = 0;
    rpdo_last = 0;
    pdo_writes = 0;
    test_node_start_od(&t, od, 4, &hooks, NULL);
}

static void start(void)
{
    start_od(&test_od);
}

/* Node 4 with TPDO1's event timer off, so only changes make it transmit. */
static void start_quiet(void)
{
    start();
    ck_assert_uint_eq(write_param(0x1800, 5, 0, 2), 0);
}

static void go_operational(void)
{
    test_rx(&t, "000#0104");
}

/* TPDO6 valid with the given transmission type; TPDO1 disabled so only TPDO6 talks. */
static void tpdo6_only(uint8_t type)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1800, 1, 0x80000184, 4), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, type, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 5, 0, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
}

/* RPDO6 on 304h with the given mapping entries (CiA 301 procedure), the node operational. */
static void rpdo6_mapped(const uint32_t *entries, uint8_t count)
{
    ck_assert_uint_eq(write_param(0x1605, 0, 0, 1), 0);
    for (uint8_t i = 0; i < count; i++)
        ck_assert_uint_eq(write_param(0x1605, (uint8_t)(i + 1), entries[i], 4), 0);
    ck_assert_uint_eq(write_param(0x1605, 0, count, 1), 0);
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
}

static void sync_frame(const char *text)
{
    test_rx(&t, text);
}

/* ---- ATV312 manual vectors ----------------------------------------------------------- */

START_TEST(t31_02_tpdo1_status_word)
{
    start_quiet();
    go_operational();
    /* Entering Operational sends the current data once. */
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 0);
    test_advance(&t, 100 * MS);
    app_set(0x6041, 0, 0x0607);
    ck_assert_uint_eq(test_expect(&t, "184#0706"), 100 * MS);
    test_advance(&t, 1000 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

START_TEST(t31_03_rpdo1_control_word)
{
    start_quiet();
    go_operational();
    test_drain(&t);
    test_rx(&t, "204#0F00");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_uint_eq(rpdo_calls, 1);
    ck_assert_uint_eq(rpdo_last, 1);
    ck_assert_uint_eq(pdo_writes, 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(t31_04_tpdo6_default_mapping)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    co_od_set_value(&t.node, 0x6041, 0, 0x0607);
    co_od_set_value(&t.node, 0x6044, 0, 1500);
    go_operational();
    test_expect(&t, "184#0706");
    test_expect(&t, "284#0706DC05");
    test_expect_none(&t);
}
END_TEST

START_TEST(t31_05_rpdo6_default_mapping)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    test_rx(&t, "304#0F00B004");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), 1200);
    ck_assert_uint_eq(rpdo_last, 6);
}
END_TEST

/* The manual's procedure, by SDO frames: invalidate, sub 0 = 0, entries, sub 0 = 4, validate. */
START_TEST(t31_06_tpdo6_user_mapping)
{
    start_quiet();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1805, 1, 0x80000284, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 1, 0x60410010, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 2, 0x60440010, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 3, 0x20020410, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 4, 0x20020910, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 0, 4, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1805, 1, 0x284, 4), 0);
    co_od_set_value(&t.node, 0x6041, 0, 0x0607);
    co_od_set_value(&t.node, 0x6044, 0, 1500);
    co_od_set_value(&t.node, 0x2002, 4, 0x0028);
    co_od_set_value(&t.node, 0x2002, 9, 0x0053);
    go_operational();
    test_expect(&t, "184#0706");
    test_expect(&t, "284#0706DC0528005300");
    test_expect_none(&t);
}
END_TEST

START_TEST(t31_07_rpdo6_user_mapping)
{
    start_quiet();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1605, 0, 0, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1605, 1, 0x60400010, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1605, 2, 0x203C0210, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1605, 3, 0x203C0310, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1605, 0, 3, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    test_rx(&t, "304#0F000A001400");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 2), 10);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 3), 20);
    ck_assert_uint_eq(pdo_writes, 3);
    test_expect_none(&t);
}
END_TEST

/* ---- Event-driven TPDOs -------------------------------------------------------------- */

START_TEST(inhibit_time_delays_second_change)
{
    start_quiet();
    go_operational();
    test_expect(&t, "184#0000");
    test_advance(&t, 100 * MS);
    app_set(0x6041, 0, 0x0021);
    ck_assert_uint_eq(test_expect(&t, "184#2100"), 100 * MS);
    test_advance(&t, 5 * MS);
    app_set(0x6041, 0, 0x0023);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, 130 * MS);
    test_advance(&t, 25 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "184#2300"), 130 * MS);
    test_advance(&t, 500 * MS);
    test_expect_none(&t);
}
END_TEST

START_TEST(event_timer_resends_periodically)
{
    start();
    go_operational();
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 0);
    test_advance(&t, 350 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 100 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 200 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 300 * MS);
    test_expect_none(&t);
    /* A change at 350 ms is sent at once and restarts the timer. */
    app_set(0x6041, 0, 0x0040);
    ck_assert_uint_eq(test_expect(&t, "184#4000"), 350 * MS);
    test_advance(&t, 100 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#4000"), 450 * MS);
    test_expect_none(&t);
}
END_TEST

START_TEST(event_timer_write_restarts_timer)
{
    start();
    go_operational();
    test_expect(&t, "184#0000");
    test_advance(&t, 50 * MS);
    ck_assert_uint_eq(write_param(0x1800, 5, 20, 2), 0);
    test_advance(&t, 30 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 70 * MS);
    test_drain(&t);
    ck_assert_uint_eq(write_param(0x1800, 5, 0, 2), 0);
    test_advance(&t, 1000 * MS);
    test_expect_none(&t);
}
END_TEST

START_TEST(application_request_respects_inhibit)
{
    start_quiet();
    go_operational();
    test_expect(&t, "184#0000");
    test_advance(&t, 10 * MS);
    co_tpdo_request(&t.node, 1);
    co_tpdo_request(&t.node, 0);
    co_tpdo_request(&t.node, CO_CONFIG_TPDO_MAX + 1);
    co_tpdo_request(&t.node, 6); /* TPDO6 is invalid: nothing */
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    test_expect_none(&t);
    test_advance(&t, 20 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 30 * MS);
    test_expect_none(&t);
}
END_TEST

START_TEST(idle_operational_node_never_wakes)
{
    start_quiet();
    go_operational();
    test_drain(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

/* ---- NMT gating ---------------------------------------------------------------------- */

START_TEST(no_pdo_in_pre_operational_or_stopped)
{
    start();
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    test_rx(&t, "204#0F00");
    test_rx(&t, "304#0F00B004");
    test_rx(&t, "184#R");
    app_set(0x6041, 0, 0x0607);
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    test_advance(&t, 1000 * MS);
    test_expect_none(&t);
    test_rx(&t, "000#0204");
    test_rx(&t, "204#0F00");
    test_rx(&t, "184#R");
    test_rx(&t, "080#");
    test_advance(&t, 1000 * MS);
    test_expect_none(&t);
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_uint_eq(rpdo_calls, 0);
}
END_TEST

START_TEST(reentering_operational_sends_at_once)
{
    start_quiet();
    go_operational();
    test_expect(&t, "184#0000");
    test_advance(&t, 1 * MS);
    test_rx(&t, "000#8004");
    test_expect_none(&t);
    test_advance(&t, 1 * MS);
    go_operational();
    /* 2 ms after the last frame: the inhibit time of the previous stay no longer applies. */
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 2 * MS);
}
END_TEST

/* ---- Synchronous TPDOs --------------------------------------------------------------- */

START_TEST(sync_cyclic_every_nth_sync)
{
    tpdo6_only(3);
    go_operational();
    test_expect_none(&t);
    for (int i = 1; i <= 7; i++) {
        test_advance(&t, 10 * MS);
        sync_frame("080#");
        if (i == 3 || i == 6) {
            ck_assert_uint_eq(test_expect(&t, "284#00000000"), (co_time_t)i * 10 * MS);
        }
        test_expect_none(&t);
    }
}
END_TEST

START_TEST(sync_acyclic_only_on_change_or_request)
{
    tpdo6_only(0);
    go_operational();
    app_set(0x6041, 0, 0x0027);
    test_expect_none(&t);
    sync_frame("080#");
    test_expect(&t, "284#27000000");
    sync_frame("080#");
    test_expect_none(&t);
    app_set(0x6044, 0, 1500);
    test_expect_none(&t);
    sync_frame("080#");
    test_expect(&t, "284#2700DC05");
    co_tpdo_request(&t.node, 6);
    sync_frame("080#");
    test_expect(&t, "284#2700DC05");
    sync_frame("080#");
    test_expect_none(&t);
}
END_TEST

START_TEST(sync_start_value_with_counter)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1019, 0, 10, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, 2, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 6, 3, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    go_operational();
    test_drain(&t);
    sync_frame("080#01");
    sync_frame("080#02");
    test_expect_none(&t);
    sync_frame("080#03");
    test_expect(&t, "284#00000000");
    sync_frame("080#04");
    test_expect_none(&t);
    sync_frame("080#05");
    test_expect(&t, "284#00000000");
    sync_frame("080#06");
    test_expect_none(&t);
}
END_TEST

START_TEST(sync_start_value_ignored_without_counter)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1805, 2, 1, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 6, 3, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    go_operational();
    test_drain(&t);
    sync_frame("080#");
    test_expect(&t, "284#00000000");
}
END_TEST

START_TEST(sync_window_drops_late_transmission)
{
    tpdo6_only(1);
    ck_assert_uint_eq(write_param(0x1007, 0, 1000, 4), 0);
    go_operational();
    co_frame_t sync = test_frame("080#");
    /* The runtime runs the node 1 ms after the SYNC: still inside the window. */
    co_node_receive(&t.node, &sync, 10 * MS);
    co_node_process(&t.node, 11 * MS);
    ck_assert_uint_eq(t.bus.count - t.bus.next, 1);
    test_expect(&t, "284#00000000");
    /* 1.001 ms late: outside, the transmission is dropped. */
    co_node_receive(&t.node, &sync, 20 * MS);
    co_node_process(&t.node, 21 * MS + 1);
    test_expect_none(&t);
}
END_TEST

START_TEST(rtr_types_252_and_253)
{
    tpdo6_only(253);
    go_operational();
    test_expect_none(&t);
    co_od_set_value(&t.node, 0x6041, 0, 0x0027);
    test_rx(&t, "284#R");
    test_expect(&t, "284#27000000");
    ck_assert_uint_eq(write_param(0x1805, 2, 252, 1), 0);
    test_rx(&t, "284#R"); /* nothing sampled yet */
    test_expect_none(&t);
    sync_frame("080#");
    test_expect_none(&t);
    co_od_set_value(&t.node, 0x6041, 0, 0x0040);
    test_rx(&t, "284#R");
    test_expect(&t, "284#27000000");
    /* Bit 30 set (no RTR) is refused while the type needs RTRs. */
    ck_assert_uint_eq(write_param(0x1805, 1, 0x40000284, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1805, 2, 255, 1), 0);
    test_expect(&t, "284#40000000");
    ck_assert_uint_eq(write_param(0x1805, 1, 0x40000284, 4), 0);
    test_expect(&t, "284#40000000");
    ck_assert_uint_eq(write_param(0x1805, 2, 253, 1), CO_SDO_ABORT_VALUE_RANGE);
    test_expect_none(&t);
}
END_TEST

START_TEST(rtr_on_event_tpdo_and_forbidden_rtr)
{
    start_quiet();
    go_operational();
    test_expect(&t, "184#0000");
    test_rx(&t, "184#R");
    test_expect_none(&t);
    test_advance(&t, 30 * MS);
    ck_assert_uint_eq(test_expect(&t, "184#0000"), 30 * MS);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x40000184, 4), 0);
    test_expect(&t, "184#0000"); /* restarted PDO sends its data */
    test_advance(&t, 100 * MS);
    test_rx(&t, "184#R");
    test_advance(&t, 100 * MS);
    test_expect_none(&t);
}
END_TEST

/* ---- Synchronous RPDOs --------------------------------------------------------------- */

START_TEST(rpdo_sync_applied_at_next_sync)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 2, 1, 1), 0);
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    test_rx(&t, "304#0F00B004");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_uint_eq(rpdo_calls, 0);
    sync_frame("080#");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), 1200);
    ck_assert_uint_eq(rpdo_calls, 1);
    ck_assert_uint_eq(rpdo_last, 6);
    sync_frame("080#");
    ck_assert_uint_eq(rpdo_calls, 1);
}
END_TEST

/* CiA 301 7.5.2.7: a synchronous RPDO received after the synchronous window (1007h) closed is
 * discarded; one inside it is applied at the next SYNC. */
START_TEST(rpdo_sync_outside_window_discarded)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 2, 1, 1), 0);
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    ck_assert_uint_eq(write_param(0x1007, 0, 1000, 4), 0);
    go_operational();
    test_drain(&t);
    co_frame_t sync = test_frame("080#");
    co_frame_t rpdo = test_frame("304#0F00B004");
    co_node_receive(&t.node, &sync, 10 * MS);
    co_node_receive(&t.node, &rpdo, 11 * MS + 1); /* 1.001 ms after the SYNC: discarded */
    co_node_receive(&t.node, &sync, 20 * MS);
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_uint_eq(rpdo_calls, 0);
    co_node_receive(&t.node, &rpdo, 21 * MS); /* 1 ms after: inside */
    co_node_receive(&t.node, &sync, 30 * MS);
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_uint_eq(rpdo_calls, 1);
}
END_TEST

/* ---- RPDO errors --------------------------------------------------------------------- */

START_TEST(rpdo_short_frame_not_applied_emcy_8210)
{
    start_quiet();
    go_operational();
    test_drain(&t);
    test_rx(&t, "204#0F");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_uint_eq(rpdo_calls, 0);
    test_expect(&t, "084#1082110100010200");
    test_rx(&t, "204#0F");
    test_expect_none(&t);
    test_rx(&t, "204#0600");
    test_expect(&t, "084#0000000000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 6);
}
END_TEST

START_TEST(rpdo_long_frame_applied_emcy_8220)
{
    start_quiet();
    go_operational();
    test_drain(&t);
    test_rx(&t, "204#0F00AABB");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_uint_eq(rpdo_calls, 1);
    test_expect(&t, "084#2082110100040200");
    /* Then a short one: 0x8220 clears, 0x8210 is raised. */
    test_rx(&t, "204#");
    test_expect(&t, "084#0000000000000000");
    test_expect(&t, "084#1082110100000200");
    test_expect_none(&t);
}
END_TEST

START_TEST(rpdo_deadline_emcy_8250)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 5, 100, 2), 0);
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    /* Monitoring starts with the first reception. */
    test_advance(&t, 500 * MS);
    test_expect_none(&t);
    test_rx(&t, "304#0F00B004");
    test_advance(&t, 60 * MS);
    test_rx(&t, "304#0F00B004");
    test_advance(&t, 100 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "084#5082110600000400"), 660 * MS);
    test_advance(&t, 1000 * MS);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
    test_rx(&t, "304#0F00B004");
    test_expect(&t, "084#0000000000000000");
}
END_TEST

START_TEST(length_error_shared_by_rpdos_clears_last)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    test_rx(&t, "204#0F");
    test_expect(&t, "084#1082110100010200");
    test_rx(&t, "304#0F00");
    test_expect_none(&t); /* 0x8210 is already active */
    test_rx(&t, "204#0F00");
    test_expect_none(&t); /* RPDO6 still holds it */
    test_rx(&t, "304#0F00B004");
    test_expect(&t, "084#0000000000000000");
}
END_TEST

/* Issue 7, item 6, with its frames (node 5): reset node ends RPDO1's length error together with
 * its EMCY, so the same short frame after the reset raises the EMCY again. */
START_TEST(rpdo_length_error_raised_again_after_reset_node)
{
    uint32_t reg;
    test_node_start(&t, 5, &hooks, NULL);
    test_rx(&t, "000#0105");
    test_expect(&t, "185#0000");
    test_rx(&t, "205#06");
    test_expect(&t, "085#1082110100010200");
    test_rx(&t, "000#8105");
    test_expect(&t, "705#00");
    ck_assert_uint_eq(test_sdo_read(&t, 0x1001, 0, &reg), 0);
    ck_assert_uint_eq(reg, 0);
    test_rx(&t, "000#0105");
    test_expect(&t, "185#0000");
    test_rx(&t, "205#06");
    test_expect(&t, "085#1082110100010200");
    ck_assert_uint_eq(test_sdo_read(&t, 0x1001, 0, &reg), 0);
    ck_assert_uint_eq(reg, 0x11);
    test_rx(&t, "205#0600");
    test_expect(&t, "085#0000000000000000");
    test_expect_none(&t);
}
END_TEST

/* An invalid RPDO receives nothing, so no frame could end its errors any more: they end when it
 * is made invalid, each EMCY unless another RPDO still holds it. */
START_TEST(rpdo_errors_end_when_it_is_invalidated)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1405, 5, 100, 2), 0);
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    go_operational();
    test_drain(&t);
    test_rx(&t, "304#0F");
    test_expect(&t, "084#1082110600010400");
    ck_assert_uint_eq(write_param(0x1405, 1, 0x80000304, 4), 0);
    test_expect(&t, "084#0000000000000000");
    ck_assert_int_eq(co_od_value(&t.node, 0x1001, 0), 0);
    /* The timeout likewise. */
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    test_rx(&t, "304#0F00B004");
    test_advance(&t, 100 * MS);
    test_expect(&t, "084#5082110600000400");
    ck_assert_uint_eq(write_param(0x1405, 1, 0x80000304, 4), 0);
    test_expect(&t, "084#0000000000000000");
    /* RPDO1 still holds 0x8210: it stays until RPDO1's next right frame. */
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    test_rx(&t, "204#0F");
    test_expect(&t, "084#1082110100010200");
    test_rx(&t, "304#0F");
    ck_assert_uint_eq(write_param(0x1405, 1, 0x80000304, 4), 0);
    test_expect_none(&t);
    ck_assert(co_emcy_is_active(&t.node, CO_EMCY_PDO_LENGTH));
    test_rx(&t, "204#0F00");
    test_expect(&t, "084#0000000000000000");
    test_expect_none(&t);
}
END_TEST

/* ---- Parameter rules ----------------------------------------------------------------- */

START_TEST(cob_id_rules)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1800, 1, 0x185, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x20000184, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0xA0000184, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x00001184, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1400, 1, 0x205, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x184, 4), 0);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x80000185, 4), 0);
    /* Restricted CAN-IDs (NMT error control, SDO) cannot be made valid. */
    ck_assert_uint_eq(write_param(0x1800, 1, 0x704, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x584, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x185, 4), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1800, 1), 0x185);
    go_operational();
    test_expect(&t, "185#0000");
    ck_assert_uint_eq(write_param(0x1400, 1, 0x80000205, 4), 0);
    ck_assert_uint_eq(write_param(0x1400, 1, 0x205, 4), 0);
    test_rx(&t, "204#0F00");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    test_rx(&t, "205#0F00");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
}
END_TEST

/* CiA 301 7.3.5 restricted CAN-IDs at both edges of every range, for an RPDO and a TPDO (the
 * CCT's "Other 10"): refused for a valid PDO, accepted with bit 31 set and just outside. */
START_TEST(restricted_can_ids_at_every_edge)
{
    static const uint16_t comm[] = {0x1400, 0x1800};
    start_quiet();
    for (size_t c = 0; c < sizeof(comm) / sizeof(comm[0]); c++) {
        ck_assert_uint_eq(write_param(comm[c], 1, 0x80000000u, 4), 0);
        for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++) {
            uint32_t id = test_restricted_can_id[i];
            ck_assert_uint_eq(write_param(comm[c], 1, id, 4), CO_SDO_ABORT_VALUE_RANGE);
            ck_assert_uint_eq(write_param(comm[c], 1, 0x80000000u | id, 4), 0);
        }
        for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++) {
            uint32_t id = test_free_can_id[i];
            ck_assert_uint_eq(write_param(comm[c], 1, id, 4), 0);
            ck_assert_uint_eq(write_param(comm[c], 1, 0x80000000u | id, 4), 0);
        }
    }
}
END_TEST

START_TEST(transmission_type_rules)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1805, 2, 241, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1805, 2, 251, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1405, 2, 252, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1405, 2, 253, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1405, 2, 241, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 2), 255);
    ck_assert_int_eq(co_od_value(&t.node, 0x1405, 2), 255);
    /* Allowed while valid, too. */
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    for (unsigned type = 0; type <= 240; type += 60)
        ck_assert_uint_eq(write_param(0x1805, 2, type, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, 252, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, 253, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 2, 254, 1), 0);
    ck_assert_uint_eq(write_param(0x1405, 2, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1405, 2, 254, 1), 0);
    /* TPDO1's type is read-only in the ATV312 dictionary. */
    ck_assert_uint_eq(write_param(0x1800, 2, 1, 1), CO_SDO_ABORT_READ_ONLY);
}
END_TEST

START_TEST(inhibit_and_start_value_only_while_invalid)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1800, 3, 500, 2), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1800, 3), 300);
    ck_assert_uint_eq(write_param(0x1805, 3, 500, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 6, 241, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1805, 6, 240, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    ck_assert_uint_eq(write_param(0x1805, 3, 300, 2), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_param(0x1805, 6, 1, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 3), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 6), 240);
    /* The ATV312 minimum of 10 ms is the dictionary's limit. */
    ck_assert_uint_eq(write_param(0x1800, 1, 0x80000184, 4), 0);
    ck_assert_uint_eq(write_param(0x1800, 3, 99, 2), CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(write_param(0x1800, 3, 0, 2), 0);
    /* An RPDO's event timer may change while valid. */
    ck_assert_uint_eq(write_param(0x1405, 1, 0x304, 4), 0);
    ck_assert_uint_eq(write_param(0x1405, 5, 50, 2), 0);
}
END_TEST

START_TEST(inhibit_from_dictionary_applies)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1805, 3, 1000, 2), 0); /* 100 ms */
    ck_assert_uint_eq(write_param(0x1805, 5, 0, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    go_operational();
    test_expect(&t, "184#0000");
    test_expect(&t, "284#00000000");
    test_advance(&t, 10 * MS);
    app_set(0x6044, 0, 1);
    test_expect_none(&t);
    test_advance(&t, 90 * MS);
    ck_assert_uint_eq(test_expect(&t, "284#00000100"), 100 * MS);
}
END_TEST

/* A device that prints TPDO1's inhibit time in 1 ms (co_node_config_t.tpdo_inhibit_ms, the ATV312
 * manual's object table: 1800h:03 "unit = 1 ms", 1805h:03 "unit = 0,1 ms"): 100 in 1800h:03 holds
 * TPDO1 back 100 ms to the microsecond, 100 in 1805h:03 TPDO6 10 ms. */
START_TEST(inhibit_unit_per_tpdo)
{
    co_node_config_t config = {
        .node_id = 4, .od = &test_od, .hooks = &hooks, .tpdo_inhibit_ms = 1u << 0};
    test_node_start_config(&t, &config);
    ck_assert_uint_eq(write_param(0x1800, 5, 0, 2), 0);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x80000184, 4), 0);
    ck_assert_uint_eq(write_param(0x1800, 3, 100, 2), 0);
    ck_assert_uint_eq(write_param(0x1800, 1, 0x184, 4), 0);
    ck_assert_uint_eq(write_param(0x1805, 3, 100, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 5, 0, 2), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    go_operational();
    test_expect(&t, "184#0000");
    test_expect(&t, "284#00000000");
    test_advance(&t, 1 * MS);
    app_set(0x6041, 0, 0x0021);
    test_expect_none(&t);
    ck_assert_uint_eq(t.bus.deadline, 10 * MS);
    test_advance(&t, 9 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "284#21000000"), 10 * MS);
    test_advance(&t, 90 * MS - 1);
    test_expect_none(&t);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "184#2100"), 100 * MS);
    test_expect_none(&t);
}
END_TEST

/* ---- Dynamic mapping ----------------------------------------------------------------- */

START_TEST(mapping_refused_while_valid_or_enabled)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    ck_assert_uint_eq(write_param(0x1A05, 0, 0, 1), CO_SDO_ABORT_UNSUPPORTED_ACCESS);
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x60440010, 4), CO_SDO_ABORT_UNSUPPORTED_ACCESS);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x80000284, 4), 0);
    /* Invalid, but sub 0 still 2: the entries stay locked. */
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x60440010, 4), CO_SDO_ABORT_UNSUPPORTED_ACCESS);
    ck_assert_int_eq(co_od_value(&t.node, 0x1A05, 1), 0x60410010);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x60420010, 4), CO_SDO_ABORT_UNSUPPORTED_ACCESS);
    /* PDO1's mapping is static. */
    ck_assert_uint_eq(write_param(0x1A00, 1, 0x60440010, 4), CO_SDO_ABORT_READ_ONLY);
    ck_assert_uint_eq(write_param(0x1600, 1, 0x60420010, 4), CO_SDO_ABORT_READ_ONLY);
}
END_TEST

START_TEST(mapping_entry_aborts)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1605, 0, 0, 1), 0);
    /* Absent object, object not mappable at all. */
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x50000010, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x20000440, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    /* Wrong direction: rww in a TPDO, ro/rwr in an RPDO. */
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x60400010, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x60410010, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x20000108, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    /* Bit length other than the object's. */
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x60410008, 4), CO_SDO_ABORT_PARAM_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x60410020, 4), CO_SDO_ABORT_PARAM_INCOMPATIBLE);
    /* Dummies only in RPDOs, with their type's length. */
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x00050008, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x00050010, 4), CO_SDO_ABORT_PARAM_INCOMPATIBLE);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x00080020, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x00050008, 4), 0);
    /* Sub 0 beyond the dictionary's 4 entries. */
    ck_assert_uint_eq(write_param(0x1A05, 0, 5, 1), CO_SDO_ABORT_VALUE_HIGH);
}
END_TEST

START_TEST(mapping_longer_than_64_bits)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1A05, 1, 0x20000720, 4), 0);
    ck_assert_uint_eq(write_param(0x1A05, 2, 0x20000320, 4), 0);
    ck_assert_uint_eq(write_param(0x1A05, 3, 0x20000108, 4), 0);
    ck_assert_uint_eq(write_param(0x1A05, 0, 3, 1), CO_SDO_ABORT_PDO_LENGTH);
    ck_assert_int_eq(co_od_value(&t.node, 0x1A05, 0), 0);
    ck_assert_uint_eq(write_param(0x1A05, 0, 2, 1), 0);
    /* Sub 0 = n re-checks entries written while it was 0, e.g. an empty one. */
    ck_assert_uint_eq(write_param(0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1A05, 4, 0, 4), 0);
    ck_assert_uint_eq(write_param(0x1A05, 0, 4, 1), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_param(0x1A05, 0, 2, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    co_od_set_value(&t.node, 0x2000, 7, 0x11223344);
    co_od_set_value(&t.node, 0x2000, 3, -2);
    go_operational();
    test_expect(&t, "184#0000");
    test_expect(&t, "284#44332211FEFFFFFF");
}
END_TEST

START_TEST(rpdo_dummy_mapping_skips_bytes)
{
    start_quiet();
    static const uint32_t mapping[] = {0x00050008, 0x60400010, 0x00070020};
    rpdo6_mapped(mapping, 3);
    test_rx(&t, "304#AA0F0011223344");
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0x000F);
    ck_assert_uint_eq(pdo_writes, 1);
    test_expect_none(&t);
}
END_TEST

/* CiA 306 [DummyUsage]: an RPDO maps as dummies only the data types the dictionary declares
 * (co_od_t.dummy_types); any other data type index is an object it does not have (0x06040041). */
START_TEST(dummy_mapping_only_for_declared_types)
{
    static co_od_t od;
    od = test_od;
    od.dummy_types = 0;
    start_od(&od);
    ck_assert_uint_eq(write_param(0x1605, 0, 0, 1), 0);
    test_rx(&t, "604#2305160108000500"); /* 1605h:01h = 00050008h */
    test_expect(&t, "584#8005160141000406");
    ck_assert_int_eq(co_od_value(&t.node, 0x1605, 1), 0x60400010);
    for (uint8_t type = CO_DT_INTEGER8; type <= CO_DT_UNSIGNED32; type++) {
        uint32_t entry = (uint32_t)type << 16 | (uint32_t)co_od_type_size(type) * 8u;
        ck_assert_uint_eq(write_param(0x1605, 1, entry, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    }
    /* A dictionary that declares UNSIGNED8 only. */
    od.dummy_types = CO_OD_DUMMY(CO_DT_UNSIGNED8);
    start_od(&od);
    ck_assert_uint_eq(write_param(0x1605, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1605, 1, 0x00070020, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    static const uint32_t mapping[] = {0x00050008, 0x60420010};
    rpdo6_mapped(mapping, 2);
    test_rx(&t, "304#AA3412");
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), 0x1234);
    ck_assert_uint_eq(pdo_writes, 1);
}
END_TEST

START_TEST(zero_length_mapping_sends_empty_frame)
{
    start_quiet();
    ck_assert_uint_eq(write_param(0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(write_param(0x1805, 1, 0x284, 4), 0);
    go_operational();
    test_expect(&t, "184#0000");
    test_expect(&t, "284#");
    test_expect_none(&t);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("pdo");
    TCase *tc = tcase_create("pdo");
    tcase_add_test(tc, t31_02_tpdo1_status_word);
    tcase_add_test(tc, t31_03_rpdo1_control_word);
    tcase_add_test(tc, t31_04_tpdo6_default_mapping);
    tcase_add_test(tc, t31_05_rpdo6_default_mapping);
    tcase_add_test(tc, t31_06_tpdo6_user_mapping);
    tcase_add_test(tc, t31_07_rpdo6_user_mapping);
    tcase_add_test(tc, inhibit_time_delays_second_change);
    tcase_add_test(tc, event_timer_resends_periodically);
    tcase_add_test(tc, event_timer_write_restarts_timer);
    tcase_add_test(tc, application_request_respects_inhibit);
    tcase_add_test(tc, idle_operational_node_never_wakes);
    tcase_add_test(tc, no_pdo_in_pre_operational_or_stopped);
    tcase_add_test(tc, reentering_operational_sends_at_once);
    tcase_add_test(tc, sync_cyclic_every_nth_sync);
    tcase_add_test(tc, sync_acyclic_only_on_change_or_request);
    tcase_add_test(tc, sync_start_value_with_counter);
    tcase_add_test(tc, sync_start_value_ignored_without_counter);
    tcase_add_test(tc, sync_window_drops_late_transmission);
    tcase_add_test(tc, rtr_types_252_and_253);
    tcase_add_test(tc, rtr_on_event_tpdo_and_forbidden_rtr);
    tcase_add_test(tc, rpdo_sync_applied_at_next_sync);
    tcase_add_test(tc, rpdo_sync_outside_window_discarded);
    tcase_add_test(tc, rpdo_short_frame_not_applied_emcy_8210);
    tcase_add_test(tc, rpdo_long_frame_applied_emcy_8220);
    tcase_add_test(tc, rpdo_deadline_emcy_8250);
    tcase_add_test(tc, length_error_shared_by_rpdos_clears_last);
    tcase_add_test(tc, rpdo_length_error_raised_again_after_reset_node);
    tcase_add_test(tc, rpdo_errors_end_when_it_is_invalidated);
    tcase_add_test(tc, cob_id_rules);
    tcase_add_test(tc, restricted_can_ids_at_every_edge);
    tcase_add_test(tc, transmission_type_rules);
    tcase_add_test(tc, inhibit_and_start_value_only_while_invalid);
    tcase_add_test(tc, inhibit_from_dictionary_applies);
    tcase_add_test(tc, inhibit_unit_per_tpdo);
    tcase_add_test(tc, mapping_refused_while_valid_or_enabled);
    tcase_add_test(tc, mapping_entry_aborts);
    tcase_add_test(tc, mapping_longer_than_64_bits);
    tcase_add_test(tc, rpdo_dummy_mapping_skips_bytes);
    tcase_add_test(tc, dummy_mapping_only_for_declared_types);
    tcase_add_test(tc, zero_length_mapping_sends_empty_frame);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
