/* SPDX-License-Identifier: Apache-2.0 */
/* A consumer of the installed canopen package: one node on the dictionary of counter.eds (its
 * table generated at build time by co-edstool), driven in-process with injected time the way a
 * runtime drives it. Each step hands the node a frame, or only lets time pass, and checks the one
 * frame the node answers with, byte for byte. Every frame is printed in candump -L format by the
 * Linux runtime's formatter (canopen::linux). Exits 0 when every answer is right, 1 otherwise. */
#include "co/co_node.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "counter_od.h"

#include <stdio.h>
#include <string.h>

#define NODE_ID 5

static co_frame_t sent[4];
static size_t sent_count;

static void send_frame(void *user, const co_frame_t *frame)
{
    (void)user;
    if (sent_count < sizeof sent / sizeof sent[0])
        sent[sent_count] = *frame;
    sent_count++;
}

static void print_frame(FILE *out, co_time_t now, const char *direction, const co_frame_t *frame)
{
    struct timespec at = {.tv_sec = (time_t)(now / 1000000u),
                          .tv_nsec = (long)(now % 1000000u) * 1000};
    struct can_frame can;
    char line[CO_CANDUMP_LINE_MAX];
    co_linux_frame_to_can(frame, &can);
    co_candump_format(line, sizeof line, &at, direction, &can);
    fputs(line, out);
}

static bool same_frame(const co_frame_t *a, const co_frame_t *b)
{
    return a->id == b->id && a->len == b->len && a->flags == b->flags &&
           memcmp(a->data, b->data, a->len) == 0;
}

typedef struct step {
    const char *what;
    co_time_t at;
    bool has_request; /* false: only time passes */
    co_frame_t request;
    co_frame_t answer;
} step_t;

#define SDO_RX (0x600 + NODE_ID) /* requests to the node's SDO server */
#define SDO_TX (0x580 + NODE_ID) /* its answers */

static const step_t steps[] = {
    {.what = "SDO write 2000h = 500",
     .at = 1000,
     .has_request = true,
     .request = {.id = SDO_RX, .len = 8, .data = {0x2B, 0x00, 0x20, 0x00, 0xF4, 0x01}},
     .answer = {.id = SDO_TX, .len = 8, .data = {0x60, 0x00, 0x20, 0x00}}},
    {.what = "SDO write 2000h = 5000, above its HighLimit: abort 06090031",
     .at = 2000,
     .has_request = true,
     .request = {.id = SDO_RX, .len = 8, .data = {0x2B, 0x00, 0x20, 0x00, 0x88, 0x13}},
     .answer = {.id = SDO_TX, .len = 8, .data = {0x80, 0x00, 0x20, 0x00, 0x31, 0x00, 0x09, 0x06}}},
    {.what = "SDO read 2000h: still 500",
     .at = 3000,
     .has_request = true,
     .request = {.id = SDO_RX, .len = 8, .data = {0x40, 0x00, 0x20, 0x00}},
     .answer = {.id = SDO_TX, .len = 8, .data = {0x4B, 0x00, 0x20, 0x00, 0xF4, 0x01}}},
    {.what = "SDO write 1017h = 100 ms heartbeat",
     .at = 4000,
     .has_request = true,
     .request = {.id = SDO_RX, .len = 8, .data = {0x2B, 0x17, 0x10, 0x00, 0x64, 0x00}},
     .answer = {.id = SDO_TX, .len = 8, .data = {0x60, 0x17, 0x10, 0x00}}},
    {.what = "100 ms later: heartbeat, Pre-operational",
     .at = 104000,
     .has_request = false,
     .answer = {.id = 0x700 + NODE_ID, .len = 1, .data = {0x7F}}},
};

/* Checks that exactly the expected frame was sent since the last check. */
static bool check_answer(const char *what, co_time_t now, const co_frame_t *expected)
{
    for (size_t i = 0; i < sent_count && i < sizeof sent / sizeof sent[0]; i++)
        print_frame(stdout, now, "tx", &sent[i]);
    bool ok = sent_count == 1 && same_frame(&sent[0], expected);
    if (!ok) {
        fflush(stdout);
        fprintf(stderr, "consumer: %s: expected one frame, ", what);
        print_frame(stderr, now, "expected", expected);
        fprintf(stderr, "consumer: the node sent %zu frame(s), shown above\n", sent_count);
    }
    sent_count = 0;
    return ok;
}

int main(void)
{
    static co_node_t node;
    static uint8_t od_data[COUNTER_OD_DATA_SIZE];
    co_node_config_t config = {
        .node_id = NODE_ID, .od = &counter_od, .od_data = od_data, .send = send_frame};
    int err = co_node_init(&node, &config);
    if (err != 0) {
        fprintf(stderr, "consumer: co_node_init: error %d\n", err);
        return 1;
    }
    co_node_start(&node, 0);
    const co_frame_t boot_up = {.id = 0x700 + NODE_ID, .len = 1, .data = {0x00}};
    bool ok = check_answer("boot-up", 0, &boot_up);

    co_time_t deadline = co_node_process(&node, 0);
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        const step_t *s = &steps[i];
        if (s->has_request) {
            print_frame(stdout, s->at, "rx", &s->request);
            co_node_receive(&node, &s->request, s->at);
        } else if (deadline != s->at) {
            fprintf(stderr, "consumer: %s: the node's next deadline is %llu us, expected %llu\n",
                    s->what, (unsigned long long)deadline, (unsigned long long)s->at);
            ok = false;
        }
        deadline = co_node_process(&node, s->at);
        ok = check_answer(s->what, s->at, &s->answer) && ok;
    }
    puts(ok ? "consumer: every answer as expected" : "consumer: FAILED");
    return ok ? 0 : 1;
}
