/* SPDX-License-Identifier: Apache-2.0 */
/* Explicit messaging: the requests of the explicit connections (instance 1 on group 2 message 4,
 * instances 10-14 on the group 3 IDs the UCMM gave them), of the group 2 only unconnected port
 * (message 6) and of the UCMM (group 3 message 6), their responses (group 2 message 3, the
 * connection's group 3 ID, group 3 message 5), and the fragmentation protocol both ways with its
 * acknowledgements on the connections (common/fragment.c, which the scanner shares). */
#include <string.h>

#include "devicenet/slave/dn_slave.h"

/* How long a fragment of a response waits for its acknowledgement before it is sent once more,
 * and then before the response is given up (the project's choice: docs/devicenet.md). */
#define DN_FRAG_ACK_WAIT_US 1000000u
#define DN_FRAG_RETRIES 1u

/* Where a request came from and where its answer goes. */
typedef struct origin {
    int index;            /* the explicit connection's conn[] position; -1: unconnected */
    bool ucmm;            /* unconnected: the UCMM (group 3), else the group 2 only port */
    uint8_t client;       /* the client's MAC ID */
    uint16_t response_id; /* the CAN-ID of the answer */
} origin_t;

static void send_fragment(dn_node_t *node, unsigned index)
{
    uint8_t frame[8];
    dn_fragments_t *tx = &dn_messages(node, index)->tx;
    uint8_t len = dn_fragment_frame(tx, frame);
    dn_send(node, node->conn[index].produced_id, frame, len);
    DN_COUNT(node, fragments);
    tx->deadline = node->now + DN_FRAG_ACK_WAIT_US;
}

/* A response body (service byte first) in one frame, or in fragments above 7 bytes on a
 * connection (an unconnected response always fits one frame). */
static void send_response(dn_node_t *node, const origin_t *origin, uint8_t header,
                          const uint8_t *body, uint8_t len)
{
    if (len <= DN_FRAME_BODY) {
        uint8_t frame[8];
        frame[0] = header;
        memcpy(&frame[1], body, len);
        dn_send(node, origin->response_id, frame, (uint8_t)(1 + len));
        return;
    }
    dn_fragment_start(&dn_messages(node, (unsigned)origin->index)->tx, header, body, len);
    send_fragment(node, (unsigned)origin->index);
}

static void send_ack(dn_node_t *node, unsigned index, uint8_t header, uint8_t count, uint8_t status)
{
    uint8_t frame[8];
    uint8_t len = dn_fragment_ack_frame(header, count, status, frame);
    dn_send(node, node->conn[index].produced_id, frame, len);
}

/* The header of a message to the client: the request's XID, and the MAC ID that the CAN-ID does
 * not carry (group 2 carries the slave's, group 3 the sender's): the client's. */
static uint8_t header_to_client(uint8_t request_header, const origin_t *origin)
{
    return (uint8_t)((request_header & DN_HDR_XID) | origin->client);
}

/* The services an unconnected port has: Allocate and Release on group 2 message 6, Open and
 * Close on the UCMM (a connection has every class's). */
static dn_status_t port_refusal(const origin_t *origin, uint8_t service)
{
    if (origin->index >= 0)
        return DN_OK;
    if (origin->ucmm)
        return service == DN_SVC_OPEN_EXPLICIT || service == DN_SVC_CLOSE
                   ? DN_OK
                   : DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    return service == DN_SVC_ALLOCATE || service == DN_SVC_RELEASE
               ? DN_OK
               : DN_STATUS(DN_GS_SERVICE_NOT_SUPPORTED, DN_AC_INVALID_GROUP2_MESSAGE);
}

static dn_status_t dispatch(dn_node_t *node, const origin_t *origin, dn_request_t *request,
                            dn_reply_t *reply)
{
    if (!origin->ucmm)
        return dn_route(node, request, reply);
    return request->service == DN_SVC_OPEN_EXPLICIT ? dn_ucmm_open(node, request, reply)
                                                    : dn_ucmm_close(node, request);
}

/* Parses a request body (service, then class and instance, and the attribute for Get/Set; the
 * UCMM's services carry their data right after the service), dispatches it and answers. */
static void execute(dn_node_t *node, const origin_t *origin, uint8_t header, const uint8_t *body,
                    uint8_t len)
{
    if (len == 0 || body[0] & DN_SERVICE_RESPONSE)
        return;
    DN_COUNT(node, explicit_requests);
    uint8_t service = body[0];
    dn_request_t request;
    memset(&request, 0, sizeof(request));
    request.service = service;
    request.master_mac = origin->client;
    request.connection = origin->index >= 0 ? dn_connection_instance((unsigned)origin->index) : 0;
    dn_reply_t reply;
    reply.len = 0;
    reply.overflow = false;
    uint8_t path =
        origin->ucmm                                                                       ? 1u
        : service == DN_SVC_GET_ATTRIBUTE_SINGLE || service == DN_SVC_SET_ATTRIBUTE_SINGLE ? 4u
                                                                                           : 3u;
    dn_status_t status = port_refusal(origin, service);
    if (status == DN_OK && len < path) {
        status = DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    } else if (status == DN_OK) {
        if (!origin->ucmm) {
            request.class_id = body[1];
            request.instance = body[2];
            request.attribute = path == 4u ? body[3] : 0;
        }
        request.data = &body[path];
        request.len = (uint8_t)(len - path);
        node->request_connection = request.connection;
        status = dispatch(node, origin, &request, &reply);
        node->request_connection = 0;
    }
    uint8_t response[DN_MESSAGE_MAX];
    uint8_t response_len;
    if (status == DN_OK) {
        response[0] = (uint8_t)(service | DN_SERVICE_RESPONSE);
        memcpy(&response[1], reply.data, reply.len);
        response_len = (uint8_t)(1 + reply.len);
    } else {
        DN_COUNT(node, error_responses);
        response[0] = DN_SVC_ERROR_RESPONSE | DN_SERVICE_RESPONSE;
        response[1] = (uint8_t)status;
        response[2] = (uint8_t)(status >> 8);
        response_len = 3;
    }
    send_response(node, origin, header_to_client(header, origin), response, response_len);
    if (node->pending_reset >= 0) {
        uint8_t type = (uint8_t)node->pending_reset;
        node->pending_reset = -1;
        const dn_app_t *app = node->config->app;
        if (app->reset)
            app->reset(app->user, type);
    }
}

/* A fragment of a request, or the client's acknowledgement of a fragment of a response. */
static void fragment_receive(dn_node_t *node, const origin_t *origin, const co_frame_t *frame)
{
    unsigned index = (unsigned)origin->index;
    uint8_t count = frame->data[1] & DN_FRAG_COUNT;
    if ((frame->data[1] & DN_FRAG_TYPE) == DN_FRAG_ACK) {
        uint8_t status = frame->len > 2 ? frame->data[2] : (uint8_t)DN_FRAG_ACK_SUCCESS;
        if (dn_fragment_acknowledged(&dn_messages(node, index)->tx, count, status) ==
            DN_FRAGMENT_ACK_NEXT)
            send_fragment(node, index);
        return;
    }
    DN_COUNT(node, fragments);
    dn_fragments_t *rx = &dn_messages(node, index)->rx;
    uint8_t to_client = header_to_client(frame->data[0], origin) | DN_HDR_FRAG;
    switch (dn_fragment_receive(rx, frame->data, frame->len)) {
    case DN_FRAGMENT_RX_TAKEN:
    case DN_FRAGMENT_RX_REPEATED:
        send_ack(node, index, to_client, count, DN_FRAG_ACK_SUCCESS);
        break;
    case DN_FRAGMENT_RX_TOO_MUCH:
        send_ack(node, index, to_client, count, DN_FRAG_ACK_TOO_MUCH_DATA);
        break;
    case DN_FRAGMENT_RX_COMPLETE:
        send_ack(node, index, to_client, count, DN_FRAG_ACK_SUCCESS);
        execute(node, origin, (uint8_t)(rx->header & ~DN_HDR_FRAG), rx->body, rx->len);
        break;
    case DN_FRAGMENT_RX_IGNORED:
    case DN_FRAGMENT_RX_LOST:
        break;
    }
}

void dn_explicit_receive(dn_node_t *node, const co_frame_t *frame, unsigned index)
{
    const dn_connection_t *c = &node->conn[index];
    if (frame->len < 2 || c->state != DN_CONN_ESTABLISHED)
        return;
    dn_explicit_activity(node, index);
    /* Group 2 carries the master's MAC ID in the header; group 3 the sender's in the CAN-ID. */
    origin_t origin = {(int)index, false,
                       index == DN_EXPLICIT ? (uint8_t)(frame->data[0] & DN_HDR_MAC)
                                            : c->client_mac,
                       c->produced_id};
    if (frame->data[0] & DN_HDR_FRAG)
        fragment_receive(node, &origin, frame);
    else
        execute(node, &origin, frame->data[0], &frame->data[1], (uint8_t)(frame->len - 1));
}

void dn_unconnected_receive(dn_node_t *node, const co_frame_t *frame, bool ucmm, uint8_t client)
{
    /* The unconnected ports carry no fragments. */
    if (frame->len < 2 || frame->data[0] & DN_HDR_FRAG)
        return;
    origin_t origin = {-1, ucmm, client,
                       ucmm ? dn_group3_id(DN_G3_UNCONNECTED_RESPONSE, node->config->mac_id)
                            : node->ids.explicit_response};
    execute(node, &origin, frame->data[0], &frame->data[1], (uint8_t)(frame->len - 1));
}

/* The fragmented responses of each connection: the repeat of an unacknowledged fragment, or the
 * response given up. */
co_time_t dn_explicit_process(dn_node_t *node)
{
    co_time_t next = CO_TIME_NEVER;
    for (unsigned i = 0; i < DN_CONN_COUNT; i++) {
        if (!dn_is_explicit(i))
            continue;
        dn_fragments_t *tx = &dn_messages(node, i)->tx;
        if (!tx->active)
            continue;
        if (node->conn[i].state != DN_CONN_ESTABLISHED) {
            tx->active = false;
            continue;
        }
        if (node->now >= tx->deadline) {
            if (tx->retries >= DN_FRAG_RETRIES) {
                tx->active = false;
                continue;
            }
            tx->retries++;
            send_fragment(node, i);
        }
        next = co_time_min(next, tx->deadline);
    }
    return next;
}

uint8_t dn_node_request_connection(const dn_node_t *node)
{
    return node->request_connection;
}
