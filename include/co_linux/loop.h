/* The Linux runtime: one epoll loop that owns a SocketCAN socket (PF_CAN, SOCK_RAW, CAN_RAW), a
 * timerfd armed to the earliest deadline of its devices, a signalfd (SIGINT, SIGTERM) and a
 * netlink socket watching the interface go down and come back.
 *
 * A device is anything built on the portable core (a co_node_t, a drive wrapping one): the loop
 * gives it the received frames and the frames other local devices sent that its node consumes
 * (every frame for a device that does not name its node), calls its process function after each
 * frame and when its deadline is due, and transmits what it sends, the frames of one wake-up in
 * one sendmmsg. The socket's receive filter (CAN_RAW_FILTER) holds the consumed COB-IDs, so a
 * frame for nobody does not wake the loop. When no device has a deadline the timer is disarmed:
 * an idle loop does not wake up. See docs/runtime.md.
 */
#ifndef CO_LINUX_LOOP_H
#define CO_LINUX_LOOP_H

#include "co/co_types.h"
#include "co_linux/txq.h"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <signal.h>
#include <stdio.h>
#include <sys/socket.h>

/* CiA 301 table 21 emergency codes the runtime reports to the devices. */
#define CO_LINUX_EMCY_CAN_OVERRUN 0x8110 /* frames lost: TX queue full, controller overflow */
#define CO_LINUX_EMCY_CAN_PASSIVE 0x8120 /* CAN controller in error passive mode */
#define CO_LINUX_EMCY_BUS_OFF 0x8140     /* recovered from bus off (active while bus off) */

/* Received frames read per recvmmsg call. */
#define CO_LINUX_RX_BATCH 32
/* While each read finds one frame, frames are read one by one (recv, not recvmmsg, which looks
 * into the empty queue a second time, some 400 ns natively); every RX_PROBE_EVERY-th read is a
 * batch again, so a burst is read in batches after at most that many wake-ups: as many frames as
 * one batch, read one per wake-up, at most. */
#define CO_LINUX_RX_PROBE_EVERY 32
/* Queued frames written per sendmmsg call (a lone frame goes by send). */
#define CO_LINUX_TX_BATCH 64
/* Routing keys: an 11-bit CAN-ID, plus 2048 for a remote request. */
#define CO_LINUX_ROUTE_KEYS 4096u

struct co_node;
typedef struct co_linux_loop co_linux_loop_t;

/* What the loop calls on a device; ctx is the device's own object. Only bus_event may be NULL. */
typedef struct co_linux_device_ops {
    /* Once, when the loop starts: leave Initialising, send the boot-up. */
    void (*start)(void *ctx, co_time_t now);
    /* The interface came back after being down: restart communication so the master sees the
     * device again (the daemon's drives reset communication, which sends a boot-up). */
    void (*restart)(void *ctx, co_time_t now);
    void (*receive)(void *ctx, const co_frame_t *frame, co_time_t now);
    /* Runs what is due; returns the next deadline or CO_TIME_NEVER. */
    co_time_t (*process)(void *ctx, co_time_t now);
    /* A CAN communication condition began (active) or ended; emcy_code is one of
     * CO_LINUX_EMCY_*. */
    void (*bus_event)(void *ctx, uint16_t emcy_code, bool active);
    /* The device's core node, which must stay the same: frames reach the device only when the
     * node consumes their COB-ID (co_consumers.h). NULL: the device gets every frame, and the
     * socket then receives the whole bus. */
    const struct co_node *(*node)(void *ctx);
} co_linux_device_ops_t;

/* One device's share of the loop's traffic (co_linux_stats_t), counted where the loop routes a
 * frame to it and where it sends one: an increment each, no search. */
typedef struct co_linux_device_stats {
    unsigned long long rx;         /* frames routed to it: from the bus and from local devices */
    unsigned long long tx;         /* frames it sent */
    unsigned long long tx_dropped; /* of those, not queued: interface down or queue full */
} co_linux_device_stats_t;

typedef struct co_linux_device {
    const co_linux_device_ops_t *ops;
    void *ctx;
    co_linux_loop_t *loop;
    co_time_t deadline;
    uint32_t generation; /* the node's consumer generation the routes were built from */
    co_linux_device_stats_t stats;
    struct co_linux_device *next;
} co_linux_device_t;

/* The core's send callback (co_send_fn) for a device: pass the co_linux_device_t as `user`.
 * Never blocks: the frame is written, queued, or dropped and counted when the queue is full. */
void co_linux_device_send(void *device, const co_frame_t *frame);

typedef enum co_linux_open_result {
    CO_LINUX_OPEN_OK = 0,
    CO_LINUX_OPEN_NO_CAN,   /* the kernel has no PF_CAN / CAN_RAW (EAFNOSUPPORT, EPROTONOSUPPORT) */
    CO_LINUX_OPEN_NO_IFACE, /* no network interface of that name */
    CO_LINUX_OPEN_NOT_CAN,  /* the interface exists but is not a CAN interface */
    CO_LINUX_OPEN_OS_ERROR  /* a system call failed: see open_call and open_errno */
} co_linux_open_result_t;

typedef struct co_linux_loop_config {
    const char *iface;   /* at most IFNAMSIZ - 1 characters */
    FILE *trace;         /* every frame in and out in candump -L format, or NULL */
    size_t txq_capacity; /* frames waiting for the socket; 0 = CO_TXQ_MAX */
} co_linux_loop_config_t;

/* Counters, for logs and tests. */
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

/* A descriptor of the application's that the loop watches besides its own (a control socket,
 * its connections): fn runs when it is readable, then the loop settles as after any event. */
typedef void (*co_linux_watch_fn)(void *ctx, int fd);
#define CO_LINUX_WATCH_MAX 16

typedef struct co_linux_watch {
    int fd; /* -1: free */
    co_linux_watch_fn fn;
    void *ctx;
} co_linux_watch_t;

typedef struct co_linux_condition {
    uint16_t emcy_code;
    bool wanted;   /* what the bus says */
    bool reported; /* what the devices were told */
} co_linux_condition_t;

/* Opaque in practice: fields are public only so the loop can live on the stack or in static
 * storage. It must not be moved after co_linux_loop_open. */
struct co_linux_loop {
    char iface[IFNAMSIZ];
    int epoll_fd, can_fd, timer_fd, signal_fd, link_fd;
    bool link_up;
    bool running;
    int exit_status;
    sigset_t old_mask;

    co_linux_device_t *devices;
    size_t device_count;

    /* Routes (docs/runtime.md): the devices consuming key k are route_devices[route_first[k]]
     * up to route_devices[route_first[k + 1]], in the order they were added. */
    uint32_t route_first[CO_LINUX_ROUTE_KEYS + 1];
    co_linux_device_t **route_devices;
    size_t route_capacity;
    bool routes_stale;   /* a node's consumed set changed: rebuild before the next frame */
    bool route_all;      /* every device gets every frame (a device without node, no memory) */
    bool filter_applied; /* `filters` is what the current socket has */
    bool filter_stale;   /* the routes, the socket or the trace changed since it was computed */
    bool kernel_filter;  /* the socket is a CAN_RAW socket: CAN_RAW_FILTER applies */
    bool socket_given;   /* co_linux_loop_open_fd: no link monitoring, a peer that can hang up */
    bool rx_end;        /* a read of the given socket returned its end (nothing, after a hang-up) */
    bool rx_one_by_one; /* the last batch read brought one frame: read them one by one */
    unsigned rx_reads_alone; /* single reads since the last batch read */
    size_t filter_count;

    co_time_t now;
    struct timespec wall; /* CLOCK_REALTIME of this wake-up, for the trace */
    co_time_t timer_armed;

    co_txq_t txq;   /* frames waiting for the socket */
    co_txq_t local; /* frames sent by one device, waiting for the other local devices */
    co_linux_tx_wait_t tx_wait;
    co_time_t retry_at;
    size_t dropped_in_burst;

    co_linux_condition_t conditions[3]; /* overrun, passive, bus off */
    bool traffic_since_overrun;

    FILE *trace;
    bool trace_dirty;

    co_linux_stats_t stats;

    co_linux_watch_t watches[CO_LINUX_WATCH_MAX];

    const char *open_call; /* the system call that failed in co_linux_loop_open */
    int open_errno;

    struct can_frame rx_frames[CO_LINUX_RX_BATCH];
    struct iovec rx_iov[CO_LINUX_RX_BATCH];
    struct mmsghdr rx_msgs[CO_LINUX_RX_BATCH];
    struct can_frame tx_frames[CO_LINUX_TX_BATCH];
    struct iovec tx_iov[CO_LINUX_TX_BATCH];
    struct mmsghdr tx_msgs[CO_LINUX_TX_BATCH];
    struct can_filter filters[CAN_RAW_FILTER_MAX];
};

/* Monotonic time in microseconds (CLOCK_MONOTONIC), the clock of every deadline. */
co_time_t co_linux_now(void);

/* Opens the socket on the interface, the timer, the signal and netlink descriptors. SIGINT and
 * SIGTERM are blocked from here on (they are read from the signalfd). An interface that exists
 * but is down is not an error: the loop waits for it. On failure everything opened is closed. */
co_linux_open_result_t co_linux_loop_open(co_linux_loop_t *loop,
                                          const co_linux_loop_config_t *config);

/* Like co_linux_loop_open, on `fd`: a socket the caller opened that carries one struct can_frame
 * per datagram (SOCK_SEQPACKET, SOCK_DGRAM or SOCK_RAW), such as one end of an AF_UNIX
 * SOCK_SEQPACKET socketpair, a bus between processes on a kernel without CAN (tests, bench/native),
 * or a CAN_RAW socket of the caller's. config->iface only names it in the logs. The loop makes
 * fd non-blocking and owns it from then on (co_linux_loop_close closes it); on failure the caller
 * keeps it (CO_LINUX_OPEN_OS_ERROR, open_errno ENOTSOCK for a non-socket, EPROTOTYPE for a stream
 * socket). The bus is up as long as fd is open: no link monitoring. The receive filter is set only
 * on a CAN_RAW socket: another socket carries the whole bus and the routes sort it. When the peer
 * hangs up, the frames it sent before are handled, their replies written, and co_linux_loop_run
 * returns 0. */
co_linux_open_result_t co_linux_loop_open_fd(co_linux_loop_t *loop,
                                             const co_linux_loop_config_t *config, int fd);

/* Attaches a device (before co_linux_loop_run). */
void co_linux_loop_add(co_linux_loop_t *loop, co_linux_device_t *device,
                       const co_linux_device_ops_t *ops, void *ctx);

/* Starts every device and runs until SIGINT or SIGTERM (returns 0), co_linux_loop_stop, or a
 * failure of the loop itself (returns EX_OSERR). */
int co_linux_loop_run(co_linux_loop_t *loop);

/* Watches fd (readable) for the application; 0, or -1 with errno set (ENOSPC when
 * CO_LINUX_WATCH_MAX descriptors are watched already). */
int co_linux_loop_watch(co_linux_loop_t *loop, int fd, co_linux_watch_fn fn, void *ctx);
/* Stops watching fd (before the application closes it); may be called from its fn. */
void co_linux_loop_unwatch(co_linux_loop_t *loop, int fd);
/* Runs a device's process function now and takes its new deadline: the application changed the
 * device outside a frame or a deadline (from a watched descriptor's fn). */
void co_linux_device_process(co_linux_device_t *device);

/* Makes co_linux_loop_run return `status` after the current wake-up. */
void co_linux_loop_stop(co_linux_loop_t *loop, int status);

/* Closes every descriptor and restores the signal mask. */
void co_linux_loop_close(co_linux_loop_t *loop);

#endif
