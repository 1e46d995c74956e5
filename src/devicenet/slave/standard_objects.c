/* SPDX-License-Identifier: Apache-2.0 */
/* The library's CIP objects as the Altivar 312 DeviceNet manual lists them: Identity (0x01) with
 * its status word, Message router (0x02), DeviceNet (0x03), Assembly (0x04), Acknowledge handler
 * (0x2B), and the table of the Connection object (0x05), whose handler is in connection.c; the
 * registry of these classes that the message router searches first. */
#include "devicenet/slave/dn_slave.h"

#define IDENTITY_REVISION 1u
#define DEVICENET_REVISION 2u
#define ASSEMBLY_REVISION 2u
#define ACK_HANDLER_REVISION 1u

#define ATTR_REVISION 1u
#define ASSEMBLY_ATTR_MAX_INSTANCE 2u
#define ASSEMBLY_ATTR_DATA 3u
#define IDENTITY_ATTR_FATAL_LOG 100u
#define IDENTITY_RESET_OUT_OF_BOX 1u

/* Identity: class revision; vendor, device type, product code, revision, status, serial number,
 * product name, fatal log. */
static const dn_attribute_t identity_attributes[] = {
    {0, ATTR_REVISION, DN_GET, 0},
    {1, 1, DN_GET, 0},
    {1, 2, DN_GET, 0},
    {1, 3, DN_GET, 0},
    {1, 4, DN_GET, 0},
    {1, 5, DN_GET, 0},
    {1, 6, DN_GET, 0},
    {1, 7, DN_GET, 0},
    {1, IDENTITY_ATTR_FATAL_LOG, DN_GET, 0},
};

static dn_status_t identity_reset(dn_node_t *node, const dn_request_t *request)
{
    if (request->instance == 0)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->len > 1)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    uint8_t type = request->len ? request->data[0] : 0;
    if (type > IDENTITY_RESET_OUT_OF_BOX)
        return DN_ERROR(DN_GS_INVALID_PARAMETER);
    node->pending_reset = type;
    return DN_OK;
}

/* The Identity status's extended device status (bits 4-7): the I/O connections' state. */
static uint16_t extended_status(const dn_node_t *node)
{
    if (dn_io_in_state(node, DN_CONN_TIMED_OUT))
        return DN_EXT_FAULTED_IO;
    if (dn_io_in_state(node, DN_CONN_ESTABLISHED))
        return node->idle ? DN_EXT_IDLE : DN_EXT_RUN;
    return DN_EXT_NO_IO;
}

uint16_t dn_node_identity_status(const dn_node_t *node)
{
    const dn_config_t *config = node->config;
    uint16_t status = node->faults;
    if (node->allocation)
        status |= DN_STATUS_OWNED;
    if (config->configured || node->stored.quick_connect ||
        node->stored.consumed_assembly != config->default_consumed_assembly ||
        node->stored.produced_assembly != config->default_produced_assembly)
        status |= DN_STATUS_CONFIGURED;
    status |= (uint16_t)(extended_status(node) << DN_STATUS_EXTENDED_SHIFT);
    if (node->duplicate_mac || config->mac_switch_changed || config->baud_switch_changed)
        status |= DN_STATUS_MINOR_RECOVERABLE;
    return status;
}

static dn_status_t identity_handler(dn_node_t *node, const dn_object_t *object,
                                    const dn_request_t *request, dn_reply_t *reply)
{
    (void)object;
    if (request->service == DN_SVC_RESET)
        return identity_reset(node, request);
    if (request->service != DN_SVC_GET_ATTRIBUTE_SINGLE)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    const dn_config_t *config = node->config;
    if (request->instance == 0) {
        dn_reply_u16(reply, IDENTITY_REVISION);
        return DN_OK;
    }
    switch (request->attribute) {
    case 1:
        dn_reply_u16(reply, config->vendor_id);
        break;
    case 2:
        dn_reply_u16(reply, config->device_type);
        break;
    case 3:
        dn_reply_u16(reply, config->product_code);
        break;
    case 4:
        dn_reply_u8(reply, config->major_revision);
        dn_reply_u8(reply, config->minor_revision);
        break;
    case 5:
        dn_reply_u16(reply, dn_node_identity_status(node));
        break;
    case 6:
        dn_reply_u32(reply, config->serial_number);
        break;
    case 7:
        dn_reply_short_string(reply, config->product_name);
        break;
    default: /* the fatal log: empty, the emulation has no fatal events */
        break;
    }
    return DN_OK;
}

/* Message router: no services, no attributes (the manual's table). */
static dn_status_t message_router_handler(dn_node_t *node, const dn_object_t *object,
                                          const dn_request_t *request, dn_reply_t *reply)
{
    (void)node, (void)object, (void)request, (void)reply;
    return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
}

/* DeviceNet: class revision; MAC ID, baud rate, BOI, bus-off counter, allocation information,
 * switch changed flags, switch values, quick connect. */
#define DEVICENET_ATTR_BOI 3u
#define DEVICENET_ATTR_BUS_OFF_COUNTER 4u
#define DEVICENET_ATTR_QUICK_CONNECT 10u

static const dn_attribute_t devicenet_attributes[] = {
    {0, ATTR_REVISION, DN_GET, 0},
    {1, 1, DN_GET, 0},
    {1, 2, DN_GET, 0},
    {1, DEVICENET_ATTR_BOI, DN_GET_SET, 1},
    {1, DEVICENET_ATTR_BUS_OFF_COUNTER, DN_GET_SET, 1},
    {1, 5, DN_GET, 0},
    {1, 6, DN_GET, 0},
    {1, 7, DN_GET, 0},
    {1, 8, DN_GET, 0},
    {1, 9, DN_GET, 0},
    {1, DEVICENET_ATTR_QUICK_CONNECT, DN_GET_SET, 1},
};

static dn_status_t devicenet_get(dn_node_t *node, uint8_t attribute, dn_reply_t *reply)
{
    const dn_config_t *config = node->config;
    switch (attribute) {
    case 1:
        dn_reply_u8(reply, config->mac_id);
        break;
    case 2:
        dn_reply_u8(reply, config->baud_rate);
        break;
    case DEVICENET_ATTR_BOI:
        dn_reply_u8(reply, node->bus_off_interrupt);
        break;
    case DEVICENET_ATTR_BUS_OFF_COUNTER:
        dn_reply_u8(reply, node->bus_off_counter);
        break;
    case 5:
        dn_reply_u8(reply, node->allocation);
        dn_reply_u8(reply, node->master_mac);
        break;
    case 6:
        dn_reply_u8(reply, config->mac_switch_changed);
        break;
    case 7:
        dn_reply_u8(reply, config->baud_switch_changed);
        break;
    case 8:
        dn_reply_u8(reply, config->mac_switch);
        break;
    case 9:
        dn_reply_u8(reply, config->baud_switch);
        break;
    default:
        dn_reply_u8(reply, node->stored.quick_connect);
        break;
    }
    return DN_OK;
}

static dn_status_t devicenet_set(dn_node_t *node, const dn_request_t *request)
{
    uint8_t value = request->data[0];
    if (request->attribute == DEVICENET_ATTR_BUS_OFF_COUNTER) {
        node->bus_off_counter = 0; /* any value written clears the counter */
        return DN_OK;
    }
    if (value > 1)
        return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
    if (request->attribute == DEVICENET_ATTR_BOI) {
        node->bus_off_interrupt = value;
        return DN_OK;
    }
    dn_stored_t stored = node->stored;
    stored.quick_connect = value;
    return dn_store(node, &stored);
}

static dn_status_t devicenet_handler(dn_node_t *node, const dn_object_t *object,
                                     const dn_request_t *request, dn_reply_t *reply)
{
    (void)object;
    bool instance = request->instance != 0;
    switch (request->service) {
    case DN_SVC_GET_ATTRIBUTE_SINGLE:
        if (!instance) {
            dn_reply_u16(reply, DEVICENET_REVISION);
            return DN_OK;
        }
        return devicenet_get(node, request->attribute, reply);
    case DN_SVC_SET_ATTRIBUTE_SINGLE:
        return devicenet_set(node, request);
    case DN_SVC_ALLOCATE:
        return instance ? dn_allocate(node, request, reply) : DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    case DN_SVC_RELEASE:
        return instance ? dn_release(node, request) : DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    default:
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    }
}

/* Assembly: class revision and highest instance; attribute 3, the data, of every instance. */
static const dn_attribute_t assembly_attributes[] = {
    {0, ATTR_REVISION, DN_GET, 0},
    {0, ASSEMBLY_ATTR_MAX_INSTANCE, DN_GET, 0},
    {DN_EVERY_INSTANCE, ASSEMBLY_ATTR_DATA, DN_GET_SET, 0},
};

static uint16_t highest_assembly(const dn_config_t *config)
{
    uint16_t highest = 0;
    for (uint8_t i = 0; i < config->assembly_count; i++)
        if (config->assemblies[i].instance > highest)
            highest = config->assemblies[i].instance;
    return highest;
}

/* A Set of a produced assembly is refused (the drive's data), and of the consumed assembly while
 * an I/O connection consumes it (the manual: "rejected if there's an I/O connection"). */
static dn_status_t assembly_set(dn_node_t *node, const dn_assembly_t *assembly,
                                const dn_request_t *request)
{
    if (assembly->produced)
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
    if (request->len < assembly->size)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (request->len > assembly->size)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    if (assembly->instance == node->consumed_assembly && dn_io_consuming(node))
        return DN_ERROR(DN_GS_OBJECT_STATE_CONFLICT);
    const dn_app_t *app = node->config->app;
    app->write_assembly(app->user, assembly->instance, request->data);
    return DN_OK;
}

static dn_status_t assembly_handler(dn_node_t *node, const dn_object_t *object,
                                    const dn_request_t *request, dn_reply_t *reply)
{
    (void)object;
    bool get = request->service == DN_SVC_GET_ATTRIBUTE_SINGLE;
    if (!get && request->service != DN_SVC_SET_ATTRIBUTE_SINGLE)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0) {
        if (request->attribute == ATTR_REVISION)
            dn_reply_u16(reply, ASSEMBLY_REVISION);
        else
            dn_reply_u16(reply, highest_assembly(node->config));
        return DN_OK;
    }
    const dn_assembly_t *assembly = dn_node_assembly(node, request->instance);
    if (assembly == NULL)
        return DN_ERROR(DN_GS_OBJECT_DOES_NOT_EXIST);
    if (!get)
        return assembly_set(node, assembly, request);
    uint8_t data[DN_IO_MAX];
    const dn_app_t *app = node->config->app;
    app->read_assembly(app->user, assembly->instance, data);
    dn_reply_bytes(reply, data, assembly->size);
    return DN_OK;
}

/* Connection: class revision and the stored assembly selection (100 consumed, 101 produced);
 * the predefined set's instance attributes (connection.c answers them). */
static const dn_attribute_t connection_attributes[] = {
    {0, ATTR_REVISION, DN_GET, 0},
    {0, 100, DN_GET_SET, 2},
    {0, 101, DN_GET_SET, 2},
    {DN_EVERY_INSTANCE, 1, DN_GET, 0},
    {DN_EVERY_INSTANCE, 2, DN_GET, 0},
    {DN_EVERY_INSTANCE, 3, DN_GET, 0},
    {DN_EVERY_INSTANCE, 4, DN_GET, 0},
    {DN_EVERY_INSTANCE, 5, DN_GET, 0},
    {DN_EVERY_INSTANCE, 6, DN_GET, 0},
    {DN_EVERY_INSTANCE, 7, DN_GET, 0},
    {DN_EVERY_INSTANCE, 8, DN_GET, 0},
    {DN_EVERY_INSTANCE, 9, DN_GET_SET, 2},
    {DN_EVERY_INSTANCE, 12, DN_GET_SET, 1},
    {DN_EVERY_INSTANCE, 13, DN_GET, 0},
    {DN_EVERY_INSTANCE, 14, DN_GET, 0},
    {DN_EVERY_INSTANCE, 15, DN_GET, 0},
    {DN_EVERY_INSTANCE, 16, DN_GET, 0},
    {DN_EVERY_INSTANCE, 17, DN_GET_SET, 2},
    {DN_EVERY_INSTANCE, 18, DN_GET_SET, 1},
};

/* Acknowledge handler: class revision; instance 1's acknowledge timer (ms), retry limit and
 * producing connection instance. */
#define ACK_ATTR_TIMER 1u
#define ACK_ATTR_RETRY_LIMIT 2u
#define ACK_ATTR_PRODUCER 3u

static const dn_attribute_t ack_handler_attributes[] = {
    {0, ATTR_REVISION, DN_GET, 0},
    {1, ACK_ATTR_TIMER, DN_GET_SET, 2},
    {1, ACK_ATTR_RETRY_LIMIT, DN_GET_SET, 1},
    {1, ACK_ATTR_PRODUCER, DN_GET, 0},
};

static dn_status_t ack_handler_handler(dn_node_t *node, const dn_object_t *object,
                                       const dn_request_t *request, dn_reply_t *reply)
{
    (void)object;
    if (request->service == DN_SVC_SET_ATTRIBUTE_SINGLE) {
        if (request->attribute == ACK_ATTR_RETRY_LIMIT) {
            node->retry_limit = request->data[0];
            return DN_OK;
        }
        uint16_t timer = co_get_u16(request->data);
        if (timer == 0)
            return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
        node->ack_timer = timer;
        return DN_OK;
    }
    if (request->service != DN_SVC_GET_ATTRIBUTE_SINGLE)
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0)
        dn_reply_u16(reply, ACK_HANDLER_REVISION);
    else if (request->attribute == ACK_ATTR_TIMER)
        dn_reply_u16(reply, node->ack_timer);
    else if (request->attribute == ACK_ATTR_RETRY_LIMIT)
        dn_reply_u8(reply, node->retry_limit);
    else
        dn_reply_u16(reply, DN_CONN_COS_CYCLIC);
    return DN_OK;
}

#define TABLE(t) (uint8_t)(sizeof(t) / sizeof((t)[0])), (t)

static const dn_object_t standard_objects[] = {
    {DN_CLASS_IDENTITY, DN_CLASS_IDENTITY, 1, TABLE(identity_attributes), identity_handler, NULL},
    {DN_CLASS_MESSAGE_ROUTER, DN_CLASS_MESSAGE_ROUTER, 1, 0, NULL, message_router_handler, NULL},
    {DN_CLASS_DEVICENET, DN_CLASS_DEVICENET, 1, TABLE(devicenet_attributes), devicenet_handler,
     NULL},
    {DN_CLASS_ASSEMBLY, DN_CLASS_ASSEMBLY, UINT8_MAX, TABLE(assembly_attributes), assembly_handler,
     NULL},
    {DN_CLASS_CONNECTION, DN_CLASS_CONNECTION, DN_CONN_UCMM_LAST, TABLE(connection_attributes),
     dn_connection_handler, NULL},
    {DN_CLASS_ACK_HANDLER, DN_CLASS_ACK_HANDLER, 1, TABLE(ack_handler_attributes),
     ack_handler_handler, NULL},
};

const dn_object_t *dn_standard_object(uint8_t class_id)
{
    for (size_t i = 0; i < sizeof(standard_objects) / sizeof(standard_objects[0]); i++)
        if (standard_objects[i].class_first == class_id)
            return &standard_objects[i];
    return NULL;
}
