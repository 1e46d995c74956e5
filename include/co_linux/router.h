/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime's router: the devices of a loop, which of them consumes which COB-ID (from their
 * nodes' consumed sets, co_consumers.h), the frames one device sent on their way to the others,
 * and the socket's receive filter (CAN_RAW_FILTER) that keeps a frame for nobody from waking the
 * loop. docs/runtime.md, "Routing and the receive filter". */
#ifndef CO_LINUX_ROUTER_H
#define CO_LINUX_ROUTER_H

#include "co_linux/device.h"
#include "co_linux/txq.h"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <stdbool.h>
#include <stddef.h>

/* Routing keys: an 11-bit CAN-ID, plus 2048 for a remote request. */
#define CO_LINUX_ROUTE_KEYS 4096u

/* The socket's receive filter. */
typedef struct co_linux_filter {
    bool applied; /* `entries` is what the current socket has */
    bool stale;   /* the routes, the socket or the trace changed since it was computed */
    size_t count;
    struct can_filter entries[CAN_RAW_FILTER_MAX];
} co_linux_filter_t;

typedef struct co_linux_router {
    const char *iface; /* the bus's name, for the logs */
    co_linux_device_t *devices;
    size_t device_count;
    /* The devices consuming key k are route_devices[route_first[k]] up to
     * route_devices[route_first[k + 1]], in the order they were added. */
    uint32_t route_first[CO_LINUX_ROUTE_KEYS + 1];
    co_linux_device_t **route_devices;
    size_t route_capacity;
    bool routes_stale; /* a node's consumed set changed: rebuild before the next frame */
    bool route_all;    /* every device gets every frame (a device without node, no memory) */
    co_txq_t local;    /* frames sent by one device, waiting for the other local devices */
    co_linux_filter_t filter;
} co_linux_router_t;

/* No device, no route; iface names the bus in the logs. */
void co_linux_router_init(co_linux_router_t *router, const char *iface);
/* Frees the routing table. */
void co_linux_router_close(co_linux_router_t *router);

/* Appends a device; the routes are rebuilt before the next frame. */
void co_linux_router_add(co_linux_router_t *router, co_linux_device_t *device);

/* Runs a device's process function and keeps its deadline; notices a changed consumed set. */
void co_linux_router_process(co_linux_router_t *router, co_linux_device_t *device, co_time_t now);

/* Hands a frame to the devices that consume it, except `origin` (the device that sent it, or
 * NULL), each processed right after; returns how many got it. */
size_t co_linux_router_route(co_linux_router_t *router, const co_frame_t *frame, const void *origin,
                             co_time_t now);

/* Keeps a frame a device sent for the other devices of the loop (the socket does not receive its
 * own frames); co_linux_router_deliver_local hands it over. */
void co_linux_router_share(co_linux_router_t *router, const co_frame_t *frame,
                           const co_linux_device_t *origin);
/* Routes the shared frames, and those their receivers send in turn, until none is left. */
void co_linux_router_deliver_local(co_linux_router_t *router, co_time_t now);

/* The socket is new: its filter is set again. */
void co_linux_router_new_socket(co_linux_router_t *router);
/* Whether the socket must receive the whole bus changed (a trace stopped): the filter is
 * computed again. */
void co_linux_router_refilter(co_linux_router_t *router);

/* Rebuilds stale routes and, on a CAN_RAW socket (fd; -1: none), sets a filter that changed;
 * whole_bus: a trace shows every frame. True when a filter was set. */
bool co_linux_router_update(co_linux_router_t *router, int fd, bool whole_bus);

#endif
