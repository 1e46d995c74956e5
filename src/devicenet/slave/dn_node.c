/* SPDX-License-Identifier: Apache-2.0 */
/* The composition root of a DeviceNet slave, the top of its floors: configuration, the duplicate
 * MAC ID check, frame routing by identifier to the explicit messages and the connections, the
 * earliest deadline, bus off and the LEDs. */
#include <string.h>

#include "devicenet/slave/dn_slave.h"

/* The stored selection if the table has it in that direction, else the default. */
static const dn_assembly_t *select_assembly(const dn_node_t *node, uint16_t stored,
                                            uint16_t fallback, bool produced)
{
    const dn_assembly_t *a = dn_node_assembly(node, stored);
    if (a == NULL || a->produced != produced)
        a = dn_node_assembly(node, fallback);
    return a != NULL && a->produced == produced ? a : NULL;
}

static bool objects_sorted(const dn_config_t *config)
{
    for (uint8_t i = 0; i < config->object_count; i++) {
        const dn_object_t *o = &config->objects[i];
        if (o->class_last < o->class_first || o->handler == NULL)
            return false;
        if (i > 0 && o->class_first <= config->objects[i - 1].class_last)
            return false;
    }
    return true;
}

int dn_node_init(dn_node_t *node, const dn_config_t *config)
{
    memset(node, 0, sizeof(*node));
    node->config = config;
    if (config->mac_id > DN_MAC_ID_MAX)
        return DN_INIT_BAD_MAC_ID;
    const dn_app_t *app = config->app;
    if (app == NULL || app->send == NULL || app->read_assembly == NULL ||
        app->write_assembly == NULL || !objects_sorted(config))
        return DN_INIT_BAD_CONFIG;
    for (uint8_t i = 0; i < config->assembly_count; i++)
        if (config->assemblies[i].size == 0 || config->assemblies[i].size > DN_IO_MAX)
            return DN_INIT_BAD_ASSEMBLY;
    const dn_assembly_t *consumed = select_assembly(node, config->stored.consumed_assembly,
                                                    config->default_consumed_assembly, false);
    const dn_assembly_t *produced = select_assembly(node, config->stored.produced_assembly,
                                                    config->default_produced_assembly, true);
    if (consumed == NULL || produced == NULL)
        return DN_INIT_BAD_ASSEMBLY;
    node->consumed_assembly = consumed->instance;
    node->consumed_size = consumed->size;
    node->produced_assembly = produced->instance;
    node->produced_size = produced->size;
    node->stored = config->stored;
    node->stored.consumed_assembly = consumed->instance;
    node->stored.produced_assembly = produced->instance;
    node->ids = dn_predefined_ids(config->mac_id);
    node->link = DN_LINK_OFF;
    node->link_deadline = CO_TIME_NEVER;
    node->pending_reset = -1;
    node->led_test_start = CO_TIME_NEVER;
    dn_connections_reset(node);
    return DN_INIT_OK;
}

/* The duplicate MAC ID check message: request or response, port 0, vendor ID, serial number. */
static void send_duplicate_mac(dn_node_t *node, uint8_t flags)
{
    uint8_t data[DN_DUP_MAC_LEN];
    data[0] = flags;
    co_put_u16(&data[1], node->config->vendor_id);
    co_put_u32(&data[3], node->config->serial_number);
    dn_send(node, node->ids.duplicate_mac, data, DN_DUP_MAC_LEN);
}

void dn_node_start(dn_node_t *node, co_time_t now)
{
    node->now = now;
    node->duplicate_mac = false;
    dn_connections_end(node, DN_END_OFFLINE);
    node->link = DN_LINK_DUP_CHECK_1;
    node->link_deadline = now + DN_DUP_MAC_WAIT_US;
    send_duplicate_mac(node, 0);
}

void dn_node_power_up(dn_node_t *node, co_time_t now)
{
    node->led_test_start = now;
    dn_node_start(node, now);
}

/* A check message with this node's MAC ID: while checking, another node has it (a request of a
 * node checking the same MAC ID, or a response of one online); online, a request is answered. */
static void duplicate_mac_receive(dn_node_t *node, const co_frame_t *frame)
{
    if (frame->len != DN_DUP_MAC_LEN)
        return;
    if (node->link == DN_LINK_DUP_CHECK_1 || node->link == DN_LINK_DUP_CHECK_2) {
        node->duplicate_mac = true;
        node->link = DN_LINK_FAULTED;
        node->link_deadline = CO_TIME_NEVER;
    } else if (node->link == DN_LINK_ONLINE && !(frame->data[0] & DN_DUP_MAC_RESPONSE)) {
        send_duplicate_mac(node, DN_DUP_MAC_RESPONSE);
    }
}

size_t dn_node_consumed_ids(const dn_node_t *node, uint16_t ids[DN_NODE_CONSUMED_IDS])
{
    static const uint8_t messages[] = {DN_G2_MASTER_COS_CYCLIC_ACK, DN_G2_MASTER_EXPLICIT_REQUEST,
                                       DN_G2_MASTER_POLL_COS_CYCLIC, DN_G2_UNCONNECTED_REQUEST,
                                       DN_G2_DUPLICATE_MAC_CHECK};
    size_t count = 0;
    for (size_t i = 0; i < sizeof messages; i++)
        ids[count++] = dn_group2_id(node->config->mac_id, messages[i]);
    for (uint8_t message = 0; message <= DN_G3_UNCONNECTED_REQUEST; message++)
        if (message != DN_G3_UNCONNECTED_RESPONSE)
            for (uint8_t mac = 0; mac <= DN_MAC_ID_MAX; mac++)
                ids[count++] = dn_group3_id(message, mac);
    return count;
}

/* Group 3: a UCMM request whose header names this node, or a request on a connection the UCMM
 * opened (its CAN-ID is the client's). */
static void group3_receive(dn_node_t *node, const co_frame_t *frame, dn_can_id_t id)
{
    if (id.message_id == DN_G3_UNCONNECTED_REQUEST) {
        if (frame->len >= 1 && (frame->data[0] & DN_HDR_MAC) == node->config->mac_id)
            dn_unconnected_receive(node, frame, true, id.mac_id);
        return;
    }
    int index = dn_ucmm_connection(node, (uint16_t)frame->id);
    if (index >= 0)
        dn_explicit_receive(node, frame, (unsigned)index);
}

void dn_node_receive(dn_node_t *node, const co_frame_t *frame, co_time_t now)
{
    node->now = now;
    if (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF) || frame->len > CO_FRAME_DLC_MAX ||
        node->link == DN_LINK_OFF)
        return;
    dn_can_id_t id = dn_can_id_decode(frame->id);
    if (id.group == 3) {
        if (node->link == DN_LINK_ONLINE)
            group3_receive(node, frame, id);
        return;
    }
    /* The predefined set's frames to this slave are all group 2 with its MAC ID. */
    if (id.group != 2 || id.mac_id != node->config->mac_id)
        return;
    if (id.message_id == DN_G2_DUPLICATE_MAC_CHECK) {
        duplicate_mac_receive(node, frame);
        return;
    }
    if (node->link != DN_LINK_ONLINE)
        return;
    switch (id.message_id) {
    case DN_G2_UNCONNECTED_REQUEST:
        if (frame->len >= 1)
            dn_unconnected_receive(node, frame, false, frame->data[0] & DN_HDR_MAC);
        break;
    case DN_G2_MASTER_EXPLICIT_REQUEST:
        dn_explicit_receive(node, frame, DN_EXPLICIT);
        break;
    case DN_G2_MASTER_POLL_COS_CYCLIC:
        dn_io_receive(node, frame);
        break;
    case DN_G2_MASTER_COS_CYCLIC_ACK:
        dn_cos_ack_receive(node);
        break;
    default: /* bit-strobe and multicast poll are not served */
        break;
    }
}

static void link_process(dn_node_t *node)
{
    if (node->now < node->link_deadline)
        return;
    if (node->link == DN_LINK_DUP_CHECK_1) {
        node->link = DN_LINK_DUP_CHECK_2;
        node->link_deadline = node->now + DN_DUP_MAC_WAIT_US;
        send_duplicate_mac(node, 0);
    } else if (node->link == DN_LINK_DUP_CHECK_2) {
        node->link = DN_LINK_ONLINE;
        node->link_deadline = CO_TIME_NEVER;
    }
}

/* The manual's start-up LED test ("A LED test is performed during start-up, after module init is
 * complete"): three steps of 0.25 s units, MS twice then NS twice, then both off; the manual's
 * table lost its colours, read as green then red (docs/decisions.md, D-DEVICENET-LEDS). */
#define LED_TEST_STEP_US 250000u
#define LED_TEST_STEPS 5u
static const dn_led_t led_test_ms[LED_TEST_STEPS] = {DN_LED_GREEN, DN_LED_RED, DN_LED_GREEN,
                                                     DN_LED_GREEN, DN_LED_GREEN};
static const dn_led_t led_test_ns[LED_TEST_STEPS] = {DN_LED_OFF, DN_LED_OFF, DN_LED_GREEN,
                                                     DN_LED_RED, DN_LED_OFF};

/* The LED test's step at the node's time, or -1 when it is over (or not started). */
static int led_test_step(const dn_node_t *node)
{
    if (node->led_test_start == CO_TIME_NEVER || node->link == DN_LINK_OFF ||
        node->now < node->led_test_start)
        return -1;
    co_time_t step = (node->now - node->led_test_start) / LED_TEST_STEP_US;
    return step < LED_TEST_STEPS ? (int)step : -1;
}

static co_time_t led_test_deadline(const dn_node_t *node)
{
    int step = led_test_step(node);
    return step < 0 ? CO_TIME_NEVER
                    : node->led_test_start + (co_time_t)(step + 1) * LED_TEST_STEP_US;
}

co_time_t dn_node_process(dn_node_t *node, co_time_t now)
{
    node->now = now;
    link_process(node);
    co_time_t leds = led_test_deadline(node);
    if (node->link != DN_LINK_ONLINE)
        return co_time_min(node->link_deadline, leds);
    co_time_t next = co_time_min(leds, dn_explicit_process(node));
    return co_time_min(next, dn_connections_process(node));
}

void dn_node_stop(dn_node_t *node, co_time_t now)
{
    node->now = now;
    dn_connections_end(node, DN_END_OFFLINE);
    node->link = DN_LINK_OFF;
    node->link_deadline = CO_TIME_NEVER;
}

void dn_node_bus_off(dn_node_t *node, co_time_t now)
{
    node->now = now;
    if (node->bus_off_counter < UINT8_MAX)
        node->bus_off_counter++;
    dn_connections_end(node, DN_END_BUS_OFF);
    if (node->bus_off_interrupt) {
        dn_node_start(node, now);
        return;
    }
    node->link = DN_LINK_FAULTED;
    node->link_deadline = CO_TIME_NEVER;
}

void dn_node_set_faults(dn_node_t *node, uint16_t faults)
{
    node->faults = faults & (DN_STATUS_MINOR_RECOVERABLE | DN_STATUS_MINOR_UNRECOVERABLE |
                             DN_STATUS_MAJOR_RECOVERABLE | DN_STATUS_MAJOR_UNRECOVERABLE);
}

void dn_node_set_commissioning(dn_node_t *node, bool needed)
{
    node->needs_commissioning = needed;
}

dn_led_t dn_node_ms_led(const dn_node_t *node)
{
    if (node->link == DN_LINK_OFF)
        return DN_LED_OFF;
    int step = led_test_step(node);
    if (step >= 0)
        return led_test_ms[step];
    if (node->faults & (DN_STATUS_MINOR_UNRECOVERABLE | DN_STATUS_MAJOR_UNRECOVERABLE))
        return DN_LED_RED;
    return node->needs_commissioning ? DN_LED_FLASHING_GREEN : DN_LED_GREEN;
}

dn_led_t dn_node_ns_led(const dn_node_t *node)
{
    int step = led_test_step(node);
    if (step >= 0)
        return led_test_ns[step];
    switch (node->link) {
    case DN_LINK_FAULTED:
        return DN_LED_RED;
    case DN_LINK_ONLINE:
        if (dn_io_in_state(node, DN_CONN_TIMED_OUT))
            return DN_LED_FLASHING_RED;
        for (unsigned i = 0; i < DN_CONN_COUNT; i++)
            if (node->conn[i].state == DN_CONN_ESTABLISHED)
                return DN_LED_GREEN;
        return DN_LED_FLASHING_GREEN;
    default: /* off, or checking its MAC ID: not online yet */
        return DN_LED_OFF;
    }
}
