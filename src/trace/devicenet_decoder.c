/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace's DeviceNet decoder (devicenet_decoder.h): identifiers by dn_link.h, services, classes
 * and status texts by cip_text.h, I/O data by the Altivar 312 card's assemblies. */
#include "trace/devicenet_decoder.h"

#include "co/co_cia402_master.h" /* co_cia402_state_name */
#include "trace/cip_assembly.h"
#include "trace/cip_text.h"
#include "trace/decoder.h" /* cotrace_control_word_command */
#include "trace/text.h"

#include <string.h>

/* Group 3 UCMM services (the slave library serves them, D-DEVICENET-UCMM) and the group 4
 * offline connection set (DeviceNet's public descriptions; not served). */
#define UCMM_OPEN_EXPLICIT 0x4Bu
#define UCMM_CLOSE 0x4Cu
#define G4_COMM_FAULT_RESPONSE 0x2Cu
#define G4_COMM_FAULT_REQUEST 0x2Du
#define G4_OFFLINE_OWNER_RESPONSE 0x2Eu
#define G4_OFFLINE_OWNER_REQUEST 0x2Fu

/* Connection class attributes selecting the I/O assemblies (the manual: 5/0/100 and 5/0/101). */
#define CONN_CLASS_CONSUMED_ASSEMBLY 100u
#define CONN_CLASS_PRODUCED_ASSEMBLY 101u
#define ASSEMBLY_DATA_ATTRIBUTE 3u
#define BODY_FORMAT_8_8 0u
/* The data of Allocate (the allocation choice, the allocator's MAC ID) and of Release (the
 * choice). */
#define ALLOCATE_DATA_LEN 2u
#define RELEASE_DATA_LEN 1u

typedef enum explicit_kind { EXPLICIT_REQUEST, UNCONNECTED_REQUEST, EXPLICIT_RESPONSE } kind_t;

/* ---- explicit messages ------------------------------------------------------------------- */

static void say_service(text_t *t, uint8_t service)
{
    const char *name = cip_service_name(service);
    if (name)
        say(t, "%s", name);
    else
        say(t, "service 0x%02X", service & DN_SERVICE_CODE);
}

static void say_request(text_t *t, const cotrace_dn_request_t *rq)
{
    say_service(t, rq->service);
    const char *name = cip_class_name(rq->class_id);
    if (name)
        say(t, " %s (0x%02X)", name, rq->class_id);
    else
        say(t, " class 0x%02X", rq->class_id);
    say(t, " instance %u", rq->instance);
    if (rq->has_attribute)
        say(t, " attribute %u", rq->attribute);
}

static void say_choice(text_t *t, uint8_t choice)
{
    static const struct {
        uint8_t bit;
        const char *name;
    } bits[] = {{DN_ALLOC_EXPLICIT, "explicit"},
                {DN_ALLOC_POLLED, "polled"},
                {DN_ALLOC_BIT_STROBE, "bit-strobe"},
                {DN_ALLOC_MULTICAST_POLL, "multicast poll"},
                {DN_ALLOC_COS, "change of state"},
                {DN_ALLOC_CYCLIC, "cyclic"},
                {DN_ALLOC_ACK_SUPPRESSION, "acknowledge suppression"},
                {0x80, "reserved"}};
    say(t, "choice 0x%02X", choice);
    const char *sep = " (";
    for (size_t i = 0; i < sizeof bits / sizeof bits[0]; i++) {
        if (choice & bits[i].bit) {
            say(t, "%s%s", sep, bits[i].name);
            sep = ", ";
        }
    }
    if (choice)
        say(t, ")");
}

/* I/O data by the card's assemblies (cip_assembly.h): the bits set, the Control supervisor's
 * state, the speeds in rpm and the DRIVECOM words with their meaning. */
static void say_assembly(text_t *t, uint16_t instance, const uint8_t *data, size_t len)
{
    const cip_assembly_t *assembly = cip_assembly(instance);
    say(t, "assembly %u", instance);
    if (!assembly || len != CIP_ASSEMBLY_SIZE) {
        if (assembly)
            say(t, " (%u bytes) does not fit %zu bytes", CIP_ASSEMBLY_SIZE, len);
        say(t, ": ");
        say_bytes(t, data, len);
        return;
    }
    const char *sep = ": ";
    for (uint8_t i = 0; i < assembly->field_count; i++) {
        const cip_field_t *f = &assembly->fields[i];
        int32_t value = cip_field_get(f, data);
        const char *meaning = NULL;
        switch (f->kind) {
        case CIP_FIELD_BIT:
            if (!value)
                continue;
            say(t, "%s%s", sep, f->name);
            break;
        case CIP_FIELD_STATE:
            say(t, "%s%s %d %s", sep, f->name, (int)value,
                cip_supervisor_state_name((uint8_t)value));
            break;
        case CIP_FIELD_RPM:
            say(t, "%s%s %d rpm", sep, f->name, (int)value);
            break;
        case CIP_FIELD_CONTROL_WORD:
        case CIP_FIELD_STATUS_WORD:
            meaning = f->kind == CIP_FIELD_CONTROL_WORD
                          ? cotrace_control_word_command((uint16_t)value)
                          : co_cia402_state_name(co_cia402_state((uint16_t)value));
            say(t, "%s%s 0x%04X%s%s", sep, f->name, (unsigned)value, meaning ? " " : "",
                meaning ? meaning : "");
            break;
        }
        sep = ", ";
    }
}

/* An attribute's value: an assembly's data by its instance, a SHORT_STRING as text, else the
 * bytes (with the little-endian number of 1..4 bytes). */
static void say_attribute_value(text_t *t, const cotrace_dn_request_t *rq, const uint8_t *data,
                                size_t len)
{
    if (rq && rq->class_id == DN_CLASS_ASSEMBLY && rq->instance != 0 &&
        rq->attribute == ASSEMBLY_DATA_ATTRIBUTE) {
        say_assembly(t, rq->instance, data, len);
        return;
    }
    bool short_string = len >= 2 && data[0] == len - 1;
    for (size_t i = 1; short_string && i < len; i++)
        short_string = data[i] >= 0x20 && data[i] <= 0x7E;
    if (short_string)
        say(t, "\"%.*s\"", (int)(len - 1), (const char *)&data[1]);
    else
        say_value(t, data, len, len);
}

static void request_body(cotrace_dn_node_t *n, const uint8_t *body, size_t len, text_t *t)
{
    cotrace_dn_request_t *rq = &n->last;
    memset(rq, 0, sizeof *rq);
    uint8_t service = body[0];
    bool attribute =
        service == DN_SVC_GET_ATTRIBUTE_SINGLE || service == DN_SVC_SET_ATTRIBUTE_SINGLE;
    size_t path = attribute ? 4u : 3u;
    if (len < path) {
        say_service(t, service);
        say(t, ", path cut short: ");
        say_bytes(t, &body[1], len - 1);
        return;
    }
    rq->valid = true;
    rq->service = service;
    rq->class_id = body[1];
    rq->instance = body[2];
    rq->has_attribute = attribute;
    rq->attribute = attribute ? body[3] : 0;
    const uint8_t *data = &body[path];
    size_t dlen = len - path;
    rq->len = (uint8_t)dlen;
    memcpy(rq->data, data, dlen < sizeof rq->data ? dlen : sizeof rq->data);
    say_request(t, rq);
    if (service == DN_SVC_ALLOCATE && dlen == ALLOCATE_DATA_LEN) {
        say(t, ", ");
        say_choice(t, data[0]);
        say(t, ", allocator %u", data[1]);
    } else if (service == DN_SVC_RELEASE && dlen == RELEASE_DATA_LEN) {
        say(t, ", ");
        say_choice(t, data[0]);
    } else if (dlen) {
        say(t, " = ");
        say_attribute_value(t, rq, data, dlen);
    }
}

/* A Connection class attribute 100/101 as a Set carried it or a Get answered it: the stored
 * selection, used after a restart. */
static void note_selection(cotrace_dn_node_t *n, const cotrace_dn_request_t *rq,
                           const uint8_t *value, size_t len)
{
    if (rq->class_id != DN_CLASS_CONNECTION || rq->instance != 0 || len != 2)
        return;
    if (rq->attribute == CONN_CLASS_CONSUMED_ASSEMBLY)
        n->stored_consumed = co_get_u16(value);
    else if (rq->attribute == CONN_CLASS_PRODUCED_ASSEMBLY)
        n->stored_produced = co_get_u16(value);
}

/* What a success response changes of what the trace knows of the slave: only what a request of
 * the service's form asked for (a choice and the allocator's MAC ID for Allocate, a choice for
 * Release, a UINT for a Set of an assembly selection), which its line showed as such; the slave
 * library refuses any other length (src/devicenet/slave/connection.c). */
static void apply_success(cotrace_dn_node_t *n, const cotrace_dn_request_t *rq, const uint8_t *data,
                          size_t len)
{
    switch (rq->service) {
    case DN_SVC_ALLOCATE:
        if (rq->len == ALLOCATE_DATA_LEN)
            n->allocation |= rq->data[0];
        return;
    case DN_SVC_RELEASE:
        if (rq->len == RELEASE_DATA_LEN)
            n->allocation &= (uint8_t)~rq->data[0];
        return;
    case DN_SVC_SET_ATTRIBUTE_SINGLE:
        note_selection(n, rq, rq->data, rq->len);
        return;
    case DN_SVC_GET_ATTRIBUTE_SINGLE:
        note_selection(n, rq, data, len);
        return;
    default:
        return;
    }
}

static void response_body(cotrace_dn_node_t *n, const uint8_t *body, size_t len, text_t *t)
{
    cotrace_dn_request_t *rq = &n->last;
    uint8_t service = body[0] & DN_SERVICE_CODE;
    const uint8_t *data = &body[1];
    size_t dlen = len - 1;
    if (service == DN_SVC_ERROR_RESPONSE) {
        if (rq->valid) {
            say_request(t, rq);
            say(t, ": ");
        }
        if (dlen == 0) {
            say(t, "error response without a status");
        } else {
            say(t, "error 0x%02X %s", data[0], cip_general_status_text(data[0]));
            if (dlen > 1)
                say(t, ", additional code 0x%02X", data[1]);
        }
        rq->valid = false;
        return;
    }
    bool answers = rq->valid && rq->service == service;
    if (answers) {
        say_request(t, rq);
        apply_success(n, rq, data, dlen);
    } else {
        say_service(t, service);
    }
    rq->valid = false;
    if (service == DN_SVC_GET_ATTRIBUTE_SINGLE && dlen) {
        say(t, " = ");
        say_attribute_value(t, answers ? rq : NULL, data, dlen);
    } else if (service == DN_SVC_ALLOCATE && dlen == 1) {
        if (data[0] == BODY_FORMAT_8_8)
            say(t, ": message body format 8/8");
        else
            say(t, ": message body format 0x%02X", data[0]);
    } else {
        say(t, ": done");
        if (dlen) {
            say(t, ", answered ");
            say_value(t, data, dlen, dlen);
        }
    }
}

/* The master's identifiers carry its requests, the slave's its responses; the service code's
 * response bit says which a body is. A body of the other kind is said as it is and changes nothing
 * the trace knows: a response on the master's identifier is no answer of the slave's. */
static void message_body(cotrace_dn_node_t *n, kind_t kind, const uint8_t *body, size_t len,
                         text_t *t)
{
    bool response = body[0] & DN_SERVICE_RESPONSE;
    if (response != (kind == EXPLICIT_RESPONSE)) {
        say_service(t, body[0] & DN_SERVICE_CODE);
        say(t,
            response ? " response on a request identifier" : " request on a response identifier");
        if (len > 1) {
            say(t, ": ");
            say_bytes(t, &body[1], len - 1);
        }
    } else if (response) {
        response_body(n, body, len, t);
    } else {
        request_body(n, body, len, t);
    }
}

static const char *fragment_type_name(uint8_t type)
{
    return type == DN_FRAG_FIRST ? "first" : type == DN_FRAG_MIDDLE ? "middle" : "last";
}

/* A fragment of an explicit message (either direction), or an acknowledgement of one; the
 * message is reassembled by the slave's and scanner's own rules (dn_fragment.h) and decoded
 * whole at its last fragment. */
static void fragment(cotrace_dn_node_t *n, kind_t kind, const struct can_frame *f, text_t *t)
{
    dn_fragments_t *m = kind == EXPLICIT_RESPONSE ? &n->response : &n->request;
    uint8_t type = f->data[1] & DN_FRAG_TYPE;
    uint8_t count = f->data[1] & DN_FRAG_COUNT;
    if (type == DN_FRAG_ACK) {
        uint8_t status = f->len > 2 ? f->data[2] : DN_FRAG_ACK_SUCCESS;
        say(t, "fragment %u acknowledged: ", count);
        if (status == DN_FRAG_ACK_SUCCESS)
            say(t, "success");
        else if (status == DN_FRAG_ACK_TOO_MUCH_DATA)
            say(t, "too much data");
        else
            say(t, "status 0x%02X", status);
        return;
    }
    uint8_t chunk = (uint8_t)(f->len - 2u);
    uint8_t previous = m->count;
    say(t, "fragment %u (%s)", count, fragment_type_name(type));
    switch (dn_fragment_receive(m, f->data, f->len)) {
    case DN_FRAGMENT_RX_IGNORED:
        say(t, " without a first fragment: ");
        say_bytes(t, &f->data[2], chunk);
        return;
    case DN_FRAGMENT_RX_REPEATED:
        say(t, " repeated");
        return;
    case DN_FRAGMENT_RX_LOST:
        say(t, " out of sequence after %u: message dropped", previous);
        return;
    case DN_FRAGMENT_RX_TOO_MUCH:
        say(t, ": more than %u bytes, message dropped", DN_MESSAGE_MAX);
        return;
    case DN_FRAGMENT_RX_TAKEN:
        say(t, ", %u bytes", chunk);
        return;
    case DN_FRAGMENT_RX_COMPLETE:
        break;
    }
    say(t, ", %u bytes, message of %u bytes: ", chunk, m->len);
    if (m->len == 0)
        say(t, "empty");
    else
        message_body(n, kind, m->body, m->len, t);
}

static void explicit_frame(cotrace_dn_node_t *n, const struct can_frame *f, kind_t kind, text_t *t)
{
    static const char *const names[] = {"explicit request from", "unconnected request from",
                                        "explicit response to"};
    if (f->len < 2) {
        say(t, "%s ?: malformed: %u bytes, an explicit message has a header and a service",
            names[kind], f->len);
        return;
    }
    say(t, "%s %u: ", names[kind], f->data[0] & DN_HDR_MAC);
    if (f->data[0] & DN_HDR_FRAG) {
        fragment(n, kind, f, t);
        return;
    }
    message_body(n, kind, &f->data[1], f->len - 1u, t);
}

/* ---- link: duplicate MAC ID check -------------------------------------------------------- */

/* A node's check request is its start: the connections are gone, and a stored assembly
 * selection is now in use. */
static void node_restarts(cotrace_dn_node_t *n)
{
    n->allocation = 0;
    n->consumed = n->stored_consumed;
    n->produced = n->stored_produced;
    memset(&n->request, 0, sizeof n->request);
    memset(&n->response, 0, sizeof n->response);
    memset(&n->last, 0, sizeof n->last);
}

static void duplicate_mac_check(cotrace_dn_node_t *n, const struct can_frame *f, text_t *t)
{
    if (f->len != DN_DUP_MAC_LEN) {
        say(t, "duplicate MAC ID check malformed: %u bytes, it has %u", f->len, DN_DUP_MAC_LEN);
        return;
    }
    bool response = f->data[0] & DN_DUP_MAC_RESPONSE;
    if (!response)
        node_restarts(n);
    say(t, "duplicate MAC ID check %s, port %u, vendor 0x%04X, serial number 0x%08lX",
        response ? "response" : "request", f->data[0] & (uint8_t)~DN_DUP_MAC_RESPONSE,
        co_get_u16(&f->data[1]), (unsigned long)co_get_u32(&f->data[3]));
}

/* ---- I/O --------------------------------------------------------------------------------- */

static bool cos_without_poll(const cotrace_dn_node_t *n)
{
    return !(n->allocation & DN_ALLOC_POLLED) && n->allocation & (DN_ALLOC_COS | DN_ALLOC_CYCLIC);
}

static const char *production_name(const cotrace_dn_node_t *n)
{
    if (n->allocation & DN_ALLOC_COS)
        return "COS data";
    if (n->allocation & DN_ALLOC_CYCLIC)
        return "cyclic data";
    return "COS/cyclic data";
}

static void say_io(text_t *t, uint16_t assembly, const struct can_frame *f)
{
    if (f->len == 0)
        say(t, "no data (idle)");
    else
        say_assembly(t, assembly, f->data, f->len);
}

/* Group 2 message 5: the poll command, or with COS/cyclic and no poll the master's data. */
static void master_io(const cotrace_dn_node_t *n, const struct can_frame *f, text_t *t)
{
    say(t, "%s: ", cos_without_poll(n) ? production_name(n) : "poll command");
    say_io(t, n->consumed, f);
}

/* Group 1 message 0xF: the poll response, or the slave's acknowledgement of the master's
 * COS/cyclic data. */
static void slave_poll_response(const cotrace_dn_node_t *n, const struct can_frame *f, text_t *t)
{
    if (cos_without_poll(n) && f->len == 0) {
        say(t, "COS/cyclic acknowledge");
        return;
    }
    say(t, "poll response: ");
    say_io(t, n->produced, f);
}

static void say_data(text_t *t, const char *what, const struct can_frame *f)
{
    say(t, "%s", what);
    if (f->len) {
        say(t, ": ");
        say_bytes(t, f->data, f->len);
    }
}

/* ---- groups ------------------------------------------------------------------------------ */

static void group1(cotrace_dn_node_t *n, dn_can_id_t id, const struct can_frame *f, text_t *t)
{
    switch (id.message_id) {
    case DN_G1_SLAVE_POLL_RESPONSE:
        slave_poll_response(n, f, t);
        return;
    case DN_G1_SLAVE_COS_CYCLIC:
        say(t, "%s: ", production_name(n));
        say_io(t, n->produced, f);
        return;
    case DN_G1_SLAVE_BIT_STROBE_RESPONSE:
        say_data(t, "bit-strobe response", f);
        return;
    case DN_G1_SLAVE_MULTICAST_POLL_RESPONSE:
        say_data(t, "multicast poll response", f);
        return;
    default:
        say_data(t, "not in the predefined master/slave connection set", f);
        return;
    }
}

static void group2(cotrace_dn_node_t *n, dn_can_id_t id, const struct can_frame *f, text_t *t)
{
    switch (id.message_id) {
    case DN_G2_MASTER_BIT_STROBE:
        say_data(t, "bit-strobe command", f);
        return;
    case DN_G2_MASTER_MULTICAST_POLL:
        say_data(t, "multicast poll command", f);
        return;
    case DN_G2_MASTER_COS_CYCLIC_ACK:
        say_data(t, "COS/cyclic acknowledge", f);
        return;
    case DN_G2_SLAVE_EXPLICIT_RESPONSE:
        explicit_frame(n, f, EXPLICIT_RESPONSE, t);
        return;
    case DN_G2_MASTER_EXPLICIT_REQUEST:
        explicit_frame(n, f, EXPLICIT_REQUEST, t);
        return;
    case DN_G2_MASTER_POLL_COS_CYCLIC:
        master_io(n, f, t);
        return;
    case DN_G2_UNCONNECTED_REQUEST:
        explicit_frame(n, f, UNCONNECTED_REQUEST, t);
        return;
    default:
        duplicate_mac_check(n, f, t);
        return;
    }
}

/* The data of the UCMM's Open and Close: the request's body format, group and the client's
 * message ID; the response's body format, the two message IDs and the connection instance; the
 * instance Close names. */
static void say_ucmm_data(text_t *t, uint8_t service, bool response, const uint8_t *data,
                          size_t len)
{
    if (service == UCMM_OPEN_EXPLICIT && !response && len == 2) {
        say(t, ": body format %u, group %u, source message ID %u", data[0] & DN_UCMM_BODY_FORMAT,
            data[1] >> DN_UCMM_GROUP_SHIFT, data[1] & DN_UCMM_MESSAGE_ID);
    } else if (service == UCMM_OPEN_EXPLICIT && response && len == 4) {
        say(t, ": body format %u, destination message ID %u, source message ID %u, instance %u",
            data[0] & DN_UCMM_BODY_FORMAT, data[1] >> DN_UCMM_GROUP_SHIFT,
            data[1] & DN_UCMM_MESSAGE_ID, co_get_u16(&data[2]));
    } else if (service == UCMM_CLOSE && !response && len == 2) {
        say(t, ": instance %u", co_get_u16(data));
    } else if (service == DN_SVC_ERROR_RESPONSE && len >= 1) {
        say(t, ": 0x%02X %s", data[0], cip_general_status_text(data[0]));
    } else if (len) {
        say(t, ": ");
        say_bytes(t, data, len);
    }
}

/* Group 3 messages 5 and 6: the UCMM's requests and responses (open and close an explicit
 * connection). */
static void ucmm(dn_can_id_t id, const struct can_frame *f, text_t *t)
{
    bool request = id.message_id == DN_G3_UNCONNECTED_REQUEST;
    if (f->len < 2) {
        say_data(t, request ? "UCMM request, malformed" : "UCMM response, malformed", f);
        return;
    }
    say(t, "UCMM %s %u: ", request ? "request to" : "response to", f->data[0] & DN_HDR_MAC);
    uint8_t service = f->data[1] & DN_SERVICE_CODE;
    bool response = f->data[1] & DN_SERVICE_RESPONSE;
    if (service == UCMM_OPEN_EXPLICIT)
        say(t, "Open Explicit Messaging Connection");
    else if (service == UCMM_CLOSE)
        say(t, "Close Connection");
    else
        say_service(t, service);
    say(t, response ? " response" : " request");
    say_ucmm_data(t, service, response, &f->data[2], f->len - 2u);
}

/* Group 3 messages 0-4: an explicit message on a connection the UCMM opened. Its header names
 * the other end (the server of a request, the client of a response); the service's
 * request/response bit tells which, and the server's record names what a response answers. */
static void group3(cotrace_dn_decoder_t *dec, dn_can_id_t id, const struct can_frame *f, text_t *t)
{
    if (id.message_id == DN_G3_UNCONNECTED_REQUEST || id.message_id == DN_G3_UNCONNECTED_RESPONSE) {
        ucmm(id, f, t);
        return;
    }
    if (f->len < 2 || f->data[0] & DN_HDR_FRAG) {
        say_data(t, "UCMM connection message", f);
        return;
    }
    uint8_t other = f->data[0] & DN_HDR_MAC;
    bool response = f->data[1] & DN_SERVICE_RESPONSE;
    say(t, "UCMM connection %s %u: ", response ? "response to" : "request to", other);
    cotrace_dn_node_t *server = &dec->node[response ? id.mac_id : other];
    message_body(server, response ? EXPLICIT_RESPONSE : EXPLICIT_REQUEST, &f->data[1], f->len - 1u,
                 t);
}

static void group4(dn_can_id_t id, const struct can_frame *f, text_t *t)
{
    switch (id.message_id) {
    case G4_COMM_FAULT_RESPONSE:
        say_data(t, "communication faulted response", f);
        return;
    case G4_COMM_FAULT_REQUEST:
        say_data(t, "communication faulted request", f);
        return;
    case G4_OFFLINE_OWNER_RESPONSE:
        say_data(t, "offline ownership response", f);
        return;
    case G4_OFFLINE_OWNER_REQUEST:
        say_data(t, "offline ownership request", f);
        return;
    default:
        say_data(t, "reserved", f);
        return;
    }
}

/* Whose MAC ID the identifier carries: the sender's in groups 1 and 3 and in group 2's
 * bit-strobe, multicast poll, response and check messages, the slave's (the destination) in
 * the master's group 2 messages. */
static const char *mac_role(dn_can_id_t id)
{
    if (id.group != 2)
        return "from";
    switch (id.message_id) {
    case DN_G2_MASTER_COS_CYCLIC_ACK:
    case DN_G2_MASTER_EXPLICIT_REQUEST:
    case DN_G2_MASTER_POLL_COS_CYCLIC:
    case DN_G2_UNCONNECTED_REQUEST:
        return "to";
    default:
        return "from";
    }
}

void cotrace_dn_decode(cotrace_dn_decoder_t *dec, const struct can_frame *f, char *out, size_t cap)
{
    text_t t;
    if (!say_start(&t, out, cap, f, "DeviceNet"))
        return;
    uint32_t can_id = f->can_id & CAN_SFF_MASK;
    if (f->can_id & CAN_RTR_FLAG) {
        say(&t, "remote frame 0x%03lX: DeviceNet has none", (unsigned long)can_id);
        return;
    }
    dn_can_id_t id = dn_can_id_decode(can_id);
    if (id.group == 0) {
        say(&t, "identifier 0x%03lX: invalid in DeviceNet", (unsigned long)can_id);
        return;
    }
    if (id.group == 4) {
        say(&t, "G4 msg %u: ", id.message_id);
        group4(id, f, &t);
        return;
    }
    say(&t, "G%u msg %u %s %u: ", id.group, id.message_id, mac_role(id), id.mac_id);
    cotrace_dn_node_t *n = &dec->node[id.mac_id];
    if (id.group == 1)
        group1(n, id, f, &t);
    else if (id.group == 2)
        group2(n, id, f, &t);
    else
        group3(dec, id, f, &t);
}

void cotrace_dn_decoder_init(cotrace_dn_decoder_t *dec, uint16_t consumed, uint16_t produced)
{
    memset(dec, 0, sizeof *dec);
    for (size_t i = 0; i <= DN_MAC_ID_MAX; i++) {
        cotrace_dn_node_t *n = &dec->node[i];
        n->consumed = n->stored_consumed = consumed ? consumed : COTRACE_DN_CONSUMED_DEFAULT;
        n->produced = n->stored_produced = produced ? produced : COTRACE_DN_PRODUCED_DEFAULT;
    }
}
