/* SPDX-License-Identifier: Apache-2.0 */
/* Load generator of bench/socketcan, bench/native and bench/devicenet on raw SocketCAN (python
 * is too slow to measure the floor).
 *
 *   sdo_rtt IFACE NODE-ID COUNT          expedited uploads of 1000h, one at a time
 *   sdo_rtt --sync IFACE NODE-ID COUNT   SYNC -> synchronous TPDO6 latency
 *   sdo_rtt --poll IFACE MAC-ID COUNT    DeviceNet poll commands, one at a time
 *   sdo_rtt --every=US ...               one transaction every US microseconds (a paced load)
 *
 * IFACE may be --fd=FD: a socket the generator inherits, one struct can_frame per datagram
 * (bench/native: one end of an AF_UNIX SOCK_SEQPACKET socketpair, on a kernel without CAN).
 *
 * Each transaction is timed with CLOCK_MONOTONIC from before the request's write to after the
 * answer's read; the next starts when the answer is in. WARM_UP transactions come first and are
 * not counted (the first ones fault pages in). --sync first makes TPDO6 synchronous (1805h:02 = 1,
 * with the PDO invalid meanwhile, as CiA 301 asks; the ATV312's TPDO1 has a read-only
 * transmission type) and valid on 280h + NODE-ID by SDO, starts the node (NMT), then sends SYNC
 * after SYNC and times the TPDO each one triggers. --poll sends poll commands of 4 bytes of zeros
 * (an assembly 21 that neither runs nor stops the drive; group 2 message 5 of MAC-ID) and waits
 * for each poll response (group 1 message 15): the polled connection must be allocated and
 * established already (bench/devicenet does it with dnscan). --every=US, before the rest, starts
 * the transactions US microseconds apart (the first at once, clock_nanosleep to an absolute
 * time) instead of back to back, so that the answering program sleeps between them as on a bus
 * whose frames are spread (bench/native-devicenet). Prints one JSON line: transactions per
 * second, latency p50/p99/max in microseconds. Exits 1, saying why, when an answer is missing or an
 * SDO request is aborted. */
#include "dn/dn_link.h"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

enum {
    NMT_ID = 0x000,
    NMT_START = 0x01,
    SYNC_ID = 0x080,
    TPDO6_BASE = 0x280,
    SDO_TX_BASE = 0x580,
    SDO_RX_BASE = 0x600,
    SDO_UPLOAD_REQUEST = 0x40,
    SDO_DOWNLOAD_EXPEDITED_1 = 0x2F,
    SDO_DOWNLOAD_EXPEDITED_4 = 0x23,
    SDO_ABORT = 0x80,
    TPDO6_COMM = 0x1805,
    TRANSMISSION_SYNC_1 = 1,
    WARM_UP = 100,
    ANSWER_TIMEOUT_MS = 1000,
    NODE_ID_MAX = 127,
    POLL_COMMAND_LEN = 4, /* the output assemblies of the Altivar 312 are 4 bytes */
};

typedef enum transaction_kind { SDO_UPLOAD, SYNC_TPDO, POLL } transaction_kind_t;

/* CiA 301: bit 31 of a PDO's COB-ID, the PDO does not exist. */
static const uint32_t COB_ID_INVALID = 0x80000000u;

typedef struct {
    int fd;
    unsigned node;
} bus_t;

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* The CAN-IDs the generator waits for: `filters` (two) exact ones of its kind of transaction. */
static void answer_ids(transaction_kind_t kind, unsigned node, struct can_filter filters[2])
{
    const canid_t exact = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
    canid_t poll_response = dn_group1_id(DN_G1_SLAVE_POLL_RESPONSE, (uint8_t)node);
    filters[0] = (struct can_filter){kind == POLL ? poll_response : SDO_TX_BASE + node, exact};
    filters[1] = (struct can_filter){kind == POLL ? poll_response : TPDO6_BASE + node, exact};
}

static int open_bus(bus_t *bus, const char *iface, unsigned node, transaction_kind_t kind)
{
    bus->node = node;
    if (strncmp(iface, "--fd=", 5) == 0) {
        char *end = NULL;
        long fd = strtol(iface + 5, &end, 10);
        bus->fd = (int)fd;
        if (*end == '\0' && end != iface + 5 && fd >= 0 && fd <= 1023)
            return 0;
        fprintf(stderr, "sdo_rtt: bad %s\n", iface);
        return -1;
    }
    bus->fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (bus->fd < 0) {
        perror("sdo_rtt: socket");
        return -1;
    }
    struct can_filter filters[2];
    answer_ids(kind, node, filters);
    struct sockaddr_can addr = {.can_family = AF_CAN, .can_ifindex = (int)if_nametoindex(iface)};
    if (addr.can_ifindex == 0) {
        fprintf(stderr, "sdo_rtt: no interface %s\n", iface);
        return -1;
    }
    if (setsockopt(bus->fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters, sizeof filters) != 0 ||
        bind(bus->fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        perror("sdo_rtt: bind");
        return -1;
    }
    return 0;
}

static int send_frame(const bus_t *bus, canid_t id, const uint8_t *data, uint8_t len)
{
    struct can_frame frame = {.can_id = id, .can_dlc = len};
    if (len > 0) /* a SYNC has no data, and memcpy's source must not be NULL even then */
        memcpy(frame.data, data, len);
    if (write(bus->fd, &frame, sizeof frame) != (ssize_t)sizeof frame) {
        perror("sdo_rtt: write");
        return -1;
    }
    return 0;
}

/* Waits for the next frame on `id`; frames on the other CAN-ID of the filter are skipped. */
static int receive_frame(const bus_t *bus, canid_t id, struct can_frame *frame)
{
    for (;;) {
        struct pollfd pfd = {.fd = bus->fd, .events = POLLIN};
        int ready = poll(&pfd, 1, ANSWER_TIMEOUT_MS);
        if (ready < 0 && errno == EINTR)
            continue;
        if (ready <= 0) {
            fprintf(stderr, "sdo_rtt: no frame on %03X from node %u within %d ms\n", id, bus->node,
                    ANSWER_TIMEOUT_MS);
            return -1;
        }
        if (read(bus->fd, frame, sizeof *frame) != (ssize_t)sizeof *frame) {
            perror("sdo_rtt: read");
            return -1;
        }
        if (frame->can_id == id)
            return 0;
    }
}

static int sdo_transfer(const bus_t *bus, const uint8_t request[8])
{
    struct can_frame reply;
    if (send_frame(bus, SDO_RX_BASE + bus->node, request, 8) != 0 ||
        receive_frame(bus, SDO_TX_BASE + bus->node, &reply) != 0)
        return -1;
    if (reply.data[0] == SDO_ABORT) {
        uint32_t code = (uint32_t)reply.data[4] | (uint32_t)reply.data[5] << 8 |
                        (uint32_t)reply.data[6] << 16 | (uint32_t)reply.data[7] << 24;
        fprintf(stderr, "sdo_rtt: node %u aborted %02X%02X:%02X: %08X\n", bus->node, request[2],
                request[1], request[3], code);
        return -1;
    }
    return 0;
}

static int sdo_upload_1000h(const bus_t *bus)
{
    const uint8_t request[8] = {SDO_UPLOAD_REQUEST, 0x00, 0x10, 0x00};
    return sdo_transfer(bus, request);
}

static int sdo_download(const bus_t *bus, uint16_t index, uint8_t sub, uint32_t value, bool u32)
{
    const uint8_t request[8] = {u32 ? SDO_DOWNLOAD_EXPEDITED_4 : SDO_DOWNLOAD_EXPEDITED_1,
                                (uint8_t)index,
                                (uint8_t)(index >> 8),
                                sub,
                                (uint8_t)value,
                                (uint8_t)(value >> 8),
                                (uint8_t)(value >> 16),
                                (uint8_t)(value >> 24)};
    return sdo_transfer(bus, request);
}

static int sync_tpdo6(const bus_t *bus)
{
    struct can_frame tpdo;
    if (send_frame(bus, SYNC_ID, NULL, 0) != 0)
        return -1;
    return receive_frame(bus, TPDO6_BASE + bus->node, &tpdo);
}

static int make_tpdo6_synchronous(const bus_t *bus)
{
    const uint32_t cob_id = TPDO6_BASE + bus->node;
    const uint8_t start[2] = {NMT_START, (uint8_t)bus->node};
    if (sdo_download(bus, TPDO6_COMM, 1, cob_id | COB_ID_INVALID, true) != 0 ||
        sdo_download(bus, TPDO6_COMM, 2, TRANSMISSION_SYNC_1, false) != 0 ||
        sdo_download(bus, TPDO6_COMM, 1, cob_id, true) != 0)
        return -1;
    return send_frame(bus, NMT_ID, start, sizeof start);
}

/* One poll command and its response; bus->node is the MAC ID here. */
static int poll_command(const bus_t *bus)
{
    const uint8_t command[POLL_COMMAND_LEN] = {0};
    struct can_frame response;
    uint8_t mac_id = (uint8_t)bus->node;
    if (send_frame(bus, dn_group2_id(mac_id, DN_G2_MASTER_POLL_COS_CYCLIC), command,
                   sizeof command) != 0)
        return -1;
    return receive_frame(bus, dn_group1_id(DN_G1_SLAVE_POLL_RESPONSE, mac_id), &response);
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static double percentile_us(const uint64_t *sorted, size_t count, double p)
{
    size_t rank = (size_t)(p * (double)(count - 1) + 0.5);
    return (double)sorted[rank] / 1000.0;
}

static const struct {
    const char *option; /* the first argument that selects it */
    const char *name;   /* in the JSON line */
    int (*run)(const bus_t *);
    unsigned long id_min, id_max;
} KINDS[] = {
    [SDO_UPLOAD] = {NULL, "sdo_upload", sdo_upload_1000h, 1, NODE_ID_MAX},
    [SYNC_TPDO] = {"--sync", "sync_tpdo", sync_tpdo6, 1, NODE_ID_MAX},
    [POLL] = {"--poll", "poll", poll_command, 0, DN_MAC_ID_MAX},
};

/* Sleeps until `start` + `index` x `interval_ns` (CLOCK_MONOTONIC); nothing when interval_ns is 0.
 */
static void wait_turn(uint64_t start, size_t index, uint64_t interval_ns)
{
    if (interval_ns == 0)
        return;
    uint64_t at = start + index * interval_ns;
    struct timespec ts = {.tv_sec = (time_t)(at / 1000000000u),
                          .tv_nsec = (long)(at % 1000000000u)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR)
        continue;
}

int main(int argc, char **argv)
{
    uint64_t interval_ns = 0;
    if (argc > 1 && strncmp(argv[1], "--every=", 8) == 0) {
        char *end = NULL;
        interval_ns = strtoull(argv[1] + 8, &end, 10) * 1000u;
        if (*end != '\0' || interval_ns == 0) {
            fprintf(stderr, "sdo_rtt: bad %s\n", argv[1]);
            return 64;
        }
        argc--;
        argv++;
    }
    transaction_kind_t kind = SDO_UPLOAD;
    for (transaction_kind_t k = SYNC_TPDO; k <= POLL && argc > 1; k++)
        if (strcmp(argv[1], KINDS[k].option) == 0)
            kind = k;
    int options = kind != SDO_UPLOAD;
    char **args = argv + 1 + options;
    char *end_node = NULL, *end_count = NULL;
    bool three = argc == 4 + options;
    unsigned long node = three ? strtoul(args[1], &end_node, 0) : 0;
    unsigned long count = three ? strtoul(args[2], &end_count, 0) : 0;
    if (!three || *end_node != '\0' || *end_count != '\0' || node < KINDS[kind].id_min ||
        node > KINDS[kind].id_max || count < 1 || count > 10000000) {
        fprintf(stderr,
                "usage: sdo_rtt [--sync] (IFACE | --fd=FD) NODE-ID (1-127) COUNT (1-10000000)\n"
                "       sdo_rtt --poll (IFACE | --fd=FD) MAC-ID (0-63) COUNT (1-10000000)\n"
                "       (either after --every=US: one transaction every US microseconds)\n");
        return 64;
    }
    bus_t bus;
    if (open_bus(&bus, args[0], (unsigned)node, kind) != 0)
        return 1;
    int (*transaction)(const bus_t *) = KINDS[kind].run;
    if (kind == SYNC_TPDO && make_tpdo6_synchronous(&bus) != 0)
        return 1;
    for (int i = 0; i < WARM_UP; i++) {
        if (transaction(&bus) != 0)
            return 1;
    }
    uint64_t *latency = malloc(count * sizeof *latency);
    if (latency == NULL) {
        perror("sdo_rtt");
        return 1;
    }
    uint64_t started = now_ns();
    for (size_t i = 0; i < count; i++) {
        wait_turn(started, i, interval_ns);
        uint64_t t0 = now_ns();
        if (transaction(&bus) != 0)
            return 1;
        latency[i] = now_ns() - t0;
    }
    double seconds = (double)(now_ns() - started) / 1e9;
    qsort(latency, count, sizeof *latency, compare_u64);
    printf("{\"mode\": \"%s\", \"count\": %lu, \"per_s\": %.0f, \"p50_us\": %.1f, \"p99_us\": "
           "%.1f, \"max_us\": %.1f}\n",
           KINDS[kind].name, count, (double)count / seconds, percentile_us(latency, count, 0.50),
           percentile_us(latency, count, 0.99), percentile_us(latency, count, 1.0));
    free(latency);
    return 0;
}
