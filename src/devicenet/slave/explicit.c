/* SPDX-License-Identifier: Apache-2.0 */
/* Explicit messaging: the requests of the explicit connection (instance 1, group 2 message 4)
 * and of the group 2 only unconnected port (message 6), their responses (message 3), and the
 * fragmentation protocol both ways with its acknowledgements (common/fragment.c, which the
 * scanner shares). */
#include <string.h>

#include "devicenet/slave/dn_slave.h"

/* How long a fragment of a response waits for its acknowledgement before it is sent once more,
 * and then before the response is given up (the project's choice: docs/devicenet.md). */
#define DN_FRAG_ACK_WAIT_US 1000000u
#define DN_FRAG_RETRIES 1u

static void send_fragment(dn_node_t *node)
{
    uint8_t frame[8];
    uint8_t len = dn_fragment_frame(&node->tx, frame);
    dn_send(node, node->ids.explicit_response, frame, len);
    DN_COUNT(node, fragments);
    node->tx.deadline = node->now + DN_FRAG_ACK_WAIT_US;
}

/* A response body (service byte first) in one frame, or in fragments above 7 bytes. */
static void send_response(dn_node_t *node, uint8_t header, const uint8_t *body, uint8_t len)
{
    if (len <= DN_FRAME_BODY) {
        uint8_t frame[8];
        frame[0] = header;
        memcpy(&frame[1], body, len);
        dn_send(node, node->ids.explicit_response, frame, (uint8_t)(1 + len));
        return;
    }
    dn_fragment_start(&node->tx, header, body, len);
    send_fragment(node);
}

static void send_ack(dn_node_t *node, uint8_t header, uint8_t count, uint8_t status)
{
    uint8_t frame[8];
    uint8_t len = dn_fragment_ack_frame(header, count, status, frame);
    dn_send(node, node->ids.explicit_response, frame, len);
}

/* Parses a request body (service, class, instance, attribute for Get/Set), routes it and
 * answers; the header of the answer keeps the request's XID and MAC ID. */
static void execute(dn_node_t *node, uint8_t header, const uint8_t *body, uint8_t len,
                    bool unconnected)
{
    if (len == 0 || body[0] & DN_SERVICE_RESPONSE)
        return;
    DN_COUNT(node, explicit_requests);
    uint8_t service = body[0];
    dn_request_t request;
    memset(&request, 0, sizeof(request));
    request.service = service;
    request.master_mac = header & DN_HDR_MAC;
    dn_reply_t reply;
    reply.len = 0;
    reply.overflow = false;
    uint8_t path =
        service == DN_SVC_GET_ATTRIBUTE_SINGLE || service == DN_SVC_SET_ATTRIBUTE_SINGLE ? 4u : 3u;
    dn_status_t status;
    if (unconnected && service != DN_SVC_ALLOCATE && service != DN_SVC_RELEASE) {
        status = DN_STATUS(DN_GS_SERVICE_NOT_SUPPORTED, DN_AC_INVALID_GROUP2_MESSAGE);
    } else if (len < path) {
        status = DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    } else {
        request.class_id = body[1];
        request.instance = body[2];
        request.attribute = path == 4u ? body[3] : 0;
        request.data = &body[path];
        request.len = (uint8_t)(len - path);
        status = dn_route(node, &request, &reply);
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
    send_response(node, (uint8_t)(header & (DN_HDR_XID | DN_HDR_MAC)), response, response_len);
    if (node->pending_reset >= 0) {
        uint8_t type = (uint8_t)node->pending_reset;
        node->pending_reset = -1;
        const dn_app_t *app = node->config->app;
        if (app->reset)
            app->reset(app->user, type);
    }
}

/* A fragment of a request, or the master's acknowledgement of a fragment of a response. */
static void fragment_receive(dn_node_t *node, const co_frame_t *frame)
{
    uint8_t count = frame->data[1] & DN_FRAG_COUNT;
    if ((frame->data[1] & DN_FRAG_TYPE) == DN_FRAG_ACK) {
        uint8_t status = frame->len > 2 ? frame->data[2] : (uint8_t)DN_FRAG_ACK_SUCCESS;
        if (dn_fragment_acknowledged(&node->tx, count, status) == DN_FRAGMENT_ACK_NEXT)
            send_fragment(node);
        return;
    }
    DN_COUNT(node, fragments);
    dn_fragments_t *rx = &node->rx;
    switch (dn_fragment_receive(rx, frame->data, frame->len)) {
    case DN_FRAGMENT_RX_TAKEN:
    case DN_FRAGMENT_RX_REPEATED:
        send_ack(node, rx->header, count, DN_FRAG_ACK_SUCCESS);
        break;
    case DN_FRAGMENT_RX_TOO_MUCH:
        send_ack(node, frame->data[0], count, DN_FRAG_ACK_TOO_MUCH_DATA);
        break;
    case DN_FRAGMENT_RX_COMPLETE:
        send_ack(node, rx->header, count, DN_FRAG_ACK_SUCCESS);
        execute(node, (uint8_t)(rx->header & ~DN_HDR_FRAG), rx->body, rx->len, false);
        break;
    case DN_FRAGMENT_RX_IGNORED:
    case DN_FRAGMENT_RX_LOST:
        break;
    }
}

void dn_explicit_receive(dn_node_t *node, const co_frame_t *frame, bool unconnected)
{
    if (frame->len < 2)
        return;
    if (!unconnected) {
        if (node->conn[DN_EXPLICIT].state != DN_CONN_ESTABLISHED)
            return;
        dn_explicit_activity(node);
    }
    if (frame->data[0] & DN_HDR_FRAG) {
        if (!unconnected) /* the unconnected port carries no fragments */
            fragment_receive(node, frame);
        return;
    }
    execute(node, frame->data[0], &frame->data[1], (uint8_t)(frame->len - 1), unconnected);
}

co_time_t dn_explicit_process(dn_node_t *node)
{
    dn_fragments_t *tx = &node->tx;
    if (!tx->active)
        return CO_TIME_NEVER;
    if (node->conn[DN_EXPLICIT].state != DN_CONN_ESTABLISHED) {
        tx->active = false;
        return CO_TIME_NEVER;
    }
    if (node->now >= tx->deadline) {
        if (tx->retries >= DN_FRAG_RETRIES) {
            tx->active = false;
            return CO_TIME_NEVER;
        }
        tx->retries++;
        send_fragment(node);
    }
    return tx->deadline;
}
