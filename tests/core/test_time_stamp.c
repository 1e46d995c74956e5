/* SPDX-License-Identifier: Apache-2.0 */
/* TIME (1012h): the TIME_OF_DAY codec and its calendar, the consumer handing the received time to
 * the application in Pre-operational and Operational only, the producer's frame, the 1012h rules
 * of CiA 301 7.5.2.12, a node without the service, and the consumed COB-IDs. Frame-exact. */
#include "check_main.h"
#include "co/co_consumers.h"
#include "test_bus.h"
#include "test_od.h"

static test_node_t t;
static unsigned time_calls;
static co_time_of_day_t received;

static void on_time(co_node_t *node, const co_time_of_day_t *time)
{
    (void)node;
    time_calls++;
    received = *time;
}

static const co_app_hooks_t hooks = {.time_stamp = on_time};

static void start(const co_time_stamp_code_t *code)
{
    time_calls = 0;
    co_node_config_t config = {.node_id = 4, .od = &test_od, .hooks = &hooks, .time_stamp = code};
    test_node_start_config(&t, &config);
}

static uint32_t write_cob_id(uint32_t value)
{
    uint8_t data[4];
    co_put_u32(data, value);
    return co_od_write(&t.node, CO_IDX_TIME_COB_ID, 0, data, 4, CO_OD_ORIGIN_SDO);
}

START_TEST(time_of_day_codec_and_calendar)
{
    /* 2026-11-29 12:34:56.789: day 15673 since 1984-01-01 (3D39h), 45 296 789 ms (02B32C95h). */
    co_time_of_day_t time = {.ms = 45296789u, .days = 15673u};
    uint8_t data[6];
    co_time_of_day_encode(&time, data);
    const uint8_t expected[6] = {0x95, 0x2C, 0xB3, 0x02, 0x39, 0x3D};
    ck_assert_mem_eq(data, expected, 6);
    co_time_of_day_t back;
    ck_assert(co_time_of_day_decode(data, 6, &back));
    ck_assert_uint_eq(back.ms, time.ms);
    ck_assert_uint_eq(back.days, time.days);
    ck_assert(!co_time_of_day_decode(data, 5, &back));
    /* The 4 reserved bits are ignored. */
    data[3] |= 0xF0;
    ck_assert(co_time_of_day_decode(data, 6, &back));
    ck_assert_uint_eq(back.ms, 45296789u);
    co_civil_time_t c;
    co_time_of_day_civil(&time, &c);
    ck_assert_int_eq(c.year, 2026);
    ck_assert_uint_eq(c.month, 11);
    ck_assert_uint_eq(c.day, 29);
    ck_assert_uint_eq(c.hour, 12);
    ck_assert_uint_eq(c.minute, 34);
    ck_assert_uint_eq(c.second, 56);
    ck_assert_uint_eq(c.ms, 789);
    co_time_of_day_civil(&(co_time_of_day_t){.ms = 0, .days = 0}, &c);
    ck_assert_int_eq(c.year, 1984);
    ck_assert_uint_eq(c.month, 1);
    ck_assert_uint_eq(c.day, 1);
    co_time_of_day_civil(&(co_time_of_day_t){.ms = 86399999u, .days = 59}, &c); /* leap day */
    ck_assert_uint_eq(c.month, 2);
    ck_assert_uint_eq(c.day, 29);
    ck_assert_uint_eq(c.hour, 23);
    ck_assert_uint_eq(c.ms, 999);
    /* The text, zeros in front; the last day 16 bits count. */
    char text[CO_TIME_OF_DAY_TEXT_SIZE];
    co_time_of_day_format(&time, text);
    ck_assert_str_eq(text, "2026-11-29 12:34:56.789");
    co_time_of_day_format(&(co_time_of_day_t){.ms = 3723004u, .days = 59}, text);
    ck_assert_str_eq(text, "1984-02-29 01:02:03.004");
    co_time_of_day_format(&(co_time_of_day_t){.ms = 86399999u, .days = 65535u}, text);
    ck_assert_str_eq(text, "2163-06-06 23:59:59.999");
    /* 2026-11-29T12:34:56.789Z is 1 795 955 696 789 ms after 1970-01-01. */
    ck_assert(co_time_of_day_from_unix_ms(1795955696789ull, &back));
    ck_assert_uint_eq(back.days, 15673u);
    ck_assert_uint_eq(back.ms, 45296789u);
    ck_assert(!co_time_of_day_from_unix_ms(441763199999ull, &back)); /* 1983-12-31 */
    ck_assert(co_time_of_day_from_unix_ms(441763200000ull, &back));
    ck_assert_uint_eq(back.days, 0);
}
END_TEST

START_TEST(consumer_hands_the_time_in_pre_operational_and_operational)
{
    start(&co_time_stamp);
    test_rx(&t, "100#952CB302393D"); /* 1012h = 100h: not consumed */
    ck_assert_uint_eq(time_calls, 0);
    ck_assert_uint_eq(write_cob_id(0x80000100u), 0);
    test_rx(&t, "100#952CB302393D");
    ck_assert_uint_eq(time_calls, 1);
    ck_assert_uint_eq(received.ms, 45296789u);
    ck_assert_uint_eq(received.days, 15673u);
    test_rx(&t, "100#952CB30239"); /* 5 bytes: dropped */
    test_rx(&t, "100#R");          /* a remote frame: not TIME */
    ck_assert_uint_eq(time_calls, 1);
    test_rx(&t, "000#0104");     /* Operational */
    test_expect(&t, "184#0000"); /* the test dictionary's TPDO1 */
    test_rx(&t, "100#000000000000");
    ck_assert_uint_eq(time_calls, 2);
    ck_assert_uint_eq(received.days, 0);
    test_rx(&t, "000#0204"); /* Stopped: no TIME */
    test_rx(&t, "100#952CB302393D");
    ck_assert_uint_eq(time_calls, 2);
    test_expect_none(&t);
}
END_TEST

START_TEST(producer_sends_the_time_handed_in)
{
    start(&co_time_stamp);
    co_time_of_day_t time = {.ms = 45296789u, .days = 15673u};
    ck_assert(!co_time_stamp_send(&t.node, &time)); /* 1012h bit 30 clear */
    test_expect_none(&t);
    ck_assert_uint_eq(write_cob_id(0x40000100u), 0);
    ck_assert(co_time_stamp_send(&t.node, &time));
    test_expect(&t, "100#952CB302393D");
    test_rx(&t, "000#0204"); /* Stopped: no TIME */
    ck_assert(!co_time_stamp_send(&t.node, &time));
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000"); /* the test dictionary's TPDO1 */
    ck_assert(co_time_stamp_send(&t.node, &(co_time_of_day_t){.ms = 1, .days = 2}));
    test_expect(&t, "100#010000000200");
    test_expect_none(&t);
}
END_TEST

START_TEST(cob_id_rules)
{
    start(&co_time_stamp);
    /* 29-bit CAN-ID, bits 28..11, a restricted CAN-ID: 06090030h. */
    ck_assert_uint_eq(write_cob_id(0x20000100u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x00000900u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x80000101u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x80000181u), 0);
    /* Consumed: no new CAN-ID, bits 31/30 may change. */
    ck_assert_uint_eq(write_cob_id(0x80000182u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0xC0000181u), 0);
    ck_assert_uint_eq(write_cob_id(0x40000182u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x00000181u), 0);
    ck_assert_uint_eq(write_cob_id(0x00000182u), 0);
    ck_assert_uint_eq(co_od_value(&t.node, CO_IDX_TIME_COB_ID, 0), 0x182);
}
END_TEST

START_TEST(a_node_without_the_service_neither_consumes_nor_produces)
{
    start(NULL);
    ck_assert_uint_eq(write_cob_id(0x80000100u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x40000100u), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(write_cob_id(0x00000200u), 0);
    test_rx(&t, "100#952CB302393D");
    ck_assert_uint_eq(time_calls, 0);
}
END_TEST

static bool consumes(uint16_t can_id)
{
    return co_node_consumes(&t.node, can_id, false);
}

START_TEST(consumed_cob_ids_follow_1012h)
{
    start(&co_time_stamp);
    ck_assert(!consumes(0x100));
    uint32_t generation = t.node.consumer_generation;
    uint8_t data[4];
    co_put_u32(data, 0x80000100u);
    ck_assert_uint_eq(co_od_write(&t.node, CO_IDX_TIME_COB_ID, 0, data, 4, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_ne(t.node.consumer_generation, generation);
    ck_assert(consumes(0x100));
    co_put_u32(data, 0x40000100u); /* produced only */
    ck_assert_uint_eq(co_od_write(&t.node, CO_IDX_TIME_COB_ID, 0, data, 4, CO_OD_ORIGIN_SDO), 0);
    ck_assert(!consumes(0x100));
    /* A reset communication brings the default back, for the consumer as for the dictionary. */
    ck_assert_uint_eq(write_cob_id(0x80000100u), 0);
    test_rx(&t, "000#8204");
    test_drain(&t);
    ck_assert(!consumes(0x100));
    test_rx(&t, "100#000000000000");
    ck_assert_uint_eq(time_calls, 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("time_stamp");
    TCase *tc = tcase_create("time_stamp");
    tcase_add_test(tc, time_of_day_codec_and_calendar);
    tcase_add_test(tc, consumer_hands_the_time_in_pre_operational_and_operational);
    tcase_add_test(tc, producer_sends_the_time_handed_in);
    tcase_add_test(tc, cob_id_rules);
    tcase_add_test(tc, a_node_without_the_service_neither_consumes_nor_produces);
    tcase_add_test(tc, consumed_cob_ids_follow_1012h);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
