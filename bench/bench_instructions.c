/* SPDX-License-Identifier: Apache-2.0 */
/* Counts the instructions the core executes per frame, under callgrind (deterministic, unlike
 * times on a shared machine): bench/instructions runs it as
 *   valgrind --tool=callgrind --collect-atstart=no bench_instructions [iterations]
 * Each operation runs `iterations` times (default 1000; at most 1000, see FRAME_INTERVAL_US) on a
 * fresh node; only the core's calls for
 * the frame are collected (co_node_receive and the co_node_process a runtime makes after it, as
 * src/linux/loop.c does), between two CALLGRIND_TOGGLE_COLLECT, and each operation's count is
 * dumped under its name (CALLGRIND_DUMP_STATS_AT). Outside valgrind the requests do nothing and
 * the program only checks that every operation answers as it should. */
#include "bench_od.h"
#include "co/co_node.h"
#include "sync4_od.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#define NODE_ID 4
/* CiA 301 SDO server command specifiers (bits 5-7 of byte 0). */

typedef struct bench {
    co_node_t node;
    uint8_t data[BENCH_OD_DATA_SIZE > SYNC4_OD_DATA_SIZE ? BENCH_OD_DATA_SIZE : SYNC4_OD_DATA_SIZE];
    unsigned long sent;
    co_frame_t last;
    co_time_t now;
} bench_t;

static void count_frame(void *user, const co_frame_t *frame)
{
    bench_t *b = user;
    b->sent++;
    b->last = *frame;
}

static void setup(bench_t *b, const co_od_t *od, bool operational)
{
    memset(b, 0, sizeof(*b));
    co_node_config_t config = {
        .node_id = NODE_ID, .od = od, .od_data = b->data, .send = count_frame, .user = b};
    if (co_node_init(&b->node, &config) != 0) {
        fprintf(stderr, "bench_instructions: the %s dictionary does not initialise\n", od->name);
        exit(1);
    }
    co_node_start(&b->node, 0);
    if (operational) {
        co_frame_t start = {.id = 0x000, .len = 2, .data = {0x01, NODE_ID}};
        co_node_receive(&b->node, &start, 0);
        co_node_process(&b->node, 0);
    }
    b->sent = 0;
}

/* Frames 50 us apart, a busy 1 Mbit/s bus: the 1000 frames of a run take 50 ms, within which
 * no timer of the dictionaries expires (the ATV312's TPDO event timers are 100 ms and more), so
 * that every frame counted is an answer. */
#define FRAME_INTERVAL_US 50

/* What a runtime does with one received frame, the part that is measured. */
static void handle(bench_t *b, const co_frame_t *frame)
{
    b->now += FRAME_INTERVAL_US;
    CALLGRIND_TOGGLE_COLLECT;
    co_node_receive(&b->node, frame, b->now);
    co_node_process(&b->node, b->now);
    CALLGRIND_TOGGLE_COLLECT;
}

static const co_frame_t sdo_upload_1000 = {.id = 0x604, .len = 8, .data = {0x40, 0x00, 0x10}};

static void op_sdo_expedited_upload(bench_t *b)
{
    handle(b, &sdo_upload_1000);
}

static void op_sdo_expedited_download(bench_t *b)
{
    co_frame_t f = {.id = 0x604, .len = 8, .data = {0x2B, 0x17, 0x10, 0x00, 0x64}};
    handle(b, &f);
}

/* The initiate request is not collected: only the segment request and its answer. */
static void op_sdo_upload_segment(bench_t *b)
{
    co_frame_t init = {.id = 0x604, .len = 8, .data = {0x40, 0x08, 0x10, 0x00}};
    b->now += FRAME_INTERVAL_US;
    co_node_receive(&b->node, &init, b->now);
    co_node_process(&b->node, b->now);
    co_frame_t segment = {.id = 0x604, .len = 8, .data = {0x60}};
    handle(b, &segment);
}

static void op_rpdo1(bench_t *b)
{
    co_frame_t f = {
        .id = 0x204, .len = 2, .data = {(uint8_t)((b->now / FRAME_INTERVAL_US) & 0x0F)}};
    handle(b, &f);
}

static void op_sync_4_tpdos(bench_t *b)
{
    co_frame_t f = {.id = CO_CAN_ID_SYNC, .len = 0};
    handle(b, &f);
}

typedef struct operation {
    const char *name;
    void (*run)(bench_t *);
    const co_od_t *od;
    bool operational;
    /* Frames the node must send per operation, and for an SDO the command specifier of the
     * last one (bits 5-7 of its first byte), so that an abort is not measured as an answer. */
    unsigned long frames;
    bool sdo;
    uint8_t scs;
} operation_t;

int main(int argc, char **argv)
{
    unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 1000;
    if (n == 0 || n > 1000) {
        fprintf(stderr, "usage: bench_instructions [iterations 1..1000]\n");
        return 2;
    }
    const operation_t ops[] = {
        {"SDO expedited upload request (1000h)", op_sdo_expedited_upload, &bench_od, false, 1, true,
         CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_INITIATE)},
        {"SDO expedited download request (1017h)", op_sdo_expedited_download, &bench_od, false, 1,
         true, CO_SDO_COMMAND(CO_SDO_SCS_DOWNLOAD_INITIATE)},
        {"SDO upload segment request (1008h)", op_sdo_upload_segment, &bench_od, false, 2, true,
         CO_SDO_COMMAND(CO_SDO_SCS_UPLOAD_SEGMENT)},
        {"RPDO1 received and applied (6040h)", op_rpdo1, &bench_od, true, 0, false, 0},
        {"SYNC with 4 synchronous TPDOs", op_sync_4_tpdos, &sync4_od, true, 4, false, 0},
    };
    static bench_t b;
    int failed = 0;
    for (size_t k = 0; k < sizeof ops / sizeof ops[0]; k++) {
        setup(&b, ops[k].od, ops[k].operational);
        CALLGRIND_ZERO_STATS;
        for (unsigned long i = 0; i < n; i++)
            ops[k].run(&b);
        CALLGRIND_DUMP_STATS_AT(ops[k].name);
        bool answered =
            b.sent == ops[k].frames * n && (!ops[k].sdo || (b.last.data[0] & 0xE0) == ops[k].scs);
        if (!answered) {
            fprintf(stderr,
                    "bench_instructions: %s: %lu frames sent (expected %lu), last %03X#%02X\n",
                    ops[k].name, b.sent, ops[k].frames * n, (unsigned)b.last.id, b.last.data[0]);
            failed = 1;
        }
        printf("%s\t%lu\n", ops[k].name, n);
    }
    return failed;
}
