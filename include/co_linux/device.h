/* SPDX-License-Identifier: Apache-2.0 */
/* A device of the runtime: anything built on the portable core (a co_node_t, a drive wrapping
 * one) that the loop starts, hands frames to, processes at its deadline and tells of bus
 * conditions, through the operations it gives (co_linux/loop.h attaches it). */
#ifndef CO_LINUX_DEVICE_H
#define CO_LINUX_DEVICE_H

#include "co/co_consumers.h"
#include "co/co_types.h"

#include <stdbool.h>
#include <stdint.h>

struct co_node;
typedef struct co_linux_loop co_linux_loop_t;

/* The most CAN-IDs one device consumes: a core node's (CO_CONSUMERS_MAX), or a DeviceNet card's,
 * which takes group 3 from every source MAC ID (the UCMM and its connections: 6 x 64 IDs). */
#define CO_LINUX_DEVICE_CONSUMERS_MAX 512u
_Static_assert(CO_CONSUMERS_MAX <= CO_LINUX_DEVICE_CONSUMERS_MAX,
               "a node's CAN-IDs fit a device's");

/* What the loop calls on a device; ctx is the device's own object. Only bus_event and
 * bus_warning may be NULL. */
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
    /* The controller reached (active) or left its error warning level, which has no EMCY: a
     * device shows it on an indicator (CiA 303-3's ERR single flash). */
    void (*bus_warning)(void *ctx, bool active);
    /* The device's core node, which must stay the same: frames reach the device only when the
     * node consumes their COB-ID (co_consumers.h). NULL: the device gets every frame, and the
     * socket then receives the whole bus, unless `consumers` names what the device takes. */
    const struct co_node *(*node)(void *ctx);
    /* A device that is no core node (a DeviceNet card): fills cobs (at most
     * CO_LINUX_DEVICE_CONSUMERS_MAX) with the CAN-IDs it consumes, which never change, and returns
     * their number; frames reach it only on those. Used when `node` is NULL; both NULL: every
     * frame. */
    size_t (*consumers)(void *ctx, co_cob_t *cobs);
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

#endif
