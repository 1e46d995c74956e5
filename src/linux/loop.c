#include "co_linux/loop.h"
#include "co/co_node.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "co_linux/log.h"

#include <errno.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/ioctl.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <unistd.h>

/* epoll_event.data.u32 tags; the watched descriptors take TAG_WATCH and above. */
enum { TAG_CAN, TAG_TIMER, TAG_SIGNAL, TAG_LINK, TAG_WATCH };

enum { COND_OVERRUN, COND_PASSIVE, COND_BUS_OFF };

/* ENOBUFS from a CAN socket means the interface's queue is full; the socket itself may still
 * look writable, so EPOLLOUT cannot tell when to retry. Retry after this long instead. */
#define ENOBUFS_RETRY_US 1000u

/* Received batches handled per wake-up before other descriptors get their turn. */
#define RX_ROUNDS 4

typedef enum { WRITE_OK, WRITE_BLOCKED, WRITE_DOWN, WRITE_FAILED } write_result_t;

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

static void device_process(co_linux_device_t *dev, co_time_t now)
{
    dev->deadline = dev->ops->process(dev->ctx, now);
}

static int update_epoll(co_linux_loop_t *loop, bool want_out)
{
    struct epoll_event ev = {.events = EPOLLIN | (want_out ? EPOLLOUT : 0u), .data.u32 = TAG_CAN};
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

static write_result_t write_frame(co_linux_loop_t *loop, const co_frame_t *frame)
{
    struct can_frame cf;
    co_linux_frame_to_can(frame, &cf);
    ssize_t n = write(loop->can_fd, &cf, sizeof cf);
    if (n == (ssize_t)sizeof cf) {
        loop->stats.tx++;
        loop->traffic_since_overrun = true;
        trace_frame(loop, &cf);
        return WRITE_OK;
    }
    if (n < 0 && (errno == EAGAIN || errno == ENOBUFS))
        return WRITE_BLOCKED;
    if (n < 0 && errno_means_down(errno)) {
        link_went_down(loop, strerror(errno));
        return WRITE_DOWN;
    }
    co_log(CO_LOG_ERROR, "%s: write of frame %03X failed: %s", loop->iface, (unsigned)frame->id,
           n < 0 ? strerror(errno) : "short write");
    return WRITE_FAILED;
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

/* Writes queued frames in order until the socket refuses one. */
static void flush_txq(co_linux_loop_t *loop)
{
    bool progress = false;
    const co_txq_entry_t *e;
    while (loop->link_up && (e = co_txq_peek(&loop->txq)) != NULL) {
        switch (write_frame(loop, &e->frame)) {
        case WRITE_OK:
            co_txq_pop(&loop->txq);
            progress = true;
            break;
        case WRITE_BLOCKED:
            set_tx_wait(loop,
                        errno == ENOBUFS && !progress ? CO_LINUX_TX_RETRY : CO_LINUX_TX_EPOLLOUT);
            return;
        case WRITE_DOWN:
            return;
        case WRITE_FAILED:
            frame_dropped(loop, &e->frame, "write error");
            co_txq_pop(&loop->txq);
            break;
        }
    }
    set_tx_wait(loop, CO_LINUX_TX_READY);
    if (loop->dropped_in_burst) {
        co_log(CO_LOG_WARN, "%s: transmit queue drained; %zu frames were dropped while it was full",
               loop->iface, loop->dropped_in_burst);
        loop->dropped_in_burst = 0;
    }
}

void co_linux_device_send(void *device, const co_frame_t *frame)
{
    co_linux_device_t *dev = device;
    co_linux_loop_t *loop = dev->loop;
    if (!loop->link_up) {
        loop->stats.down_dropped++;
        return;
    }
    bool accepted = true;
    if (co_txq_count(&loop->txq) == 0) {
        switch (write_frame(loop, frame)) {
        case WRITE_OK:
            break;
        case WRITE_BLOCKED:
            co_txq_push(&loop->txq, frame, dev);
            set_tx_wait(loop, CO_LINUX_TX_EPOLLOUT);
            break;
        case WRITE_DOWN:
            loop->stats.down_dropped++;
            return;
        case WRITE_FAILED:
            frame_dropped(loop, frame, "write error");
            accepted = false;
            break;
        }
    } else if (!co_txq_push(&loop->txq, frame, dev)) {
        frame_dropped(loop, frame, "transmit queue full");
        accepted = false;
    }
    /* The socket does not receive its own frames (CAN_RAW_RECV_OWN_MSGS is off), so the other
     * devices of this loop get them from here, after the current call returns. */
    if (accepted && loop->device_count > 1 && !co_txq_push(&loop->local, frame, dev))
        co_log(CO_LOG_WARN, "%s: local delivery queue full: frame %03X not seen by local devices",
               loop->iface, (unsigned)frame->id);
}

static void deliver_local(co_linux_loop_t *loop)
{
    const co_txq_entry_t *e;
    while ((e = co_txq_peek(&loop->local)) != NULL) {
        co_txq_entry_t entry = *e;
        co_txq_pop(&loop->local);
        for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
            if (dev == entry.origin)
                continue;
            dev->ops->receive(dev->ctx, &entry.frame, loop->now);
            device_process(dev, loop->now);
        }
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
    for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next) {
        dev->ops->receive(dev->ctx, &frame, loop->now);
        device_process(dev, loop->now);
    }
    deliver_local(loop);
}

static void receive_frames(co_linux_loop_t *loop)
{
    for (int round = 0; round < RX_ROUNDS && loop->can_fd >= 0; round++) {
        int n = recvmmsg(loop->can_fd, loop->rx_msgs, CO_LINUX_RX_BATCH, MSG_DONTWAIT, NULL);
        if (n < 0) {
            if (errno_means_down(errno))
                link_went_down(loop, strerror(errno));
            else if (errno != EAGAIN && errno != EINTR)
                co_log(CO_LOG_ERROR, "%s: recvmmsg: %s", loop->iface, strerror(errno));
            return;
        }
        for (int i = 0; i < n; i++) {
            if (loop->rx_msgs[i].msg_len == CAN_MTU)
                handle_rx_frame(loop, &loop->rx_frames[i]);
        }
        if (n < CO_LINUX_RX_BATCH)
            return;
    }
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

static void handle_timer(co_linux_loop_t *loop)
{
    uint64_t expirations;
    if (read(loop->timer_fd, &expirations, sizeof expirations) < 0 && errno != EAGAIN)
        co_log(CO_LOG_ERROR, "timerfd read: %s", strerror(errno));
    loop->timer_armed = CO_TIME_NEVER;
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
static void settle(co_linux_loop_t *loop)
{
    deliver_local(loop);
    /* Bounded: each condition can change at most once per round. */
    for (int round = 0; round < 3 && report_conditions(loop); round++)
        deliver_local(loop);
    arm_timer(loop);
    flush_trace(loop);
}

static void update_clocks(co_linux_loop_t *loop)
{
    loop->now = co_linux_now();
    if (loop->trace)
        clock_gettime(CLOCK_REALTIME, &loop->wall);
}

static void handle_watch(co_linux_loop_t *loop, uint32_t tag)
{
    for (co_linux_watch_t *w = loop->watches; w; w = w->next) {
        if (w->tag != tag)
            continue;
        w->readable(w->ctx, loop->now);
        for (co_linux_device_t *dev = loop->devices; dev; dev = dev->next)
            device_process(dev, loop->now);
        return;
    }
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
                handle_watch(loop, events[i].data.u32);
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
    device->next = NULL;
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

int co_linux_loop_watch(co_linux_loop_t *loop, co_linux_watch_t *watch, int fd,
                        void (*readable)(void *ctx, co_time_t now), void *ctx)
{
    /* Tags are never reused, so an event still pending for a watch just removed finds none. */
    *watch = (co_linux_watch_t){.fd = fd,
                                .readable = readable,
                                .ctx = ctx,
                                .tag = TAG_WATCH + loop->next_watch_tag++,
                                .next = loop->watches};
    if (add_to_epoll(loop, fd, watch->tag) != 0)
        return -1;
    loop->watches = watch;
    return 0;
}

void co_linux_loop_unwatch(co_linux_loop_t *loop, co_linux_watch_t *watch)
{
    for (co_linux_watch_t **w = &loop->watches; *w; w = &(*w)->next) {
        if (*w == watch) {
            *w = watch->next;
            epoll_ctl(loop->epoll_fd, EPOLL_CTL_DEL, watch->fd, NULL);
            return;
        }
    }
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

/* The descriptors every loop needs besides the CAN socket; sets open_call on failure. */
static int open_loop_descriptors(co_linux_loop_t *loop)
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
    loop->open_call = "netlink socket (RTMGRP_LINK)";
    return open_link_monitor(loop);
}

co_linux_open_result_t co_linux_loop_open(co_linux_loop_t *loop,
                                          const co_linux_loop_config_t *config)
{
    memset(loop, 0, sizeof *loop);
    loop->epoll_fd = loop->can_fd = loop->timer_fd = loop->signal_fd = loop->link_fd = -1;
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

    co_linux_open_result_t result = CO_LINUX_OPEN_OS_ERROR;
    if (open_loop_descriptors(loop) != 0) {
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
}
