/* SPDX-License-Identifier: Apache-2.0 */
/* What the files of the DeviceNet slave call in one another, floor by floor from the ground up;
 * a file calls only the floors below its own (dn_node.c, the composition root, is the top). Not
 * installed. */
#ifndef DN_SLAVE_H
#define DN_SLAVE_H

#include "dn/dn_node.h"

#define DN_US_PER_MS 1000u

/* conn[] positions of the predefined set's instances 1, 2 and 4, and of the UCMM's 10-14. */
#define DN_EXPLICIT 0u
#define DN_IO_CONSUMER 1u /* instance 2: polled, or the master's COS/cyclic data */
#define DN_IO_PRODUCER 2u /* instance 4: the slave's COS/cyclic data */
#define DN_UCMM_FIRST 3u  /* instance 10; 11-14 follow */

/* An explicit messaging connection: instance 1 or one the UCMM opened. */
static inline bool dn_is_explicit(unsigned index)
{
    return index == DN_EXPLICIT || index >= DN_UCMM_FIRST;
}

/* The fragmented messages of explicit connection conn[index]. */
static inline dn_messages_t *dn_messages(dn_node_t *node, unsigned index)
{
    return &node->messages[index == DN_EXPLICIT ? 0u : index - DN_UCMM_FIRST + 1u];
}

/* An explicit connection's messages in progress are given up (it ended, or the node restarts). */
static inline void dn_messages_drop(dn_node_t *node, unsigned index)
{
    dn_messages(node, index)->rx.active = false;
    dn_messages(node, index)->tx.active = false;
}

/* Counts one event in the application's dn_stats_t, when it keeps one. */
#define DN_COUNT(node, counter)                                                                    \
    do {                                                                                           \
        dn_stats_t *stats_ = (node)->config->app->stats;                                           \
        if (stats_)                                                                                \
            stats_->counter++;                                                                     \
    } while (0)

/* Whether either I/O connection (instance 2 or 4) is in this state. */
static inline bool dn_io_in_state(const dn_node_t *node, uint8_t state)
{
    return node->conn[DN_IO_CONSUMER].state == state || node->conn[DN_IO_PRODUCER].state == state;
}

/* application.c: what several floors reach of the application (dn_node_assembly is public). */
void dn_send(dn_node_t *node, uint16_t can_id, const uint8_t *data, uint8_t len);
void dn_io_event(dn_node_t *node, dn_io_event_t event);
/* Keeps new stored values through the application, or refuses them (0x19). */
dn_status_t dn_store(dn_node_t *node, const dn_stored_t *stored);

/* connection.c: the predefined connection set and the Connection object's handler. */
void dn_connections_reset(dn_node_t *node);
/* Every connection goes, as at a restart; the Established ones are told with this cause. */
void dn_connections_end(dn_node_t *node, dn_end_cause_t cause);
dn_status_t dn_allocate(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply);
dn_status_t dn_release(dn_node_t *node, const dn_request_t *request);
/* The UCMM's Open Explicit Messaging Connection and Close (group 3 message 6). */
dn_status_t dn_ucmm_open(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply);
dn_status_t dn_ucmm_close(dn_node_t *node, const dn_request_t *request);
/* The Connection instance at a conn[] position. */
uint8_t dn_connection_instance(unsigned index);
/* The conn[] position of an Established UCMM connection consuming this CAN-ID, or -1. */
int dn_ucmm_connection(const dn_node_t *node, uint16_t can_id);
/* A request came on the explicit connection at conn[index]: its watchdog starts again. */
void dn_explicit_activity(dn_node_t *node, unsigned index);
void dn_io_receive(dn_node_t *node, const co_frame_t *frame);
void dn_cos_ack_receive(dn_node_t *node);
co_time_t dn_connections_process(dn_node_t *node);
bool dn_io_consuming(const dn_node_t *node);
dn_status_t dn_connection_handler(dn_node_t *node, const dn_object_t *object,
                                  const dn_request_t *request, dn_reply_t *reply);

/* standard_objects.c: Identity (with dn_node_identity_status, public), Message router,
 * DeviceNet, Assembly, Acknowledge handler, and the Connection object's table. */
const dn_object_t *dn_standard_object(uint8_t class_id);

/* message_router.c: the library's classes and then the application's. */
dn_status_t dn_route(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply);

/* explicit.c: the requests of an explicit connection (conn[index]: instance 1 or 10-14), and of
 * the unconnected ports (group 2 message 6, Allocate/Release; the UCMM, group 3 message 6,
 * Open/Close) from the client of MAC ID `client`. */
void dn_explicit_receive(dn_node_t *node, const co_frame_t *frame, unsigned index);
void dn_unconnected_receive(dn_node_t *node, const co_frame_t *frame, bool ucmm, uint8_t client);
co_time_t dn_explicit_process(dn_node_t *node);

#endif
