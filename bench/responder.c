/* SPDX-License-Identifier: Apache-2.0 */
/* The floor of a round trip over SocketCAN (issue 10 section 3, issue 18): the least a program
 * must do to answer a request, so that bench/socketcan and bench/devicenet can compare the daemon
 * with it.
 *
 *   responder [--clock] [--poll] IFACE ID
 *
 * One CAN_RAW socket filtered to the request's CAN-ID, one epoll set; each wake-up reads one
 * request and writes one answer: three system calls per transaction, nothing else. The request
 * is an SDO expedited upload on 0x600 + ID (node ID 1..127), answered with an expedited upload
 * response (4 bytes, the request's index and sub-index) on 0x580 + ID; with --poll it is a
 * DeviceNet poll command (group 2 message 5 of MAC ID 0..63), answered with a poll response of 4
 * bytes (an assembly 71 of zeros) on group 1 message 15. IFACE may be --fd=FD: it answers on a
 * socket it inherits instead, one struct can_frame per datagram (bench/native: one end of an
 * AF_UNIX SOCK_SEQPACKET socketpair, on a kernel without CAN): the CAN-ID is then checked by the
 * program, as the kernel's filter does on CAN, and the peer's hang-up ends it. With --clock it
 * also reads CLOCK_MONOTONIC after each wake-up, as an event loop must to time its protocols (the
 * daemon does): a fourth system call where clock_gettime has no vDSO (User-Mode Linux), none on a
 * native kernel. */
#include "dn/dn_link.h"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

enum {
    SDO_RX_BASE = 0x600,
    SDO_TX_BASE = 0x580,
    SDO_UPLOAD_EXPEDITED_4 = 0x43, /* scs 2, expedited, size indicated, 4 bytes */
    NODE_ID_MAX = 127,
    POLL_RESPONSE_LEN = 4, /* the input assemblies of the Altivar 312 are 4 bytes */
};

/* What the responder answers: the request's CAN-ID and the answer's. */
typedef struct exchange {
    bool poll;
    canid_t request_id;
    canid_t reply_id;
} exchange_t;

static int open_socket(const char *iface, canid_t request_id)
{
    int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) {
        perror("responder: socket");
        return -1;
    }
    struct can_filter filter = {.can_id = request_id,
                                .can_mask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG};
    struct sockaddr_can addr = {.can_family = AF_CAN, .can_ifindex = (int)if_nametoindex(iface)};
    if (addr.can_ifindex == 0) {
        fprintf(stderr, "responder: no interface %s\n", iface);
        close(fd);
        return -1;
    }
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, &filter, sizeof filter) != 0 ||
        bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        perror("responder: bind");
        close(fd);
        return -1;
    }
    return fd;
}

/* The inherited socket of --fd=FD, or -1 (said why) when FD is not a number. */
static int given_socket(const char *arg)
{
    char *end = NULL;
    long fd = strtol(arg + 5, &end, 10);
    if (*end != '\0' || end == arg + 5 || fd < 0 || fd > 1023) {
        fprintf(stderr, "responder: bad %s\n", arg);
        return -1;
    }
    return (int)fd;
}

static void answer(const exchange_t *x, const struct can_frame *request, struct can_frame *reply)
{
    memset(reply, 0, sizeof *reply);
    reply->can_id = x->reply_id;
    if (x->poll) {
        reply->can_dlc = POLL_RESPONSE_LEN;
        return;
    }
    reply->can_dlc = 8;
    reply->data[0] = SDO_UPLOAD_EXPEDITED_4;
    memcpy(&reply->data[1], &request->data[1], 3);
}

int main(int argc, char **argv)
{
    bool read_clock = false, poll = false;
    int arg = 1;
    for (; arg < argc; arg++) {
        if (strcmp(argv[arg], "--clock") == 0)
            read_clock = true;
        else if (strcmp(argv[arg], "--poll") == 0)
            poll = true;
        else
            break;
    }
    char *end = NULL;
    unsigned long id = argc - arg == 2 ? strtoul(argv[arg + 1], &end, 0) : 0;
    unsigned long id_min = poll ? 0 : 1, id_max = poll ? DN_MAC_ID_MAX : NODE_ID_MAX;
    if (argc - arg != 2 || *end != '\0' || id < id_min || id > id_max) {
        fprintf(stderr, "usage: responder [--clock] (IFACE | --fd=FD) NODE-ID (1-127)\n"
                        "       responder [--clock] --poll (IFACE | --fd=FD) MAC-ID (0-63)\n");
        return 64;
    }
    exchange_t x = {poll, SDO_RX_BASE + (canid_t)id, SDO_TX_BASE + (canid_t)id};
    if (poll) {
        x.request_id = dn_group2_id((uint8_t)id, DN_G2_MASTER_POLL_COS_CYCLIC);
        x.reply_id = dn_group1_id(DN_G1_SLAVE_POLL_RESPONSE, (uint8_t)id);
    }
    bool given = strncmp(argv[arg], "--fd=", 5) == 0;
    int fd = given ? given_socket(argv[arg]) : open_socket(argv[arg], x.request_id);
    int ep = epoll_create1(0);
    struct epoll_event ev = {.events = EPOLLIN};
    if (fd < 0 || ep < 0 || epoll_ctl(ep, EPOLL_CTL_ADD, fd, &ev) != 0) {
        perror("responder: epoll");
        return 1;
    }
    for (;;) {
        if (epoll_wait(ep, &ev, 1, -1) < 0)
            continue;
        struct timespec now;
        if (read_clock)
            clock_gettime(CLOCK_MONOTONIC, &now);
        struct can_frame request;
        ssize_t got = read(fd, &request, sizeof request);
        if (got == 0)
            return 0; /* the peer of a given socket hung up */
        if (got != (ssize_t)sizeof request || request.can_id != x.request_id)
            continue;
        struct can_frame reply;
        answer(&x, &request, &reply);
        if (write(fd, &reply, sizeof reply) != (ssize_t)sizeof reply)
            perror("responder: write");
    }
}
