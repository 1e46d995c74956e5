/* SPDX-License-Identifier: Apache-2.0 */
/* The Linux runtime: one loop, the composition of an event loop (co_linux/events.h: epoll, a
 * timerfd armed to the earliest deadline of its devices, a signalfd for SIGINT and SIGTERM), a CAN
 * bus (co_linux/can_bus.h: a SocketCAN socket, PF_CAN, SOCK_RAW, CAN_RAW, and a netlink socket
 * watching the interface go down and come back) and a router (co_linux/router.h).
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
#include "co_linux/can_bus.h"
#include "co_linux/conditions.h"
#include "co_linux/device.h"
#include "co_linux/events.h"
#include "co_linux/router.h"
#include "co_linux/txq.h"

#include <net/if.h>
#include <stdio.h>

/* The core's send callback (co_send_fn) for a device: pass the co_linux_device_t as `user`.
 * Never blocks: the frame is written, queued, or dropped and counted when the queue is full. */
void co_linux_device_send(void *device, const co_frame_t *frame);

typedef struct co_linux_loop_config {
    const char *iface;   /* at most IFNAMSIZ - 1 characters */
    FILE *trace;         /* every frame in and out in candump -L format, or NULL */
    size_t txq_capacity; /* frames waiting for the socket; 0 = CO_TXQ_MAX */
} co_linux_loop_config_t;

/* A descriptor of the application's that the loop watches besides its own (a control socket,
 * its connections): fn runs when it is readable, then the loop settles as after any event. */
typedef void (*co_linux_watch_fn)(void *ctx, int fd);
#define CO_LINUX_WATCH_MAX 16

typedef struct co_linux_watch {
    int fd; /* -1: free */
    co_linux_watch_fn fn;
    void *ctx;
} co_linux_watch_t;

/* Called at the end of every wake-up, once it has settled: frames delivered, conditions reported,
 * the transmit queue written as far as the socket took it (co_linux_loop_on_settled). */
typedef void (*co_linux_settled_fn)(void *ctx, co_linux_loop_t *loop);

/* The composition of the runtime's parts: the event loop (co_linux/events.h), the CAN bus
 * (co_linux/can_bus.h) and the router (co_linux/router.h). Opaque in practice: fields are public
 * only so the loop can live on the stack or in static storage, and for the counters and the
 * state a program reports. It must not be moved after co_linux_loop_open. */
struct co_linux_loop {
    char iface[IFNAMSIZ];
    co_time_t now; /* CLOCK_MONOTONIC at the start of this wake-up */
    co_linux_events_t events;
    co_linux_bus_t bus;
    co_linux_router_t router;
    co_linux_stats_t stats;
    co_linux_watch_t watches[CO_LINUX_WATCH_MAX];
    co_linux_settled_fn settled; /* NULL: none */
    void *settled_ctx;
    const char *open_call; /* the system call that failed in co_linux_loop_open */
    int open_errno;
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

/* Calls fn(ctx, loop) at the end of every wake-up from then on, the first being the one that
 * starts the devices (NULL: no more calls; fn may call this). For an application that waits for
 * something the wake-ups bring about, such as the start's frames written (co_linux_loop_sent_all).
 */
void co_linux_loop_on_settled(co_linux_loop_t *loop, co_linux_settled_fn fn, void *ctx);
/* True when every frame the devices sent has gone to the socket: the interface is up and the
 * transmit queue is empty. (While the interface is down their frames are dropped, not sent.) */
bool co_linux_loop_sent_all(const co_linux_loop_t *loop);

/* Makes co_linux_loop_run return `status` after the current wake-up. */
void co_linux_loop_stop(co_linux_loop_t *loop, int status);

/* Closes every descriptor and restores the signal mask. */
void co_linux_loop_close(co_linux_loop_t *loop);

#endif
