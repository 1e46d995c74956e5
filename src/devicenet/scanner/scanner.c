/* SPDX-License-Identifier: Apache-2.0 */
/* The DeviceNet scanner (include/dn/dn_scanner.h): its duplicate MAC ID check, the slaves'
 * requests on the unconnected port and the explicit connection with fragmentation both ways,
 * the polled connection, kept and re-established when lost, and the slaves' COS/cyclic data. */
#include "dn/dn_scanner.h"

#include <string.h>

#include "devicenet/common/frame_send.h"

#define NO_SLAVE 0xFFu
/* A fragment of a request waits `timeout` for its acknowledgement, and is sent once more
 * before the request is given up (as the slave does with its responses). */
#define FRAGMENT_RETRIES 1u
/* Get/Set_Attribute_Single carry the attribute after the class and instance. */
#define PATH_LEN 2u /* class, instance: 8/8 body format */

static void send_frame(dn_scanner_t *scanner, uint16_t can_id, const uint8_t *data, uint8_t len)
{
    const dn_scanner_app_t *app = scanner->config->app;
    dn_frame_send(app->send, app->user, can_id, data, len);
}

int dn_scanner_init(dn_scanner_t *scanner, const dn_scanner_config_t *config)
{
    memset(scanner, 0, sizeof(*scanner));
    scanner->config = config;
    scanner->link = DN_SCANNER_OFF;
    scanner->link_deadline = CO_TIME_NEVER;
    scanner->timeout = config->timeout ? config->timeout : DN_SCANNER_TIMEOUT_DEFAULT_US;
    memset(scanner->slave_index, NO_SLAVE, sizeof(scanner->slave_index));
    if (config->app == NULL || config->app->send == NULL || config->app->done == NULL ||
        (config->slave_count && config->slaves == NULL))
        return DN_SCANNER_INIT_BAD_CONFIG;
    if (config->mac_id > DN_MAC_ID_MAX || config->slave_count > DN_MAC_ID_MAX + 1u)
        return DN_SCANNER_INIT_BAD_MAC_ID;
    for (uint8_t i = 0; i < config->slave_count; i++) {
        dn_slave_t *slave = &config->slaves[i];
        uint8_t mac_id = slave->mac_id;
        if (mac_id > DN_MAC_ID_MAX || scanner->slave_index[mac_id] != NO_SLAVE)
            return DN_SCANNER_INIT_BAD_MAC_ID;
        memset(slave, 0, sizeof(*slave));
        slave->mac_id = mac_id;
        slave->ids = dn_predefined_ids(mac_id);
        slave->deadline = CO_TIME_NEVER;
        slave->next_poll = CO_TIME_NEVER;
        slave->poll_deadline = CO_TIME_NEVER;
        slave->xid = DN_HDR_XID; /* toggled before each request: the first has XID 0 */
        scanner->slave_index[mac_id] = i;
    }
    return DN_SCANNER_INIT_OK;
}

dn_slave_t *dn_scanner_slave(dn_scanner_t *scanner, uint8_t mac_id)
{
    if (mac_id > DN_MAC_ID_MAX || scanner->slave_index[mac_id] == NO_SLAVE)
        return NULL;
    return &scanner->config->slaves[scanner->slave_index[mac_id]];
}

/* ---- the duplicate MAC ID check ----------------------------------------------------------- */

static void send_duplicate_mac(dn_scanner_t *scanner, uint8_t flags)
{
    const dn_scanner_config_t *config = scanner->config;
    uint8_t data[DN_DUP_MAC_LEN];
    data[0] = flags;
    co_put_u16(&data[1], config->vendor_id);
    co_put_u32(&data[3], config->serial_number);
    send_frame(scanner, dn_group2_id(config->mac_id, DN_G2_DUPLICATE_MAC_CHECK), data,
               DN_DUP_MAC_LEN);
}

void dn_scanner_start(dn_scanner_t *scanner, co_time_t now)
{
    scanner->now = now;
    scanner->link = DN_SCANNER_CHECKING;
    scanner->checks_sent = 1;
    scanner->link_deadline = now + DN_DUP_MAC_WAIT_US;
    send_duplicate_mac(scanner, 0);
}

void dn_scanner_start_online(dn_scanner_t *scanner, co_time_t now)
{
    scanner->now = now;
    scanner->link = DN_SCANNER_ONLINE;
    scanner->link_deadline = CO_TIME_NEVER;
}

/* A check message with the scanner's MAC ID: while checking, another node has it; online, a
 * request is answered. */
static void duplicate_mac_receive(dn_scanner_t *scanner, const co_frame_t *frame)
{
    if (frame->len != DN_DUP_MAC_LEN)
        return;
    if (scanner->link == DN_SCANNER_CHECKING) {
        scanner->link = DN_SCANNER_DUPLICATE;
        scanner->link_deadline = CO_TIME_NEVER;
    } else if (scanner->link == DN_SCANNER_ONLINE && !(frame->data[0] & DN_DUP_MAC_RESPONSE)) {
        send_duplicate_mac(scanner, DN_DUP_MAC_RESPONSE);
    }
}

static void link_process(dn_scanner_t *scanner)
{
    if (scanner->link != DN_SCANNER_CHECKING || scanner->now < scanner->link_deadline)
        return;
    if (scanner->checks_sent == 1) {
        scanner->checks_sent = 2;
        scanner->link_deadline = scanner->now + DN_DUP_MAC_WAIT_US;
        send_duplicate_mac(scanner, 0);
    } else {
        scanner->link = DN_SCANNER_ONLINE;
        scanner->link_deadline = CO_TIME_NEVER;
    }
}

/* ---- requests --------------------------------------------------------------------------- */

static void recovery_result(dn_scanner_t *scanner, dn_slave_t *slave, const dn_result_t *result);

/* A Close to the UCMM forgets the connection whatever its outcome: refused (the slave's watchdog
 * already deleted it: 0x16) or unanswered, the connection is of no more use, and a scanner that
 * kept it would send every later request to a group 3 ID no one consumes. */
static void finish(dn_scanner_t *scanner, dn_slave_t *slave, dn_result_status_t status,
                   uint8_t general, uint8_t additional, const uint8_t *data, uint8_t len)
{
    if (slave->to_ucmm && slave->service == DN_SVC_CLOSE)
        slave->ucmm_instance = 0;
    slave->busy = false;
    slave->tx.active = false;
    slave->rx.active = false;
    slave->deadline = CO_TIME_NEVER;
    dn_result_t result = {slave->mac_id, slave->service, status, general, additional, len, data};
    if (slave->recovering_request) {
        slave->recovering_request = false;
        recovery_result(scanner, slave, &result);
        return;
    }
    const dn_scanner_app_t *app = scanner->config->app;
    app->done(app->user, &result);
}

/* Where a request goes: the group 2 only unconnected port, the UCMM (group 3 message 6) or the
 * explicit connection, the UCMM's when one is open. */
typedef enum port { PORT_UNCONNECTED, PORT_UCMM, PORT_EXPLICIT } port_t;

static uint16_t explicit_request_id(const dn_scanner_t *scanner, const dn_slave_t *slave)
{
    return slave->ucmm_instance ? dn_group3_id(slave->ucmm_message, scanner->config->mac_id)
                                : slave->ids.explicit_request;
}

static void send_fragment(dn_scanner_t *scanner, dn_slave_t *slave)
{
    uint8_t frame[8];
    uint8_t len = dn_fragment_frame(&slave->tx, frame);
    send_frame(scanner, explicit_request_id(scanner, slave), frame, len);
    slave->deadline = scanner->now + scanner->timeout;
}

static dn_slave_t *idle_slave(dn_scanner_t *scanner, uint8_t mac_id)
{
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (scanner->link != DN_SCANNER_ONLINE || slave == NULL || slave->busy)
        return NULL;
    return slave;
}

/* Sends a request body (service first) on a port, in fragments above 7 bytes on the explicit
 * connection. The header carries the MAC ID that the CAN-ID does not: on group 2 the
 * scanner's (the CAN-ID has the slave's), on group 3 the slave's. */
static bool start_request(dn_scanner_t *scanner, uint8_t mac_id, const uint8_t *body, uint8_t len,
                          port_t port, co_time_t now)
{
    scanner->now = now;
    dn_slave_t *slave = idle_slave(scanner, mac_id);
    if (slave == NULL || len > DN_MESSAGE_MAX || (port != PORT_EXPLICIT && len > DN_FRAME_BODY))
        return false;
    slave->busy = true;
    slave->recovering_request = false;
    slave->service = body[0];
    slave->to_ucmm = port == PORT_UCMM;
    slave->response_id = port == PORT_UCMM ? dn_group3_id(DN_G3_UNCONNECTED_RESPONSE, mac_id)
                         : port == PORT_EXPLICIT && slave->ucmm_instance
                             ? slave->ucmm_response
                             : slave->ids.explicit_response;
    slave->xid ^= DN_HDR_XID;
    slave->rx.active = false;
    bool group3 = port == PORT_UCMM || (port == PORT_EXPLICIT && slave->ucmm_instance);
    uint8_t header = (uint8_t)(slave->xid | (group3 ? mac_id : scanner->config->mac_id));
    if (len > DN_FRAME_BODY) {
        dn_fragment_start(&slave->tx, header, body, len);
        send_fragment(scanner, slave);
        return true;
    }
    uint8_t frame[8];
    frame[0] = header;
    memcpy(&frame[1], body, len);
    uint16_t can_id = port == PORT_UNCONNECTED ? slave->ids.unconnected
                      : port == PORT_UCMM
                          ? dn_group3_id(DN_G3_UNCONNECTED_REQUEST, scanner->config->mac_id)
                          : explicit_request_id(scanner, slave);
    send_frame(scanner, can_id, frame, (uint8_t)(1 + len));
    slave->deadline = now + scanner->timeout;
    return true;
}

/* Allocate and Release: [service][class 3][instance 1][choice] (+ the allocator's MAC ID). */
bool dn_scanner_allocate(dn_scanner_t *scanner, uint8_t mac_id, uint8_t choice, co_time_t now)
{
    uint8_t body[] = {DN_SVC_ALLOCATE, DN_CLASS_DEVICENET, 1, choice, scanner->config->mac_id};
    if (!start_request(scanner, mac_id, body, sizeof(body), PORT_UNCONNECTED, now))
        return false;
    dn_scanner_slave(scanner, mac_id)->choice = choice;
    return true;
}

bool dn_scanner_release(dn_scanner_t *scanner, uint8_t mac_id, uint8_t choice, co_time_t now)
{
    uint8_t body[] = {DN_SVC_RELEASE, DN_CLASS_DEVICENET, 1, choice};
    if (!start_request(scanner, mac_id, body, sizeof(body), PORT_UNCONNECTED, now))
        return false;
    dn_scanner_slave(scanner, mac_id)->choice = choice;
    return true;
}

/* Whether a slave holds its ucmm_message: a connection open, or an Open not answered yet. */
static bool holds_ucmm_message(const dn_slave_t *slave)
{
    return slave->ucmm_instance != 0 ||
           (slave->busy && slave->to_ucmm && slave->service == DN_SVC_OPEN_EXPLICIT);
}

/* The lowest group 3 message ID of the scanner's that no other slave's UCMM connection uses or
 * asks for (the slaves tell their connections apart by the CAN-ID alone), or
 * DN_G3_CONNECTED_LAST + 1. */
static uint8_t free_ucmm_message(const dn_scanner_t *scanner)
{
    const dn_scanner_config_t *config = scanner->config;
    uint8_t message = 0;
    for (uint8_t i = 0; i < config->slave_count && message <= DN_G3_CONNECTED_LAST;)
        if (holds_ucmm_message(&config->slaves[i]) && config->slaves[i].ucmm_message == message) {
            message++;
            i = 0;
        } else {
            i++;
        }
    return message;
}

/* Open: [service][body format 8/8][group 3 | the scanner's message ID]. */
bool dn_scanner_ucmm_open(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now)
{
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    uint8_t message = free_ucmm_message(scanner);
    if (slave == NULL || slave->ucmm_instance || message > DN_G3_CONNECTED_LAST)
        return false;
    uint8_t body[] = {DN_SVC_OPEN_EXPLICIT, DN_BODY_FORMAT_8_8,
                      (uint8_t)(DN_UCMM_GROUP_3 << DN_UCMM_GROUP_SHIFT | message)};
    if (!start_request(scanner, mac_id, body, sizeof(body), PORT_UCMM, now))
        return false;
    slave->ucmm_message = message;
    return true;
}

/* Close: [service][instance UINT]. */
bool dn_scanner_ucmm_close(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now)
{
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (slave == NULL || slave->ucmm_instance == 0)
        return false;
    uint8_t body[3] = {DN_SVC_CLOSE};
    co_put_u16(&body[1], slave->ucmm_instance);
    return start_request(scanner, mac_id, body, sizeof(body), PORT_UCMM, now);
}

bool dn_scanner_request(dn_scanner_t *scanner, uint8_t mac_id, uint8_t service, uint8_t class_id,
                        uint8_t instance, const uint8_t *data, uint8_t len, co_time_t now)
{
    if (len > DN_MESSAGE_MAX - 1u - PATH_LEN)
        return false;
    uint8_t body[DN_MESSAGE_MAX];
    body[0] = service;
    body[1] = class_id;
    body[2] = instance;
    if (len)
        memcpy(&body[3], data, len);
    return start_request(scanner, mac_id, body, (uint8_t)(3 + len), PORT_EXPLICIT, now);
}

bool dn_scanner_get(dn_scanner_t *scanner, uint8_t mac_id, uint8_t class_id, uint8_t instance,
                    uint8_t attribute, co_time_t now)
{
    return dn_scanner_request(scanner, mac_id, DN_SVC_GET_ATTRIBUTE_SINGLE, class_id, instance,
                              &attribute, 1, now);
}

bool dn_scanner_set(dn_scanner_t *scanner, uint8_t mac_id, uint8_t class_id, uint8_t instance,
                    uint8_t attribute, const uint8_t *value, uint8_t len, co_time_t now)
{
    uint8_t data[DN_MESSAGE_MAX];
    if (len > DN_MESSAGE_MAX - 1u)
        return false;
    data[0] = attribute;
    if (len)
        memcpy(&data[1], value, len);
    return dn_scanner_request(scanner, mac_id, DN_SVC_SET_ATTRIBUTE_SINGLE, class_id, instance,
                              data, (uint8_t)(1 + len), now);
}

bool dn_scanner_set_expected_packet_rate(dn_scanner_t *scanner, uint8_t mac_id, uint8_t connection,
                                         uint16_t ms, co_time_t now)
{
    uint8_t value[2];
    co_put_u16(value, ms);
    return dn_scanner_set(scanner, mac_id, DN_CLASS_CONNECTION, connection,
                          DN_CONN_ATTR_EXPECTED_PACKET_RATE, value, sizeof(value), now);
}

/* Open's response: [service][body format][the scanner's | the slave's message ID][instance]:
 * the connection the scanner asked for, 8/8, an instance of 10-14, else a bad response. */
static bool ucmm_opened(dn_scanner_t *scanner, dn_slave_t *slave, const uint8_t *body, uint8_t len)
{
    uint8_t server = len == 5 ? body[2] & DN_UCMM_MESSAGE_ID : 0;
    uint16_t instance = len == 5 ? co_get_u16(&body[3]) : 0;
    if (len != 5 || (body[1] & DN_UCMM_BODY_FORMAT) != DN_BODY_FORMAT_8_8 ||
        body[2] >> DN_UCMM_GROUP_SHIFT != slave->ucmm_message || server > DN_G3_CONNECTED_LAST ||
        instance < DN_CONN_UCMM_FIRST || instance > DN_CONN_UCMM_LAST) {
        finish(scanner, slave, DN_RESULT_BAD_RESPONSE, 0, DN_AC_NONE, NULL, 0);
        return false;
    }
    slave->ucmm_instance = instance;
    slave->ucmm_response = dn_group3_id(server, slave->mac_id);
    return true;
}

/* A whole response body: success (the service with the response bit), the error response, or
 * something else. Allocate and Release keep what the slave granted, Open the UCMM connection
 * (finish forgets it after a Close). */
static void response_complete(dn_scanner_t *scanner, dn_slave_t *slave, const uint8_t *body,
                              uint8_t len)
{
    if (len >= 1 && body[0] == (DN_SVC_ERROR_RESPONSE | DN_SERVICE_RESPONSE)) {
        uint8_t general = len >= 2 ? body[1] : 0;
        uint8_t additional = len >= 3 ? body[2] : (uint8_t)DN_AC_NONE;
        finish(scanner, slave, DN_RESULT_CIP_ERROR, general, additional, NULL, 0);
        return;
    }
    if (len == 0 || body[0] != (slave->service | DN_SERVICE_RESPONSE)) {
        finish(scanner, slave, DN_RESULT_BAD_RESPONSE, 0, DN_AC_NONE, NULL, 0);
        return;
    }
    if (slave->to_ucmm) {
        if (slave->service == DN_SVC_OPEN_EXPLICIT && !ucmm_opened(scanner, slave, body, len))
            return;
    } else if (slave->service == DN_SVC_ALLOCATE) {
        slave->allocated |= slave->choice;
    } else if (slave->service == DN_SVC_RELEASE) {
        slave->allocated &= (uint8_t)~slave->choice;
    }
    finish(scanner, slave, DN_RESULT_OK, 0, 0, &body[1], (uint8_t)(len - 1));
}

static void send_ack(dn_scanner_t *scanner, dn_slave_t *slave, uint8_t header, uint8_t count,
                     uint8_t status)
{
    uint8_t frame[8];
    if (slave->ucmm_instance) /* group 3: the header names the slave */
        header = (uint8_t)((header & ~DN_HDR_MAC) | slave->mac_id);
    uint8_t len = dn_fragment_ack_frame(header, count, status, frame);
    send_frame(scanner, explicit_request_id(scanner, slave), frame, len);
}

/* A fragment of the response, or the slave's acknowledgement of a fragment of the request. */
static void fragment_receive(dn_scanner_t *scanner, dn_slave_t *slave, const co_frame_t *frame)
{
    uint8_t count = frame->data[1] & DN_FRAG_COUNT;
    if ((frame->data[1] & DN_FRAG_TYPE) == DN_FRAG_ACK) {
        uint8_t status = frame->len > 2 ? frame->data[2] : (uint8_t)DN_FRAG_ACK_SUCCESS;
        switch (dn_fragment_acknowledged(&slave->tx, count, status)) {
        case DN_FRAGMENT_ACK_NEXT:
            send_fragment(scanner, slave);
            break;
        case DN_FRAGMENT_ACK_DONE:
            slave->deadline = scanner->now + scanner->timeout; /* now the response */
            break;
        case DN_FRAGMENT_ACK_REFUSED:
            finish(scanner, slave, DN_RESULT_FRAGMENT_ERROR, 0, status, NULL, 0);
            break;
        case DN_FRAGMENT_ACK_IGNORED:
            break;
        }
        return;
    }
    if (slave->tx.active)
        return; /* no response before the request went through */
    dn_fragments_t *rx = &slave->rx;
    switch (dn_fragment_receive(rx, frame->data, frame->len)) {
    case DN_FRAGMENT_RX_TAKEN:
        send_ack(scanner, slave, rx->header, count, DN_FRAG_ACK_SUCCESS);
        slave->deadline = scanner->now + scanner->timeout;
        break;
    case DN_FRAGMENT_RX_REPEATED:
        send_ack(scanner, slave, rx->header, count, DN_FRAG_ACK_SUCCESS);
        break;
    case DN_FRAGMENT_RX_TOO_MUCH:
        send_ack(scanner, slave, frame->data[0], count, DN_FRAG_ACK_TOO_MUCH_DATA);
        finish(scanner, slave, DN_RESULT_BAD_RESPONSE, 0, DN_AC_NONE, NULL, 0);
        break;
    case DN_FRAGMENT_RX_COMPLETE:
        send_ack(scanner, slave, rx->header, count, DN_FRAG_ACK_SUCCESS);
        response_complete(scanner, slave, rx->body, rx->len);
        break;
    case DN_FRAGMENT_RX_LOST:
        finish(scanner, slave, DN_RESULT_FRAGMENT_LOST, 0, DN_AC_NONE, NULL, 0);
        break;
    case DN_FRAGMENT_RX_IGNORED:
        break;
    }
}

/* The slave's answer on the CAN-ID of the request in progress (group 2 message 3, the UCMM's
 * group 3 message 5 or the slave's ID on the UCMM connection): only one addressed to this scanner
 * (the header's MAC ID is the other end's: the master's) with the XID of the request in progress.
 */
static void response_receive(dn_scanner_t *scanner, dn_slave_t *slave, const co_frame_t *frame)
{
    if (!slave->busy || frame->len < 2 ||
        (frame->data[0] & (DN_HDR_XID | DN_HDR_MAC)) != (slave->xid | scanner->config->mac_id))
        return;
    if (frame->data[0] & DN_HDR_FRAG)
        fragment_receive(scanner, slave, frame);
    else if (!slave->tx.active)
        response_complete(scanner, slave, &frame->data[1], (uint8_t)(frame->len - 1));
}

static co_time_t request_process(dn_scanner_t *scanner, dn_slave_t *slave)
{
    if (!slave->busy || scanner->now < slave->deadline)
        return slave->deadline;
    if (slave->tx.active && slave->tx.retries < FRAGMENT_RETRIES) {
        slave->tx.retries++;
        send_fragment(scanner, slave);
        return slave->deadline;
    }
    finish(scanner, slave, DN_RESULT_TIMEOUT, 0, DN_AC_NONE, NULL, 0);
    return slave->deadline; /* the callback may have started the next request */
}

void dn_scanner_abandon(dn_scanner_t *scanner, uint8_t mac_id)
{
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (slave == NULL)
        return;
    if (slave->recovering_request)
        slave->recovery = DN_RECOVERY_WAITING; /* the try starts over when due */
    slave->busy = false;
    slave->recovering_request = false;
    slave->tx.active = false;
    slave->rx.active = false;
    slave->deadline = CO_TIME_NEVER;
}

/* ---- I/O ------------------------------------------------------------------------------- */

static void io_report(dn_scanner_t *scanner, const dn_slave_t *slave, dn_io_kind_t kind,
                      const uint8_t *data, uint8_t len)
{
    const dn_scanner_app_t *app = scanner->config->app;
    if (app->io)
        app->io(app->user, slave->mac_id, kind, data, len);
}

bool dn_scanner_set_output(dn_scanner_t *scanner, uint8_t mac_id, const uint8_t *data, uint8_t len)
{
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (slave == NULL || len > sizeof(slave->output))
        return false;
    if (len)
        memcpy(slave->output, data, len);
    slave->output_len = len;
    return true;
}

static void connection_report(dn_scanner_t *scanner, const dn_slave_t *slave,
                              dn_connection_event_t event, const dn_result_t *result)
{
    const dn_scanner_app_t *app = scanner->config->app;
    if (app->connection)
        app->connection(app->user, slave->mac_id, event, result);
}

/* A kept connection whose polls went unanswered too often: polls stop, the first try is due. */
static void connection_lost(dn_scanner_t *scanner, dn_slave_t *slave)
{
    slave->recovery = DN_RECOVERY_WAITING;
    slave->tries = 0;
    slave->next_try = scanner->now;
    slave->lost++;
    connection_report(scanner, slave, DN_CONNECTION_LOST, NULL);
}

static void missed(dn_scanner_t *scanner, dn_slave_t *slave)
{
    slave->poll_deadline = CO_TIME_NEVER;
    slave->missed++;
    if (slave->missed_in_row < UINT8_MAX)
        slave->missed_in_row++;
    io_report(scanner, slave, DN_IO_POLL_MISSED, NULL, 0);
    if (slave->keep_choice && slave->recovery == DN_RECOVERY_NONE &&
        slave->missed_in_row >= DN_SCANNER_LOST_AFTER_MISSED)
        connection_lost(scanner, slave);
}

/* Polls go to an allocated polled connection that no try is re-establishing. */
static bool pollable(const dn_slave_t *slave)
{
    return (slave->allocated & DN_ALLOC_POLLED) && slave->recovery == DN_RECOVERY_NONE;
}

static void send_poll(dn_scanner_t *scanner, dn_slave_t *slave)
{
    if (slave->poll_deadline != CO_TIME_NEVER)
        missed(scanner, slave); /* the previous poll is still unanswered */
    if (!pollable(slave))
        return; /* that miss lost the connection */
    send_frame(scanner, slave->ids.poll_command, slave->output, slave->output_len);
    slave->polls++;
    slave->poll_deadline = scanner->now + scanner->timeout;
}

bool dn_scanner_poll(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now)
{
    scanner->now = now;
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (scanner->link != DN_SCANNER_ONLINE || slave == NULL || !pollable(slave))
        return false;
    send_poll(scanner, slave);
    return true;
}

bool dn_scanner_poll_every(dn_scanner_t *scanner, uint8_t mac_id, co_time_t period_us,
                           co_time_t now)
{
    scanner->now = now;
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (slave == NULL || (period_us && !(slave->allocated & DN_ALLOC_POLLED)))
        return false;
    slave->poll_period = period_us;
    slave->next_poll = period_us ? now : CO_TIME_NEVER;
    if (slave->recovering_request)
        dn_scanner_abandon(scanner, mac_id);
    slave->keep_choice = 0;
    slave->recovery = DN_RECOVERY_NONE;
    return true;
}

bool dn_scanner_keep_polling(dn_scanner_t *scanner, uint8_t mac_id, co_time_t period_us,
                             uint16_t rate_ms, co_time_t now)
{
    const uint8_t needed = DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED;
    dn_slave_t *slave = dn_scanner_slave(scanner, mac_id);
    if (slave == NULL || period_us == 0 || (slave->allocated & needed) != needed ||
        !dn_scanner_poll_every(scanner, mac_id, period_us, now))
        return false;
    slave->keep_choice = slave->allocated;
    slave->keep_rate_ms = rate_ms;
    slave->missed_in_row = 0;
    return true;
}

/* ---- re-establishing a kept polled connection (D-DEVICENET-RECONNECT) ---------------------- */

static bool start_recovery_step(dn_scanner_t *scanner, dn_slave_t *slave, dn_recovery_t step)
{
    bool started;
    uint8_t mac_id = slave->mac_id;
    co_time_t now = scanner->now;
    switch (step) {
    case DN_RECOVERY_RELEASE:
        started = dn_scanner_release(scanner, mac_id, slave->keep_choice, now);
        break;
    case DN_RECOVERY_ALLOCATE:
        started = dn_scanner_allocate(scanner, mac_id, slave->keep_choice, now);
        break;
    default:
        started = dn_scanner_set_expected_packet_rate(scanner, mac_id, DN_CONN_POLL,
                                                      slave->keep_rate_ms, now);
        break;
    }
    if (started) {
        slave->recovering_request = true;
        slave->recovery = step;
    }
    return started;
}

/* A try failed: the next one a second later, or, once the quick tries are spent (reported
 * once), ten seconds later. */
static void try_failed(dn_scanner_t *scanner, dn_slave_t *slave, const dn_result_t *result)
{
    slave->recovery = DN_RECOVERY_WAITING;
    if (slave->tries < DN_SCANNER_RECONNECT_TRIES) {
        slave->next_try = scanner->now + DN_SCANNER_RECONNECT_INTERVAL_US;
        return;
    }
    slave->next_try = scanner->now + DN_SCANNER_RECONNECT_SLOW_US;
    if (slave->tries == DN_SCANNER_RECONNECT_TRIES)
        connection_report(scanner, slave, DN_CONNECTION_FAILED, result);
}

/* The end of a step: the next step, the connection up again, or the try failed. */
static void recovery_result(dn_scanner_t *scanner, dn_slave_t *slave, const dn_result_t *result)
{
    if (result->status != DN_RESULT_OK) {
        try_failed(scanner, slave, result);
        return;
    }
    if (slave->recovery == DN_RECOVERY_RELEASE || slave->recovery == DN_RECOVERY_ALLOCATE) {
        dn_recovery_t next =
            slave->recovery == DN_RECOVERY_RELEASE ? DN_RECOVERY_ALLOCATE : DN_RECOVERY_RATE;
        if (!start_recovery_step(scanner, slave, next))
            try_failed(scanner, slave, result);
        return;
    }
    slave->recovery = DN_RECOVERY_NONE;
    slave->missed_in_row = 0;
    slave->restored++;
    connection_report(scanner, slave, DN_CONNECTION_RESTORED, NULL);
}

/* A try is due and the slave free of requests: its first step. */
static co_time_t recovery_process(dn_scanner_t *scanner, dn_slave_t *slave)
{
    if (slave->recovery != DN_RECOVERY_WAITING)
        return CO_TIME_NEVER;
    if (scanner->now < slave->next_try)
        return slave->next_try;
    if (slave->busy)
        return CO_TIME_NEVER; /* the application's request ends first: processed again then */
    if (slave->tries < UINT8_MAX)
        slave->tries++;
    start_recovery_step(scanner, slave, DN_RECOVERY_RELEASE);
    return CO_TIME_NEVER;
}

static co_time_t poll_process(dn_scanner_t *scanner, dn_slave_t *slave)
{
    if (scanner->now >= slave->poll_deadline)
        missed(scanner, slave);
    if (slave->poll_period && scanner->now >= slave->next_poll) {
        if (pollable(slave))
            send_poll(scanner, slave);
        /* the next period from the one due, so that a late call does not shift the schedule */
        slave->next_poll += slave->poll_period;
        if (slave->next_poll <= scanner->now)
            slave->next_poll = scanner->now + slave->poll_period;
    }
    return co_time_min(slave->poll_deadline, slave->poll_period ? slave->next_poll : CO_TIME_NEVER);
}

/* Group 1 from a slave: its poll response (message 0xF) or its COS/cyclic data (0xD), which
 * is acknowledged unless the allocation suppressed acknowledgements. */
static void io_receive(dn_scanner_t *scanner, dn_slave_t *slave, uint8_t message_id,
                       const co_frame_t *frame)
{
    if (message_id == DN_G1_SLAVE_POLL_RESPONSE && (slave->allocated & DN_ALLOC_POLLED)) {
        if (slave->poll_deadline == CO_TIME_NEVER) {
            slave->late++;
            io_report(scanner, slave, DN_IO_POLL_LATE, frame->data, frame->len);
            return;
        }
        slave->poll_deadline = CO_TIME_NEVER;
        slave->responses++;
        slave->missed_in_row = 0;
        io_report(scanner, slave, DN_IO_POLL_RESPONSE, frame->data, frame->len);
    } else if (message_id == DN_G1_SLAVE_COS_CYCLIC &&
               (slave->allocated & (DN_ALLOC_COS | DN_ALLOC_CYCLIC))) {
        if (!(slave->allocated & DN_ALLOC_ACK_SUPPRESSION))
            send_frame(scanner, slave->ids.cos_ack, NULL, 0);
        io_report(scanner, slave, DN_IO_COS_DATA, frame->data, frame->len);
    }
}

/* ---- frames and time ------------------------------------------------------------------- */

void dn_scanner_receive(dn_scanner_t *scanner, const co_frame_t *frame, co_time_t now)
{
    scanner->now = now;
    if (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF) || frame->len > CO_FRAME_DLC_MAX ||
        scanner->link == DN_SCANNER_OFF)
        return;
    dn_can_id_t id = dn_can_id_decode(frame->id);
    if (id.group == 2 && id.message_id == DN_G2_DUPLICATE_MAC_CHECK &&
        id.mac_id == scanner->config->mac_id) {
        duplicate_mac_receive(scanner, frame);
        return;
    }
    if (scanner->link != DN_SCANNER_ONLINE)
        return;
    dn_slave_t *slave = dn_scanner_slave(scanner, id.mac_id);
    if (slave == NULL)
        return;
    if (frame->id == slave->response_id)
        response_receive(scanner, slave, frame);
    else if (id.group == 1)
        io_receive(scanner, slave, id.message_id, frame);
}

co_time_t dn_scanner_process(dn_scanner_t *scanner, co_time_t now)
{
    scanner->now = now;
    link_process(scanner);
    if (scanner->link != DN_SCANNER_ONLINE)
        return scanner->link_deadline;
    co_time_t next = CO_TIME_NEVER;
    const dn_scanner_config_t *config = scanner->config;
    for (uint8_t i = 0; i < config->slave_count; i++) {
        dn_slave_t *slave = &config->slaves[i];
        next = co_time_min(next, request_process(scanner, slave));
        next = co_time_min(next, poll_process(scanner, slave));
        next = co_time_min(next, recovery_process(scanner, slave));
    }
    return next;
}
