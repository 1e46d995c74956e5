/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime's composition root: the event loop, the CAN bus and the router put together, and
 * what a wake-up owes the devices after its handlers ran (co_linux/loop.h). */
#include "co_linux/loop.h"
#include "co/co_node.h"
#include "co_linux/log.h"

#include <errno.h>
#include <string.h>
#include <sysexits.h>
#include <time.h>

/* Ready descriptors taken per epoll_wait. */
#define EVENTS_PER_WAIT 8

co_time_t co_linux_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (co_time_t)ts.tv_sec * 1000000u + (co_time_t)ts.tv_nsec / 1000u;
}

static void process(co_linux_loop_t *loop, co_linux_device_t *dev)
{
    co_linux_router_process(&loop->router, dev, loop->now);
}

void co_linux_device_send(void *device, const co_frame_t *frame)
{
    co_linux_device_t *dev = device;
    co_linux_loop_t *loop = dev->loop;
    dev->stats.tx++;
    if (!co_linux_bus_send(&loop->bus, frame, dev)) {
        dev->stats.tx_dropped++;
        return;
    }
    /* The socket does not receive its own frames (CAN_RAW_RECV_OWN_MSGS is off), so the other
     * devices of this loop get them from here, after the current call returns. */
    co_linux_router_share(&loop->router, frame, dev);
}

void co_linux_device_process(co_linux_device_t *device)
{
    process(device->loop, device);
}

static void bus_received(void *ctx, const co_frame_t *frame)
{
    co_linux_loop_t *loop = ctx;
    if (co_linux_router_route(&loop->router, frame, NULL, loop->now) == 0)
        loop->stats.unrouted++;
    co_linux_router_deliver_local(&loop->router, loop->now);
}

static void bus_came_up(void *ctx)
{
    co_linux_loop_t *loop = ctx;
    co_linux_router_new_socket(&loop->router);
    co_log(CO_LOG_INFO, "interface %s is up: restarting communication of %zu device(s)",
           loop->iface, loop->router.device_count);
    for (co_linux_device_t *dev = loop->router.devices; dev; dev = dev->next) {
        dev->ops->restart(dev->ctx, loop->now);
        process(loop, dev);
    }
}

static void timer_fired(void *ctx, uint32_t events)
{
    co_linux_loop_t *loop = ctx;
    (void)events;
    co_linux_bus_retry(&loop->bus);
    for (co_linux_device_t *dev = loop->router.devices; dev; dev = dev->next) {
        if (dev->deadline <= loop->now)
            process(loop, dev);
    }
}

static void tell_device(co_linux_loop_t *loop, co_linux_device_t *dev,
                        const co_linux_condition_t *condition)
{
    if (condition->emcy_code == CO_LINUX_EMCY_NONE) {
        if (dev->ops->bus_warning)
            dev->ops->bus_warning(dev->ctx, condition->wanted);
        return;
    }
    if (dev->ops->bus_event) {
        dev->ops->bus_event(dev->ctx, condition->emcy_code, condition->wanted);
        process(loop, dev);
    }
}

static void tell_devices(co_linux_loop_t *loop, const co_linux_condition_t *condition)
{
    for (co_linux_device_t *dev = loop->router.devices; dev; dev = dev->next)
        tell_device(loop, dev, condition);
}

/* Returns true when a device was told something (it may have sent frames, or a dropped frame may
 * have raised another condition). */
static bool report_conditions(co_linux_loop_t *loop)
{
    co_linux_conditions_t *conditions = &loop->bus.conditions;
    const co_txq_t *queue = &loop->bus.tx.queue;
    bool reported = false;
    co_linux_conditions_end_overrun(conditions, loop->iface, co_txq_count(queue));
    for (int i = 0; i < CO_LINUX_CONDITIONS; i++) {
        if (!co_linux_conditions_take(conditions, i, co_txq_count(queue), queue->capacity))
            continue;
        reported = true;
        tell_devices(loop, &conditions->items[i]);
    }
    return reported;
}

static void arm_timer(co_linux_loop_t *loop)
{
    co_time_t next = co_linux_bus_deadline(&loop->bus);
    for (co_linux_device_t *dev = loop->router.devices; dev; dev = dev->next)
        next = co_time_min(next, dev->deadline);
    co_linux_events_arm(&loop->events, next, loop->now);
}

/* The routes and the filter follow a changed consumer set before the frames of the wake-up
 * leave: a master that reacts to the SDO reply of a COB-ID write finds the filter updated. */
static void update_routes(co_linux_loop_t *loop)
{
    int filtered_fd = loop->bus.kernel_filter ? loop->bus.can_fd : -1;
    if (co_linux_router_update(&loop->router, filtered_fd, loop->bus.trace != NULL))
        loop->stats.filters++;
}

static void deliver_and_transmit(co_linux_loop_t *loop)
{
    co_linux_router_deliver_local(&loop->router, loop->now);
    update_routes(loop);
    co_linux_bus_transmit(&loop->bus);
}

/* After every wake-up: everything the handlers caused is delivered, reported and timed. */
static void settle(co_linux_loop_t *loop)
{
    deliver_and_transmit(loop);
    /* Bounded: each condition can change at most once per round. */
    for (int round = 0; round < CO_LINUX_CONDITIONS && report_conditions(loop); round++)
        deliver_and_transmit(loop);
    arm_timer(loop);
    if (!co_linux_bus_flush_trace(&loop->bus))
        co_linux_router_refilter(&loop->router); /* the socket no longer needs the whole bus */
    if (loop->settled)
        loop->settled(loop->settled_ctx, loop);
}

void co_linux_loop_on_settled(co_linux_loop_t *loop, co_linux_settled_fn fn, void *ctx)
{
    loop->settled = fn;
    loop->settled_ctx = ctx;
}

bool co_linux_loop_sent_all(const co_linux_loop_t *loop)
{
    return loop->bus.link_up && co_txq_count(&loop->bus.tx.queue) == 0;
}

static void update_clocks(co_linux_loop_t *loop)
{
    loop->now = co_linux_now();
    co_linux_bus_wake(&loop->bus, loop->now);
}

static void run_watch(void *ctx, uint32_t events)
{
    const co_linux_watch_t *watch = ctx;
    (void)events;
    watch->fn(watch->ctx, watch->fd);
}

int co_linux_loop_watch(co_linux_loop_t *loop, int fd, co_linux_watch_fn fn, void *ctx)
{
    for (int slot = 0; slot < CO_LINUX_WATCH_MAX; slot++) {
        co_linux_watch_t *watch = &loop->watches[slot];
        if (watch->fd >= 0)
            continue;
        if (co_linux_events_add(&loop->events, fd, EPOLLIN, run_watch, watch) != 0)
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
            co_linux_events_remove(&loop->events, fd);
            loop->watches[slot].fd = -1;
        }
    }
}

int co_linux_loop_run(co_linux_loop_t *loop)
{
    loop->events.running = true;
    update_clocks(loop);
    for (co_linux_device_t *dev = loop->router.devices; dev; dev = dev->next) {
        dev->ops->start(dev->ctx, loop->now);
        process(loop, dev);
    }
    settle(loop);
    while (loop->events.running) {
        struct epoll_event fired[EVENTS_PER_WAIT];
        int n = co_linux_events_wait(&loop->events, fired, EVENTS_PER_WAIT);
        if (n < 0)
            return EX_OSERR;
        loop->stats.wakeups++;
        update_clocks(loop);
        co_linux_events_dispatch(&loop->events, fired, n);
        settle(loop);
    }
    return loop->events.exit_status;
}

void co_linux_loop_stop(co_linux_loop_t *loop, int status)
{
    co_linux_events_stop(&loop->events, status);
}

void co_linux_loop_add(co_linux_loop_t *loop, co_linux_device_t *device,
                       const co_linux_device_ops_t *ops, void *ctx)
{
    *device = (co_linux_device_t){.ops = ops, .ctx = ctx, .loop = loop, .deadline = CO_TIME_NEVER};
    co_linux_router_add(&loop->router, device);
}

static void init_loop(co_linux_loop_t *loop, const co_linux_loop_config_t *config)
{
    memset(loop, 0, sizeof *loop);
    snprintf(loop->iface, sizeof loop->iface, "%s", config->iface);
    for (int slot = 0; slot < CO_LINUX_WATCH_MAX; slot++)
        loop->watches[slot].fd = -1;
    co_linux_events_init(&loop->events);
    co_linux_bus_host_t host = {.events = &loop->events,
                                .stats = &loop->stats,
                                .received = bus_received,
                                .came_up = bus_came_up,
                                .ctx = loop};
    co_linux_bus_init(&loop->bus, &host, loop->iface, config->trace, config->txq_capacity);
    co_linux_router_init(&loop->router, loop->iface);
}

/* Keeps what failed for the program's message and closes what was opened. */
static co_linux_open_result_t open_failed(co_linux_loop_t *loop, co_linux_open_result_t result,
                                          const char *call)
{
    loop->open_call = call;
    loop->open_errno = errno;
    co_linux_loop_close(loop);
    return result;
}

co_linux_open_result_t co_linux_loop_open(co_linux_loop_t *loop,
                                          const co_linux_loop_config_t *config)
{
    init_loop(loop, config);
    const char *call = co_linux_events_open(&loop->events, timer_fired, loop);
    if (call != NULL)
        return open_failed(loop, CO_LINUX_OPEN_OS_ERROR, call);
    co_linux_open_result_t result = co_linux_bus_open(&loop->bus, &call);
    if (result != CO_LINUX_OPEN_OK)
        return open_failed(loop, result, call);
    co_linux_router_new_socket(&loop->router);
    return CO_LINUX_OPEN_OK;
}

co_linux_open_result_t co_linux_loop_open_fd(co_linux_loop_t *loop,
                                             const co_linux_loop_config_t *config, int fd)
{
    init_loop(loop, config);
    bool can_raw = false;
    if (!co_linux_bus_keeps_frames(fd, &can_raw))
        return open_failed(loop, CO_LINUX_OPEN_OS_ERROR, "getsockopt(SO_TYPE)");
    const char *call = co_linux_events_open(&loop->events, timer_fired, loop);
    if (call == NULL && co_linux_bus_open_fd(&loop->bus, fd, can_raw, &call) == CO_LINUX_OPEN_OK) {
        co_linux_router_new_socket(&loop->router);
        return CO_LINUX_OPEN_OK;
    }
    return open_failed(loop, CO_LINUX_OPEN_OS_ERROR, call);
}

void co_linux_loop_close(co_linux_loop_t *loop)
{
    co_linux_bus_close(&loop->bus);
    co_linux_events_close(&loop->events);
    co_linux_router_close(&loop->router);
}
