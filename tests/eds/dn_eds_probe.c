/* SPDX-License-Identifier: Apache-2.0 */
/* The emulated ATV312 on DeviceNet asked what its EDS (eds/00F3000218090100.EDS) says, for
 * tests/eds/test_devicenet_eds.py: the drive behind its DeviceNet adapter at MAC ID 25 and the
 * project's scanner at MAC ID 1, wired to each other in memory with injected time. After the
 * drive's duplicate MAC ID check the scanner allocates the explicit connection; then each line
 * of standard input is one request, each line of standard output its result:
 *
 *   get CLASS INSTANCE ATTRIBUTE          -> ok [HEX]
 *   set CLASS INSTANCE ATTRIBUTE HEX      -> error GG AA   (CIP general status, additional code)
 *   od INDEX SUB-INDEX                    -> ok HEX | abort CODE  (the drive's dictionary, read
 *                                            as the card reads it)
 *
 * Numbers in hex, data as hex bytes in bus order ("E803"). Exit status 0, or 1 when the setup
 * or a request fails (a timeout, a line it cannot read). */
#include <stdio.h>
#include <string.h>

#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "dn/dn_scanner.h"

#define DRIVE_MAC 25u
#define SCANNER_MAC 1u
#define QUEUE 64
#define CHECK_US 3000000u /* the drive's duplicate MAC ID check: two requests a second apart */

typedef struct queue {
    co_frame_t frame[QUEUE];
    size_t count;
} queue_t;

typedef struct probe {
    drive_t drive;
    uint8_t od_data[ATV312_OD_DATA_SIZE];
    drive_dn_t dn;
    dn_scanner_t scanner;
    dn_slave_t slave;
    queue_t to_scanner, to_drive;
    co_time_t now;
    bool done;
    dn_result_t result;
    uint8_t data[DN_MESSAGE_MAX];
} probe_t;

static void push(queue_t *q, const co_frame_t *frame)
{
    if (q->count < QUEUE)
        q->frame[q->count++] = *frame;
}

static void drive_send(void *user, const co_frame_t *frame)
{
    push(&((probe_t *)user)->to_scanner, frame);
}

static void scanner_send(void *user, const co_frame_t *frame)
{
    push(&((probe_t *)user)->to_drive, frame);
}

static void scanner_done(void *user, const dn_result_t *result)
{
    probe_t *p = user;
    p->result = *result;
    if (result->len)
        memcpy(p->data, result->data, result->len);
    p->result.data = p->data;
    p->done = true;
}

static bool keep_selection(void *user, const dn_stored_t *stored)
{
    (void)user;
    (void)stored;
    return true;
}

/* Delivers the frames each side sent to the other until both are quiet. */
static void deliver(probe_t *p)
{
    while (p->to_drive.count || p->to_scanner.count) {
        queue_t to_drive = p->to_drive, to_scanner = p->to_scanner;
        p->to_drive.count = p->to_scanner.count = 0;
        for (size_t i = 0; i < to_drive.count; i++)
            drive_dn_receive(&p->dn, &to_drive.frame[i], p->now);
        for (size_t i = 0; i < to_scanner.count; i++)
            dn_scanner_receive(&p->scanner, &to_scanner.frame[i], p->now);
        (void)drive_dn_process(&p->dn, p->now);
        (void)dn_scanner_process(&p->scanner, p->now);
    }
}

/* Runs both sides until `until`, or until the request in progress is done. */
static void run(probe_t *p, co_time_t until)
{
    for (;;) {
        deliver(p);
        if (p->done)
            return;
        co_time_t next =
            co_time_min(drive_dn_process(&p->dn, p->now), dn_scanner_process(&p->scanner, p->now));
        deliver(p);
        if (p->done || next > until)
            return;
        if (next > p->now)
            p->now = next;
    }
}

static bool finish(probe_t *p)
{
    run(p, p->now + DN_SCANNER_TIMEOUT_DEFAULT_US * 4u);
    bool done = p->done;
    p->done = false;
    return done;
}

static bool setup(probe_t *p, const dn_scanner_config_t *sc)
{
    drive_config_t dc = {.profile = atv312_devicenet_profile.drive,
                         .od_data = p->od_data,
                         .node_id = 1,
                         .send = drive_dn_drop_frame};
    if (drive_init(&p->drive, &dc) != 0)
        return false;
    drive_dn_config_t c = {.drive = &p->drive,
                           .profile = &atv312_devicenet_profile,
                           .mac_id = DRIVE_MAC,
                           .baud_rate = 2,
                           .serial_number = 0x12345678,
                           .send = drive_send,
                           .user = p,
                           .store = keep_selection};
    if (drive_dn_init(&p->dn, &c) != 0 || dn_scanner_init(&p->scanner, sc) != DN_SCANNER_INIT_OK)
        return false;
    drive_dn_start(&p->dn, p->now);
    run(p, p->now + CHECK_US);
    p->to_scanner.count = 0; /* the drive's check requests */
    dn_scanner_start_online(&p->scanner, p->now);
    return dn_scanner_allocate(&p->scanner, DRIVE_MAC, DN_ALLOC_EXPLICIT, p->now) && finish(p) &&
           p->result.status == DN_RESULT_OK;
}

static int hex_bytes(const char *text, uint8_t *out, size_t max)
{
    size_t n = 0;
    unsigned byte;
    while (*text && n < max && sscanf(text, "%2x", &byte) == 1 && text[1]) {
        out[n++] = (uint8_t)byte;
        text += 2;
    }
    return *text ? -1 : (int)n;
}

static void print_result(const dn_result_t *r)
{
    if (r->status == DN_RESULT_OK) {
        printf("ok ");
        for (uint8_t i = 0; i < r->len; i++)
            printf("%02X", r->data[i]);
        printf("\n");
    } else if (r->status == DN_RESULT_CIP_ERROR) {
        printf("error %02X %02X\n", r->general, r->additional);
    } else {
        printf("failed %d\n", (int)r->status);
    }
}

/* The drive's dictionary entry, read as an SDO upload would read it. */
static void print_entry(probe_t *p, uint16_t index, uint8_t subindex)
{
    const co_od_entry_t *entry;
    uint32_t abort_code = co_od_read_check(&p->drive.node, index, subindex, &entry);
    if (abort_code != 0) {
        printf("abort %08X\n", (unsigned)abort_code);
        return;
    }
    const uint8_t *bytes = co_od_bytes(&p->drive.node, entry);
    printf("ok ");
    for (size_t i = 0; i < co_od_length(&p->drive.node, entry); i++)
        printf("%02X", bytes[i]);
    printf("\n");
}

static bool request(probe_t *p, const char *line)
{
    char verb[8], hex[2 * DN_MESSAGE_MAX + 1] = "";
    unsigned cls, inst, attr;
    int fields = sscanf(line, "%7s %x %x %x %128s", verb, &cls, &inst, &attr, hex);
    uint8_t value[DN_MESSAGE_MAX];
    bool sent;
    if (fields == 4 && strcmp(verb, "get") == 0) {
        sent = dn_scanner_get(&p->scanner, DRIVE_MAC, (uint8_t)cls, (uint8_t)inst, (uint8_t)attr,
                              p->now);
    } else if (fields == 5 && strcmp(verb, "set") == 0) {
        int len = hex_bytes(hex, value, sizeof value);
        if (len < 0)
            return false;
        sent = dn_scanner_set(&p->scanner, DRIVE_MAC, (uint8_t)cls, (uint8_t)inst, (uint8_t)attr,
                              value, (uint8_t)len, p->now);
    } else if (fields == 3 && strcmp(verb, "od") == 0) {
        print_entry(p, (uint16_t)cls, (uint8_t)inst);
        return true;
    } else {
        return false;
    }
    if (!sent || !finish(p))
        return false;
    print_result(&p->result);
    return p->result.status == DN_RESULT_OK || p->result.status == DN_RESULT_CIP_ERROR;
}

int main(void)
{
    static probe_t probe;
    probe_t *p = &probe;
    const dn_scanner_app_t app = {.user = p, .send = scanner_send, .done = scanner_done};
    p->slave.mac_id = DRIVE_MAC;
    const dn_scanner_config_t sc = {.mac_id = SCANNER_MAC,
                                    .vendor_id = 0x00F3,
                                    .serial_number = 1,
                                    .slaves = &p->slave,
                                    .slave_count = 1,
                                    .app = &app};
    if (!setup(p, &sc)) {
        fprintf(stderr, "dn_eds_probe: the drive did not come online and allocate\n");
        return 1;
    }
    char line[256];
    while (fgets(line, sizeof line, stdin)) {
        if (!request(p, line)) {
            fprintf(stderr, "dn_eds_probe: request failed: %s", line);
            return 1;
        }
        fflush(stdout);
    }
    return 0;
}
