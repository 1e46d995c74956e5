/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/can_bus.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "co_linux/log.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <net/if.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

/* ENOBUFS from a CAN socket means the interface's queue is full; the socket itself may still
 * look writable, so EPOLLOUT cannot tell when to retry. Retry after this long instead. */
#define ENOBUFS_RETRY_US 1000u

/* Received batches handled per wake-up before other descriptors get their turn. */
#define RX_ROUNDS 4

static void init_batches(co_linux_bus_t *bus)
{
    for (int i = 0; i < CO_LINUX_RX_BATCH; i++) {
        bus->rx.iov[i].iov_base = &bus->rx.frames[i];
        bus->rx.iov[i].iov_len = sizeof bus->rx.frames[i];
        bus->rx.msgs[i].msg_hdr.msg_iov = &bus->rx.iov[i];
        bus->rx.msgs[i].msg_hdr.msg_iovlen = 1;
    }
    for (int i = 0; i < CO_LINUX_TX_BATCH; i++) {
        bus->tx.iov[i].iov_base = &bus->tx.frames[i];
        bus->tx.iov[i].iov_len = sizeof bus->tx.frames[i];
        bus->tx.msgs[i].msg_hdr.msg_iov = &bus->tx.iov[i];
        bus->tx.msgs[i].msg_hdr.msg_iovlen = 1;
    }
}

co_linux_can_state_t co_linux_bus_can_state(const co_linux_bus_t *bus)
{
    if (!bus->link_up)
        return CO_LINUX_CAN_DOWN;
    if (co_linux_conditions_active(&bus->conditions, CO_LINUX_EMCY_BUS_OFF))
        return CO_LINUX_CAN_BUS_OFF;
    if (co_linux_conditions_active(&bus->conditions, CO_LINUX_EMCY_CAN_PASSIVE))
        return CO_LINUX_CAN_ERROR_PASSIVE;
    if (co_linux_conditions_warning(&bus->conditions))
        return CO_LINUX_CAN_ERROR_WARNING;
    return CO_LINUX_CAN_ERROR_ACTIVE;
}

void co_linux_bus_init(co_linux_bus_t *bus, const co_linux_bus_host_t *host, const char *iface,
                       FILE *trace, size_t txq_capacity)
{
    memset(bus, 0, sizeof *bus);
    bus->host = *host;
    bus->iface = iface;
    bus->can_fd = bus->link_fd = -1;
    bus->trace = trace;
    bus->tx.retry_at = CO_TIME_NEVER;
    co_txq_init(&bus->tx.queue, txq_capacity ? txq_capacity : CO_TXQ_MAX);
    co_linux_conditions_init(&bus->conditions);
    init_batches(bus);
}

static bool errno_means_down(int err)
{
    return err == ENETDOWN || err == ENODEV || err == ENXIO;
}

/* ---- the trace ---- */

static void trace_frame(co_linux_bus_t *bus, const struct can_frame *frame)
{
    if (!bus->trace)
        return;
    char line[CO_CANDUMP_LINE_MAX];
    size_t len = co_candump_format(line, sizeof line, &bus->wall, bus->iface, frame);
    fwrite(line, 1, len, bus->trace);
    bus->trace_dirty = true;
}

/* One flush per wake-up, not per frame: the trace costs one write(2) however many frames. */
bool co_linux_bus_flush_trace(co_linux_bus_t *bus)
{
    if (!bus->trace_dirty)
        return true;
    bus->trace_dirty = false;
    if (fflush(bus->trace) != 0 || ferror(bus->trace)) {
        co_log(CO_LOG_ERROR, "trace: write failed (%s): tracing stopped", strerror(errno));
        bus->trace = NULL;
        return false;
    }
    return true;
}

void co_linux_bus_wake(co_linux_bus_t *bus, co_time_t now)
{
    bus->now = now;
    if (bus->trace)
        clock_gettime(CLOCK_REALTIME, &bus->wall);
}

/* ---- the transmit side ---- */

/* A given socket's peer can hang up (EPOLLRDHUP); a CAN_RAW socket has no peer. */
static uint32_t socket_events(const co_linux_bus_t *bus)
{
    return EPOLLIN | (bus->socket_given ? EPOLLRDHUP : 0u);
}

static void set_tx_wait(co_linux_bus_t *bus, co_linux_tx_wait_t wait)
{
    /* Every refusal pushes the retry 1 ms on, also when already waiting to retry: a retry time
     * left in the past would make the timer fire at once, forever. */
    bus->tx.retry_at = wait == CO_LINUX_TX_RETRY ? bus->now + ENOBUFS_RETRY_US : CO_TIME_NEVER;
    if (bus->tx.wait == wait)
        return;
    bool had_out = bus->tx.wait == CO_LINUX_TX_EPOLLOUT;
    bool want_out = wait == CO_LINUX_TX_EPOLLOUT;
    bus->tx.wait = wait;
    if (had_out != want_out && bus->can_fd >= 0 &&
        co_linux_events_modify(bus->host.events, bus->can_fd,
                               socket_events(bus) | (want_out ? EPOLLOUT : 0u)) != 0)
        co_log(CO_LOG_ERROR, "epoll_ctl: %s", strerror(errno));
}

static void close_can_socket(co_linux_bus_t *bus)
{
    if (bus->can_fd < 0)
        return;
    co_linux_events_remove(bus->host.events, bus->can_fd);
    close(bus->can_fd);
    bus->can_fd = -1;
}

static void link_went_down(co_linux_bus_t *bus, const char *why)
{
    if (!bus->link_up)
        return;
    bus->link_up = false;
    size_t lost = co_txq_clear(&bus->tx.queue);
    bus->host.stats->down_dropped += lost;
    set_tx_wait(bus, CO_LINUX_TX_READY);
    close_can_socket(bus);
    co_log(CO_LOG_WARN, "interface %s is down (%s): %zu queued frames dropped, waiting for it",
           bus->iface, why, lost);
}

static void frame_dropped(co_linux_bus_t *bus, const co_frame_t *frame, const char *why)
{
    bus->host.stats->tx_dropped++;
    if (bus->tx.dropped_in_burst++ == 0)
        co_log(CO_LOG_WARN, "%s: frame %03X dropped: %s (queue of %zu frames)", bus->iface,
               (unsigned)frame->id, why, bus->tx.queue.capacity);
    else
        co_log(CO_LOG_DEBUG, "%s: frame %03X dropped: %s", bus->iface, (unsigned)frame->id, why);
    co_linux_conditions_set(&bus->conditions, bus->iface, CO_LINUX_COND_OVERRUN, true);
}

/* A lone frame goes by send: sendmmsg would copy in its message and I/O vector headers for it. */
static int send_frames(co_linux_bus_t *bus, size_t count)
{
    if (count > 1)
        return sendmmsg(bus->can_fd, bus->tx.msgs, (unsigned)count, MSG_DONTWAIT);
    ssize_t sent = send(bus->can_fd, &bus->tx.frames[0], CAN_MTU, MSG_DONTWAIT);
    return sent < 0 ? -1 : 1;
}

/* Writes up to CO_LINUX_TX_BATCH queued frames in one system call; returns how many the socket
 * took (errno says why when 0). */
static int write_batch(co_linux_bus_t *bus)
{
    size_t count = co_txq_count(&bus->tx.queue);
    if (count > CO_LINUX_TX_BATCH)
        count = CO_LINUX_TX_BATCH;
    for (size_t i = 0; i < count; i++)
        co_linux_frame_to_can(&co_txq_at(&bus->tx.queue, i)->frame, &bus->tx.frames[i]);
    int sent = send_frames(bus, count);
    if (sent <= 0)
        return 0;
    bus->host.stats->tx_calls++;
    bus->host.stats->tx += (unsigned)sent;
    bus->conditions.traffic_since_overrun = true;
    for (int i = 0; i < sent; i++) {
        trace_frame(bus, &bus->tx.frames[i]);
        co_txq_pop(&bus->tx.queue);
    }
    return sent;
}

/* Writes queued frames in order, a batch per system call, until the queue is empty or the socket
 * refuses. */
static void flush_queue(co_linux_bus_t *bus)
{
    bool progress = false;
    while (bus->link_up && co_txq_count(&bus->tx.queue) > 0) {
        if (write_batch(bus) > 0) {
            progress = true;
            continue;
        }
        int err = errno;
        if (err == EAGAIN || err == ENOBUFS) {
            set_tx_wait(bus,
                        err == ENOBUFS && !progress ? CO_LINUX_TX_RETRY : CO_LINUX_TX_EPOLLOUT);
            return;
        }
        if (errno_means_down(err)) {
            link_went_down(bus, strerror(err));
            return;
        }
        const co_frame_t *frame = &co_txq_peek(&bus->tx.queue)->frame;
        co_log(CO_LOG_ERROR, "%s: write of frame %03X failed: %s", bus->iface, (unsigned)frame->id,
               strerror(err));
        frame_dropped(bus, frame, "write error");
        co_txq_pop(&bus->tx.queue);
    }
    set_tx_wait(bus, CO_LINUX_TX_READY);
    if (bus->tx.dropped_in_burst) {
        co_log(CO_LOG_WARN, "%s: transmit queue drained; %zu frames were dropped while it was full",
               bus->iface, bus->tx.dropped_in_burst);
        bus->tx.dropped_in_burst = 0;
    }
}

void co_linux_bus_transmit(co_linux_bus_t *bus)
{
    if (bus->tx.wait == CO_LINUX_TX_READY)
        flush_queue(bus);
}

bool co_linux_bus_send(co_linux_bus_t *bus, const co_frame_t *frame, const void *origin)
{
    /* Frames wait in the queue until the wake-up settles, so that the frames of one wake-up
     * leave in one sendmmsg; a full queue is written out first, so a frame is dropped only when
     * the socket cannot take any more. */
    if (co_txq_full(&bus->tx.queue))
        co_linux_bus_transmit(bus);
    if (!bus->link_up) {
        bus->host.stats->down_dropped++;
        return false;
    }
    if (!co_txq_push(&bus->tx.queue, frame, origin)) {
        frame_dropped(bus, frame, "transmit queue full");
        return false;
    }
    return true;
}

co_time_t co_linux_bus_deadline(const co_linux_bus_t *bus)
{
    return bus->tx.wait == CO_LINUX_TX_RETRY ? bus->tx.retry_at : CO_TIME_NEVER;
}

void co_linux_bus_retry(co_linux_bus_t *bus)
{
    if (bus->tx.wait == CO_LINUX_TX_RETRY && bus->tx.retry_at <= bus->now)
        flush_queue(bus);
}

/* ---- the receive side ---- */

static void set_condition(co_linux_bus_t *bus, co_linux_condition_kind_t which, bool active)
{
    co_linux_conditions_set(&bus->conditions, bus->iface, which, active);
}

/* The controller's error state from the kernel's error frames (linux/can/error.h): bus off, and
 * its restart, in the class bits; otherwise CAN_ERR_CRTL's byte names the state entered, error
 * active, warning or passive (the kernel's can_change_state), up or down. Error passive is above
 * the warning limit, so it is a warning too; error active ends both. */
static void handle_controller_state(co_linux_bus_t *bus, uint8_t crtl)
{
    if (crtl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) {
        set_condition(bus, CO_LINUX_COND_WARNING, true);
        set_condition(bus, CO_LINUX_COND_PASSIVE, true);
    } else if (crtl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) {
        set_condition(bus, CO_LINUX_COND_PASSIVE, false);
        set_condition(bus, CO_LINUX_COND_WARNING, true);
    } else if (crtl & CAN_ERR_CRTL_ACTIVE) {
        set_condition(bus, CO_LINUX_COND_PASSIVE, false);
        set_condition(bus, CO_LINUX_COND_WARNING, false);
    }
    if (crtl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW))
        set_condition(bus, CO_LINUX_COND_OVERRUN, true);
}

static void handle_error_frame(co_linux_bus_t *bus, const struct can_frame *cf)
{
    bus->host.stats->error_frames++;
    if (cf->can_id & CAN_ERR_BUSOFF)
        set_condition(bus, CO_LINUX_COND_BUS_OFF, true);
    if (cf->can_id & CAN_ERR_RESTARTED) {
        set_condition(bus, CO_LINUX_COND_BUS_OFF, false);
        set_condition(bus, CO_LINUX_COND_PASSIVE, false);
        set_condition(bus, CO_LINUX_COND_WARNING, false);
    }
    if (cf->can_id & CAN_ERR_CRTL)
        handle_controller_state(bus, cf->data[1]);
}

static void handle_rx_frame(co_linux_bus_t *bus, const struct can_frame *cf)
{
    trace_frame(bus, cf);
    if (cf->can_id & CAN_ERR_FLAG) {
        handle_error_frame(bus, cf);
        return;
    }
    bus->host.stats->rx++;
    bus->conditions.traffic_since_overrun = true;
    co_frame_t frame;
    co_linux_frame_from_can(cf, &frame);
    bus->host.received(bus->host.ctx, &frame);
}

static void read_failed(co_linux_bus_t *bus, const char *call)
{
    if (errno_means_down(errno))
        link_went_down(bus, strerror(errno));
    else if (errno != EAGAIN && errno != EINTR)
        co_log(CO_LOG_ERROR, "%s: %s: %s", bus->iface, call, strerror(errno));
}

/* One frame, without recvmmsg's second look into a queue that is empty: the buffer has a byte
 * more than a frame so that a longer datagram (a CAN FD frame on a given socket) shows. */
static void receive_one(co_linux_bus_t *bus)
{
    union {
        struct can_frame frame;
        uint8_t longer[CAN_MTU + 1];
    } rx;
    ssize_t got = recv(bus->can_fd, &rx, sizeof rx, MSG_DONTWAIT);
    if (got < 0)
        read_failed(bus, "recv");
    else if (got == CAN_MTU)
        handle_rx_frame(bus, &rx.frame);
    else if (got == 0)
        bus->rx.end = true;
}

/* Returns how many datagrams were read. */
static int receive_batches(co_linux_bus_t *bus)
{
    int total = 0;
    for (int round = 0; round < RX_ROUNDS && bus->can_fd >= 0; round++) {
        int n = recvmmsg(bus->can_fd, bus->rx.msgs, CO_LINUX_RX_BATCH, MSG_DONTWAIT, NULL);
        if (n < 0) {
            read_failed(bus, "recvmmsg");
            return total;
        }
        total += n;
        for (int i = 0; i < n; i++) {
            /* A longer datagram (a CAN FD frame on a given socket) arrives cut to CAN_MTU. */
            const struct mmsghdr *msg = &bus->rx.msgs[i];
            if (msg->msg_len == CAN_MTU && !(msg->msg_hdr.msg_flags & MSG_TRUNC))
                handle_rx_frame(bus, &bus->rx.frames[i]);
            else if (msg->msg_len == 0)
                bus->rx.end = true;
        }
        if (n < CO_LINUX_RX_BATCH)
            return total;
    }
    return total;
}

/* A wake-up nearly always finds one frame (a CAN frame takes 50 us or more on the wire), and
 * recvmmsg then looks into the empty queue a second time: while batches bring one frame, frames
 * are read one by one, with a batch every CO_LINUX_RX_PROBE_EVERY reads to catch a burst. */
static void receive_frames(co_linux_bus_t *bus)
{
    if (bus->rx.one_by_one && ++bus->rx.reads_alone < CO_LINUX_RX_PROBE_EVERY) {
        receive_one(bus);
        return;
    }
    bus->rx.reads_alone = 0;
    bus->rx.one_by_one = receive_batches(bus) == 1;
}

/* The frames it sent before are read already (the reads reached the end); the replies to them
 * still leave when the wake-up settles, then the loop ends. Reading on would return end-of-file
 * for ever. */
static void peer_hung_up(co_linux_bus_t *bus)
{
    co_log(CO_LOG_INFO, "%s: the peer closed the socket: stopping", bus->iface);
    co_linux_events_remove(bus->host.events, bus->can_fd);
    co_linux_events_stop(bus->host.events, 0);
}

static void socket_ready(void *ctx, uint32_t events)
{
    co_linux_bus_t *bus = ctx;
    if (events & (EPOLLERR | EPOLLHUP)) {
        int err = 0;
        socklen_t len = sizeof err;
        getsockopt(bus->can_fd, SOL_SOCKET, SO_ERROR, &err, &len);
        if (errno_means_down(err)) {
            link_went_down(bus, strerror(err));
            return;
        }
        if (err)
            co_log(CO_LOG_WARN, "%s: socket error: %s", bus->iface, strerror(err));
    }
    if (events & EPOLLIN)
        receive_frames(bus);
    if (bus->socket_given && bus->rx.end && (events & (EPOLLRDHUP | EPOLLHUP))) {
        peer_hung_up(bus);
        return;
    }
    if ((events & EPOLLOUT) && bus->link_up)
        flush_queue(bus);
}

/* ---- the socket on an interface and its link ---- */

static co_linux_open_result_t open_can_socket(co_linux_bus_t *bus, const char **call)
{
    int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        *call = "socket(PF_CAN, SOCK_RAW, CAN_RAW)";
        return errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT ? CO_LINUX_OPEN_NO_CAN
                                                                 : CO_LINUX_OPEN_OS_ERROR;
    }
    struct sockaddr_can addr = {.can_family = AF_CAN,
                                .can_ifindex = (int)if_nametoindex(bus->iface)};
    can_err_mask_t err_mask = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED;
    co_linux_open_result_t result = CO_LINUX_OPEN_OS_ERROR;
    if (addr.can_ifindex == 0) {
        *call = "if_nametoindex";
        result = CO_LINUX_OPEN_NO_IFACE;
    } else if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0) {
        *call = "setsockopt(CAN_RAW_ERR_FILTER)";
    } else if (bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        *call = "bind";
        result = errno == ENODEV ? CO_LINUX_OPEN_NOT_CAN : CO_LINUX_OPEN_OS_ERROR;
    } else if (co_linux_events_add(bus->host.events, fd, EPOLLIN, socket_ready, bus) != 0) {
        *call = "epoll_ctl";
    } else {
        bus->can_fd = fd;
        bus->kernel_filter = true;
        return CO_LINUX_OPEN_OK;
    }
    int err = errno;
    close(fd);
    errno = err;
    return result;
}

/* IFF_UP of the interface, asked by name so a deleted and re-created interface is found again. */
static bool link_is_up(const co_linux_bus_t *bus)
{
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    snprintf(ifr.ifr_name, sizeof ifr.ifr_name, "%s", bus->iface);
    if (ioctl(bus->link_fd, SIOCGIFFLAGS, &ifr) != 0)
        return false;
    return (ifr.ifr_flags & IFF_UP) != 0;
}

static void link_came_up(co_linux_bus_t *bus)
{
    const char *call;
    if (open_can_socket(bus, &call) != CO_LINUX_OPEN_OK) {
        co_log(CO_LOG_ERROR, "interface %s is up but cannot be opened: %s: %s", bus->iface, call,
               strerror(errno));
        return;
    }
    bus->link_up = true;
    co_linux_conditions_restart(&bus->conditions);
    bus->host.came_up(bus->host.ctx);
}

/* The netlink messages only say that some link changed: drain them, then ask about ours. */
static void link_changed(void *ctx, uint32_t events)
{
    co_linux_bus_t *bus = ctx;
    (void)events;
    char buf[8192];
    for (;;) {
        ssize_t n = recv(bus->link_fd, buf, sizeof buf, MSG_DONTWAIT);
        /* ENOBUFS: messages were lost, which the state query below makes up for. */
        if (n <= 0 && !(n < 0 && errno == ENOBUFS))
            break;
    }
    bool up = link_is_up(bus);
    if (up && !bus->link_up)
        link_came_up(bus);
    else if (!up && bus->link_up)
        link_went_down(bus, "link event");
}

static int open_link_monitor(co_linux_bus_t *bus)
{
    bus->link_fd = socket(AF_NETLINK, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, NETLINK_ROUTE);
    if (bus->link_fd < 0)
        return -1;
    struct sockaddr_nl addr = {.nl_family = AF_NETLINK, .nl_groups = RTMGRP_LINK};
    if (bind(bus->link_fd, (struct sockaddr *)&addr, sizeof addr) != 0)
        return -1;
    return co_linux_events_add(bus->host.events, bus->link_fd, EPOLLIN, link_changed, bus);
}

co_linux_open_result_t co_linux_bus_open(co_linux_bus_t *bus, const char **call)
{
    if (open_link_monitor(bus) != 0) {
        *call = "netlink socket (RTMGRP_LINK)";
        return CO_LINUX_OPEN_OS_ERROR;
    }
    co_linux_open_result_t result = open_can_socket(bus, call);
    if (result != CO_LINUX_OPEN_OK)
        return result;
    bus->link_up = true;
    if (!link_is_up(bus)) {
        close_can_socket(bus);
        bus->link_up = false;
        co_log(CO_LOG_WARN, "interface %s is down: waiting for it to come up", bus->iface);
    }
    return CO_LINUX_OPEN_OK;
}

/* ---- a socket of the caller's ---- */

/* Frames keep their boundaries only on a datagram or sequenced-packet socket. */
bool co_linux_bus_keeps_frames(int fd, bool *can_raw)
{
    int type, domain;
    socklen_t len = sizeof type;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0)
        return false;
    if (type != SOCK_SEQPACKET && type != SOCK_DGRAM && type != SOCK_RAW) {
        errno = EPROTOTYPE;
        return false;
    }
    len = sizeof domain;
    if (getsockopt(fd, SOL_SOCKET, SO_DOMAIN, &domain, &len) != 0)
        return false;
    *can_raw = domain == AF_CAN;
    return true;
}

co_linux_open_result_t co_linux_bus_open_fd(co_linux_bus_t *bus, int fd, bool can_raw,
                                            const char **call)
{
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        *call = "fcntl(O_NONBLOCK)";
        return CO_LINUX_OPEN_OS_ERROR;
    }
    bus->socket_given = true;
    bus->kernel_filter = can_raw;
    if (co_linux_events_add(bus->host.events, fd, socket_events(bus), socket_ready, bus) != 0) {
        *call = "epoll_ctl";
        return CO_LINUX_OPEN_OS_ERROR;
    }
    bus->can_fd = fd;
    bus->link_up = true;
    return CO_LINUX_OPEN_OK;
}

void co_linux_bus_close(co_linux_bus_t *bus)
{
    int *fds[] = {&bus->can_fd, &bus->link_fd};
    for (size_t i = 0; i < sizeof fds / sizeof fds[0]; i++) {
        if (*fds[i] >= 0)
            close(*fds[i]);
        *fds[i] = -1;
    }
    if (bus->trace)
        fflush(bus->trace);
}
