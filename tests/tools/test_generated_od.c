/* SPDX-License-Identifier: Apache-2.0 */
/* The table edstool.py generates from fixtures/device.eds, used by a real node: it validates,
 * loads the EDS defaults with node-id terms added, enforces the EDS limits and the hooks file,
 * answers SDO uploads with the EDS values and maps the dummies of [DummyUsage]. */
#include "check_main.h"
#include "co/co_node.h"
#include "dev_od.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

#define NODE_ID 5

extern unsigned test_hook_serial_reads;

static co_frame_t sent[16];
static size_t sent_count;
static uint8_t data[DEV_OD_DATA_SIZE];
static co_node_t node;

static void record_frame(void *user, const co_frame_t *frame)
{
    (void)user;
    if (sent_count < sizeof sent / sizeof sent[0])
        sent[sent_count++] = *frame;
}

static void start_node(void)
{
    co_node_config_t config = {
        .node_id = NODE_ID, .od = &dev_od, .od_data = data, .send = record_frame};
    sent_count = 0;
    ck_assert_int_eq(co_node_init(&node, &config), 0);
    co_node_start(&node, 0);
    ck_assert_uint_eq(sent_count, 1); /* boot-up */
    sent_count = 0;
}

static co_frame_t sdo_request(uint8_t command, uint16_t index, uint8_t sub)
{
    co_frame_t f = {.id = CO_CAN_ID_SDO_RX + NODE_ID, .len = 8};
    f.data[0] = command;
    co_put_u16(&f.data[1], index);
    f.data[3] = sub;
    return f;
}

START_TEST(table_validates_and_matches_header)
{
    uint16_t position;
    ck_assert_int_eq(co_od_validate(&dev_od, &position), CO_OD_VALID);
    ck_assert_uint_eq(dev_od.count, DEV_OD_ENTRIES);
    ck_assert_uint_eq(dev_od.data_size, DEV_OD_DATA_SIZE);
    ck_assert_ptr_eq(dev_od.defaults, dev_od_defaults);
}
END_TEST

START_TEST(defaults_loaded_with_node_id)
{
    start_node();
    ck_assert_int_eq(co_od_value(&node, 0x1000, 0), 0x00010192);
    ck_assert_int_eq(co_od_value(&node, 0x1018, 1), 0x5F);
    ck_assert_int_eq(co_od_value(&node, 0x1014, 0), 0x80 + NODE_ID);
    ck_assert_int_eq(co_od_value(&node, 0x1200, 1), 0x600 + NODE_ID);
    ck_assert_int_eq(co_od_value(&node, 0x1200, 2), 0x580 + NODE_ID);
    ck_assert_int_eq(co_od_value(&node, 0x1800, 1), 0x180 + NODE_ID);
    ck_assert_int_eq(co_od_value(&node, 0x2000, 1), -5);
    ck_assert_int_eq(co_od_value(&node, 0x2000, 3), -100000);
    ck_assert_int_eq(co_od_value(&node, 0x2000, 4), -2);
    ck_assert_int_eq(co_od_value(&node, 0x2000, 5), 0x0102030405060708);
    ck_assert_int_eq(co_od_value(&node, 0x2002, 2), 9);
    ck_assert_int_eq(co_od_value(&node, 0x2002, 3), 7);
    float real32;
    memcpy(&real32, co_od_bytes(&node, co_od_find(&dev_od, 0x2000, 6)), sizeof real32);
    ck_assert(real32 == 1.5f);
}
END_TEST

START_TEST(limits_zero_ok_and_hooks_apply)
{
    start_node();
    uint8_t v[2];
    co_put_u16(v, 9);
    ck_assert_uint_eq(co_od_write(&node, 0x2001, 0, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_LOW);
    co_put_u16(v, 1001);
    ck_assert_uint_eq(co_od_write(&node, 0x2001, 0, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_HIGH);
    co_put_u16(v, 0);
    ck_assert_uint_eq(co_od_write(&node, 0x2001, 0, v, 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_int_eq(co_od_value(&node, 0x2001, 0), 0);

    co_put_u16(v, (uint16_t)-101);
    ck_assert_uint_eq(co_od_write(&node, 0x2000, 2, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_VALUE_LOW);
    co_put_u16(v, (uint16_t)-100);
    ck_assert_uint_eq(co_od_write(&node, 0x2000, 2, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_DATA_LOCAL);
    ck_assert_int_eq(co_od_value(&node, 0x2000, 2), -10);
    /* hex limits 0xFF9C..0x0064 of an INTEGER16 are -100..100 */
    ck_assert_uint_eq(co_od_write(&node, 0x2000, 0x0C, v, 2, CO_OD_ORIGIN_APP), 0);
    co_put_u16(v, (uint16_t)-101);
    ck_assert_uint_eq(co_od_write(&node, 0x2000, 0x0C, v, 2, CO_OD_ORIGIN_APP),
                      CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(co_od_write(&node, 0x2000, 0x0C, v, 2, CO_OD_ORIGIN_SDO),
                      CO_SDO_ABORT_READ_ONLY);

    const co_od_entry_t *e;
    unsigned reads = test_hook_serial_reads;
    ck_assert_uint_eq(co_od_read_check(&node, 0x1018, 4, &e), 0);
    ck_assert_uint_eq(test_hook_serial_reads, reads + 1);
    ck_assert_uint_eq(co_od_read_check(&node, 0x2000, 5, &e), CO_SDO_ABORT_WRITE_ONLY);
}
END_TEST

START_TEST(strings_keep_eds_default_and_capacity)
{
    start_node();
    const co_od_entry_t *e;
    ck_assert_uint_eq(co_od_read_check(&node, 0x1008, 0, &e), 0);
    ck_assert_uint_eq(co_od_length(&node, e), 10);
    ck_assert_mem_eq(co_od_bytes(&node, e), "TestDevice", 10);
    e = co_od_find(&dev_od, 0x1009, 0);
    ck_assert_uint_eq(e->size, 16);
    ck_assert_uint_eq(co_od_length(&node, e), 3);
}
END_TEST

START_TEST(sdo_upload_of_string_gives_eds_default)
{
    start_node();
    /* expedited: 1009h "1.0", 3 bytes (n = 1, e = 1, s = 1) */
    co_frame_t request = sdo_request(0x40, 0x1009, 0);
    co_node_receive(&node, &request, 1000);
    co_node_process(&node, 1000);
    ck_assert_uint_eq(sent_count, 1);
    ck_assert_uint_eq(sent[0].id, 0x580 + NODE_ID);
    ck_assert_uint_eq(sent[0].data[0], 0x47);
    ck_assert_mem_eq(&sent[0].data[4], "1.0", 3);

    /* segmented: 1008h "TestDevice", 10 bytes */
    sent_count = 0;
    request = sdo_request(0x40, 0x1008, 0);
    co_node_receive(&node, &request, 2000);
    co_node_process(&node, 2000);
    ck_assert_uint_eq(sent_count, 1);
    ck_assert_uint_eq(sent[0].data[0], 0x41);
    ck_assert_uint_eq(co_get_u32(&sent[0].data[4]), 10);
    char text[16] = {0};
    size_t got = 0;
    for (uint8_t toggle = 0; got < 10; toggle ^= 0x10) {
        sent_count = 0;
        co_frame_t segment = {.id = CO_CAN_ID_SDO_RX + NODE_ID, .len = 8};
        segment.data[0] = (uint8_t)(0x60 | toggle);
        co_node_receive(&node, &segment, 3000);
        co_node_process(&node, 3000);
        ck_assert_uint_eq(sent_count, 1);
        ck_assert_uint_eq(sent[0].data[0] & 0x10, toggle);
        size_t n = 7 - ((sent[0].data[0] >> 1) & 7);
        ck_assert_uint_le(got + n, 10);
        memcpy(text + got, &sent[0].data[1], n);
        got += n;
        ck_assert_uint_eq(sent[0].data[0] & 1, got == 10);
    }
    ck_assert_str_eq(text, "TestDevice");
}
END_TEST

static uint32_t write_value(uint16_t index, uint8_t sub, uint32_t value, size_t len)
{
    uint8_t v[4];
    co_put_u32(v, value);
    return co_od_write(&node, index, sub, v, len, CO_OD_ORIGIN_SDO);
}

/* [DummyUsage] declares UNSIGNED8 and UNSIGNED16: RPDO1 maps those as dummies, no other. */
START_TEST(dummy_usage_reaches_the_pdo_engine)
{
    ck_assert_uint_eq(dev_od.dummy_types,
                      CO_OD_DUMMY(CO_DT_UNSIGNED8) | CO_OD_DUMMY(CO_DT_UNSIGNED16));
    start_node();
    ck_assert_uint_eq(write_value(0x1400, 1, 0x80000000u + 0x200 + NODE_ID, 4), 0);
    ck_assert_uint_eq(write_value(0x1600, 0, 0, 1), 0);
    ck_assert_uint_eq(write_value(0x1600, 1, 0x00050008, 4), 0);
    ck_assert_uint_eq(write_value(0x1600, 1, 0x00060010, 4), 0);
    ck_assert_uint_eq(write_value(0x1600, 1, 0x00020008, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_uint_eq(write_value(0x1600, 1, 0x00070020, 4), CO_SDO_ABORT_NOT_MAPPABLE);
    ck_assert_int_eq(co_od_value(&node, 0x1600, 1), 0x00060010);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("generated_od");
    TCase *tc = tcase_create("generated_od");
    tcase_add_test(tc, table_validates_and_matches_header);
    tcase_add_test(tc, defaults_loaded_with_node_id);
    tcase_add_test(tc, limits_zero_ok_and_hooks_apply);
    tcase_add_test(tc, strings_keep_eds_default_and_capacity);
    tcase_add_test(tc, sdo_upload_of_string_gives_eds_default);
    tcase_add_test(tc, dummy_usage_reaches_the_pdo_engine);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
