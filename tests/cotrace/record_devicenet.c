/* SPDX-License-Identifier: Apache-2.0 */
/* Records tests/cotrace/devicenet.log: the portable DeviceNet slave (src/devicenet) at MAC ID 25
 * with the Altivar 312 card's assemblies, driven by a scripted scanner at MAC ID 1 with injected
 * time, every frame of both written as candump -L prints it. The same program gives the same
 * trace byte for byte (the test cotrace_devicenet_log compares), so that the trace cotrace and
 * tshark decode (test_devicenet.py) is the library's real behaviour, and can be made again:
 *
 *     build/tests/cotrace/cotrace_record_devicenet > tests/cotrace/devicenet.log
 *
 * The script: the duplicate MAC ID check (the slave's, the scanner's, and one for MAC ID 25 the
 * slave answers), a UCMM request the Group 2 only server ignores, Allocate, Get (one answered in
 * fragments), a fragmented Set, refusals, polls (with idle), change of state with its
 * acknowledgements, the assembly selection and an Identity Reset that applies it, the polls on
 * 100/101, Release. */
#include "dn/dn_node.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SLAVE_MAC 25u
#define EPOCH_S 1700000000ull

typedef struct recorder {
    dn_node_t node;
    dn_config_t config;
    dn_app_t app;
    co_time_t now;
    co_time_t deadline;
    uint8_t consumed[3][4]; /* 20, 21, 100 */
    uint8_t produced[3][4]; /* 70, 71, 101 */
    dn_stored_t stored;
    int reset_type;
} recorder_t;

static const dn_assembly_t assemblies[] = {
    {20, 4, false}, {21, 4, false}, {70, 4, true}, {71, 4, true}, {100, 4, false}, {101, 4, true},
};

static void print_frame(co_time_t now, const co_frame_t *f)
{
    unsigned long long us = EPOCH_S * 1000000ull + now;
    printf("(%llu.%06llu) vcan0 %03X#", us / 1000000ull, us % 1000000ull, (unsigned)f->id);
    for (uint8_t i = 0; i < f->len; i++)
        printf("%02X", f->data[i]);
    printf("\n");
}

static void on_send(void *user, const co_frame_t *frame)
{
    recorder_t *r = user;
    print_frame(r->now, frame);
}

static uint8_t *assembly_data(recorder_t *r, uint16_t instance)
{
    switch (instance) {
    case 20:
        return r->consumed[0];
    case 21:
        return r->consumed[1];
    case 100:
        return r->consumed[2];
    case 70:
        return r->produced[0];
    case 71:
        return r->produced[1];
    default:
        return r->produced[2];
    }
}

static void on_read(void *user, uint16_t instance, uint8_t *data)
{
    memcpy(data, assembly_data(user, instance), 4);
}

static void on_write(void *user, uint16_t instance, const uint8_t *data)
{
    memcpy(assembly_data(user, instance), data, 4);
}

static bool on_store(void *user, const dn_stored_t *stored)
{
    recorder_t *r = user;
    r->stored = *stored;
    return true;
}

static void on_reset(void *user, uint8_t type)
{
    recorder_t *r = user;
    r->reset_type = type;
}

static void start(recorder_t *r)
{
    r->config.stored = r->stored;
    if (dn_node_init(&r->node, &r->config) != DN_INIT_OK) {
        fprintf(stderr, "record_devicenet: dn_node_init refused the configuration\n");
        exit(1);
    }
    dn_node_start(&r->node, r->now);
    r->deadline = dn_node_process(&r->node, r->now);
}

static void setup(recorder_t *r)
{
    memset(r, 0, sizeof *r);
    r->reset_type = -1;
    r->app = (dn_app_t){.user = r,
                        .send = on_send,
                        .read_assembly = on_read,
                        .write_assembly = on_write,
                        .store = on_store,
                        .reset = on_reset};
    dn_config_t *c = &r->config;
    c->mac_id = SLAVE_MAC;
    c->baud_rate = 2;
    c->mac_switch = SLAVE_MAC;
    c->baud_switch = 2;
    c->vendor_id = 0x00F3;
    c->device_type = 2;
    c->product_code = 6153;
    c->major_revision = 1;
    c->minor_revision = 2;
    c->serial_number = 0x12345678;
    c->product_name = "ATV312";
    c->assemblies = assemblies;
    c->assembly_count = sizeof assemblies / sizeof assemblies[0];
    c->default_consumed_assembly = 21;
    c->default_produced_assembly = 71;
    c->app = &r->app;
}

/* Time passes: the node's deadlines run as they come. */
static void advance(recorder_t *r, co_time_t us)
{
    co_time_t target = r->now + us;
    while (r->deadline <= target) {
        if (r->deadline > r->now)
            r->now = r->deadline;
        r->deadline = dn_node_process(&r->node, r->now);
    }
    r->now = target;
}

/* The scanner sends "ID#DATA" (hex) 1 ms after the last event; an Identity Reset the node asked
 * for is carried out after its response, as an application would. */
static void scanner(recorder_t *r, const char *text)
{
    advance(r, 1000);
    co_frame_t f;
    memset(&f, 0, sizeof f);
    char *end;
    f.id = (uint32_t)strtoul(text, &end, 16);
    for (const char *p = end + 1; p[0] && p[1] && f.len < 8; p += 2) {
        char byte[3] = {p[0], p[1], '\0'};
        f.data[f.len++] = (uint8_t)strtoul(byte, NULL, 16);
    }
    print_frame(r->now, &f);
    dn_node_receive(&r->node, &f, r->now);
    r->deadline = dn_node_process(&r->node, r->now);
    if (r->reset_type >= 0) {
        r->reset_type = -1;
        start(r);
    }
}

/* The drive's input data, as the application changes them. */
static void drive_data(recorder_t *r, uint16_t instance, const char *hex)
{
    uint8_t *data = assembly_data(r, instance);
    for (int i = 0; i < 4; i++) {
        char byte[3] = {hex[2 * i], hex[2 * i + 1], '\0'};
        data[i] = (uint8_t)strtoul(byte, NULL, 16);
    }
    r->deadline = dn_node_process(&r->node, r->now);
}

static void script(recorder_t *r)
{
    /* The slave's check: two requests a second apart, online a second later. The scanner's own
     * check (MAC ID 1), then one for MAC ID 25 that the slave answers. */
    start(r);
    advance(r, 2000000);
    scanner(r, "40F#00F300EFBEADDE");
    scanner(r, "4CF#00F300EFBEADDE");
    /* The UCMM: Open Explicit Messaging Connection (group 3, the client's message ID 1), a Get
     * on the connection it opened (instance 10), Close. */
    scanner(r, "781#194B0031");
    scanner(r, "641#190E010101");
    scanner(r, "781#194C0A00");
    /* Allocate the explicit connection; Get the vendor, the product name (in two fragments). */
    scanner(r, "4CE#014B03010101");
    scanner(r, "4CC#010E010101");
    scanner(r, "4CC#010E010107");
    scanner(r, "4CC#81C000");
    scanner(r, "4CC#81C100");
    /* A Set in fragments: the output assembly 21's data (8 bytes of body). */
    scanner(r, "4CC#8100100415036100");
    scanner(r, "4CC#8181B004");
    /* Refusals: an attribute, a class, a Set of a Get-only attribute, an Allocate of another
     * master. */
    scanner(r, "4CC#010E010163");
    scanner(r, "4CC#010E660101");
    scanner(r, "4CC#0110010101F300");
    scanner(r, "4CE#054B03010205");
    /* Polled I/O: allocate, the expected packet rate (established), polls, an idle poll. */
    drive_data(r, 71, "70030000");
    scanner(r, "4CE#014B03010201");
    scanner(r, "4CC#01100502096400");
    scanner(r, "4CD#61000000");
    drive_data(r, 71, "F404B004");
    scanner(r, "4CD#6100B004");
    scanner(r, "4CD#");
    /* Change of state, acknowledged: allocate, establish, the data and their acknowledgements. */
    scanner(r, "4CE#014B03011001");
    scanner(r, "4CC#01100504096400");
    scanner(r, "4CA#");
    drive_data(r, 71, "F404A804");
    scanner(r, "4CA#");
    /* Select the transparent assemblies; an Identity Reset applies them. */
    scanner(r, "4CC#01100500646400");
    scanner(r, "4CC#01100500656500");
    scanner(r, "4CC#010E050064");
    scanner(r, "4CC#0105010100");
    advance(r, 2000000);
    /* Polls on 100/101 after the restart, then Release. */
    drive_data(r, 101, "2706B004");
    scanner(r, "4CE#014B03010301");
    scanner(r, "4CC#01100502096400");
    scanner(r, "4CD#0F00B004");
    scanner(r, "4CE#014C030103");
}

int main(void)
{
    static recorder_t r;
    setup(&r);
    script(&r);
    return fflush(stdout) == 0 ? 0 : 1;
}
