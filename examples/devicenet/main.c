/* SPDX-License-Identifier: Apache-2.0 */
/* A consumer of the installed DeviceNet libraries: a slave (dn_node_t, one 4-byte assembly each
 * way) and a scanner (dn_scanner_t) on an in-process bus. The scanner allocates the explicit and
 * polled connections, reads the slave's product name (Identity 1/1/7, fragmented: 8 bytes), sets
 * the polled connection's expected packet rate and polls once; each answer is checked and the
 * program exits 0 only when all are right. */
#include "dn/dn_node.h"
#include "dn/dn_scanner.h"

#include <stdio.h>
#include <string.h>

#define SLAVE_MAC 25u
#define SCANNER_MAC 1u
#define QUEUE 16u

/* The bus: frames in the order sent, delivered to the other side. */
typedef struct bus {
    co_frame_t frame[QUEUE];
    unsigned count;
} bus_t;

static bus_t to_slave, to_scanner;
static int failures;

static void queue(bus_t *bus, const co_frame_t *frame)
{
    if (bus->count == QUEUE) {
        fprintf(stderr, "devicenet example: bus queue full\n");
        failures++;
        return;
    }
    bus->frame[bus->count++] = *frame;
}

static void slave_send(void *user, const co_frame_t *frame)
{
    (void)user;
    queue(&to_scanner, frame);
}

static void scanner_send(void *user, const co_frame_t *frame)
{
    (void)user;
    queue(&to_slave, frame);
}

/* The slave's application: assembly 150 consumed, 151 produced (output + 1 in each byte). */
static uint8_t output[4];

static void read_assembly(void *user, uint16_t instance, uint8_t *data)
{
    (void)user;
    (void)instance;
    for (unsigned i = 0; i < sizeof output; i++)
        data[i] = (uint8_t)(output[i] + 1u);
}

static void write_assembly(void *user, uint16_t instance, const uint8_t *data)
{
    (void)user;
    (void)instance;
    memcpy(output, data, sizeof output);
}

static const dn_assembly_t assemblies[] = {{150, 4, false}, {151, 4, true}};
static const dn_app_t slave_app = {
    .send = slave_send, .read_assembly = read_assembly, .write_assembly = write_assembly};
static const dn_config_t slave_config = {
    .mac_id = SLAVE_MAC,
    .vendor_id = 0xFFFF,
    .device_type = 0,
    .product_code = 1,
    .major_revision = 1,
    .minor_revision = 1,
    .serial_number = 0x00000001,
    .product_name = "EXAMPLE",
    .assemblies = assemblies,
    .assembly_count = 2,
    .default_consumed_assembly = 150,
    .default_produced_assembly = 151,
    .app = &slave_app,
};

/* The scanner's application: what each request gave. */
static dn_result_t last;
static uint8_t last_data[DN_MESSAGE_MAX];
static bool done;
static uint8_t input[8];
static uint8_t input_len;

static void scanner_done(void *user, const dn_result_t *result)
{
    (void)user;
    last = *result;
    memcpy(last_data, result->data, result->len);
    done = true;
}

static void scanner_io(void *user, uint8_t mac_id, dn_io_kind_t kind, const uint8_t *data,
                       uint8_t len)
{
    (void)user;
    (void)mac_id;
    if (kind == DN_IO_POLL_RESPONSE) {
        memcpy(input, data, len);
        input_len = len;
    }
}

static const dn_scanner_app_t scanner_app = {
    .send = scanner_send, .done = scanner_done, .io = scanner_io};
static dn_slave_t slaves[1] = {{.mac_id = SLAVE_MAC}};
static const dn_scanner_config_t scanner_config = {
    .mac_id = SCANNER_MAC, .slaves = slaves, .slave_count = 1, .app = &scanner_app};

static dn_node_t node;
static dn_scanner_t scanner;
static co_time_t now;

/* Delivers the frames both ways until the bus is quiet, a millisecond apart. */
static void settle(void)
{
    while (to_slave.count || to_scanner.count) {
        now += 1000;
        bus_t slave_in = to_slave, scanner_in = to_scanner;
        to_slave.count = to_scanner.count = 0;
        for (unsigned i = 0; i < slave_in.count; i++)
            dn_node_receive(&node, &slave_in.frame[i], now);
        dn_node_process(&node, now);
        for (unsigned i = 0; i < scanner_in.count; i++)
            dn_scanner_receive(&scanner, &scanner_in.frame[i], now);
        dn_scanner_process(&scanner, now);
    }
}

static void check(bool ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "devicenet example: %s\n", what);
        failures++;
    }
}

int main(void)
{
    check(dn_node_init(&node, &slave_config) == 0, "the slave's configuration is refused");
    check(dn_scanner_init(&scanner, &scanner_config) == DN_SCANNER_INIT_OK,
          "the scanner's configuration is refused");
    if (failures)
        return 1;
    /* The slave's duplicate MAC ID check: two requests a second apart, then a second's wait. */
    dn_node_power_up(&node, now);
    for (int second = 0; second < 3; second++) {
        now += 1000000;
        dn_node_process(&node, now);
        to_scanner.count = 0; /* the scanner is not on the bus yet */
    }
    check(node.link == DN_LINK_ONLINE, "the slave is not online");
    dn_scanner_start_online(&scanner, now);

    done = false;
    dn_scanner_allocate(&scanner, SLAVE_MAC, DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED, now);
    settle();
    check(done && last.status == DN_RESULT_OK, "Allocate failed");

    done = false;
    dn_scanner_get(&scanner, SLAVE_MAC, DN_CLASS_IDENTITY, 1, 7, now);
    settle();
    check(done && last.status == DN_RESULT_OK && last.len == 8 &&
              memcmp(last_data,
                     "\x07"
                     "EXAMPLE",
                     8) == 0,
          "the product name is not \"EXAMPLE\"");

    /* The polled connection (instance 2) is established by its expected packet rate. */
    done = false;
    dn_scanner_set_expected_packet_rate(&scanner, SLAVE_MAC, 2, 100, now);
    settle();
    check(done && last.status == DN_RESULT_OK, "the expected packet rate was refused");

    static const uint8_t out[4] = {0x10, 0x20, 0x30, 0x40};
    dn_scanner_set_output(&scanner, SLAVE_MAC, out, sizeof out);
    dn_scanner_poll(&scanner, SLAVE_MAC, now);
    settle();
    check(memcmp(output, out, 4) == 0, "the slave did not get the poll's output data");
    check(input_len == 4 && memcmp(input, "\x11\x21\x31\x41", 4) == 0,
          "the poll response is not the slave's input data");

    if (failures == 0)
        printf("devicenet example: allocated, product name \"EXAMPLE\", one poll: all right\n");
    return failures ? 1 : 0;
}
