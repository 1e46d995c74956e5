/* SPDX-License-Identifier: Apache-2.0 */
/* The predefined master/slave connection set: Allocate and Release, the Connection object's
 * instances 1 (explicit), 2 (polled, or the master's COS/cyclic data) and 4 (the slave's
 * COS/cyclic data) with their states and watchdogs, the I/O messages and the acknowledge
 * handler's retries; and the UCMM's explicit server instances 10-14, opened and closed on
 * group 3 (docs/decisions.md, D-DEVICENET-UCMM). */
#include <string.h>

#include "devicenet/slave/dn_slave.h"

#define CONNECTION_REVISION 1u /* the Connection class's revision (class attribute 1) */

/* The manual's default expected packet rate of the explicit connection, 0x09C8: 2500 ms rounded
 * up to the 8 ms resolution of the card's timers, which every rate written is rounded to. */
#define EXPLICIT_EPR_DEFAULT_MS 2504u
#define TIMER_RESOLUTION_MS 8u
#define EPR_MAX_MS 65528u /* the largest multiple of the resolution in a UINT */

#define ACK_TIMER_DEFAULT_MS 16u
#define RETRY_LIMIT_DEFAULT 1u
#define NO_CONNECTION_ID 0xFFFFu
#define MULTIPLIER_MAX 7u /* x512 */

/* Transport class and trigger (attribute 3) and initial communication characteristics (6). */
#define TRANSPORT_EXPLICIT_SERVER 0x83u
#define TRANSPORT_SERVER_CLASS2 0x82u /* polled, or the master's acknowledged COS/cyclic */
#define TRANSPORT_SERVER_CLASS0 0x80u /* the master's COS/cyclic without acknowledge */
#define TRANSPORT_COS 0x10u
#define TRANSPORT_CLASS2 0x02u
#define COMM_EXPLICIT 0x21u      /* produces and consumes over group 2 */
#define COMM_GROUP3 0x33u        /* the UCMM's: produces and consumes over group 3 */
#define COMM_G1_PRODUCE_G2 0x01u /* produces over group 1, consumes over group 2 */
#define COMM_G2_CONSUME_ONLY 0xF1u
#define COMM_G1_PRODUCE_ONLY 0x0Fu

#define CONNECTIONS (DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED | DN_ALLOC_COS | DN_ALLOC_CYCLIC)
#define IO_CONNECTIONS (DN_ALLOC_POLLED | DN_ALLOC_COS | DN_ALLOC_CYCLIC)
#define SUPPORTED_CHOICE (CONNECTIONS | DN_ALLOC_ACK_SUPPRESSION)

#define CONN_ATTR_STATE 1u
#define CONN_ATTR_EPR 9u
#define CONN_ATTR_TIMEOUT_ACTION 12u
#define CONN_ATTR_INHIBIT 17u
#define CONN_ATTR_MULTIPLIER 18u
#define CONN_CLASS_CONSUMED_ASSEMBLY 100u
#define CONN_CLASS_PRODUCED_ASSEMBLY 101u

static void clear(dn_connection_t *c)
{
    memset(c, 0, sizeof(*c));
    c->state = DN_CONN_NON_EXISTENT;
    c->produced_id = NO_CONNECTION_ID;
    c->consumed_id = NO_CONNECTION_ID;
    c->watchdog = CO_TIME_NEVER;
}

/* The instance at each conn[] position; the order in which the ends of several are told. */
static const uint8_t instance_of[DN_CONN_COUNT] = {
    DN_CONN_EXPLICIT, DN_CONN_POLL, DN_CONN_COS_CYCLIC, 10, 11, 12, 13, 14};
static const unsigned end_order[DN_CONN_COUNT] = {
    DN_IO_CONSUMER, DN_IO_PRODUCER, DN_EXPLICIT, 3, 4, 5, 6, 7};

uint8_t dn_connection_instance(unsigned index)
{
    return instance_of[index];
}

static void tell_ended(dn_node_t *node, unsigned index, dn_end_cause_t cause)
{
    const dn_app_t *app = node->config->app;
    if (app->connection_ended)
        app->connection_ended(app->user, instance_of[index], cause);
}

static void record_states(const dn_node_t *node, uint8_t states[DN_CONN_COUNT])
{
    for (unsigned i = 0; i < DN_CONN_COUNT; i++)
        states[i] = node->conn[i].state;
}

/* Each connection that was Established and no longer is ended now: the application is told, the
 * I/O connections first, so that it judges the explicit one knowing what is left. */
static void tell_ended_since(dn_node_t *node, const uint8_t before[DN_CONN_COUNT],
                             dn_end_cause_t cause)
{
    for (unsigned i = 0; i < DN_CONN_COUNT; i++) {
        unsigned index = end_order[i];
        if (before[index] == DN_CONN_ESTABLISHED && node->conn[index].state != DN_CONN_ESTABLISHED)
            tell_ended(node, index, cause);
    }
}

void dn_connections_reset(dn_node_t *node)
{
    for (unsigned i = 0; i < DN_CONN_COUNT; i++)
        clear(&node->conn[i]);
    node->allocation = 0;
    node->master_mac = DN_MAC_ID_NONE;
    node->ack_timer = ACK_TIMER_DEFAULT_MS;
    node->retry_limit = RETRY_LIMIT_DEFAULT;
    node->awaiting_ack = false;
    node->produce_deadline = CO_TIME_NEVER;
    node->idle = true;
    for (unsigned i = 0; i < DN_EXPLICIT_COUNT; i++)
        node->messages[i].rx.active = node->messages[i].tx.active = false;
}

void dn_connections_end(dn_node_t *node, dn_end_cause_t cause)
{
    uint8_t before[DN_CONN_COUNT];
    record_states(node, before);
    dn_connections_reset(node);
    tell_ended_since(node, before, cause);
}

/* The conn[] position of instance 1, 2 or 4, or -1. */
static int conn_index(uint8_t instance)
{
    for (unsigned i = 0; i < DN_CONN_COUNT; i++)
        if (instance_of[i] == instance)
            return (int)i;
    return -1;
}

uint8_t dn_node_connection_state(const dn_node_t *node, uint8_t instance)
{
    int index = conn_index(instance);
    return index < 0 ? DN_CONN_NON_EXISTENT : node->conn[index].state;
}

/* Inactivity: the expected packet rate times the multiplier (x4 << attribute 18); none at 0. */
static void kick(dn_node_t *node, dn_connection_t *c)
{
    c->watchdog = c->expected_packet_rate ? node->now + (co_time_t)c->expected_packet_rate *
                                                            DN_US_PER_MS * (4u << c->multiplier)
                                          : CO_TIME_NEVER;
}

static bool acknowledged(const dn_node_t *node)
{
    return !(node->allocation & DN_ALLOC_ACK_SUPPRESSION);
}

static void open_explicit(dn_node_t *node)
{
    dn_connection_t *c = &node->conn[DN_EXPLICIT];
    clear(c);
    c->state = DN_CONN_ESTABLISHED;
    c->transport = TRANSPORT_EXPLICIT_SERVER;
    c->comm = COMM_EXPLICIT;
    c->produced_id = node->ids.explicit_response;
    c->consumed_id = node->ids.explicit_request;
    c->produced_size = DN_MESSAGE_MAX;
    c->consumed_size = DN_MESSAGE_MAX;
    c->expected_packet_rate = EXPLICIT_EPR_DEFAULT_MS;
    c->timeout_action = DN_WATCHDOG_AUTO_DELETE;
    kick(node, c);
}

/* Instance 2: the poll command and its response, or, with COS/cyclic and no poll, the master's
 * COS/cyclic data and the slave's acknowledgements. */
static void open_consumer(dn_node_t *node)
{
    dn_connection_t *c = &node->conn[DN_IO_CONSUMER];
    clear(c);
    c->state = DN_CONN_CONFIGURING;
    c->consumed_id = node->ids.poll_command;
    c->consumed_size = node->consumed_size;
    if (node->allocation & DN_ALLOC_POLLED) {
        c->transport = TRANSPORT_SERVER_CLASS2;
        c->comm = COMM_G1_PRODUCE_G2;
        c->produced_id = node->ids.poll_response;
        c->produced_size = node->produced_size;
    } else if (acknowledged(node)) {
        c->transport = TRANSPORT_SERVER_CLASS2;
        c->comm = COMM_G1_PRODUCE_G2;
        c->produced_id = node->ids.poll_response;
    } else {
        c->transport = TRANSPORT_SERVER_CLASS0;
        c->comm = COMM_G2_CONSUME_ONLY;
    }
}

/* Instance 4: the slave's COS or cyclic data, acknowledged by the master unless suppressed. */
static void open_producer(dn_node_t *node)
{
    dn_connection_t *c = &node->conn[DN_IO_PRODUCER];
    clear(c);
    c->state = DN_CONN_CONFIGURING;
    c->transport = node->allocation & DN_ALLOC_COS ? TRANSPORT_COS : 0;
    c->comm = COMM_G1_PRODUCE_ONLY;
    c->produced_id = node->ids.cos_cyclic;
    c->produced_size = node->produced_size;
    if (acknowledged(node)) {
        c->transport |= TRANSPORT_CLASS2;
        c->comm = COMM_G1_PRODUCE_G2;
        c->consumed_id = node->ids.cos_ack;
    }
    node->awaiting_ack = false;
}

static bool io_allocated(const dn_node_t *node)
{
    return node->allocation & IO_CONNECTIONS;
}

/* Nothing allocated any more: the set has no master. */
static void drop_owner_if_unused(dn_node_t *node)
{
    if (!(node->allocation & CONNECTIONS)) {
        node->allocation = 0;
        node->master_mac = DN_MAC_ID_NONE;
    }
}

/* An explicit connection goes: its fragmented messages with it; instance 1 leaves the
 * allocation. */
static void delete_explicit(dn_node_t *node, unsigned index)
{
    clear(&node->conn[index]);
    dn_messages_drop(node, index);
    if (index != DN_EXPLICIT)
        return;
    node->allocation &= (uint8_t)~DN_ALLOC_EXPLICIT;
    drop_owner_if_unused(node);
}

/* The allocation choice: supported bits only, at least one connection, not COS and cyclic
 * together, acknowledge suppression only with COS/cyclic, none already allocated. */
static bool choice_valid(uint8_t choice, uint8_t allocated)
{
    uint8_t all = choice | allocated;
    return !(choice & ~SUPPORTED_CHOICE) && (choice & CONNECTIONS) &&
           !((all & DN_ALLOC_COS) && (all & DN_ALLOC_CYCLIC)) &&
           (!(choice & DN_ALLOC_ACK_SUPPRESSION) || (choice & (DN_ALLOC_COS | DN_ALLOC_CYCLIC))) &&
           !(choice & allocated & CONNECTIONS);
}

dn_status_t dn_allocate(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply)
{
    if (request->len < 2)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (request->len > 2)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    uint8_t choice = request->data[0];
    uint8_t allocator = request->data[1];
    if (allocator > DN_MAC_ID_MAX)
        return DN_ERROR(DN_GS_INVALID_PARAMETER);
    if (node->master_mac != DN_MAC_ID_NONE && node->master_mac != allocator)
        return DN_STATUS(DN_GS_OBJECT_STATE_CONFLICT, DN_AC_ALLOCATION_CONFLICT);
    if (!choice_valid(choice, node->allocation))
        return DN_STATUS(DN_GS_INVALID_PARAMETER, DN_AC_INVALID_CHOICE);
    node->allocation |= choice;
    node->master_mac = allocator;
    if (choice & DN_ALLOC_EXPLICIT)
        open_explicit(node);
    if (choice & (DN_ALLOC_COS | DN_ALLOC_CYCLIC))
        open_producer(node);
    if (choice & IO_CONNECTIONS &&
        (choice & DN_ALLOC_POLLED || node->conn[DN_IO_CONSUMER].state == DN_CONN_NON_EXISTENT))
        open_consumer(node);
    dn_reply_u8(reply, 0); /* message body format: DeviceNet 8/8 */
    return DN_OK;
}

dn_status_t dn_release(dn_node_t *node, const dn_request_t *request)
{
    if (request->len < 1)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (request->len > 1)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    uint8_t choice = request->data[0];
    if (node->master_mac != DN_MAC_ID_NONE && node->master_mac != request->master_mac)
        return DN_STATUS(DN_GS_OBJECT_STATE_CONFLICT, DN_AC_ALLOCATION_CONFLICT);
    if (choice & ~SUPPORTED_CHOICE)
        return DN_STATUS(DN_GS_INVALID_PARAMETER, DN_AC_INVALID_CHOICE);
    bool had_io = io_allocated(node);
    uint8_t states[DN_CONN_COUNT];
    record_states(node, states);
    uint8_t before = node->allocation;
    uint8_t remaining = (uint8_t)(before & ~choice);
    if (!(remaining & (DN_ALLOC_COS | DN_ALLOC_CYCLIC)))
        remaining &= (uint8_t)~DN_ALLOC_ACK_SUPPRESSION;
    node->allocation = remaining;
    if (!(remaining & (DN_ALLOC_COS | DN_ALLOC_CYCLIC))) {
        clear(&node->conn[DN_IO_PRODUCER]);
        node->awaiting_ack = false;
    }
    if (!(remaining & IO_CONNECTIONS))
        clear(&node->conn[DN_IO_CONSUMER]);
    else if (before & DN_ALLOC_POLLED && !(remaining & DN_ALLOC_POLLED))
        open_consumer(node); /* instance 2 goes on consuming the master's COS/cyclic data */
    if (before & choice & DN_ALLOC_EXPLICIT)
        delete_explicit(node, DN_EXPLICIT);
    tell_ended_since(node, states, DN_END_RELEASED);
    if (had_io && !io_allocated(node)) {
        if (node->conn[DN_EXPLICIT].state == DN_CONN_DEFERRED_DELETE)
            delete_explicit(node, DN_EXPLICIT);
        dn_io_event(node, DN_IO_RELEASED);
    }
    drop_owner_if_unused(node);
    return DN_OK;
}

bool dn_io_consuming(const dn_node_t *node)
{
    return node->conn[DN_IO_CONSUMER].state != DN_CONN_NON_EXISTENT;
}

void dn_explicit_activity(dn_node_t *node, unsigned index)
{
    kick(node, &node->conn[index]);
}

/* ---- The UCMM's explicit server connections, instances 10-14 ---- */

/* conn[index] as the manual's table of instances 10-14 has it: a transport class 3 server
 * producing with the server's message ID (instance 10 + n uses n, 0..4, so that no two of its
 * connections share a CAN-ID) and consuming the client's, 64 bytes each way, the expected packet
 * rate of instance 1 (2504 ms, a watchdog of 10 s) and auto delete. */
static void open_ucmm(dn_node_t *node, unsigned index, uint8_t client, uint16_t consumed_id)
{
    dn_connection_t *c = &node->conn[index];
    clear(c);
    c->state = DN_CONN_ESTABLISHED;
    c->transport = TRANSPORT_EXPLICIT_SERVER;
    c->comm = COMM_GROUP3;
    c->produced_id = dn_group3_id((uint8_t)(index - DN_UCMM_FIRST), node->config->mac_id);
    c->consumed_id = consumed_id;
    c->produced_size = DN_MESSAGE_MAX;
    c->consumed_size = DN_MESSAGE_MAX;
    c->expected_packet_rate = EXPLICIT_EPR_DEFAULT_MS;
    c->timeout_action = DN_WATCHDOG_AUTO_DELETE;
    c->client_mac = client;
    kick(node, c);
}

int dn_ucmm_connection(const dn_node_t *node, uint16_t can_id)
{
    for (unsigned i = DN_UCMM_FIRST; i < DN_CONN_COUNT; i++)
        if (node->conn[i].state == DN_CONN_ESTABLISHED && node->conn[i].consumed_id == can_id)
            return (int)i;
    return -1;
}

/* Open: group 3 only (the manual's Initial Comm Characteristics 33 for 10-14), the client's
 * source message ID one of group 3's connected IDs 0..4, the body format 8/8 whatever was asked
 * (the response names the one in use). A request that names a connection open already (the
 * same client and message ID: its response was lost and the client asks again) is answered with
 * that connection, not a second one; a sixth connection is 0x02 resource unavailable. */
dn_status_t dn_ucmm_open(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply)
{
    if (request->len < 2)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (request->len > 2)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    uint8_t group = request->data[1] >> DN_UCMM_GROUP_SHIFT;
    uint8_t client_message = request->data[1] & DN_UCMM_MESSAGE_ID;
    if (group != DN_UCMM_GROUP_3 || client_message > DN_G3_CONNECTED_LAST)
        return DN_ERROR(DN_GS_INVALID_PARAMETER);
    uint16_t consumed_id = dn_group3_id(client_message, request->master_mac);
    int index = dn_ucmm_connection(node, consumed_id);
    if (index >= 0) {
        kick(node, &node->conn[index]);
    } else {
        for (unsigned i = DN_UCMM_FIRST; i < DN_CONN_COUNT && index < 0; i++)
            if (node->conn[i].state == DN_CONN_NON_EXISTENT)
                index = (int)i;
        if (index < 0)
            return DN_ERROR(DN_GS_RESOURCE_UNAVAILABLE);
        open_ucmm(node, (unsigned)index, request->master_mac, consumed_id);
    }
    dn_reply_u8(reply, DN_BODY_FORMAT_8_8);
    dn_reply_u8(reply, (uint8_t)(client_message << DN_UCMM_GROUP_SHIFT |
                                 (unsigned)(index - (int)DN_UCMM_FIRST)));
    dn_reply_u16(reply, instance_of[index]);
    return DN_OK;
}

/* Close: a connection of instances 10-14 that exists (else 0x16), by the client that opened it
 * (another's 0x0C); the application is told as of a release. */
dn_status_t dn_ucmm_close(dn_node_t *node, const dn_request_t *request)
{
    if (request->len < 2)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (request->len > 2)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    uint16_t instance = co_get_u16(request->data);
    if (instance < DN_CONN_UCMM_FIRST || instance > DN_CONN_UCMM_LAST)
        return DN_ERROR(DN_GS_OBJECT_DOES_NOT_EXIST);
    unsigned index = DN_UCMM_FIRST + (unsigned)(instance - DN_CONN_UCMM_FIRST);
    dn_connection_t *c = &node->conn[index];
    if (c->state == DN_CONN_NON_EXISTENT)
        return DN_ERROR(DN_GS_OBJECT_DOES_NOT_EXIST);
    if (c->client_mac != request->master_mac)
        return DN_ERROR(DN_GS_OBJECT_STATE_CONFLICT);
    delete_explicit(node, index);
    tell_ended(node, index, DN_END_RELEASED);
    return DN_OK;
}

/* An I/O connection's watchdog, which a producer without acknowledgements does not have: it
 * consumes nothing. */
static void start_io_watchdog(dn_node_t *node, unsigned index)
{
    dn_connection_t *c = &node->conn[index];
    if (index == DN_IO_PRODUCER && c->consumed_id == NO_CONNECTION_ID)
        c->watchdog = CO_TIME_NEVER;
    else
        kick(node, c);
}

/* An I/O connection enters Established: its watchdog starts, a producer sends its first data
 * now, a consumer is idle until the master's first data. */
static void establish(dn_node_t *node, unsigned index)
{
    node->conn[index].state = DN_CONN_ESTABLISHED;
    if (index == DN_IO_PRODUCER) {
        node->produce_deadline = node->now;
        node->inhibit_until = node->now;
        node->awaiting_ack = false;
    } else {
        node->idle = true;
    }
    start_io_watchdog(node, index);
    dn_io_event(node, DN_IO_ESTABLISHED);
}

void dn_io_receive(dn_node_t *node, const co_frame_t *frame)
{
    dn_connection_t *c = &node->conn[DN_IO_CONSUMER];
    if (c->state != DN_CONN_ESTABLISHED)
        return;
    if (frame->len == 0) {
        if (!node->idle) {
            node->idle = true;
            dn_io_event(node, DN_IO_IDLE);
        }
    } else if (frame->len == c->consumed_size) {
        const dn_app_t *app = node->config->app;
        app->write_assembly(app->user, node->consumed_assembly, frame->data);
        if (node->idle) {
            node->idle = false;
            dn_io_event(node, DN_IO_RUN);
        }
    } else {
        return; /* another length than the consumed assembly's: dropped, unanswered */
    }
    DN_COUNT(node, io_messages);
    kick(node, c);
    if (c->produced_size) {
        uint8_t data[DN_IO_MAX];
        const dn_app_t *app = node->config->app;
        app->read_assembly(app->user, node->produced_assembly, data);
        dn_send(node, c->produced_id, data, (uint8_t)c->produced_size);
    } else if (c->produced_id != NO_CONNECTION_ID) {
        dn_send(node, c->produced_id, NULL, 0); /* the acknowledgement of COS/cyclic data */
    }
}

void dn_cos_ack_receive(dn_node_t *node)
{
    dn_connection_t *c = &node->conn[DN_IO_PRODUCER];
    if (c->state != DN_CONN_ESTABLISHED || c->consumed_id == NO_CONNECTION_ID)
        return;
    node->awaiting_ack = false;
    kick(node, c);
}

static void produce(dn_node_t *node, const uint8_t *data)
{
    dn_connection_t *c = &node->conn[DN_IO_PRODUCER];
    memcpy(node->last_produced, data, node->produced_size);
    dn_send(node, c->produced_id, data, node->produced_size);
    node->produce_deadline = c->expected_packet_rate
                                 ? node->now + (co_time_t)c->expected_packet_rate * DN_US_PER_MS
                                 : CO_TIME_NEVER;
    node->inhibit_until = node->now + (co_time_t)c->inhibit_time * DN_US_PER_MS;
    node->retries = 0;
    node->awaiting_ack = c->consumed_id != NO_CONNECTION_ID;
    node->ack_deadline = node->now + (co_time_t)node->ack_timer * DN_US_PER_MS;
}

/* Cyclic data at the expected packet rate; COS data on a change once the production inhibit
 * time has passed, and at the expected packet rate without one; the acknowledge handler's
 * retransmissions. */
static co_time_t producer_process(dn_node_t *node)
{
    dn_connection_t *c = &node->conn[DN_IO_PRODUCER];
    if (c->state != DN_CONN_ESTABLISHED)
        return CO_TIME_NEVER;
    uint8_t data[DN_IO_MAX];
    const dn_app_t *app = node->config->app;
    app->read_assembly(app->user, node->produced_assembly, data);
    bool cos = c->transport & TRANSPORT_COS;
    bool changed = cos && memcmp(data, node->last_produced, node->produced_size) != 0;
    if (node->now >= node->produce_deadline || (changed && node->now >= node->inhibit_until)) {
        produce(node, data);
        changed = false;
    } else if (node->awaiting_ack && node->now >= node->ack_deadline) {
        if (node->retries < node->retry_limit) {
            node->retries++;
            dn_send(node, c->produced_id, node->last_produced, node->produced_size);
            node->ack_deadline = node->now + (co_time_t)node->ack_timer * DN_US_PER_MS;
        } else {
            node->awaiting_ack = false;
            dn_io_event(node, DN_IO_ACK_FAILED);
        }
    }
    co_time_t next = node->produce_deadline;
    if (changed)
        next = co_time_min(next, node->inhibit_until);
    if (node->awaiting_ack)
        next = co_time_min(next, node->ack_deadline);
    return next;
}

/* An I/O connection's watchdog: Timed out, the application told. */
static co_time_t io_watchdog(dn_node_t *node, unsigned index)
{
    dn_connection_t *c = &node->conn[index];
    if (c->state != DN_CONN_ESTABLISHED)
        return CO_TIME_NEVER;
    if (node->now >= c->watchdog) {
        c->state = DN_CONN_TIMED_OUT;
        c->watchdog = CO_TIME_NEVER;
        if (index == DN_IO_PRODUCER)
            node->awaiting_ack = false;
        DN_COUNT(node, timeouts);
        tell_ended(node, index, DN_END_TIMEOUT);
    }
    return c->watchdog;
}

/* An explicit connection's watchdog: deleted (auto delete), or kept in deferred delete while an
 * I/O connection exists (instance 1's choice; 10-14 always delete). */
static co_time_t explicit_watchdog(dn_node_t *node, unsigned index)
{
    dn_connection_t *c = &node->conn[index];
    if (c->state != DN_CONN_ESTABLISHED)
        return CO_TIME_NEVER;
    if (node->now < c->watchdog)
        return c->watchdog;
    DN_COUNT(node, timeouts);
    if (c->timeout_action == DN_WATCHDOG_DEFERRED_DELETE && io_allocated(node)) {
        c->state = DN_CONN_DEFERRED_DELETE;
        c->watchdog = CO_TIME_NEVER;
        dn_messages_drop(node, index);
    } else {
        delete_explicit(node, index);
    }
    tell_ended(node, index, DN_END_TIMEOUT);
    return CO_TIME_NEVER;
}

co_time_t dn_connections_process(dn_node_t *node)
{
    co_time_t next = explicit_watchdog(node, DN_EXPLICIT);
    for (unsigned i = DN_UCMM_FIRST; i < DN_CONN_COUNT; i++)
        next = co_time_min(next, explicit_watchdog(node, i));
    next = co_time_min(next, io_watchdog(node, DN_IO_CONSUMER));
    next = co_time_min(next, io_watchdog(node, DN_IO_PRODUCER));
    return co_time_min(next, producer_process(node));
}

/* The Connection object's attributes. */

/* The packed EPATH of an assembly's data attribute: class 4, 16-bit instance, attribute 3. */
static void reply_assembly_path(dn_reply_t *reply, uint16_t instance)
{
    const uint8_t path[7] = {
        0x20, DN_CLASS_ASSEMBLY, 0x25, (uint8_t)instance, (uint8_t)(instance >> 8), 0x30, 0x03};
    dn_reply_bytes(reply, path, sizeof(path));
}

/* Acknowledge handler object, instance 1. */
static const uint8_t ack_handler_path[5] = {0x20, DN_CLASS_ACK_HANDLER, 0x25, 0x01, 0x00};

static void reply_path(const dn_node_t *node, unsigned index, bool produced, dn_reply_t *reply)
{
    const dn_connection_t *c = &node->conn[index];
    if (dn_is_explicit(index))
        return;
    if (produced && c->produced_size)
        reply_assembly_path(reply, node->produced_assembly);
    else if (!produced && index == DN_IO_CONSUMER)
        reply_assembly_path(reply, node->consumed_assembly);
    else if (!produced && c->consumed_id != NO_CONNECTION_ID)
        dn_reply_bytes(reply, ack_handler_path, sizeof(ack_handler_path));
}

static dn_status_t connection_get(const dn_node_t *node, unsigned index, uint8_t attribute,
                                  dn_reply_t *reply)
{
    const dn_connection_t *c = &node->conn[index];
    switch (attribute) {
    case CONN_ATTR_STATE:
        dn_reply_u8(reply, c->state);
        break;
    case 2: /* instance type: explicit 0, I/O 1 */
        dn_reply_u8(reply, !dn_is_explicit(index));
        break;
    case 3:
        dn_reply_u8(reply, c->transport);
        break;
    case 4:
        dn_reply_u16(reply, c->produced_id);
        break;
    case 5:
        dn_reply_u16(reply, c->consumed_id);
        break;
    case 6:
        dn_reply_u8(reply, c->comm);
        break;
    case 7:
        dn_reply_u16(reply, c->produced_size);
        break;
    case 8:
        dn_reply_u16(reply, c->consumed_size);
        break;
    case CONN_ATTR_EPR:
        dn_reply_u16(reply, c->expected_packet_rate);
        break;
    case CONN_ATTR_TIMEOUT_ACTION:
        dn_reply_u8(reply, c->timeout_action);
        break;
    case 13:
    case 15: {
        dn_reply_t path = {0, false, {0}};
        reply_path(node, index, attribute == 13, &path);
        dn_reply_u16(reply, path.len);
        break;
    }
    case 14:
    case 16:
        reply_path(node, index, attribute == 14, reply);
        break;
    case CONN_ATTR_INHIBIT:
        dn_reply_u16(reply, c->inhibit_time);
        break;
    default:
        dn_reply_u8(reply, c->multiplier);
        break;
    }
    return DN_OK;
}

/* A written expected packet rate is rounded up to the timer resolution and answered with the
 * value in use; it establishes an I/O connection that is configuring or timed out. */
static dn_status_t set_expected_packet_rate(dn_node_t *node, unsigned index, uint16_t rate,
                                            dn_reply_t *reply)
{
    dn_connection_t *c = &node->conn[index];
    if (rate > EPR_MAX_MS)
        rate = EPR_MAX_MS;
    rate =
        (uint16_t)((rate + TIMER_RESOLUTION_MS - 1u) / TIMER_RESOLUTION_MS * TIMER_RESOLUTION_MS);
    c->expected_packet_rate = rate;
    dn_reply_u16(reply, rate);
    if (!dn_is_explicit(index) &&
        (c->state == DN_CONN_CONFIGURING || c->state == DN_CONN_TIMED_OUT)) {
        establish(node, index);
        return DN_OK;
    }
    if (c->state == DN_CONN_ESTABLISHED) {
        if (dn_is_explicit(index))
            kick(node, c);
        else
            start_io_watchdog(node, index);
    }
    return DN_OK;
}

static dn_status_t connection_set(dn_node_t *node, unsigned index, const dn_request_t *request,
                                  dn_reply_t *reply)
{
    dn_connection_t *c = &node->conn[index];
    uint8_t value = request->data[0];
    switch (request->attribute) {
    case CONN_ATTR_EPR:
        return set_expected_packet_rate(node, index, co_get_u16(request->data), reply);
    case CONN_ATTR_TIMEOUT_ACTION: /* instance 1's only (the manual), auto or deferred delete */
        if (index != DN_EXPLICIT)
            return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
        if (value != DN_WATCHDOG_AUTO_DELETE && value != DN_WATCHDOG_DEFERRED_DELETE)
            return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
        c->timeout_action = value;
        return DN_OK;
    case CONN_ATTR_INHIBIT: /* the COS/cyclic producer's only */
        if (index != DN_IO_PRODUCER)
            return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
        c->inhibit_time = co_get_u16(request->data);
        return DN_OK;
    default: /* the timeout multiplier */
        if (value > MULTIPLIER_MAX)
            return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
        c->multiplier = value;
        if (c->state == DN_CONN_ESTABLISHED && c->watchdog != CO_TIME_NEVER)
            kick(node, c); /* the new timeout from now */
        return DN_OK;
    }
}

/* Class attributes 100 and 101: the assembly the I/O connections will use after a restart. */
static dn_status_t set_assembly_selection(dn_node_t *node, const dn_request_t *request)
{
    bool produced = request->attribute == CONN_CLASS_PRODUCED_ASSEMBLY;
    uint16_t instance = co_get_u16(request->data);
    const dn_assembly_t *a = dn_node_assembly(node, instance);
    if (a == NULL || a->produced != produced)
        return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
    dn_stored_t stored = node->stored;
    if (produced)
        stored.produced_assembly = instance;
    else
        stored.consumed_assembly = instance;
    return dn_store(node, &stored);
}

static dn_status_t connection_class(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply)
{
    if (request->service == DN_SVC_SET_ATTRIBUTE_SINGLE)
        return set_assembly_selection(node, request);
    if (request->attribute == CONN_CLASS_CONSUMED_ASSEMBLY)
        dn_reply_u16(reply, node->stored.consumed_assembly);
    else if (request->attribute == CONN_CLASS_PRODUCED_ASSEMBLY)
        dn_reply_u16(reply, node->stored.produced_assembly);
    else
        dn_reply_u16(reply, CONNECTION_REVISION);
    return DN_OK;
}

dn_status_t dn_connection_handler(dn_node_t *node, const dn_object_t *object,
                                  const dn_request_t *request, dn_reply_t *reply)
{
    (void)object;
    if (request->service != DN_SVC_GET_ATTRIBUTE_SINGLE &&
        request->service != DN_SVC_SET_ATTRIBUTE_SINGLE)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0)
        return connection_class(node, request, reply);
    int index = conn_index(request->instance);
    if (index < 0 || node->conn[index].state == DN_CONN_NON_EXISTENT)
        return DN_ERROR(DN_GS_OBJECT_DOES_NOT_EXIST);
    if (request->service == DN_SVC_SET_ATTRIBUTE_SINGLE)
        return connection_set(node, (unsigned)index, request, reply);
    return connection_get(node, (unsigned)index, request->attribute, reply);
}
