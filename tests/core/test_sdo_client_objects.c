/* SPDX-License-Identifier: Apache-2.0 */
/* SDO client channels of a node (co_sdo_clients_t), frame by frame on the in-process bus: node-id
 * 4 with the test dictionary plus 1280h (605h / 585h, server 5, valid) and 1281h (not valid),
 * against a scripted server 5. The COB-ID rules of CiA 301's "SDO client parameter" written
 * through the node's own server, with their abort codes; expedited and segmented reads and an
 * expedited write driven through the node; the timeout in the node's deadline; a channel that is
 * not valid ignores its frames; the consumed COB-IDs follow; a transfer cut by invalidation or by
 * a reset ends with the client's abort 08000022h and no frame (D-SDO-CLIENT-INVALIDATED). */
#include "check_main.h"
#include "co/co_consumers.h"
#include "co/co_sdo_clients.h"
#include "test_bus.h"
#include "test_od.h"

#include <string.h>

#define CHANNELS 2
#define TIMEOUT_MS 100u

static test_node_t t;
static co_sdo_client_channel_t channels[CHANNELS];
static co_sdo_clients_t clients;

/* The results reported, in order. */
static co_sdo_client_result_t results[4];
static unsigned result_count;
static int done_user;

static void done(void *user, const co_sdo_client_result_t *result)
{
    ck_assert_ptr_eq(user, &done_user);
    ck_assert_uint_lt(result_count, 4);
    results[result_count++] = *result;
}

static void setup(void)
{
    result_count = 0;
    ck_assert_int_eq(co_sdo_clients_init(&clients, channels, CHANNELS, done, &done_user), 0);
    co_node_config_t config = {
        .node_id = 4,
        .od = test_od_with_sdo_clients(),
        .sdo_clients = &clients,
    };
    test_node_start_config(&t, &config);
}

static void expect_result(unsigned n, co_sdo_client_status_t status, uint32_t abort_code,
                          uint32_t size, uint16_t index, uint8_t subindex)
{
    ck_assert_uint_gt(result_count, n);
    ck_assert_int_eq(results[n].status, status);
    ck_assert_uint_eq(results[n].abort_code, abort_code);
    ck_assert_uint_eq(results[n].size, size);
    ck_assert_uint_eq(results[n].index, index);
    ck_assert_uint_eq(results[n].subindex, subindex);
}

static int upload(uint8_t channel, uint16_t index, uint8_t subindex, uint8_t *buf, uint32_t cap)
{
    int err = co_node_sdo_upload(&t.node, channel, index, subindex, buf, cap, CO_SDO_CLIENT_AUTO,
                                 TIMEOUT_MS, t.bus.now);
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
    return err;
}

/* CiA 301 "SDO client parameter": each rule of the COB-IDs and of the server's node-id, written by
 * SDO through the node's own server 604h/584h, with its exact abort code. */
START_TEST(cob_id_write_rules)
{
    /* A new CAN-ID while valid before and after. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x606, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 2, 0x586, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x605, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x40000605, 4), 0); /* bit 30 kept */
    /* Bit 29 (29-bit CAN-ID), bits 28..11. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x20000605, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0xA0000605, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x00000800, 4), CO_SDO_ABORT_VALUE_RANGE);
    /* The restricted CAN-IDs but a server's default channel's, 601h-67Fh and 581h-5FFh. */
    for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++) {
        uint16_t id = test_restricted_can_id[i];
        bool default_sdo = (id >= 0x581 && id <= 0x5FF) || (id >= 0x601 && id <= 0x67F);
        ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x80000000u | id, 4),
                          default_sdo ? 0 : CO_SDO_ABORT_VALUE_RANGE);
    }
    for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++)
        ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 2, 0x80000000u | test_free_can_id[i], 4), 0);
    /* Not valid, then a new CAN-ID made valid. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x80000605, 4), 0);
    ck_assert(!channels[0].valid);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x606, 4), 0);
    ck_assert(channels[0].valid);
    ck_assert_uint_eq(channels[0].client.request_id, 0x606);
    /* The server's node-id, 1..127. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 3, 0, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 3, 128, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 3, 127, 1), 0);
    test_expect_none(&t);
    ck_assert_uint_eq(result_count, 0);
}
END_TEST

/* An expedited read of 1018h:01 of server 5: the request on 605h, the answer on 585h, the value
 * in the application's buffer. */
START_TEST(expedited_read)
{
    uint8_t buf[4] = {0};
    ck_assert_int_eq(upload(0, 0x1018, 1, buf, sizeof(buf)), 0);
    test_expect(&t, "605#4018100100000000");
    test_rx(&t, "585#4318100178563412");
    test_expect_none(&t);
    expect_result(0, CO_SDO_CLIENT_OK, 0, 4, 0x1018, 1);
    const uint8_t value[4] = {0x78, 0x56, 0x34, 0x12};
    ck_assert_mem_eq(buf, value, 4);
    ck_assert_uint_eq(t.bus.deadline, CO_TIME_NEVER);
}
END_TEST

/* A segmented read of 1008h (10 bytes) in two segments, toggling. */
START_TEST(segmented_read)
{
    uint8_t buf[16] = {0};
    ck_assert_int_eq(upload(0, 0x1008, 0, buf, sizeof(buf)), 0);
    test_expect(&t, "605#4008100000000000");
    test_rx(&t, "585#410810000A000000");
    test_expect(&t, "605#6000000000000000");
    test_rx(&t, "585#0041424344454647");
    test_expect(&t, "605#7000000000000000");
    ck_assert_uint_eq(result_count, 0);
    test_rx(&t, "585#1948494A00000000");
    test_expect_none(&t);
    expect_result(0, CO_SDO_CLIENT_OK, 0, 10, 0x1008, 0);
    ck_assert_mem_eq(buf, "ABCDEFGHIJ", 10);
}
END_TEST

/* An expedited write of two bytes to 2000h:03 of server 5, and the server's abort of the next. */
START_TEST(write_and_server_abort)
{
    static const uint8_t value[2] = {0x34, 0x12};
    ck_assert_int_eq(co_node_sdo_download(&t.node, 0, 0x2000, 3, value, 2, CO_SDO_CLIENT_AUTO,
                                          TIMEOUT_MS, t.bus.now),
                     0);
    test_expect(&t, "605#2B00200334120000");
    test_rx(&t, "585#6000200300000000");
    expect_result(0, CO_SDO_CLIENT_OK, 0, 2, 0x2000, 3);
    ck_assert_int_eq(co_node_sdo_download(&t.node, 0, 0x2000, 4, value, 2, CO_SDO_CLIENT_AUTO,
                                          TIMEOUT_MS, t.bus.now),
                     0);
    test_expect(&t, "605#2B00200434120000");
    test_rx(&t, "585#8000200402000106");
    test_expect_none(&t);
    expect_result(1, CO_SDO_CLIENT_SERVER_ABORT, 0x06010002, 0, 0x2000, 4);
}
END_TEST

/* The node's deadline is the client's timeout, at which the client aborts (05040000h). */
START_TEST(timeout_in_node_deadline)
{
    uint8_t buf[4];
    co_time_t start = t.bus.now;
    ck_assert_int_eq(upload(0, 0x1018, 1, buf, sizeof(buf)), 0);
    test_expect(&t, "605#4018100100000000");
    ck_assert_uint_eq(t.bus.deadline, start + TIMEOUT_MS * 1000u);
    test_advance(&t, TIMEOUT_MS * 1000u - 1u);
    test_expect_none(&t);
    ck_assert_uint_eq(result_count, 0);
    test_advance(&t, 1);
    ck_assert_uint_eq(test_expect(&t, "605#8018100100000405"), start + TIMEOUT_MS * 1000u);
    expect_result(0, CO_SDO_CLIENT_CLIENT_ABORT, 0x05040000, 0, 0x1018, 1);
}
END_TEST

/* Requests: no such channel, a channel not valid, a busy one, a stopped node. A channel not valid
 * takes no frame; once valid it runs. */
START_TEST(invalid_channel_ignores_frames)
{
    uint8_t buf[4];
    ck_assert_int_eq(upload(2, 0x1018, 1, buf, sizeof(buf)), CO_SDO_CLIENT_ERR_CHANNEL);
    ck_assert_int_eq(upload(1, 0x1018, 1, buf, sizeof(buf)), CO_SDO_CLIENT_ERR_INVALID);
    test_expect_none(&t);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x80000606, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 2, 0x80000586, 4), 0);
    test_rx(&t, "586#4318100178563412");
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x606, 4), 0);
    ck_assert_int_eq(upload(1, 0x1018, 1, buf, sizeof(buf)), CO_SDO_CLIENT_ERR_INVALID);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 2, 0x586, 4), 0);
    ck_assert_int_eq(upload(1, 0x1018, 1, buf, sizeof(buf)), 0);
    test_expect(&t, "606#4018100100000000");
    ck_assert_int_eq(upload(1, 0x1018, 1, buf, sizeof(buf)), CO_SDO_CLIENT_ERR_BUSY);
    test_rx(&t, "586#4318100178563412");
    expect_result(0, CO_SDO_CLIENT_OK, 0, 4, 0x1018, 1);
    /* Channel 0 made not valid while idle: its responses are nobody's. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 2, 0x80000585, 4), 0);
    test_rx(&t, "585#4318100178563412");
    test_expect_none(&t);
    ck_assert_uint_eq(result_count, 1);
    /* Stopped: no SDO (CiA 301 table 74). */
    test_rx(&t, "000#0204");
    ck_assert_int_eq(upload(1, 0x1018, 1, buf, sizeof(buf)), CO_SDO_CLIENT_ERR_INVALID);
    test_expect_none(&t);
}
END_TEST

/* The consumed COB-IDs have the valid channels' server -> client COB-IDs, and follow a write. */
START_TEST(consumed_cob_ids_follow)
{
    ck_assert(co_node_consumes(&t.node, 0x585, false));
    ck_assert(!co_node_consumes(&t.node, 0x586, false));
    uint32_t generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 2, 0x586, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(!co_node_consumes(&t.node, 0x586, false)); /* 1281h:01 still not valid */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x606, 4), 0);
    ck_assert(co_node_consumes(&t.node, 0x586, false));
    ck_assert(!co_node_consumes(&t.node, 0x606, false)); /* its requests are the node's own */
    generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 2, 0x80000585, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(!co_node_consumes(&t.node, 0x585, false));
}
END_TEST

/* A transfer whose channel becomes not valid ends at once as the client's abort 08000022h, with
 * no frame on its COB-ID; the server's late answer is ignored. */
START_TEST(transfer_cut_by_invalidation)
{
    uint8_t buf[16];
    ck_assert_int_eq(upload(0, 0x1008, 0, buf, sizeof(buf)), 0);
    test_expect(&t, "605#4008100000000000");
    test_rx(&t, "585#410810000A000000");
    test_expect(&t, "605#6000000000000000");
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x80000605, 4), 0);
    expect_result(0, CO_SDO_CLIENT_CLIENT_ABORT, 0x08000022, 0, 0x1008, 0);
    test_rx(&t, "585#0041424344454647");
    test_expect_none(&t);
    ck_assert_uint_eq(result_count, 1);
    ck_assert_uint_eq(co_node_process(&t.node, t.bus.now), CO_TIME_NEVER);
}
END_TEST

/* Reset communication ends a transfer the same way, and reloads the channels. */
START_TEST(transfer_cut_by_reset)
{
    uint8_t buf[4];
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 1, 0x606, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1281, 2, 0x586, 4), 0);
    ck_assert_int_eq(upload(0, 0x1018, 1, buf, sizeof(buf)), 0);
    test_expect(&t, "605#4018100100000000");
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    expect_result(0, CO_SDO_CLIENT_CLIENT_ABORT, 0x08000022, 0, 0x1018, 1);
    ck_assert(channels[0].valid);
    ck_assert(!channels[1].valid);
    test_expect_none(&t);
}
END_TEST

/* co_sdo_clients_init refuses no states, none, more than CO_CONFIG_SDO_CLIENTS_MAX, no callback;
 * co_node_init refuses clients it did not prepare; a node given none takes any 1280h value. */
START_TEST(init_refuses_bad_channels)
{
    co_sdo_clients_t bad;
    ck_assert_int_eq(co_sdo_clients_init(&bad, NULL, 1, done, NULL), -1);
    ck_assert_int_eq(co_sdo_clients_init(&bad, channels, 0, done, NULL), -1);
    ck_assert_int_eq(co_sdo_clients_init(&bad, channels, CO_CONFIG_SDO_CLIENTS_MAX + 1, done, NULL),
                     -1);
    ck_assert_int_eq(co_sdo_clients_init(&bad, channels, 1, NULL, NULL), -1);
    memset(&bad, 0, sizeof(bad));
    bad.channels = channels;
    bad.count = 1;
    co_node_config_t config = {.node_id = 4,
                               .od = test_od_with_sdo_clients(),
                               .od_data = t.data,
                               .send = t.node.send,
                               .sdo_clients = &bad};
    co_node_t node;
    ck_assert_int_eq(co_node_init(&node, &config), CO_NODE_ERR_CONFIG);
    config.sdo_clients = NULL;
    test_node_start_config(&t, &config);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1280, 1, 0x20000606, 4), 0);
    ck_assert_int_eq(co_node_sdo_upload(&t.node, 0, 0x1018, 1, (uint8_t[4]){0}, 4,
                                        CO_SDO_CLIENT_AUTO, TIMEOUT_MS, t.bus.now),
                     CO_SDO_CLIENT_ERR_CHANNEL);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_client_objects");
    TCase *tc = tcase_create("sdo_client_objects");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, cob_id_write_rules);
    tcase_add_test(tc, expedited_read);
    tcase_add_test(tc, segmented_read);
    tcase_add_test(tc, write_and_server_abort);
    tcase_add_test(tc, timeout_in_node_deadline);
    tcase_add_test(tc, invalid_channel_ignores_frames);
    tcase_add_test(tc, consumed_cob_ids_follow);
    tcase_add_test(tc, transfer_cut_by_invalidation);
    tcase_add_test(tc, transfer_cut_by_reset);
    tcase_add_test(tc, init_refuses_bad_channels);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
