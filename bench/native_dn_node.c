/* SPDX-License-Identifier: Apache-2.0 */
/* The daemon's side of bench/native-devicenet: atv312d's ATV312 drives behind their DeviceNet
 * cards (drive_devicenet.h), hosted as `atv312d --devicenet` hosts them (one device of the runtime
 * loop per card, routed by the CAN-IDs the card consumes), on co_linux_loop_run over a socket it
 * inherits (one end of an AF_UNIX SOCK_SEQPACKET socketpair carrying struct can_frame:
 * co_linux_loop_open_fd), so that the loop and the cards can be timed on a native kernel that has
 * no vcan.
 *
 *   native_dn_node FD FIRST-LAST      MAC IDs FIRST..LAST (0..63), one drive each
 *
 * The device operations are the daemon's (apps/atv312d/drives.c, dn_slot_ops), with its comparison
 * of the LEDs and the drive state after each call (the log lines it would write are below the
 * warning level here); no store, no control or status surface. Prints "online N" once every card
 * has passed its duplicate MAC ID check; runs until the peer hangs up or SIGTERM, then prints the
 * loop's counters and the calls into the cards as one JSON line on standard output. */
#include "co_linux/log.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/drive_devicenet.h"
#include "drive/models/models.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

/* As in atv312d: the drive's internal node-id behind its card, and the serial number base. */
#define DN_DRIVE_NODE_ID 1u
#define DN_SERIAL_BASE 0x31200000u
#define DN_BAUD_500K 2u

typedef struct bench_card {
    drive_t drive;
    uint8_t *od_data;
    drive_dn_t dn;
    co_linux_device_t device;
    uint8_t mac_id;
    dn_led_t ms_led, ns_led;  /* last compared, as atv312d logs them */
    const char *cia402_state; /* last compared */
} bench_card_t;

typedef struct bench_counts {
    unsigned long long receives, processes;
    unsigned cards, online;
} bench_counts_t;

static bench_counts_t counts;

static void compare_led(const bench_card_t *card, const char *name, dn_led_t *last, dn_led_t now)
{
    if (now != *last)
        co_log(CO_LOG_INFO, "node %u: %s LED %s -> %s", card->mac_id, name,
               drive_dn_led_name(*last), drive_dn_led_name(now));
    *last = now;
}

/* atv312d's log_state_changes for a DeviceNet drive. */
static void compare_states(bench_card_t *card)
{
    compare_led(card, "MS", &card->ms_led, dn_node_ms_led(&card->dn.node));
    compare_led(card, "NS", &card->ns_led, dn_node_ns_led(&card->dn.node));
    const char *state = drive_state_name(&card->drive);
    if (state != card->cia402_state && strcmp(state, card->cia402_state) != 0)
        co_log(CO_LOG_INFO, "node %u: CiA 402 %s -> %s", card->mac_id, card->cia402_state, state);
    card->cia402_state = state;
}

static void card_send(void *user, const co_frame_t *frame)
{
    bench_card_t *card = user;
    co_linux_device_send(&card->device, frame);
}

static void card_start(void *ctx, co_time_t now)
{
    bench_card_t *card = ctx;
    drive_dn_start(&card->dn, now);
    compare_states(card);
}

/* Never called: a given socket has no link that goes down and comes back. */
static void card_restart(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
}

static void card_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    bench_card_t *card = ctx;
    counts.receives++;
    drive_dn_receive(&card->dn, frame, now);
    compare_states(card);
}

/* Counts the cards online once, when the last one comes online. */
static void note_online(const bench_card_t *card, dn_link_state_t before)
{
    if (before == DN_LINK_ONLINE || card->dn.node.link != DN_LINK_ONLINE)
        return;
    if (++counts.online == counts.cards) {
        printf("online %u\n", counts.online);
        fflush(stdout);
    }
}

static co_time_t card_process(void *ctx, co_time_t now)
{
    bench_card_t *card = ctx;
    counts.processes++;
    dn_link_state_t before = card->dn.node.link;
    co_time_t next = drive_dn_process(&card->dn, now);
    compare_states(card);
    note_online(card, before);
    return next;
}

static size_t card_consumers(void *ctx, co_cob_t *cobs)
{
    const bench_card_t *card = ctx;
    uint16_t ids[DN_NODE_CONSUMED_IDS];
    size_t count = dn_node_consumed_ids(&card->dn.node, ids);
    for (size_t i = 0; i < count; i++)
        cobs[i] = (co_cob_t){.can_id = ids[i], .rtr = false};
    return count;
}

static const co_linux_device_ops_t card_ops = {.start = card_start,
                                               .restart = card_restart,
                                               .receive = card_receive,
                                               .process = card_process,
                                               .consumers = card_consumers};

static int init_card(bench_card_t *card, const drive_model_t *model, uint8_t mac_id)
{
    card->mac_id = mac_id;
    card->od_data = calloc(1, model->devicenet->drive->od->data_size);
    drive_config_t drive = {.profile = model->devicenet->drive,
                            .od_data = card->od_data,
                            .node_id = DN_DRIVE_NODE_ID,
                            .send = drive_dn_drop_frame,
                            .send_user = card};
    if (card->od_data == NULL || drive_init(&card->drive, &drive) != 0)
        return -1;
    drive_dn_config_t config = {.drive = &card->drive,
                                .profile = model->devicenet,
                                .mac_id = mac_id,
                                .baud_rate = DN_BAUD_500K,
                                .serial_number = DN_SERIAL_BASE + mac_id,
                                .send = card_send,
                                .user = card};
    if (drive_dn_init(&card->dn, &config) != 0)
        return -1;
    card->cia402_state = drive_state_name(&card->drive);
    return 0;
}

static long parse(const char *arg, long max)
{
    char *end = NULL;
    long value = strtol(arg, &end, 10);
    return *end == '\0' && end != arg && value >= 0 && value <= max ? value : -1;
}

static bool parse_range(const char *text, unsigned *first, unsigned *last)
{
    char extra;
    return sscanf(text, "%u-%u%c", first, last, &extra) == 2 && *first <= *last &&
           *last <= DN_MAC_ID_MAX;
}

int main(int argc, char **argv)
{
    long fd = argc == 3 ? parse(argv[1], 1023) : -1;
    unsigned first = 0, last = 0;
    if (fd < 0 || !parse_range(argv[2], &first, &last)) {
        fprintf(stderr, "usage: native_dn_node FD FIRST-LAST (MAC IDs 0..63)\n");
        return EX_USAGE;
    }
    co_log_setup("native_dn_node", CO_LOG_WARN);
    static co_linux_loop_t loop;
    co_linux_loop_config_t config = {.iface = "socketpair"};
    if (co_linux_loop_open_fd(&loop, &config, (int)fd) != CO_LINUX_OPEN_OK) {
        fprintf(stderr, "native_dn_node: %s: %s\n", loop.open_call, strerror(loop.open_errno));
        return EX_OSERR;
    }
    const drive_model_t *model = drive_model_find("atv312");
    counts.cards = last - first + 1;
    bench_card_t *cards = calloc(counts.cards, sizeof *cards);
    for (unsigned i = 0; cards != NULL && i < counts.cards; i++) {
        if (init_card(&cards[i], model, (uint8_t)(first + i)) != 0) {
            fprintf(stderr, "native_dn_node: MAC ID %u: the drive cannot be initialised\n",
                    first + i);
            return EX_SOFTWARE;
        }
        co_linux_loop_add(&loop, &cards[i].device, &card_ops, &cards[i]);
    }
    if (cards == NULL)
        return EX_OSERR;
    int rc = co_linux_loop_run(&loop);
    printf("{\"wakeups\": %llu, \"rx\": %llu, \"tx\": %llu, \"tx_calls\": %llu, \"tx_dropped\": "
           "%llu, \"unrouted\": %llu, \"receives\": %llu, \"processes\": %llu}\n",
           loop.stats.wakeups, loop.stats.rx, loop.stats.tx, loop.stats.tx_calls,
           loop.stats.tx_dropped, loop.stats.unrouted, counts.receives, counts.processes);
    co_linux_loop_close(&loop);
    for (unsigned i = 0; i < counts.cards; i++)
        free(cards[i].od_data);
    free(cards);
    return rc;
}
