/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS slave: the services of both LSS states, fastscan, and the timed switch of the bit
 * rate. Which service each state takes (CiA 305 table "LSS services per state"): switch state
 * global and identify in both; switch state selective and fastscan in waiting; configure, store,
 * activate and inquire in configuration. */
#include "co/co_lss_slave.h"
#include "co/co_node.h"

/* The node's LSS address part (1018h sub 1..4; 0 when the dictionary lacks it). */
static uint32_t address_part(const co_node_t *node, unsigned part)
{
    return co_od_param(node, CO_IDX_IDENTITY, (uint8_t)(CO_IDENTITY_VENDOR + part), 0);
}

/* CiA 305: "non-configured" is a node with neither an active nor a pending node-id; one whose
 * node-id was configured and not yet activated is no longer a candidate for fastscan. */
static bool non_configured(const co_node_t *node)
{
    return node->node_id == CO_LSS_NODE_ID_UNCONFIGURED &&
           node->lss->pending_node_id == CO_LSS_NODE_ID_UNCONFIGURED;
}

static void answer(co_node_t *node, uint8_t cs, const uint8_t *data, size_t len)
{
    co_frame_t frame;
    co_lss_frame(&frame, CO_LSS_ID_SLAVE, cs, data, len);
    co_node_send(node, &frame);
}

static void answer_error(co_node_t *node, uint8_t cs, uint8_t error, uint8_t specific)
{
    uint8_t data[2] = {error, error == CO_LSS_SPECIFIC_ERROR ? specific : 0};
    answer(node, cs, data, sizeof(data));
}

/* Switch state global to waiting. A node that had no node-id and got one starts with it now:
 * CiA 305 has it continue its NMT initialisation, which is the reset communication that boots it
 * (docs/lss.md). */
static void enter_waiting(co_node_t *node)
{
    co_lss_slave_t *lss = node->lss;
    bool was_configuring = lss->state == CO_LSS_CONFIGURATION;
    lss->state = CO_LSS_WAITING;
    lss->selected = 0;
    if (was_configuring && node->node_id == CO_LSS_NODE_ID_UNCONFIGURED &&
        lss->pending_node_id != CO_LSS_NODE_ID_UNCONFIGURED)
        co_nmt_reset(node, CO_NMT_RESET_COMMUNICATION);
}

/* Switch state selective: the four parts in order, each restarting the match when it differs;
 * the serial that completes it selects this slave. */
static void switch_selective(co_node_t *node, unsigned part, uint32_t value)
{
    co_lss_slave_t *lss = node->lss;
    if (part != CO_LSS_VENDOR && lss->selected != part) {
        lss->selected = 0;
        return;
    }
    lss->selected = value == address_part(node, part) ? (uint8_t)(part + 1) : 0;
    if (lss->selected == CO_LSS_FASTSCAN_PARTS) {
        lss->selected = 0;
        lss->state = CO_LSS_CONFIGURATION;
        answer(node, CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE, NULL, 0);
    }
}

/* Identify remote slave, 46h..4Bh in order: vendor and product equal, revision and serial within
 * their bounds (included); the last one met, the slave says it is there. */
static void identify_remote(co_node_t *node, unsigned step, uint32_t value)
{
    static const uint8_t part_of_step[] = {CO_LSS_VENDOR,   CO_LSS_PRODUCT, CO_LSS_REVISION,
                                           CO_LSS_REVISION, CO_LSS_SERIAL,  CO_LSS_SERIAL};
    co_lss_slave_t *lss = node->lss;
    if (step != 0 && lss->identified != step) {
        lss->identified = 0;
        return;
    }
    uint32_t own = address_part(node, part_of_step[step]);
    bool met;
    if (step < 2)
        met = own == value;
    else if (step % 2 == 0)
        met = own >= value; /* the low bound */
    else
        met = own <= value;
    lss->identified = met ? (uint8_t)(step + 1) : 0;
    if (lss->identified == sizeof(part_of_step)) {
        lss->identified = 0;
        answer(node, CO_LSS_CS_IDENTIFY_SLAVE, NULL, 0);
    }
}

/* Fastscan: a non-configured slave in waiting state answers when the bits bit_checked..31 of its
 * part `sub` equal the ID number's; bit 0 matched, it moves to part `next`, and past the serial
 * (next below sub) into the configuration state. */
static void fastscan(co_node_t *node, const uint8_t *data)
{
    co_lss_slave_t *lss = node->lss;
    uint32_t id_number = co_get_u32(&data[1]);
    uint8_t bit = data[5], sub = data[6], next = data[7];
    if (!non_configured(node) || (bit > CO_LSS_FASTSCAN_BIT_MAX && bit != CO_LSS_FASTSCAN_RESET) ||
        sub >= CO_LSS_FASTSCAN_PARTS || next >= CO_LSS_FASTSCAN_PARTS)
        return;
    if (bit == CO_LSS_FASTSCAN_RESET) {
        lss->fastscan_part = CO_LSS_VENDOR;
        answer(node, CO_LSS_CS_IDENTIFY_SLAVE, NULL, 0);
        return;
    }
    uint32_t mask = UINT32_MAX << bit;
    if (sub != lss->fastscan_part || ((address_part(node, sub) ^ id_number) & mask) != 0)
        return;
    answer(node, CO_LSS_CS_IDENTIFY_SLAVE, NULL, 0);
    if (bit != 0)
        return;
    lss->fastscan_part = next;
    if (next < sub)
        lss->state = CO_LSS_CONFIGURATION;
}

static bool bit_timing_valid(uint8_t table, uint8_t index)
{
    return table == CO_LSS_BIT_TIMING_TABLE &&
           (co_lss_bit_rate_kbit(index) != 0 || index == CO_LSS_BIT_TIMING_AUTO);
}

static void configure(co_node_t *node, const uint8_t *data)
{
    co_lss_slave_t *lss = node->lss;
    uint8_t cs = data[0];
    switch (cs) {
    case CO_LSS_CS_CONFIGURE_NODE_ID: {
        uint8_t id = data[1];
        bool valid = (id >= 1 && id <= CO_NODE_ID_MAX) || id == CO_LSS_NODE_ID_UNCONFIGURED;
        if (valid)
            lss->pending_node_id = id;
        answer_error(node, cs, valid ? CO_LSS_OK : CO_LSS_NODE_ID_OUT_OF_RANGE, 0);
        break;
    }
    case CO_LSS_CS_CONFIGURE_BIT_TIMING: {
        bool taken = bit_timing_valid(data[1], data[2]) && lss->hooks != NULL &&
                     lss->hooks->bit_timing_supported != NULL &&
                     lss->hooks->bit_timing_supported(node, data[2]);
        if (taken)
            lss->bit_timing = data[2];
        answer_error(node, cs, taken ? CO_LSS_OK : CO_LSS_BIT_TIMING_NOT_SUPPORTED, 0);
        break;
    }
    case CO_LSS_CS_ACTIVATE_BIT_TIMING:
        if (lss->hooks == NULL || lss->hooks->switch_bit_timing == NULL)
            break;
        lss->switch_delay = (co_time_t)co_get_u16(&data[1]) * 1000u;
        lss->switch_at = node->now + lss->switch_delay;
        lss->resume_at = CO_TIME_NEVER;
        break;
    case CO_LSS_CS_STORE: {
        uint8_t error = CO_LSS_STORE_NOT_SUPPORTED, specific = 0;
        if (lss->hooks != NULL && lss->hooks->store != NULL)
            error = lss->hooks->store(node, lss->pending_node_id, lss->bit_timing, &specific);
        answer_error(node, cs, error, specific);
        break;
    }
    case CO_LSS_CS_INQUIRE_VENDOR:
    case CO_LSS_CS_INQUIRE_PRODUCT:
    case CO_LSS_CS_INQUIRE_REVISION:
    case CO_LSS_CS_INQUIRE_SERIAL: {
        uint8_t value[4];
        co_put_u32(value, address_part(node, (unsigned)(cs - CO_LSS_CS_INQUIRE_VENDOR)));
        answer(node, cs, value, sizeof(value));
        break;
    }
    case CO_LSS_CS_INQUIRE_NODE_ID:
        answer(node, cs, &node->node_id, 1);
        break;
    default:
        break;
    }
}

static void lss_receive(co_node_t *node, const co_frame_t *frame)
{
    co_lss_slave_t *lss = node->lss;
    if (frame->len != CO_LSS_FRAME_LEN || (frame->flags & CO_FRAME_RTR))
        return;
    const uint8_t *data = frame->data;
    uint8_t cs = data[0];
    uint32_t value = co_get_u32(&data[1]);
    if (cs == CO_LSS_CS_SWITCH_GLOBAL) {
        if (data[1] == CO_LSS_WAITING)
            enter_waiting(node);
        else if (data[1] == CO_LSS_CONFIGURATION)
            lss->state = CO_LSS_CONFIGURATION;
    } else if (cs >= CO_LSS_CS_IDENTIFY_VENDOR && cs <= CO_LSS_CS_IDENTIFY_SERIAL_HIGH) {
        identify_remote(node, (unsigned)(cs - CO_LSS_CS_IDENTIFY_VENDOR), value);
    } else if (cs == CO_LSS_CS_IDENTIFY_NON_CONFIGURED) {
        if (non_configured(node))
            answer(node, CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE, NULL, 0);
    } else if (lss->state == CO_LSS_WAITING) {
        if (cs >= CO_LSS_CS_SWITCH_SELECTIVE_VENDOR && cs <= CO_LSS_CS_SWITCH_SELECTIVE_SERIAL)
            switch_selective(node, (unsigned)(cs - CO_LSS_CS_SWITCH_SELECTIVE_VENDOR), value);
        else if (cs == CO_LSS_CS_FASTSCAN)
            fastscan(node, data);
    } else {
        configure(node, data);
    }
}

/* Activate bit timing: the switch one delay after the command, the first frame one delay after
 * the switch (CiA 305), the pending index taken by the application's hook. */
static co_time_t lss_process(co_node_t *node, co_time_t now)
{
    co_lss_slave_t *lss = node->lss;
    if (now >= lss->switch_at) {
        lss->hooks->switch_bit_timing(node, lss->bit_timing);
        lss->resume_at = lss->switch_at + lss->switch_delay;
        lss->switch_at = CO_TIME_NEVER;
    }
    if (now >= lss->resume_at)
        lss->resume_at = CO_TIME_NEVER;
    return co_time_min(lss->switch_at, lss->resume_at);
}

void co_lss_slave_init(co_lss_slave_t *lss, const co_lss_slave_hooks_t *hooks, uint8_t bit_timing)
{
    lss->receive = lss_receive;
    lss->process = lss_process;
    lss->hooks = hooks;
    lss->switch_at = CO_TIME_NEVER;
    lss->resume_at = CO_TIME_NEVER;
    lss->state = CO_LSS_WAITING;
    lss->pending_node_id = CO_LSS_NODE_ID_UNCONFIGURED;
    lss->bit_timing = bit_timing;
    lss->selected = 0;
    lss->identified = 0;
    lss->fastscan_part = CO_LSS_VENDOR;
}
