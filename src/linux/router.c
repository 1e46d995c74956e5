/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/router.h"
#include "co/co_consumers.h"
#include "co/co_node.h"
#include "co_linux/log.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

/* Routing key of a remote request: the CAN-ID plus this. */
#define ROUTE_KEY_RTR 0x800u

void co_linux_router_init(co_linux_router_t *router, const char *iface)
{
    memset(router, 0, sizeof *router);
    router->iface = iface;
    co_txq_init(&router->local, CO_TXQ_MAX);
}

void co_linux_router_close(co_linux_router_t *router)
{
    free(router->route_devices);
    router->route_devices = NULL;
    router->route_capacity = 0;
}

void co_linux_router_add(co_linux_router_t *router, co_linux_device_t *device)
{
    router->routes_stale = true;
    co_linux_device_t **tail = &router->devices;
    while (*tail)
        tail = &(*tail)->next;
    *tail = device;
    router->device_count++;
}

static const co_node_t *device_node(const co_linux_device_t *dev)
{
    return dev->ops->node(dev->ctx);
}

/* Every call into a device ends here, so this is where a changed consumer set is noticed: the
 * routes are rebuilt before the next frame is routed. */
void co_linux_router_process(co_linux_router_t *router, co_linux_device_t *device, co_time_t now)
{
    device->deadline = device->ops->process(device->ctx, now);
    if (device->ops->node != NULL &&
        co_node_consumer_generation(device_node(device)) != device->generation)
        router->routes_stale = true;
}

static size_t route_key(uint16_t can_id, bool rtr)
{
    return can_id | (rtr ? ROUTE_KEY_RTR : 0u);
}

/* Room for `count` routes; false (logged) when memory is short, and every device then gets
 * every frame as before routing. */
static bool reserve_routes(co_linux_router_t *router, size_t count)
{
    if (count <= router->route_capacity)
        return true;
    co_linux_device_t **routes = realloc(router->route_devices, count * sizeof *routes);
    if (routes == NULL) {
        co_log(CO_LOG_ERROR, "routing table of %zu entries: out of memory: no routing", count);
        return false;
    }
    router->route_devices = routes;
    router->route_capacity = count;
    return true;
}

/* The COB-IDs a device consumes now: its core node's (and their generation), or the fixed ones
 * it names; false, and none, for a device that takes every frame. */
static bool device_consumers(co_linux_device_t *dev, co_cob_t *cobs, size_t *count)
{
    *count = 0;
    if (dev->ops->node != NULL) {
        const co_node_t *node = device_node(dev);
        dev->generation = co_node_consumer_generation(node);
        *count = co_node_consumers(node, cobs);
        return true;
    }
    if (dev->ops->consumers != NULL) {
        *count = dev->ops->consumers(dev->ctx, cobs);
        return true;
    }
    return false;
}

/* A counting sort of the (COB-ID, device) pairs by key: one pass counts each key's consumers, a
 * prefix sum gives each key its range, a second pass fills the ranges in device order. Runs when
 * a consumed set changed, never per frame. */
static void build_routes(co_linux_router_t *router)
{
    uint32_t cursor[CO_LINUX_ROUTE_KEYS];
    co_cob_t cobs[CO_LINUX_DEVICE_CONSUMERS_MAX];
    size_t count;
    router->routes_stale = false;
    router->filter.stale = true;
    router->route_all = false;
    memset(router->route_first, 0, sizeof router->route_first);
    for (co_linux_device_t *dev = router->devices; dev; dev = dev->next) {
        if (!device_consumers(dev, cobs, &count)) {
            router->route_all = true;
            continue;
        }
        for (size_t i = 0; i < count; i++)
            router->route_first[route_key(cobs[i].can_id, cobs[i].rtr) + 1]++;
    }
    for (size_t k = 0; k < CO_LINUX_ROUTE_KEYS; k++)
        router->route_first[k + 1] += router->route_first[k];
    if (router->route_all || !reserve_routes(router, router->route_first[CO_LINUX_ROUTE_KEYS])) {
        router->route_all = true;
        return;
    }
    memcpy(cursor, router->route_first, sizeof cursor);
    for (co_linux_device_t *dev = router->devices; dev; dev = dev->next) {
        device_consumers(dev, cobs, &count);
        for (size_t i = 0; i < count; i++)
            router->route_devices[cursor[route_key(cobs[i].can_id, cobs[i].rtr)]++] = dev;
    }
}

/* One frame to one device, and its process right after, as co_node_process requires; false
 * for the device that sent the frame. */
static bool deliver(co_linux_router_t *router, co_linux_device_t *dev, const co_frame_t *frame,
                    const void *origin, co_time_t now)
{
    if (dev == origin)
        return false;
    dev->stats.rx++;
    dev->ops->receive(dev->ctx, frame, now);
    co_linux_router_process(router, dev, now);
    return true;
}

size_t co_linux_router_route(co_linux_router_t *router, const co_frame_t *frame, const void *origin,
                             co_time_t now)
{
    if (router->routes_stale)
        build_routes(router);
    size_t delivered = 0;
    if (router->route_all) {
        for (co_linux_device_t *dev = router->devices; dev; dev = dev->next)
            delivered += deliver(router, dev, frame, origin, now);
        return delivered;
    }
    /* The core ignores 29-bit frames: no node consumes them. */
    if (frame->flags & CO_FRAME_EFF)
        return 0;
    size_t key = route_key((uint16_t)frame->id, (frame->flags & CO_FRAME_RTR) != 0);
    for (uint32_t i = router->route_first[key]; i < router->route_first[key + 1]; i++)
        delivered += deliver(router, router->route_devices[i], frame, origin, now);
    return delivered;
}

void co_linux_router_share(co_linux_router_t *router, const co_frame_t *frame,
                           const co_linux_device_t *origin)
{
    if (router->device_count > 1 && !co_txq_push(&router->local, frame, origin))
        co_log(CO_LOG_WARN, "%s: local delivery queue full: frame %03X not seen by local devices",
               router->iface, (unsigned)frame->id);
}

void co_linux_router_deliver_local(co_linux_router_t *router, co_time_t now)
{
    const co_txq_entry_t *e;
    while ((e = co_txq_peek(&router->local)) != NULL) {
        co_txq_entry_t entry = *e;
        co_txq_pop(&router->local);
        co_linux_router_route(router, &entry.frame, entry.origin, now);
    }
}

void co_linux_router_new_socket(co_linux_router_t *router)
{
    router->filter.applied = false;
    router->filter.stale = true;
}

void co_linux_router_refilter(co_linux_router_t *router)
{
    router->filter.stale = true;
}

/* The socket's receive filter: one exact entry (CAN-ID, data or remote, 11-bit) per routed key.
 * The whole bus when a trace is written (it shows every frame, as candump would) or a device
 * takes every frame; every 11-bit frame when the keys are more than the kernel accepts
 * (CAN_RAW_FILTER_MAX): the routes still sort them. Returns the number of entries. */
static size_t wanted_filter(const co_linux_router_t *router, bool whole_bus,
                            struct can_filter *wanted)
{
    if (router->route_all || whole_bus) {
        wanted[0] = (struct can_filter){.can_id = 0, .can_mask = 0};
        return 1;
    }
    size_t count = 0;
    for (size_t k = 0; k < CO_LINUX_ROUTE_KEYS; k++) {
        if (router->route_first[k] == router->route_first[k + 1])
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

static bool set_filter(int fd, const struct can_filter *filter, size_t count)
{
    return setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filter,
                      (socklen_t)(count * sizeof filter[0])) == 0;
}

/* Computed when the routes, the socket or the trace changed; set only when it differs from what
 * this socket has. True when it was set. */
static bool apply_filter(co_linux_router_t *router, int fd, bool whole_bus)
{
    co_linux_filter_t *filter = &router->filter;
    struct can_filter wanted[CAN_RAW_FILTER_MAX];
    size_t count = wanted_filter(router, whole_bus, wanted);
    filter->stale = false;
    if (filter->applied && count == filter->count &&
        memcmp(wanted, filter->entries, count * sizeof wanted[0]) == 0)
        return false;
    if (!set_filter(fd, wanted, count)) {
        /* A filter that may hide frames a node now consumes is worse than none. */
        co_log(CO_LOG_ERROR, "%s: CAN_RAW_FILTER of %zu entries: %s: receiving the whole bus",
               router->iface, count, strerror(errno));
        wanted[0] = (struct can_filter){.can_id = 0, .can_mask = 0};
        count = 1;
        if (!set_filter(fd, wanted, count)) {
            filter->applied = false;
            return false;
        }
    }
    memcpy(filter->entries, wanted, count * sizeof wanted[0]);
    filter->count = count;
    filter->applied = true;
    return true;
}

bool co_linux_router_update(co_linux_router_t *router, int fd, bool whole_bus)
{
    if (router->routes_stale)
        build_routes(router);
    return router->filter.stale && fd >= 0 && apply_filter(router, fd, whole_bus);
}
