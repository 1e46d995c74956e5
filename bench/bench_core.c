/* SPDX-License-Identifier: Apache-2.0 */
/* Measures the core's cost per protocol operation on the ATV312 dictionary, in one process with no
 * bus: the time per operation and its ratio to the cheapest operation measured in the same run
 * (these machines are shared and noisy: the ratios hold, single absolute times do not).
 *
 * Usage: bench_core [iterations]   (default 200000); prints a Markdown table. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */

#include "bench_od.h"
#include "co/co_node.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct bench {
    co_node_t node;
    uint8_t data[BENCH_OD_DATA_SIZE];
    unsigned long sent;
    co_frame_t last;
} bench_t;

static void count_frame(void *user, const co_frame_t *frame)
{
    bench_t *b = user;
    b->sent++;
    b->last = *frame;
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void setup(bench_t *b)
{
    memset(b, 0, sizeof(*b));
    co_node_config_t config = {
        .node_id = 4, .od = &bench_od, .od_data = b->data, .send = count_frame, .user = b};
    if (co_node_init(&b->node, &config) != 0) {
        fprintf(stderr, "bench: the ATV312 dictionary does not initialise\n");
        exit(1);
    }
    co_node_start(&b->node, 0);
}

static co_frame_t frame(uint32_t id, uint8_t len, const uint8_t *data)
{
    co_frame_t f = {.id = id, .len = len};
    memcpy(f.data, data, len);
    return f;
}

/* One operation of each kind; `i` makes the time and the data vary. */
static void op_idle_process(bench_t *b, unsigned long i)
{
    co_node_process(&b->node, i);
}

static void op_sdo_expedited_upload(bench_t *b, unsigned long i)
{
    static const uint8_t req[8] = {0x40, 0x00, 0x10, 0x00};
    co_frame_t f = frame(0x604, 8, req);
    co_node_receive(&b->node, &f, i);
}

static void op_sdo_expedited_download(bench_t *b, unsigned long i)
{
    uint8_t req[8] = {0x2B, 0x17, 0x10, 0x00, (uint8_t)(i & 1), 0, 0, 0};
    co_frame_t f = frame(0x604, 8, req);
    co_node_receive(&b->node, &f, i);
}

static void op_sdo_segmented_upload(bench_t *b, unsigned long i)
{
    static const uint8_t init[8] = {0x40, 0x08, 0x10, 0x00};
    co_frame_t f = frame(0x604, 8, init);
    co_node_receive(&b->node, &f, i);
    static const uint8_t seg[8] = {0x60};
    f = frame(0x604, 8, seg);
    co_node_receive(&b->node, &f, i);
}

static void op_rpdo1(bench_t *b, unsigned long i)
{
    uint8_t data[2] = {(uint8_t)(i & 0x0F), 0};
    co_frame_t f = frame(0x204, 2, data);
    co_node_receive(&b->node, &f, i);
}

static void op_tpdo1_change(bench_t *b, unsigned long i)
{
    co_od_set_value(&b->node, 0x6041, 0, (int64_t)(i & 0xFF));
    co_node_process(&b->node, (co_time_t)i * 100000u); /* past the inhibit time */
}

typedef struct measure {
    const char *name;
    void (*op)(bench_t *, unsigned long);
    bool operational;
    double ns;
    unsigned long frames;
} measure_t;

int main(int argc, char **argv)
{
    unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 200000;
    if (n == 0) {
        fprintf(stderr, "usage: bench_core [iterations > 0]\n");
        return 2;
    }
    measure_t m[] = {
        {"idle co_node_process", op_idle_process, false, 0, 0},
        {"SDO expedited upload (1000h)", op_sdo_expedited_upload, false, 0, 0},
        {"SDO expedited download (1017h)", op_sdo_expedited_download, false, 0, 0},
        {"SDO segmented upload (1008h, 2 requests)", op_sdo_segmented_upload, false, 0, 0},
        {"RPDO1 received and applied (6040h)", op_rpdo1, true, 0, 0},
        {"TPDO1 change detected and sent (6041h)", op_tpdo1_change, true, 0, 0},
    };
    size_t count = sizeof(m) / sizeof(m[0]);
    static bench_t b;
    for (size_t k = 0; k < count; k++) {
        setup(&b);
        if (m[k].operational) {
            const uint8_t start[2] = {0x01, 0x04};
            co_frame_t f = frame(0x000, 2, start);
            co_node_receive(&b.node, &f, 0);
        }
        b.sent = 0;
        double t0 = seconds();
        for (unsigned long i = 1; i <= n; i++)
            m[k].op(&b, i);
        m[k].ns = (seconds() - t0) * 1e9 / (double)n;
        m[k].frames = b.sent;
    }
    double base = m[0].ns > 0 ? m[0].ns : 1;
    printf("| operation | ns / op | ratio to idle process | frames sent / op |\n");
    printf("|---|---:|---:|---:|\n");
    for (size_t k = 0; k < count; k++)
        printf("| %s | %.1f | %.1f | %.2f |\n", m[k].name, m[k].ns, m[k].ns / base,
               (double)m[k].frames / (double)n);
    printf("\nRAM per node: sizeof(co_node_t) = %zu bytes + ATV312 data block = %u bytes; "
           "dictionary: %u entries (%zu bytes of const table).\n",
           sizeof(co_node_t), (unsigned)BENCH_OD_DATA_SIZE, (unsigned)bench_od.count,
           (size_t)bench_od.count * sizeof(co_od_entry_t));
    return 0;
}
