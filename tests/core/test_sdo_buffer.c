/* SPDX-License-Identifier: Apache-2.0 */
/* An SDO transfer buffer given by the application (co_node_config_t.sdo_buffer) and shared by two
 * nodes of the test dictionary, node-ids 4 and 5, each on its own in-process bus: a segmented or
 * block transfer holds it until it ends, the other node's transfers that need it are refused
 * with 0x060A0023 meanwhile while its expedited ones go on, every way a transfer ends frees it,
 * and the buffer's size bounds the transfers as CO_CONFIG_SDO_BUFFER does for a node's own. */
#include "check_main.h"
#include "test_bus.h"

#include <stdio.h>
#include <string.h>

#define SHARED_SIZE 16u /* 2000h:0C "Hello, CANopen!" (15 bytes) fits, 17 bytes do not */

static test_node_t a, b;
static uint8_t shared_data[SHARED_SIZE];
static co_sdo_buffer_t shared;

/* test_node_start() makes the bus and its send callback; the node is then made again with the
 * shared buffer and started, and sends its boot-up frame again. */
static void start_sharing(test_node_t *t, uint8_t node_id)
{
    test_node_start(t, node_id, NULL, NULL);
    co_node_config_t config = {
        .node_id = node_id,
        .od = t->node.od,
        .od_data = t->data,
        .send = t->node.send,
        .user = t->node.user,
        .sdo_buffer = &shared,
    };
    ck_assert_int_eq(co_node_init(&t->node, &config), 0);
    co_node_start(&t->node, t->bus.now);
    t->bus.deadline = co_node_process(&t->node, t->bus.now);
    char boot[16];
    snprintf(boot, sizeof(boot), "%03X#00", 0x700 + node_id);
    test_expect(t, boot);
}

static void setup(void)
{
    shared = (co_sdo_buffer_t){.data = shared_data, .size = SHARED_SIZE};
    start_sharing(&a, 4);
    start_sharing(&b, 5);
}

/* Node 4 starts a segmented upload of 1008h ("ATV312", 6 bytes): it holds the buffer. */
static void a_takes_buffer(void)
{
    test_rx(&a, "604#4008100000000000");
    test_expect(&a, "584#4108100006000000");
    ck_assert_ptr_eq(shared.owner, &a.node.sdo);
}

/* Node 5 is refused every transfer that needs the buffer, and not the expedited ones. */
static void b_refused_buffer(void)
{
    test_rx(&b, "605#4008100000000000"); /* segmented upload */
    test_expect(&b, "585#8008100023000A06");
    test_rx(&b, "605#2100200C10000000"); /* segmented download */
    test_expect(&b, "585#8000200C23000A06");
    test_rx(&b, "605#C600200C10000000"); /* block download */
    test_expect(&b, "585#8000200C23000A06");
    test_rx(&b, "605#A40810007F000000"); /* block upload */
    test_expect(&b, "585#8008100023000A06");
    test_rx(&b, "605#4000100000000000"); /* expedited upload */
    test_expect(&b, "585#4300100092010100");
    test_rx(&b, "605#2F00200514000000"); /* expedited download */
    test_expect(&b, "585#6000200500000000");
    test_expect_none(&b);
    ck_assert_ptr_eq(shared.owner, &a.node.sdo);
}

/* Node 5 can take the free buffer: its segmented upload of 1008h completes. */
static void b_uses_buffer(void)
{
    ck_assert_ptr_null(shared.owner);
    test_rx(&b, "605#4008100000000000");
    test_expect(&b, "585#4108100006000000");
    test_rx(&b, "605#60");
    test_expect(&b, "585#0341545633313200");
    test_expect_none(&b);
    ck_assert_ptr_null(shared.owner);
}

START_TEST(held_until_the_transfer_ends)
{
    a_takes_buffer();
    b_refused_buffer();
    test_rx(&a, "604#60");
    test_expect(&a, "584#0341545633313200");
    test_expect_none(&a);
    b_uses_buffer();
}
END_TEST

START_TEST(block_transfers_hold_it_to_their_end)
{
    test_rx(&a, "604#C600200C0F000000");
    test_expect(&a, "584#A400200C03000000"); /* blksize 3: 16 bytes in 7-byte segments */
    b_refused_buffer();
    test_rx(&a, "604#0148656C6C6F2C20");
    test_rx(&a, "604#0243414E6F70656E");
    test_rx(&a, "604#8321000000000000");
    test_expect(&a, "584#A203010000000000"); /* 16 bytes in: room for nothing but the end */
    b_refused_buffer();
    test_rx(&a, "604#D90E1E0000000000");
    test_expect(&a, "584#A100000000000000");
    b_uses_buffer();
    /* A block upload holds it until the client's end response. */
    test_rx(&a, "604#A40810007F000000");
    test_expect(&a, "584#C608100006000000");
    test_rx(&a, "604#A3");
    test_expect(&a, "584#8141545633313200");
    test_rx(&a, "604#A2017F0000000000");
    test_expect(&a, "584#C5665D0000000000");
    b_refused_buffer();
    test_rx(&a, "604#A1");
    b_uses_buffer();
}
END_TEST

START_TEST(freed_by_every_end_of_a_transfer)
{
    /* The client's abort. */
    a_takes_buffer();
    test_rx(&a, "604#8008100000000000");
    b_uses_buffer();
    /* The protocol timeout. */
    a_takes_buffer();
    test_advance(&a, 1000000);
    test_expect(&a, "584#8008100000000405");
    b_uses_buffer();
    /* A server abort: a wrong toggle bit. */
    a_takes_buffer();
    test_rx(&a, "604#70");
    test_expect(&a, "584#8008100000000305");
    b_uses_buffer();
    /* A new expedited request replacing the transfer. */
    a_takes_buffer();
    test_rx(&a, "604#4000100000000000");
    test_expect(&a, "584#4300100092010100");
    b_uses_buffer();
    /* A request the node refuses without the buffer, replacing the transfer. */
    a_takes_buffer();
    test_rx(&a, "604#4000300000000000");
    test_expect(&a, "584#8000300000000206");
    b_uses_buffer();
    /* Reset communication. */
    a_takes_buffer();
    test_rx(&a, "000#8204");
    test_expect(&a, "704#00");
    b_uses_buffer();
    test_expect_none(&a);
}
END_TEST

/* The node holding the buffer may start another transfer that needs it. */
START_TEST(holder_may_start_another_transfer)
{
    a_takes_buffer();
    test_rx(&a, "604#2100200C03000000");
    test_expect(&a, "584#6000200C00000000");
    ck_assert_ptr_eq(shared.owner, &a.node.sdo);
    test_rx(&a, "604#0978790000000000");
    test_expect(&a, "584#2000000000000000");
    ck_assert_mem_eq(co_od_bytes(&a.node, co_od_find(a.node.od, 0x2000, 0x0C)), "xy", 3);
    b_uses_buffer();
}
END_TEST

/* The buffer's size, not CO_CONFIG_SDO_BUFFER, bounds the transfers (0x05040005), and a refused
 * transfer leaves the buffer free. */
START_TEST(size_of_the_application_buffer)
{
    test_rx(&a, "604#2100200C11000000");
    test_expect(&a, "584#8000200C05000405");
    test_rx(&a, "604#C600200C11000000");
    test_expect(&a, "584#8000200C05000405");
    test_rx(&a, "604#4000200D00000000"); /* 2000h:0D, 200 bytes */
    test_expect(&a, "584#8000200D05000405");
    test_rx(&a, "604#A400200D7F000000");
    test_expect(&a, "584#8000200D05000405");
    test_expect_none(&a);
    b_uses_buffer();
}
END_TEST

START_TEST(init_needs_the_buffer_data)
{
    co_sdo_buffer_t empty = {.data = NULL, .size = SHARED_SIZE};
    co_node_config_t config = {
        .node_id = 6,
        .od = a.node.od,
        .od_data = a.data,
        .send = a.node.send,
        .sdo_buffer = &empty,
    };
    co_node_t node;
    ck_assert_int_eq(co_node_init(&node, &config), CO_NODE_ERR_CONFIG);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_buffer");
    TCase *tc = tcase_create("shared");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, held_until_the_transfer_ends);
    tcase_add_test(tc, block_transfers_hold_it_to_their_end);
    tcase_add_test(tc, freed_by_every_end_of_a_transfer);
    tcase_add_test(tc, holder_may_start_another_transfer);
    tcase_add_test(tc, size_of_the_application_buffer);
    tcase_add_test(tc, init_needs_the_buffer_data);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
