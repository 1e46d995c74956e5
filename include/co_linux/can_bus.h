/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime's CAN bus: the socket (SocketCAN CAN_RAW on an interface, or a socket of the
 * caller's carrying one struct can_frame per datagram), frames read and written in batches, the
 * transmit queue and its back-pressure, error frames and the conditions they raise, the netlink
 * monitor of the interface's link, and the candump -L trace. What a received frame is for is the
 * business of the loop it belongs to (co_linux_bus_host_t). docs/runtime.md. */
#ifndef CO_LINUX_CAN_BUS_H
#define CO_LINUX_CAN_BUS_H

#include "co/co_types.h"
#include "co_linux/conditions.h"
#include "co_linux/events.h"
#include "co_linux/txq.h"

#include <linux/can.h>
#include <stdio.h>
#include <sys/socket.h>
#include <time.h>

/* Received frames read per recvmmsg call. */
#define CO_LINUX_RX_BATCH 32
/* While each read finds one frame, frames are read one by one (recv, not recvmmsg, which looks
 * into the empty queue a second time, some 400 ns natively); every RX_PROBE_EVERY-th read is a
 * batch again, so a burst is read in batches after at most that many wake-ups: as many frames as
 * one batch, read one per wake-up, at most. */
#define CO_LINUX_RX_PROBE_EVERY 32
/* Queued frames written per sendmmsg call (a lone frame goes by send). */
#define CO_LINUX_TX_BATCH 64

typedef enum co_linux_open_result {
    CO_LINUX_OPEN_OK = 0,
    CO_LINUX_OPEN_NO_CAN,   /* the kernel has no PF_CAN / CAN_RAW (EAFNOSUPPORT, EPROTONOSUPPORT) */
    CO_LINUX_OPEN_NO_IFACE, /* no network interface of that name */
    CO_LINUX_OPEN_NOT_CAN,  /* the interface exists but is not a CAN interface */
    CO_LINUX_OPEN_OS_ERROR  /* a system call failed: see open_call and open_errno */
} co_linux_open_result_t;

/* The loop's counters, for logs and tests; the bus counts all but wakeups, unrouted, filters. */
typedef struct co_linux_stats {
    unsigned long long wakeups;      /* epoll_wait returns */
    unsigned long long rx;           /* CANopen frames received from the socket */
    unsigned long long tx;           /* frames written to the socket */
    unsigned long long tx_dropped;   /* frames dropped: TX queue full or write error */
    unsigned long long down_dropped; /* frames sent while the interface was down */
    unsigned long long error_frames; /* error frames received */
    unsigned long long tx_calls;     /* system calls that wrote frames (send for a lone one) */
    unsigned long long unrouted;     /* frames received that no device consumes */
    unsigned long long filters;      /* receive filters set on the socket */
} co_linux_stats_t;

typedef enum co_linux_tx_wait {
    CO_LINUX_TX_READY,    /* queue empty, writes go straight to the socket */
    CO_LINUX_TX_EPOLLOUT, /* queue waiting for the socket to become writable */
    CO_LINUX_TX_RETRY     /* queue waiting for a retry deadline (ENOBUFS without EPOLLOUT) */
} co_linux_tx_wait_t;

/* What the bus uses of the loop it belongs to. */
typedef struct co_linux_bus_host {
    co_linux_events_t *events; /* where its descriptors are watched */
    co_linux_stats_t *stats;   /* the counters it adds to */
    /* A CANopen frame was read (error frames the bus handles itself). */
    void (*received)(void *ctx, const co_frame_t *frame);
    /* The interface came back: the socket is new, the conditions are cleared. */
    void (*came_up)(void *ctx);
    void *ctx;
} co_linux_bus_host_t;

/* The receive side: the batch read by recvmmsg and the choice between it and recv. */
typedef struct co_linux_bus_rx {
    bool end;             /* a read of a given socket returned its end (after a hang-up) */
    bool one_by_one;      /* the last batch read brought one frame: read them one by one */
    unsigned reads_alone; /* single reads since the last batch read */
    struct can_frame frames[CO_LINUX_RX_BATCH];
    struct iovec iov[CO_LINUX_RX_BATCH];
    struct mmsghdr msgs[CO_LINUX_RX_BATCH];
} co_linux_bus_rx_t;

/* The transmit side: the queue, what it waits for, the batch written by sendmmsg. */
typedef struct co_linux_bus_tx {
    co_txq_t queue; /* frames waiting for the socket */
    co_linux_tx_wait_t wait;
    co_time_t retry_at;
    size_t dropped_in_burst;
    struct can_frame frames[CO_LINUX_TX_BATCH];
    struct iovec iov[CO_LINUX_TX_BATCH];
    struct mmsghdr msgs[CO_LINUX_TX_BATCH];
} co_linux_bus_tx_t;

typedef struct co_linux_bus {
    co_linux_bus_host_t host;
    const char *iface; /* at most IFNAMSIZ - 1 characters */
    int can_fd;        /* -1 while the interface is down */
    int link_fd;       /* the netlink monitor; -1 for a given socket */
    bool link_up;
    bool socket_given;    /* co_linux_bus_open_fd: no link monitoring, a peer that can hang up */
    bool kernel_filter;   /* the socket is a CAN_RAW socket: CAN_RAW_FILTER applies */
    co_time_t now;        /* this wake-up, for the retry deadline */
    struct timespec wall; /* CLOCK_REALTIME of this wake-up, for the trace */
    FILE *trace;          /* every frame in and out in candump -L format, or NULL */
    bool trace_dirty;
    co_linux_conditions_t conditions;
    co_linux_bus_rx_t rx;
    co_linux_bus_tx_t tx;
} co_linux_bus_t;

/* The CAN controller's state as the bus knows it, the worst that holds: the interface down, bus
 * off, error passive, an error counter at the warning level (96), or error active. */
typedef enum co_linux_can_state {
    CO_LINUX_CAN_DOWN,
    CO_LINUX_CAN_BUS_OFF,
    CO_LINUX_CAN_ERROR_PASSIVE,
    CO_LINUX_CAN_ERROR_WARNING,
    CO_LINUX_CAN_ERROR_ACTIVE
} co_linux_can_state_t;

co_linux_can_state_t co_linux_bus_can_state(const co_linux_bus_t *bus);

/* Nothing open; frames wait in a transmit queue of txq_capacity (0: CO_TXQ_MAX). */
void co_linux_bus_init(co_linux_bus_t *bus, const co_linux_bus_host_t *host, const char *iface,
                       FILE *trace, size_t txq_capacity);

/* Opens the link monitor and the socket on the interface; an interface that exists but is down
 * is not an error: the bus waits for it. On failure *call names the system call (errno set). */
co_linux_open_result_t co_linux_bus_open(co_linux_bus_t *bus, const char **call);

/* Whether fd keeps frames apart (a datagram or sequenced-packet socket; errno EPROTOTYPE for a
 * stream socket, ENOTSOCK for a non-socket) and, if so, whether it is a CAN_RAW socket. */
bool co_linux_bus_keeps_frames(int fd, bool *can_raw);
/* Takes fd (checked by co_linux_bus_keeps_frames) as the bus: non-blocking, watched, owned from
 * then on. On failure *call names the system call (errno set) and the caller keeps fd. */
co_linux_open_result_t co_linux_bus_open_fd(co_linux_bus_t *bus, int fd, bool can_raw,
                                            const char **call);

/* Closes the socket and the link monitor and flushes the trace. */
void co_linux_bus_close(co_linux_bus_t *bus);

/* The start of a wake-up: its time (and the wall clock's when tracing). */
void co_linux_bus_wake(co_linux_bus_t *bus, co_time_t now);

/* Queues a frame of `origin`'s for the socket; false when it was dropped (interface down, or the
 * queue full after writing what it held). */
bool co_linux_bus_send(co_linux_bus_t *bus, const co_frame_t *frame, const void *origin);
/* Writes the queue unless the socket refused it already (EPOLLOUT or the retry then writes it). */
void co_linux_bus_transmit(co_linux_bus_t *bus);
/* The retry deadline of a refused queue, or CO_TIME_NEVER. */
co_time_t co_linux_bus_deadline(const co_linux_bus_t *bus);
/* Writes the queue if its retry deadline passed. */
void co_linux_bus_retry(co_linux_bus_t *bus);

/* The trace's frames of this wake-up in one write(2); false when it failed and tracing stopped
 * (the socket then no longer needs the whole bus). */
bool co_linux_bus_flush_trace(co_linux_bus_t *bus);

#endif
