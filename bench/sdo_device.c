/* SPDX-License-Identifier: Apache-2.0 */
/* The device of the SDO throughput bench (bench/sdo-throughput): one node on a SocketCAN interface
 * through the Linux runtime, its dictionary bench/sdo_device.eds with two streamed DOMAINs that
 * live in this program's memory (bench/sdo_device.hooks): 2100h of up to 102400 bytes and 2101h
 * of up to 1024. An upload reads the value last written (at start: the capacity, filled with a
 * counting pattern); a download is collected aside and committed only when complete, so an
 * aborted one leaves the value as it was. Not an emulated drive: atv312d's dictionaries have no
 * DOMAIN this large, and a bench needs nothing but the SDO server.
 *
 *   sdo_device IFACE [NODE-ID]      (node-id 1..127, default 10; stops on SIGINT/SIGTERM) */
#include "co/co_node.h"
#include "co_linux/loop.h"
#include "sdo_device_od.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define IMAGE_MAX 102400u
#define RECORD_MAX 1024u

/* One streamed value: what uploads read, and the download in progress. */
typedef struct stored_value {
    uint16_t index;
    uint32_t capacity;
    uint8_t *value;
    uint32_t size;
    uint8_t *incoming;
} stored_value_t;

static uint8_t image[2][IMAGE_MAX];
static uint8_t record[2][RECORD_MAX];
static stored_value_t values[] = {
    {0x2100, IMAGE_MAX, image[0], IMAGE_MAX, image[1]},
    {0x2101, RECORD_MAX, record[0], RECORD_MAX, record[1]},
};

static stored_value_t *value_of(const co_od_entry_t *entry)
{
    return entry->index == values[0].index ? &values[0] : &values[1];
}

static uint32_t value_size(co_node_t *node, const co_od_entry_t *entry, uint32_t *size)
{
    (void)node;
    *size = value_of(entry)->size;
    return 0;
}

static uint32_t value_read(co_node_t *node, const co_od_entry_t *entry, uint32_t offset,
                           uint8_t *buf, size_t len)
{
    (void)node;
    memcpy(buf, value_of(entry)->value + offset, len);
    return 0;
}

static uint32_t value_begin(co_node_t *node, const co_od_entry_t *entry, bool size_indicated,
                            uint32_t size)
{
    (void)node;
    return size_indicated && size > value_of(entry)->capacity ? CO_SDO_ABORT_LENGTH_HIGH : 0;
}

static uint32_t value_write(co_node_t *node, const co_od_entry_t *entry, uint32_t offset,
                            const uint8_t *data, size_t len)
{
    (void)node;
    stored_value_t *v = value_of(entry);
    if (offset + len > v->capacity)
        return CO_SDO_ABORT_LENGTH_HIGH;
    memcpy(v->incoming + offset, data, len);
    return 0;
}

/* The committed value becomes the one uploads read: the two buffers swap. */
static uint32_t value_end(co_node_t *node, const co_od_entry_t *entry, uint32_t total, bool ok)
{
    (void)node;
    stored_value_t *v = value_of(entry);
    if (ok) {
        uint8_t *committed = v->incoming;
        v->incoming = v->value;
        v->value = committed;
        v->size = total;
    }
    return 0;
}

const co_od_stream_t bench_stream = {
    .size = value_size,
    .read = value_read,
    .begin = value_begin,
    .write = value_write,
    .end = value_end,
};

typedef struct device {
    co_linux_device_t link;
    co_node_t node;
    uint8_t od_data[SDO_DEVICE_OD_DATA_SIZE];
} device_t;

static void device_start(void *ctx, co_time_t now)
{
    device_t *d = ctx;
    co_node_start(&d->node, now);
}

/* After the interface was down: reset communication, which sends the boot-up. */
static void device_restart(void *ctx, co_time_t now)
{
    device_t *d = ctx;
    co_frame_t reset = {.id = 0, .len = 2, .data = {CO_NMT_CS_RESET_COMMUNICATION}};
    reset.data[1] = d->node.node_id;
    co_node_receive(&d->node, &reset, now);
}

static void device_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    device_t *d = ctx;
    co_node_receive(&d->node, frame, now);
}

static co_time_t device_process(void *ctx, co_time_t now)
{
    device_t *d = ctx;
    return co_node_process(&d->node, now);
}

static const co_linux_device_ops_t device_ops = {
    .start = device_start,
    .restart = device_restart,
    .receive = device_receive,
    .process = device_process,
};

int main(int argc, char **argv)
{
    char *end = NULL;
    long node_id = argc == 3 ? strtol(argv[2], &end, 10) : 10;
    if (argc < 2 || argc > 3 || (end != NULL && *end != '\0') || node_id < 1 || node_id > 127) {
        fprintf(stderr, "usage: sdo_device IFACE [NODE-ID 1..127]\n");
        return 64;
    }
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
        for (uint32_t n = 0; n < values[i].capacity; n++)
            values[i].value[n] = (uint8_t)(n * 7u + (n >> 8));
    static co_linux_loop_t loop;
    static device_t device;
    co_linux_loop_config_t loop_config = {.iface = argv[1]};
    if (co_linux_loop_open(&loop, &loop_config) != CO_LINUX_OPEN_OK) {
        fprintf(stderr, "sdo_device: cannot open %s: %s failed: %s\n", argv[1],
                loop.open_call ? loop.open_call : "the interface", strerror(loop.open_errno));
        return 69;
    }
    co_node_config_t config = {
        .node_id = (uint8_t)node_id,
        .od = &sdo_device_od,
        .od_data = device.od_data,
        .send = co_linux_device_send,
        .user = &device.link,
    };
    int rc = co_node_init(&device.node, &config);
    if (rc != 0) {
        fprintf(stderr, "sdo_device: co_node_init: error 0x%X\n", (unsigned)rc);
        co_linux_loop_close(&loop);
        return 70;
    }
    co_linux_loop_add(&loop, &device.link, &device_ops, &device);
    rc = co_linux_loop_run(&loop);
    co_linux_loop_close(&loop);
    return rc;
}
