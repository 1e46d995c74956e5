/* The floor of an SDO round trip over SocketCAN (issue 10 section 3): the least a program must do
 * to answer an expedited upload request, so that bench/socketcan can compare the daemon with it.
 *
 *   responder [--clock] IFACE NODE-ID
 *
 * One CAN_RAW socket filtered to 0x600 + NODE-ID, one epoll set; each wake-up reads one request
 * and writes one expedited upload response (4 bytes, the request's index and sub-index) on
 * 0x580 + NODE-ID: three system calls per transaction, nothing else. IFACE may be --fd=FD: it
 * answers on a socket it inherits instead, one struct can_frame per datagram (bench/native: one end
 * of an AF_UNIX SOCK_SEQPACKET socketpair, on a kernel without CAN): the CAN-ID is then checked by
 * the program, as the kernel's filter does on CAN, and the peer's hang-up ends it. With --clock it
 * also reads CLOCK_MONOTONIC after each wake-up, as an event loop must to time its protocols (the
 * daemon does): a fourth system call where clock_gettime has no vDSO (User-Mode Linux), none on a
 * native kernel. */
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
};

static int open_socket(const char *iface, unsigned node)
{
    int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) {
        perror("responder: socket");
        return -1;
    }
    struct can_filter filter = {.can_id = SDO_RX_BASE + node,
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

int main(int argc, char **argv)
{
    bool read_clock = argc > 1 && strcmp(argv[1], "--clock") == 0;
    char **args = argv + 1 + read_clock;
    char *end = NULL;
    unsigned long node = argc == 3 + read_clock ? strtoul(args[1], &end, 0) : 0;
    if (argc != 3 + read_clock || *end != '\0' || node < 1 || node > 127) {
        fprintf(stderr, "usage: responder [--clock] (IFACE | --fd=FD) NODE-ID (1-127)\n");
        return 64;
    }
    bool given = strncmp(args[0], "--fd=", 5) == 0;
    int fd = given ? given_socket(args[0]) : open_socket(args[0], (unsigned)node);
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
        if (got != (ssize_t)sizeof request || request.can_id != SDO_RX_BASE + node)
            continue;
        struct can_frame reply = {.can_id = SDO_TX_BASE + (canid_t)node, .can_dlc = 8};
        reply.data[0] = SDO_UPLOAD_EXPEDITED_4;
        memcpy(&reply.data[1], &request.data[1], 3);
        if (write(fd, &reply, sizeof reply) != (ssize_t)sizeof reply)
            perror("responder: write");
    }
}
