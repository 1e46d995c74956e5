#include "co_linux/loop.h"
#include "co/co_consumers.h"
#include "co/co_node.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "co_linux/log.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/ioctl.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <unistd.h>

/* epoll_event.data.u32 tags; the application's watched descriptors are TAG_WATCH + slot. */
enum { TAG_CAN, TAG_TIMER, TAG_SIGNAL, TAG_LINK, TAG_WATCH };

enum { COND_OVERRUN, COND_PASSIVE, COND_BUS_OFF };

/* ENOBUFS from a CAN socket means the interface's queue is full; the socket itself may still
 * look writable, so EPOLLOUT cannot tell when to retry. Retry after this long instead. */
#define ENOBUFS_RETRY_US 1000u

/* Received batches handled per wake-up before other descriptors get their turn. */
#define RX_ROUNDS 4

/* Routing key of a remote request: the CAN-ID plus this. */
#define ROUTE_KEY_RTR 0x800u

static const char *const condition_names[] = {"CAN overrun (frames lost)", "CAN error passive",
                                              "CAN bus off"};

co_time_t co_linux_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (co_time_t)ts.tv_sec * 1000000u + (co_time_t)ts.tv_nsec / 1000u;
}

static bool errno_means_down(int err)
{
    return err == ENETDOWN || err == ENODEV || err == ENXIO;
}

static void trace_frame(co_linux_loop_t *loop, const struct can_frame *frame)
{
    if (!loop->trace)
        return;
    char line[CO_CANDUMP_LINE_MAX];
    size_t len = co_candump_format(line, sizeof line, &loop->wall, loop->iface, frame);
    fwrite(line, 1, len, loop->trace);
    loop->trace_dirty = true;
}

/* One flush per wake-up, not per frame: the trace costs one write(2) however many frames. */
static void flush_trace(co_linux_loop_t *loop)
{
    if (!loop->trace_dirty)
        return;
    loop->trace_dirty = false;
    if (fflush(loop->trace) != 0 || ferror(loop->trace)) {
        co_log(CO_LOG_ERROR, "trace: write failed (%s): tracing stopped", strerror(errno));
        loop->trace = NULL;
        loop->filter_stale = true; /* the socket no longer needs the whole bus */
    }
}

static void set_condition(co_linux_loop_t *loop, int which, bool active)
{
    co_linux_condition_t *c = &loop->conditions[which];
    if (c->wanted == active)
        return;
    c->wanted = active;
    if (which == COND_OVERRUN)
        loop->traffic_since_overrun = false;
    co_log(active ? CO_LOG_WARN : CO_LOG_INFO, "%s: %s (EMCY %04X %s)", loop->iface,
           condition_names[which], c->emcy_code, active ? "active" : "cleared");
}

/* Every call into a device ends here, so this is where a changed consumer set is noticed: the
 * routes are rebuilt before the next frame is routed. */
static void device_process(co_linux_device_t *dev, co_time_t now)
{
    dev->deadline = dev->ops->process(dev->ctx, now);
    if (dev->ops->node != NULL &&
        co_node_consumer_generation(dev->ops->node(dev->ctx)) != dev->generation)
        dev->loop->routes_stale = true;
}

/* A given socket's peer can hang up (EPOLLRDHUP); a CAN_RAW socket has no peer. */
static uint32_t can_events(const co_linux_loop_t *loop)
{
    return EPOLLIN | (loop->socket_given ? EPOLLRDHUP : 0u);
}

static int update_epoll(co_linux_loop_t *loop, bool want_out)
{
    struct epoll_event ev = {.events = can_events(loop) | (want_out ? EPOLLOUT : 0u),
                             .data.u32 = TAG_CAN};
    return epoll_ctl(loop->epoll_fd, EPOLL_CTL_MOD, loop->can_fd, &ev);
}

static void set_tx_wait(co_linux_loop_t *loop, co_linux_tx_wait_t wait)
{
    /* Every refusal pushes the retry 1 ms on, also when already waiting to retry: a retry time
     * left in the past would make the timer fire at once, forever. */
    loop->retry_at = wait == CO_LINUX_TX_RETRY ? loop->now + ENOBUFS_RETRY_US : CO_TIME_NEVER;
    if (loop->tx_wait == wait)
        return;
    bool had_out = loop->tx_wait == CO_LINUX_TX_EPOLLOUT;
    bool want_out = wait == CO_LINUX_TX_EPOLLOUT;
    loop->tx_wait = wait;
    if (had_out != want_out && loop->can_fd >= 0 && update_epoll(loop, want_out) != 0)
        co_log(CO_LOG_ERROR, "epoll_ctl: %s", strerror(errno));
}

static void close_can_socket(co_linux_loop_t *loop)
{
    if (loop->can_fd < 0)
        return;
    epoll_ctl(loop->epoll_fd, EPOLL_CTL_DEL, loop->can_fd, NULL);
    close(loop->can_fd);
    loop->can_fd = -1;
}

static void link_went_down(co_linux_loop_t *loop, const char *why)
{
    if (!loop->link_up)
        return;
    loop->link_up = false;
    size_t lost = co_txq_clear(&loop->txq);
    loop->stats.down_dropped += lost;
    set_tx_wait(loop, CO_LINUX_TX_READY);
    close_can_socket(loop);
    co_log(CO_LOG_WARN, "interface %s is down (%s): %zu queued frames dropped, waiting for it",
           loop->iface, why, lost);
}

static void frame_dropped(co_linux_loop_t *loop, const co_frame_t *frame, const char *why)
{
    loop->stats.tx_dropped++;
    if (loop->dropped_in_burst++ == 0)
        co_log(CO_LOG_WARN, "%s: frame %03X dropped: %s (queue of %zu frames)", loop->iface,
               (unsigned)frame->id, why, loop->txq.capacity);
    else
        co_log(CO_LOG_DEBUG, "%s: frame %03X dropped: %s", loop->iface, (unsigned)frame->id, why);
    set_condition(loop, COND_OVERRUN, true);
}

/* A lone frame goes by send: sendmmsg would copy in its message and I/O vector headers for it. */
static int send_frames(co_linux_loop_t *loop, size_t count)
{
    if (count > 1)
        return sendmmsg(loop->can_fd, loop->tx_msgs, (unsigned)count, MSG_DONTWAIT);
    ssize_t sent = send(loop->can_fd, &loop->tx_frames[0], CAN_MTU, MSG_DONTWAIT);
    return sent < 0 ? -1 : 1;
}

/* Writes up to CO_LINUX_TX_BATCH queued frames in one system call; returns how many the socket
 * took (errno says why when 0). */
static int write_batch(co_linux_loop_t *loop)
{
    size_t count = co_txq_count(&loop->txq);
    if (count > CO_LINUX_TX_BATCH)
        count = CO_LINUX_TX_BATCH;
    for (size_t i = 0; i < count; i++)
        co_linux_frame_to_can(&co_txq_at(&loop->txq, i)->frame, &loop->tx_frames[i]);
    int sent = send_frames(loop, count);
    if (sent <= 0)
        return 0;
    loop->stats.tx_calls++;
    loop->stats.tx += (unsigned)sent;
    loop->traffic_since_overrun = true;
    for (int i = 0; i < sent; i++) {
        trace_frame(loop, &loop->tx_frames[i]);
        co_txq_pop(&loop->txq);
    }
    return sent;
}

/* Writes queued frames in order, a batch per system call, until the queue is empty or the socket
 * refuses. */
static void flush_txq(co_linux_loop_t *loop)
{
    bool progress = false;
    while (loop->link_up && co_txq_count(&loop->txq) > 0) {
        if (write_batch(loop) > 0) {
            progress = true;
            continue;
        }
        int err = errno;
        if (err == EAGAIN || err == ENOBUFS) {
            set_tx_wait(loop,
                        err == ENOBUFS && !progress ? CO_LINUX_TX_RETRY : CO_LINUX_TX_EPOLLOUT);
            return;
        }
        if (errno_means_down(err)) {
            link_went_down(loop, strerror(err));
            return;
        }
        const co_frame_t *frame = &co_txq_peek(&loop->txq)->frame;
        co_log(CO_LOG_ERROR, "%s: write of frame %03X failed: %s", loop->iface, (unsigned)frame->id,
               strerror(err));
        frame_dropped(loop, frame, "write error");
        co_txq_pop(&loop->txq);
    }
    set_tx_wait(loop, CO_LINUX_TX_READY);
    if (loop->dropped_in_burst) {
        co_log(CO_LOG_WARN, "%s: transmit queue drained; %zu frames were dropped while it was full",
               loop->iface, loop->dropped_in_burst);
        loop->dropped_in_burst = 0;
    }
}

/* Sends what the queue holds unless the socket already refused (then EPOLLOUT or the retry
 * timer sends it). */
static void transmit(co_linux_loop_t *loop)
{
    if (loop->tx_wait == CO_LINUX_TX_READY)
        flush_txq(loop);
}

void co_linux_device_send(void *device, const co_frame_t *frame)
{
    co_linux_device_t *dev = device;
    co_linux_loop_t *loop = dev->loop;
    dev->stats.tx++;
    /* Frames wait in the queue until the wake-up settles, so that the frames of one wake-up
     * leave in one sendmmsg; a full queue is written out first, so a frame is dropped only when
     * the socket cannot take any more. */
    if (co_txq_full(&loop->txq))
        transmit(loop);
    if (!loop->link_up) {
        loop->stats.down_dropped++;
        dev->stats.tx_dropped++;
        return;
    }
    if (!co_txq_push(&loop->txq, frame, dev)) {
        frame_dropped(loop, frame, "transmit queue full");
        dev->stats.tx_dropped++;
        return;
    }
    /* The socket does not receive its own frames (CAN_RAW_RECV_OWN_MSGS is off), so the other
     * devices of this loop get them from here, after the current call returns. */
    if (loop->device_count > 1 && !co_txq_push(&loop->local, frame, dev))
        co_log(CO_LOG_WARN, "%s: local delivery queue full: frame %03X not seen by local devices",
               loop->iface, (unsigned)frame->id);
}

static size_t route_key(uint16_t can_id, bool rtr)
{
    return can_id | (rtr ? ROUTE_KEY_RTR : 0u);
}

static const co_node_t *device_node(const co_linux_device_t *dev)
{
    return dev->ops->node(dev->ctx);
}

/* Room for `count` routes; false (logged) when memory is short, and every device then gets
 * every frame as before routing. */
static bool reserve_routes(co_linux_loop_t *loop, size_t count)
{
    if (count <= loop->route_capacity)
        return true;
    co_linux_device_t **routes = realloc(loop->route_devices, count * sizeof *routes);
    if (routes == NULL) {
        co_log(CO_LOG_ERROR, "routing table of %zu entries: out of memory: no routing", count);
        return false;
    }
    loop->route_devices = routes;
    loop->route_capacity = count;
    return true;
}

/* A counting sort of the (COB-ID, device) pairs by key: one pass counts each key's consumers, a
 * prefix sum gives each key its range, a second pass fills the ranges in device order. Runs when
 * a consumed set changed, never per frame. */
static void build_routes(co_linux_loop_t *loop)
{
    uint32_t cursor[CO_LINUX_ROUTE_KEYS];
    co_cob_t cobs[CO_CONSUMERS_MAX];
    loop->routes_stale = false;
    loop->filter_stale = true;
    loop->route_all = false;
    memset(loop->route_first, 0, sizeof loop->route_first);
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        if (dev->ops->node == NULL) {
            loop->route_all = true;
            continue;
        }
        dev->generation = co_node_consumer_generation(device_node(dev));
        size_t count = co_node_consumers(device_node(dev), cobs);
        for (size_t i = 0; i < count; i++)
            loop->route_first[route_key(cobs[i].can_id, cobs[i].rtr) + 1]++;
    }
    for (size_t k = 0; k < CO_LINUX_ROUTE_KEYS; k++)
        loop->route_first[k + 1] += loop->route_first[k];
    if (loop->route_all || !reserve_routes(loop, loop->route_first[CO_LINUX_ROUTE_KEYS])) {
        loop->route_all = true;
        return;
    }
    memcpy(cursor, loop->route_first, sizeof cursor);
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        size_t count = co_node_consumers(device_node(dev), cobs);
        for (size_t i = 0; i < count; i++)
            loop->route_devices[cursor[route_key(cobs[i].can_id, cobs[i].rtr)]++] = dev;
    }
}

/* The socket's receive filter: one exact entry (CAN-ID, data or remote, 11-bit) per routed key.
 * The whole bus when a trace is written (it shows every frame, as candump would) or a device
 * takes every frame; every 11-bit frame when the keys are more than the kernel accepts
 * (CAN_RAW_FILTER_MAX): the routes still sort them. Returns the number of entries. */
static size_t wanted_filter(const co_linux_loop_t *loop, struct can_filter *wanted)
{
    if (loop->route_all || loop->trace != NULL) {
        wanted[0] = (struct can_filter){.can_id = 0, .can_mask = 0};
        return 1;
    }
    size_t count = 0;
    for (size_t k = 0; k < CO_LINUX_ROUTE_KEYS; k++) {
        if (loop->route_first[k] == loop->route_first[k + 1])
            continue;
        if (count == CAN_RAW_FILTER_MAX) {
            wanted[0] = (struct can_filter){.can_id = 0, .can_mask = CAN_EFF_FLAG};
            return 1;
        }
        wanted[count++] = (struct can_filter){
            .can_id = (canid_t)(k & CAN_SFF_MASK) | (k & ROUTE_KEY_RTR ? CAN_RTR_FLAG : 0u),
            .can_mask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG};
    }
    return count;
}

static bool set_filter(co_linux_loop_t *loop, const struct can_filter *filter, size_t count)
{
    return setsockopt(loop->can_fd, SOL_CAN_RAW, CAN_RAW_FILTER, filter,
                      (socklen_t)(count * sizeof filter[0])) == 0;
}

/* Computed when the routes, the socket or the trace changed; set only when it differs from what
 * this socket has. */
static void apply_filter(co_linux_loop_t *loop)
{
    struct can_filter wanted[CAN_RAW_FILTER_MAX];
    size_t count = wanted_filter(loop, wanted);
    loop->filter_stale = false;
    if (loop->filter_applied && count == loop->filter_count &&
        memcmp(wanted, loop->filters, count * sizeof wanted[0]) == 0)
        return;
    if (!set_filter(loop, wanted, count)) {
        /* A filter that may hide frames a node now consumes is worse than none. */
        co_log(CO_LOG_ERROR, "%s: CAN_RAW_FILTER of %zu entries: %s: receiving the whole bus",
               loop->iface, count, strerror(errno));
        wanted[0] = (struct can_filter){.can_id = 0, .can_mask = 0};
        count = 1;
        if (!set_filter(loop, wanted, count)) {
            loop->filter_applied = false;
            return;
        }
    }
    memcpy(loop->filters, wanted, count * sizeof wanted[0]);
    loop->filter_count = count;
    loop->filter_applied = true;
    loop->stats.filters++;
}

/* One frame to one device, and its process right after, as co_node_process requires; false
 * for the device that sent the frame. */
static bool deliver(co_linux_device_t *dev, const co_frame_t *frame, const void *origin)
{
    if (dev == origin)
        return false;
    dev->stats.rx++;
    dev->ops->receive(dev->ctx, frame, dev->loop->now);
    device_process(dev, dev->loop->now);
    return true;
}

/* Hands a frame to the devices that consume it, except the one that sent it; returns how many
 * got it. */
static size_t route_frame(co_linux_loop_t *loop, const co_frame_t *frame, const void *origin)
{
    if (loop->routes_stale)
        build_routes(loop);
    size_t delivered = 0;
    if (loop->route_all) {
        for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next)
            delivered += deliver(dev, frame, origin);
        return delivered;
    }
    /* The core ignores 29-bit frames: no node consumes them. */
    if (frame->flags & CO_FRAME_EFF)
        return 0;
    size_t key = route_key((uint16_t)frame->id, (frame->flags & CO_FRAME_RTR) != 0);
    for (uint32_t i = loop->route_first[key]; i < loop->route_first[key + 1]; i++)
        delivered += deliver(loop->route_devices[i], frame, origin);
    return delivered;
}

static void deliver_local(co_linux_loop_t *loop)
{
    const co_txq_entry_t *e;
    while ((e = co_txq_peek(&loop->local)) != NULL) {
        co_txq_entry_t entry = *e;
        co_txq_pop(&loop->local);
        route_frame(loop, &entry.frame, entry.origin);
    }
}

static void handle_error_frame(co_linux_loop_t *loop, const struct can_frame *cf)
{
    loop->stats.error_frames++;
    if (cf->can_id & CAN_ERR_BUSOFF)
        set_condition(loop, COND_BUS_OFF, true);
    if (cf->can_id & CAN_ERR_RESTARTED) {
        set_condition(loop, COND_BUS_OFF, false);
        set_condition(loop, COND_PASSIVE, false);
    }
    if (!(cf->can_id & CAN_ERR_CRTL))
        return;
    uint8_t crtl = cf->data[1];
    if (crtl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))
        set_condition(loop, COND_PASSIVE, true);
    if (crtl & CAN_ERR_CRTL_ACTIVE)
        set_condition(loop, COND_PASSIVE, false);
    if (crtl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING))
        co_log(CO_LOG_WARN, "%s: CAN controller reached the error warning level", loop->iface);
    if (crtl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW))
        set_condition(loop, COND_OVERRUN, true);
}

static void handle_rx_frame(co_linux_loop_t *loop, const struct can_frame *cf)
{
    trace_frame(loop, cf);
    if (cf->can_id & CAN_ERR_FLAG) {
        handle_error_frame(loop, cf);
        return;
    }
    loop->stats.rx++;
    loop->traffic_since_overrun = true;
    co_frame_t frame;
    co_linux_frame_from_can(cf, &frame);
    if (route_frame(loop, &frame, NULL) == 0)
        loop->stats.unrouted++;
    deliver_local(loop);
}

static void read_failed(co_linux_loop_t *loop, const char *call)
{
    if (errno_means_down(errno))
        link_went_down(loop, strerror(errno));
    else if (errno != EAGAIN && errno != EINTR)
        co_log(CO_LOG_ERROR, "%s: %s: %s", loop->iface, call, strerror(errno));
}

/* One frame, without recvmmsg's second look into a queue that is empty: the buffer has a byte
 * more than a frame so that a longer datagram (a CAN FD frame on a given socket) shows. */
static void receive_one(co_linux_loop_t *loop)
{
    union {
        struct can_frame frame;
        uint8_t longer[CAN_MTU + 1];
    } rx;
    ssize_t got = recv(loop->can_fd, &rx, sizeof rx, MSG_DONTWAIT);
    if (got < 0)
        read_failed(loop, "recv");
    else if (got == CAN_MTU)
        handle_rx_frame(loop, &rx.frame);
    else if (got == 0)
        loop->rx_end = true;
}

/* Returns how many datagrams were read. */
static int receive_batches(co_linux_loop_t *loop)
{
    int total = 0;
    for (int round = 0; round < RX_ROUNDS && loop->can_fd >= 0; round++) {
        int n = recvmmsg(loop->can_fd, loop->rx_msgs, CO_LINUX_RX_BATCH, MSG_DONTWAIT, NULL);
        if (n < 0) {
            read_failed(loop, "recvmmsg");
            return total;
        }
        total += n;
        for (int i = 0; i < n; i++) {
            /* A longer datagram (a CAN FD frame on a given socket) arrives cut to CAN_MTU. */
            const struct mmsghdr *msg = &loop->rx_msgs[i];
            if (msg->msg_len == CAN_MTU && !(msg->msg_hdr.msg_flags & MSG_TRUNC))
                handle_rx_frame(loop, &loop->rx_frames[i]);
            else if (msg->msg_len == 0)
                loop->rx_end = true;
        }
        if (n < CO_LINUX_RX_BATCH)
            return total;
    }
    return total;
}

/* A wake-up nearly always finds one frame (a CAN frame takes 50 us or more on the wire), and
 * recvmmsg then looks into the empty queue a second time: while batches bring one frame, frames
 * are read one by one, with a batch every CO_LINUX_RX_PROBE_EVERY reads to catch a burst. */
static void receive_frames(co_linux_loop_t *loop)
{
    if (loop->rx_one_by_one && ++loop->rx_reads_alone < CO_LINUX_RX_PROBE_EVERY) {
        receive_one(loop);
        return;
    }
    loop->rx_reads_alone = 0;
    loop->rx_one_by_one = receive_batches(loop) == 1;
}

/* The frames it sent before are read already (the reads reached the end); the replies to them
 * still leave when the wake-up settles, then the loop ends. Reading on would return end-of-file
 * for ever. */
static void peer_hung_up(co_linux_loop_t *loop)
{
    co_log(CO_LOG_INFO, "%s: the peer closed the socket: stopping", loop->iface);
    epoll_ctl(loop->epoll_fd, EPOLL_CTL_DEL, loop->can_fd, NULL);
    co_linux_loop_stop(loop, 0);
}

static void handle_can_event(co_linux_loop_t *loop, uint32_t events)
{
    if (events & (EPOLLERR | EPOLLHUP)) {
        int err = 0;
        socklen_t len = sizeof err;
        getsockopt(loop->can_fd, SOL_SOCKET, SO_ERROR, &err, &len);
        if (errno_means_down(err)) {
            link_went_down(loop, strerror(err));
            return;
        }
        if (err)
            co_log(CO_LOG_WARN, "%s: socket error: %s", loop->iface, strerror(err));
    }
    if (events & EPOLLIN)
        receive_frames(loop);
    if (loop->socket_given && loop->rx_end && (events & (EPOLLRDHUP | EPOLLHUP))) {
        peer_hung_up(loop);
        return;
    }
    if ((events & EPOLLOUT) && loop->link_up)
        flush_txq(loop);
}

static int can_socket_open(co_linux_loop_t *loop, co_linux_open_result_t *result)
{
    int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        loop->open_call = "socket(PF_CAN, SOCK_RAW, CAN_RAW)";
        loop->open_errno = errno;
        *result = errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT ? CO_LINUX_OPEN_NO_CAN
                                                                    : CO_LINUX_OPEN_OS_ERROR;
        return -1;
    }
    struct sockaddr_can addr = {.can_family = AF_CAN,
                                .can_ifindex = (int)if_nametoindex(loop->iface)};
    can_err_mask_t err_mask = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED;
    if (addr.can_ifindex == 0) {
        loop->open_call = "if_nametoindex";
        *result = CO_LINUX_OPEN_NO_IFACE;
    } else if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0) {
        loop->open_call = "setsockopt(CAN_RAW_ERR_FILTER)";
        *result = CO_LINUX_OPEN_OS_ERROR;
    } else if (bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0) {
        loop->open_call = "bind";
        *result = errno == ENODEV ? CO_LINUX_OPEN_NOT_CAN : CO_LINUX_OPEN_OS_ERROR;
    } else {
        struct epoll_event ev = {.events = EPOLLIN, .data.u32 = TAG_CAN};
        if (epoll_ctl(loop->epoll_fd, EPOLL_CTL_ADD, fd, &ev) == 0) {
            loop->can_fd = fd;
            loop->kernel_filter = true;
            loop->filter_applied = false;
            loop->filter_stale = true;
            *result = CO_LINUX_OPEN_OK;
            return 0;
        }
        loop->open_call = "epoll_ctl";
        *result = CO_LINUX_OPEN_OS_ERROR;
    }
    loop->open_errno = errno;
    close(fd);
    return -1;
}

/* IFF_UP of the interface, asked by name so a deleted and re-created interface is found again. */
static bool link_is_up(co_linux_loop_t *loop)
{
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    memcpy(ifr.ifr_name, loop->iface, sizeof loop->iface);
    if (ioctl(loop->link_fd, SIOCGIFFLAGS, &ifr) != 0)
        return false;
    return (ifr.ifr_flags & IFF_UP) != 0;
}

static void link_came_up(co_linux_loop_t *loop)
{
    co_linux_open_result_t result;
    if (can_socket_open(loop, &result) != 0) {
        co_log(CO_LOG_ERROR, "interface %s is up but cannot be opened: %s: %s", loop->iface,
               loop->open_call, strerror(loop->open_errno));
        return;
    }
    loop->link_up = true;
    /* A controller that was down starts error active with empty queues. */
    for (int i = 0; i < 3; i++)
        loop->conditions[i].wanted = false;
    co_log(CO_LOG_INFO, "interface %s is up: restarting communication of %zu device(s)",
           loop->iface, loop->device_count);
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        dev->ops->restart(dev->ctx, loop->now);
        device_process(dev, loop->now);
    }
}

/* The netlink messages only say that some link changed: drain them, then ask about ours. */
static void handle_link_event(co_linux_loop_t *loop)
{
    char buf[8192];
    for (;;) {
        ssize_t n = recv(loop->link_fd, buf, sizeof buf, MSG_DONTWAIT);
        /* ENOBUFS: messages were lost, which the state query below makes up for. */
        if (n <= 0 && !(n < 0 && errno == ENOBUFS))
            break;
    }
    bool up = link_is_up(loop);
    if (up && !loop->link_up)
        link_came_up(loop);
    else if (!up && loop->link_up)
        link_went_down(loop, "link event");
}

static void handle_signal(co_linux_loop_t *loop)
{
    struct signalfd_siginfo info;
    while (read(loop->signal_fd, &info, sizeof info) == (ssize_t)sizeof info) {
        co_log(CO_LOG_INFO, "received %s: stopping", strsignal((int)info.ssi_signo));
        co_linux_loop_stop(loop, 0);
    }
}

/* The timerfd is not read: arm_timer's timerfd_settime resets its expiration count, and it always
 * runs after a firing, since the earliest deadline then either moved or was disarmed. Were a
 * deadline still due at the armed time, the timer is left as it is and, still readable, brings
 * the loop straight back for it. */
static void handle_timer(co_linux_loop_t *loop)
{
    if (loop->tx_wait == CO_LINUX_TX_RETRY && loop->retry_at <= loop->now)
        flush_txq(loop);
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        if (dev->deadline <= loop->now)
            device_process(dev, loop->now);
    }
}

/* Returns true when a device was told something (it may have sent frames, or a dropped frame may
 * have raised another condition). */
static bool report_conditions(co_linux_loop_t *loop)
{
    bool reported = false;
    co_linux_condition_t *overrun = &loop->conditions[COND_OVERRUN];
    if (overrun->wanted && overrun->reported && co_txq_count(&loop->txq) == 0 &&
        loop->traffic_since_overrun)
        set_condition(loop, COND_OVERRUN, false);
    for (int i = 0; i < 3; i++) {
        co_linux_condition_t *c = &loop->conditions[i];
        if (c->wanted == c->reported)
            continue;
        /* An overrun is told once its EMCY can be queued: with the queue full it would be
         * the next frame dropped, and the master would never see it. */
        if (i == COND_OVERRUN && c->wanted && co_txq_count(&loop->txq) >= loop->txq.capacity)
            continue;
        c->reported = c->wanted;
        reported = true;
        for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
            if (dev->ops->bus_event) {
                dev->ops->bus_event(dev->ctx, c->emcy_code, c->wanted);
                device_process(dev, loop->now);
            }
        }
    }
    return reported;
}

static void arm_timer(co_linux_loop_t *loop)
{
    co_time_t next = loop->tx_wait == CO_LINUX_TX_RETRY ? loop->retry_at : CO_TIME_NEVER;
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next)
        next = co_time_min(next, dev->deadline);
    if (next == loop->timer_armed)
        return;
    struct itimerspec its;
    memset(&its, 0, sizeof its);
    if (next != CO_TIME_NEVER) {
        its.it_value.tv_sec = (time_t)(next / 1000000u);
        its.it_value.tv_nsec = (long)(next % 1000000u) * 1000;
        if (its.it_value.tv_sec == 0 && its.it_value.tv_nsec == 0)
            its.it_value.tv_nsec = 1; /* all zero would disarm */
    }
    if (timerfd_settime(loop->timer_fd, TFD_TIMER_ABSTIME, &its, NULL) != 0) {
        co_log(CO_LOG_ERROR, "timerfd_settime: %s", strerror(errno));
        co_linux_loop_stop(loop, EX_OSERR);
        return;
    }
    loop->timer_armed = next;
}

/* After every wake-up: everything the handlers caused is delivered, reported and timed. */
/* The routes and the filter follow a changed consumer set before the frames of the wake-up
 * leave: a master that reacts to the SDO reply of a COB-ID write finds the filter updated. */
static void update_routes(co_linux_loop_t *loop)
{
    if (loop->routes_stale)
        build_routes(loop);
    if (loop->filter_stale && loop->can_fd >= 0 && loop->kernel_filter)
        apply_filter(loop);
}

static void settle(co_linux_loop_t *loop)
{
    deliver_local(loop);
    update_routes(loop);
    transmit(loop);
    /* Bounded: each condition can change at most once per round. */
    for (int round = 0; round < 3 && report_conditions(loop); round++) {
        deliver_local(loop);
        update_routes(loop);
        transmit(loop);
    }
    arm_timer(loop);
    flush_trace(loop);
}

static void update_clocks(co_linux_loop_t *loop)
{
    loop->now = co_linux_now();
    if (loop->trace)
        clock_gettime(CLOCK_REALTIME, &loop->wall);
}

static int add_to_epoll(co_linux_loop_t *loop, int fd, uint32_t tag);

static void handle_watch(co_linux_loop_t *loop, uint32_t slot)
{
    if (slot < CO_LINUX_WATCH_MAX && loop->watches[slot].fd >= 0)
        loop->watches[slot].fn(loop->watches[slot].ctx, loop->watches[slot].fd);
}

int co_linux_loop_watch(co_linux_loop_t *loop, int fd, co_linux_watch_fn fn, void *ctx)
{
    for (uint32_t slot = 0; slot < CO_LINUX_WATCH_MAX; slot++) {
        co_linux_watch_t *watch = &loop->watches[slot];
        if (watch->fd >= 0)
            continue;
        if (add_to_epoll(loop, fd, TAG_WATCH + slot) != 0)
            return -1;
        *watch = (co_linux_watch_t){.fd = fd, .fn = fn, .ctx = ctx};
        return 0;
    }
    errno = ENOSPC;
    return -1;
}

void co_linux_loop_unwatch(co_linux_loop_t *loop, int fd)
{
    for (int slot = 0; slot < CO_LINUX_WATCH_MAX; slot++) {
        if (loop->watches[slot].fd == fd) {
            epoll_ctl(loop->epoll_fd, EPOLL_CTL_DEL, fd, NULL);
            loop->watches[slot].fd = -1;
        }
    }
}

void co_linux_device_process(co_linux_device_t *device)
{
    device_process(device, device->loop->now);
}

int co_linux_loop_run(co_linux_loop_t *loop)
{
    loop->running = true;
    update_clocks(loop);
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        dev->ops->start(dev->ctx, loop->now);
        device_process(dev, loop->now);
    }
    settle(loop);
    while (loop->running) {
        struct epoll_event events[8];
        int n = epoll_wait(loop->epoll_fd, events, 8, -1);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            co_log(CO_LOG_ERROR, "epoll_wait: %s", strerror(errno));
            return EX_OSERR;
        }
        loop->stats.wakeups++;
        update_clocks(loop);
        for (int i = 0; i < n; i++) {
            switch (events[i].data.u32) {
            case TAG_CAN:
                if (loop->can_fd >= 0)
                    handle_can_event(loop, events[i].events);
                break;
            case TAG_TIMER:
                handle_timer(loop);
                break;
            case TAG_SIGNAL:
                handle_signal(loop);
                break;
            case TAG_LINK:
                handle_link_event(loop);
                break;
            default:
                handle_watch(loop, events[i].data.u32 - TAG_WATCH);
                break;
            }
        }
        settle(loop);
    }
    return loop->exit_status;
}

void co_linux_loop_stop(co_linux_loop_t *loop, int status)
{
    loop->running = false;
    loop->exit_status = status;
}

void co_linux_loop_add(co_linux_loop_t *loop, co_linux_device_t *device,
                       const co_linux_device_ops_t *ops, void *ctx)
{
    device->ops = ops;
    device->ctx = ctx;
    device->loop = loop;
    device->deadline = CO_TIME_NEVER;
    device->generation = 0;
    device->stats = (co_linux_device_stats_t){0};
    device->next = NULL;
    loop->routes_stale = true;
    co_linux_device_t **tail = &loop->devices;
    while (*tail)
        tail = &(*tail)->next;
    *tail = device;
    loop->device_count++;
}

static int add_to_epoll(co_linux_loop_t *loop, int fd, uint32_t tag)
{
    struct epoll_event ev = {.events = EPOLLIN, .data.u32 = tag};
    return epoll_ctl(loop->epoll_fd, EPOLL_CTL_ADD, fd, &ev);
}

static int open_link_monitor(co_linux_loop_t *loop)
{
    loop->link_fd = socket(AF_NETLINK, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, NETLINK_ROUTE);
    if (loop->link_fd < 0)
        return -1;
    struct sockaddr_nl addr = {.nl_family = AF_NETLINK, .nl_groups = RTMGRP_LINK};
    if (bind(loop->link_fd, (struct sockaddr *)&addr, sizeof addr) != 0)
        return -1;
    return add_to_epoll(loop, loop->link_fd, TAG_LINK);
}

static int open_signals(co_linux_loop_t *loop)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    if (sigprocmask(SIG_BLOCK, &set, &loop->old_mask) != 0)
        return -1;
    loop->signal_fd = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
    if (loop->signal_fd < 0)
        return -1;
    return add_to_epoll(loop, loop->signal_fd, TAG_SIGNAL);
}

/* The descriptors every loop needs besides the CAN socket (the link monitor only for an
 * interface the loop opens itself); sets open_call on failure. */
static int open_loop_descriptors(co_linux_loop_t *loop, bool monitor_link)
{
    loop->open_call = "epoll_create1";
    loop->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
    if (loop->epoll_fd < 0)
        return -1;
    loop->open_call = "timerfd_create";
    loop->timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    if (loop->timer_fd < 0 || add_to_epoll(loop, loop->timer_fd, TAG_TIMER) != 0)
        return -1;
    loop->open_call = "signalfd";
    if (open_signals(loop) != 0)
        return -1;
    if (!monitor_link)
        return 0;
    loop->open_call = "netlink socket (RTMGRP_LINK)";
    return open_link_monitor(loop);
}

static void init_loop(co_linux_loop_t *loop, const co_linux_loop_config_t *config)
{
    memset(loop, 0, sizeof *loop);
    loop->epoll_fd = loop->can_fd = loop->timer_fd = loop->signal_fd = loop->link_fd = -1;
    for (int slot = 0; slot < CO_LINUX_WATCH_MAX; slot++)
        loop->watches[slot].fd = -1;
    sigprocmask(SIG_SETMASK, NULL, &loop->old_mask);
    snprintf(loop->iface, sizeof loop->iface, "%s", config->iface);
    loop->trace = config->trace;
    loop->timer_armed = CO_TIME_NEVER;
    loop->retry_at = CO_TIME_NEVER;
    co_txq_init(&loop->txq, config->txq_capacity ? config->txq_capacity : CO_TXQ_MAX);
    co_txq_init(&loop->local, CO_TXQ_MAX);
    loop->conditions[COND_OVERRUN].emcy_code = CO_LINUX_EMCY_CAN_OVERRUN;
    loop->conditions[COND_PASSIVE].emcy_code = CO_LINUX_EMCY_CAN_PASSIVE;
    loop->conditions[COND_BUS_OFF].emcy_code = CO_LINUX_EMCY_BUS_OFF;
    for (int i = 0; i < CO_LINUX_RX_BATCH; i++) {
        loop->rx_iov[i].iov_base = &loop->rx_frames[i];
        loop->rx_iov[i].iov_len = sizeof loop->rx_frames[i];
        loop->rx_msgs[i].msg_hdr.msg_iov = &loop->rx_iov[i];
        loop->rx_msgs[i].msg_hdr.msg_iovlen = 1;
    }
    for (int i = 0; i < CO_LINUX_TX_BATCH; i++) {
        loop->tx_iov[i].iov_base = &loop->tx_frames[i];
        loop->tx_iov[i].iov_len = sizeof loop->tx_frames[i];
        loop->tx_msgs[i].msg_hdr.msg_iov = &loop->tx_iov[i];
        loop->tx_msgs[i].msg_hdr.msg_iovlen = 1;
    }
}

co_linux_open_result_t co_linux_loop_open(co_linux_loop_t *loop,
                                          const co_linux_loop_config_t *config)
{
    init_loop(loop, config);
    co_linux_open_result_t result = CO_LINUX_OPEN_OS_ERROR;
    if (open_loop_descriptors(loop, true) != 0) {
        loop->open_errno = errno;
    } else if (can_socket_open(loop, &result) == 0) {
        loop->link_up = true;
        if (!link_is_up(loop)) {
            close_can_socket(loop);
            loop->link_up = false;
            co_log(CO_LOG_WARN, "interface %s is down: waiting for it to come up", loop->iface);
        }
        return CO_LINUX_OPEN_OK;
    }
    co_linux_loop_close(loop);
    return result;
}

/* Frames keep their boundaries only on a datagram or sequenced-packet socket. */
static bool keeps_frames(int fd, int *domain)
{
    int type;
    socklen_t len = sizeof type;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0)
        return false;
    if (type != SOCK_SEQPACKET && type != SOCK_DGRAM && type != SOCK_RAW) {
        errno = EPROTOTYPE;
        return false;
    }
    len = sizeof *domain;
    return getsockopt(fd, SOL_SOCKET, SO_DOMAIN, domain, &len) == 0;
}

co_linux_open_result_t co_linux_loop_open_fd(co_linux_loop_t *loop,
                                             const co_linux_loop_config_t *config, int fd)
{
    init_loop(loop, config);
    int domain = AF_UNSPEC;
    loop->open_call = "getsockopt(SO_TYPE)";
    if (!keeps_frames(fd, &domain) || open_loop_descriptors(loop, false) != 0) {
        loop->open_errno = errno;
        co_linux_loop_close(loop);
        return CO_LINUX_OPEN_OS_ERROR;
    }
    int flags = fcntl(fd, F_GETFL);
    loop->open_call = "fcntl(O_NONBLOCK)";
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        loop->open_errno = errno;
        co_linux_loop_close(loop);
        return CO_LINUX_OPEN_OS_ERROR;
    }
    loop->socket_given = true;
    loop->kernel_filter = domain == AF_CAN;
    struct epoll_event ev = {.events = can_events(loop), .data.u32 = TAG_CAN};
    loop->open_call = "epoll_ctl";
    if (epoll_ctl(loop->epoll_fd, EPOLL_CTL_ADD, fd, &ev) != 0) {
        loop->open_errno = errno;
        co_linux_loop_close(loop);
        return CO_LINUX_OPEN_OS_ERROR;
    }
    loop->can_fd = fd;
    loop->filter_stale = true;
    loop->link_up = true;
    return CO_LINUX_OPEN_OK;
}

void co_linux_loop_close(co_linux_loop_t *loop)
{
    int *fds[] = {&loop->can_fd, &loop->timer_fd, &loop->signal_fd, &loop->link_fd,
                  &loop->epoll_fd};
    for (size_t i = 0; i < sizeof fds / sizeof fds[0]; i++) {
        if (*fds[i] >= 0)
            close(*fds[i]);
        *fds[i] = -1;
    }
    sigprocmask(SIG_SETMASK, &loop->old_mask, NULL);
    if (loop->trace)
        fflush(loop->trace);
    free(loop->route_devices);
    loop->route_devices = NULL;
    loop->route_capacity = 0;
}
