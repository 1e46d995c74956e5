/* SPDX-License-Identifier: Apache-2.0 */
/* Additional SDO server channels (co_sdo_servers_t), frame by frame on the in-process bus, node-id
 * 4, with the test dictionary plus 1201h (690h / 6A0h, valid) and 1202h (not valid): two clients
 * at once, each channel with its own transfer and buffer; the COB-ID rules of CiA 301 7.5.2.34
 * with their abort codes; a channel that is not valid ignores its frames and drops its transfer
 * when it becomes so; the consumed COB-IDs follow; a buffer shared by the channels is refused
 * while held. */
#include "check_main.h"
#include "co/co_consumers.h"
#include "co/co_sdo_servers.h"
#include "test_bus.h"
#include "test_od.h"

#include <string.h>

#define CHANNELS 2

static test_node_t t;
static co_sdo_server_t channels[CHANNELS];
static co_sdo_servers_t servers;

/* "Hello, CANopen!" with its NUL, as test_sdo.c's transfers write it. */
static const char hello[16] = "Hello, CANopen!";

static void start(co_sdo_buffer_t *node_buffer, co_sdo_buffer_t *channels_buffer)
{
    ck_assert_int_eq(co_sdo_servers_init(&servers, channels, CHANNELS, channels_buffer), 0);
    co_node_config_t config = {
        .node_id = 4,
        .od = test_od_with_sdo_servers(),
        .sdo_buffer = node_buffer,
        .sdo_servers = &servers,
    };
    test_node_start_config(&t, &config);
}

static void setup(void)
{
    start(NULL, NULL);
}

static const uint8_t *entry_bytes(uint16_t index, uint8_t sub)
{
    return co_od_bytes(&t.node, co_od_find(t.node.od, index, sub));
}

/* A segmented download on the default channel and a block download with CRC on 1201h, frame by
 * frame in turn: each channel answers on its own COB-ID, and both values are written. */
START_TEST(segmented_and_block_download_at_once)
{
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "690#C60020120F000000");
    test_expect(&t, "6A0#A40020127F000000");
    test_rx(&t, "604#0048656C6C6F2C20");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "690#0148656C6C6F2C20");
    test_expect_none(&t);
    test_rx(&t, "604#1043414E6F70656E");
    test_expect(&t, "584#3000000000000000");
    test_rx(&t, "690#0243414E6F70656E");
    test_expect_none(&t);
    test_rx(&t, "604#0D21000000000000");
    test_expect(&t, "584#2000000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x0C), hello, 16);
    ck_assert_uint_eq(channels[0].state, CO_SDO_BLOCK_DOWNLOAD_SUB);
    test_rx(&t, "690#8321000000000000");
    test_expect(&t, "6A0#A2037F0000000000");
    test_rx(&t, "690#D90E1E0000000000");
    test_expect(&t, "6A0#A100000000000000");
    ck_assert_mem_eq(entry_bytes(0x2000, 0x12), hello, 16);
    ck_assert_uint_eq(co_sdo_process(&t.node, t.bus.now), CO_TIME_NEVER);
    test_expect_none(&t);
}
END_TEST

/* A block upload on the default channel and a segmented upload on 1201h, in turn. */
START_TEST(block_and_segmented_upload_at_once)
{
    test_rx(&t, "604#2100200C0F000000");
    test_expect(&t, "584#6000200C00000000");
    test_rx(&t, "604#0048656C6C6F2C20");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "604#1043414E6F70656E");
    test_expect(&t, "584#3000000000000000");
    test_rx(&t, "604#0D21000000000000");
    test_expect(&t, "584#2000000000000000");
    test_rx(&t, "604#A400200C7F000000");
    test_expect(&t, "584#C600200C0F000000");
    test_rx(&t, "690#4000200C00000000");
    test_expect(&t, "6A0#4100200C0F000000");
    test_rx(&t, "604#A3");
    test_expect(&t, "584#0148656C6C6F2C20");
    test_expect(&t, "584#0243414E6F70656E");
    test_expect(&t, "584#8321000000000000");
    test_rx(&t, "690#60");
    test_expect(&t, "6A0#0048656C6C6F2C20");
    test_rx(&t, "604#A2037F");
    test_expect(&t, "584#D90E1E0000000000");
    test_rx(&t, "690#70");
    test_expect(&t, "6A0#1043414E6F70656E");
    test_rx(&t, "604#A1");
    test_rx(&t, "690#60");
    test_expect(&t, "6A0#0D21000000000000");
    ck_assert_uint_eq(t.node.sdo.state, CO_SDO_IDLE);
    ck_assert_uint_eq(channels[0].state, CO_SDO_IDLE);
    test_expect_none(&t);
}
END_TEST

/* Each channel's timeout is its own: the default channel's transfer times out on 584h while the
 * one on 1201h, moved on by its frames, goes on. */
START_TEST(each_channel_times_out_alone)
{
    co_sdo_set_timeout(&t.node, 1000);
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_advance(&t, 600);
    test_rx(&t, "690#4000200C00000000");
    test_expect(&t, "6A0#4100200C05000000");
    test_advance(&t, 600);
    test_expect(&t, "584#8008100000000405");
    test_rx(&t, "690#60");
    test_expect(&t, "6A0#0573686F72740000");
    test_expect_none(&t);
}
END_TEST

/* CiA 301 7.5.2.34: a COB-ID changes only while not valid; bit 29, bits 28..11 and restricted
 * CAN-IDs are refused (0x06090030); 1200h's COB-IDs are read-only (0x06010002); the client's
 * node-id is 1..127. */
START_TEST(cob_id_write_rules)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x691, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 2, 0x6A1, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x690, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x40000690, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x20000690, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0xA0000690, 4), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0x00000800, 4), CO_SDO_ABORT_VALUE_RANGE);
    for (size_t i = 0; i < TEST_RESTRICTED_CAN_IDS; i++)
        ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0x80000000u | test_restricted_can_id[i], 4),
                          CO_SDO_ABORT_VALUE_RANGE);
    for (size_t i = 0; i < TEST_FREE_CAN_IDS; i++)
        ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 2, 0x80000000u | test_free_can_id[i], 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x80000690, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x691, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1200, 1, 0x604, 4), CO_SDO_ABORT_READ_ONLY);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 3, 0, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 3, 128, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 3, 127, 1), 0);
    uint32_t value;
    ck_assert_uint_eq(test_sdo_read(&t, 0x1201, 1, &value), 0);
    ck_assert_uint_eq(value, 0x691);
    test_expect_none(&t);
}
END_TEST

/* 1202h is not valid: its frames are ignored, whatever CAN-ID it holds; valid, it answers. */
START_TEST(invalid_channel_ignores_frames)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0x80000698, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 2, 0x800006A8, 4), 0);
    test_rx(&t, "698#4008100000000000");
    test_expect_none(&t);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0x698, 4), 0);
    test_rx(&t, "698#4008100000000000");
    test_expect_none(&t); /* its server -> client COB-ID is not valid yet */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 2, 0x6A8, 4), 0);
    test_rx(&t, "698#4000100000000000");
    test_expect(&t, "6A8#4300100092010100");
    test_expect_none(&t);
}
END_TEST

/* A transfer under way ends silently when its channel's COB-ID becomes not valid; its buffer is
 * free again, and the valid channel takes it up again from idle. */
START_TEST(transfer_dropped_when_channel_invalidated)
{
    test_rx(&t, "690#4008100000000000");
    test_expect(&t, "6A0#4108100006000000");
    ck_assert_ptr_eq(channels[0].buffer->owner, &channels[0]);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 2, 0x800006A0, 4), 0);
    ck_assert_uint_eq(channels[0].state, CO_SDO_IDLE);
    ck_assert_ptr_null(channels[0].buffer->owner);
    test_rx(&t, "690#6000000000000000");
    test_expect_none(&t);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 2, 0x6A0, 4), 0);
    test_rx(&t, "690#6000000000000000");
    test_expect(&t, "6A0#8000000001000405");
    test_expect_none(&t);
}
END_TEST

/* The consumed COB-IDs have the valid channels' client -> server COB-IDs, and follow a write;
 * reset communication reloads them from the dictionary. */
START_TEST(consumed_cob_ids_follow)
{
    ck_assert(co_node_consumes(&t.node, 0x604, false));
    ck_assert(co_node_consumes(&t.node, 0x690, false));
    ck_assert(!co_node_consumes(&t.node, 0x698, false));
    uint32_t generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 1, 0x698, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(!co_node_consumes(&t.node, 0x698, false)); /* 1202h:02 still not valid */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1202, 2, 0x6A8, 4), 0);
    ck_assert(co_node_consumes(&t.node, 0x698, false));
    generation = co_node_consumer_generation(&t.node);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1201, 1, 0x80000690, 4), 0);
    ck_assert_uint_ne(co_node_consumer_generation(&t.node), generation);
    ck_assert(!co_node_consumes(&t.node, 0x690, false));
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert(co_node_consumes(&t.node, 0x690, false));
    ck_assert(!co_node_consumes(&t.node, 0x698, false));
    co_cob_t cobs[CO_CONSUMERS_MAX];
    ck_assert_uint_le(co_node_consumers(&t.node, cobs), CO_CONSUMERS_MAX);
}
END_TEST

/* One buffer for the default channel and the additional ones (co_sdo_servers_t.buffer): the
 * transfer that holds it refuses the others' with 0x060A0023, not their expedited transfers. */
START_TEST(shared_buffer_refused_while_held)
{
    static uint8_t shared_data[64];
    static co_sdo_buffer_t shared;
    shared = (co_sdo_buffer_t){.data = shared_data, .size = sizeof(shared_data)};
    start(&shared, &shared);
    test_rx(&t, "604#4008100000000000");
    test_expect(&t, "584#4108100006000000");
    test_rx(&t, "690#4008100000000000");
    test_expect(&t, "6A0#8008100023000A06");
    test_rx(&t, "690#4000100000000000");
    test_expect(&t, "6A0#4300100092010100");
    test_rx(&t, "604#6000000000000000");
    test_expect(&t, "584#0341545633313200");
    test_rx(&t, "690#4008100000000000");
    test_expect(&t, "6A0#4108100006000000");
    ck_assert_ptr_eq(shared.owner, &channels[0]);
    test_expect_none(&t);
}
END_TEST

/* co_sdo_servers_init refuses no states, none, more than CO_CONFIG_SDO_SERVERS_MAX, a buffer
 * without data; co_node_init refuses servers it did not prepare. */
START_TEST(init_refuses_bad_channels)
{
    co_sdo_servers_t bad;
    co_sdo_buffer_t no_data = {.data = NULL, .size = 16};
    ck_assert_int_eq(co_sdo_servers_init(&bad, NULL, 1, NULL), -1);
    ck_assert_int_eq(co_sdo_servers_init(&bad, channels, 0, NULL), -1);
    ck_assert_int_eq(co_sdo_servers_init(&bad, channels, CO_CONFIG_SDO_SERVERS_MAX + 1, NULL), -1);
    ck_assert_int_eq(co_sdo_servers_init(&bad, channels, 1, &no_data), -1);
    static uint8_t data[4096];
    memset(&bad, 0, sizeof(bad));
    bad.channels = channels;
    bad.count = 1;
    co_node_config_t config = {.node_id = 4,
                               .od = test_od_with_sdo_servers(),
                               .od_data = data,
                               .send = t.node.send,
                               .sdo_servers = &bad};
    co_node_t node;
    ck_assert_int_eq(co_node_init(&node, &config), CO_NODE_ERR_CONFIG);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_servers");
    TCase *tc = tcase_create("sdo_servers");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, segmented_and_block_download_at_once);
    tcase_add_test(tc, block_and_segmented_upload_at_once);
    tcase_add_test(tc, each_channel_times_out_alone);
    tcase_add_test(tc, cob_id_write_rules);
    tcase_add_test(tc, invalid_channel_ignores_frames);
    tcase_add_test(tc, transfer_dropped_when_channel_invalidated);
    tcase_add_test(tc, consumed_cob_ids_follow);
    tcase_add_test(tc, shared_buffer_refused_while_held);
    tcase_add_test(tc, init_refuses_bad_channels);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
