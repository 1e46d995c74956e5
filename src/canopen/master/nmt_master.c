/* SPDX-License-Identifier: Apache-2.0 */
/* NMT master: commands, the state of nodes 1..127, heartbeat consumers and node guarding (CiA 301
 * sections 7.2.8.2.1 and 7.2.8.3). */
#include "co/co_nmt_master.h"

#define BOOT_UP_STATE 0x00u
/* A guarding request asks for the 1-byte reply: classic CAN remote frames carry the length of the
 * data they request, and two masters requesting with different DLCs would collide on the bus. */
#define GUARD_REQUEST_DLC 1u

static bool node_id_valid(uint8_t node_id)
{
    return node_id >= 1 && node_id <= CO_NMT_MASTER_NODE_ID_MAX;
}

static co_nmt_master_slave_t *slave_of(co_nmt_master_t *master, uint8_t node_id)
{
    return &master->slave[node_id - 1];
}

static bool command_valid(uint8_t command)
{
    return command == CO_NMT_CS_START || command == CO_NMT_CS_STOP ||
           command == CO_NMT_CS_ENTER_PRE_OPERATIONAL || command == CO_NMT_CS_RESET_NODE ||
           command == CO_NMT_CS_RESET_COMMUNICATION;
}

static bool state_valid(uint8_t state)
{
    return state == CO_NMT_STOPPED || state == CO_NMT_OPERATIONAL ||
           state == CO_NMT_PRE_OPERATIONAL;
}

static void report(co_nmt_master_t *master, co_nmt_master_event_kind_t kind, uint8_t node_id,
                   uint8_t old_state)
{
    if (master->event == NULL)
        return;
    co_nmt_master_event_t event = {.kind = kind,
                                   .node_id = node_id,
                                   .state = slave_of(master, node_id)->state,
                                   .old_state = old_state};
    master->event(master->user, &event);
}

static void guarding_restart_toggle(co_nmt_master_slave_t *slave)
{
    slave->expected_toggle = 0;
}

bool co_nmt_master_init(co_nmt_master_t *master, const co_nmt_master_config_t *config)
{
    if (config == NULL || config->send == NULL)
        return false;
    master->send = config->send;
    master->user = config->user;
    master->event = config->event;
    for (uint8_t id = 1; id <= CO_NMT_MASTER_NODE_ID_MAX; id++) {
        co_nmt_master_slave_t *slave = slave_of(master, id);
        *slave = (co_nmt_master_slave_t){.state = CO_NMT_MASTER_STATE_UNKNOWN,
                                         .next_request = CO_TIME_NEVER};
        co_hb_monitor_configure(&slave->heartbeat, 0);
    }
    return true;
}

bool co_nmt_master_command(co_nmt_master_t *master, uint8_t command, uint8_t node_id)
{
    if (!command_valid(command) || node_id > CO_NMT_MASTER_NODE_ID_MAX)
        return false;
    co_frame_t frame = {.id = CO_CAN_ID_NMT, .len = 2, .data = {command, node_id}};
    master->send(master->user, &frame);
    /* A reset communication (also part of a reset node) sets the slave's toggle back to 0
     * (CiA 301 7.2.8.3.1). */
    if (command == CO_NMT_CS_RESET_NODE || command == CO_NMT_CS_RESET_COMMUNICATION) {
        for (uint8_t id = 1; id <= CO_NMT_MASTER_NODE_ID_MAX; id++) {
            if (node_id == CO_NMT_MASTER_ALL_NODES || node_id == id)
                guarding_restart_toggle(slave_of(master, id));
        }
    }
    return true;
}

static bool guarded(const co_nmt_master_slave_t *slave)
{
    return slave->guard_us != 0;
}

static bool heartbeat_monitored(const co_nmt_master_slave_t *slave)
{
    return slave->heartbeat.time_us != 0;
}

bool co_nmt_master_heartbeat(co_nmt_master_t *master, uint8_t node_id, uint16_t ms)
{
    if (!node_id_valid(node_id) || guarded(slave_of(master, node_id)))
        return false;
    co_hb_monitor_configure(&slave_of(master, node_id)->heartbeat, (uint32_t)ms * 1000u);
    return true;
}

bool co_nmt_master_await_heartbeat(co_nmt_master_t *master, uint8_t node_id, uint16_t ms,
                                   co_time_t now)
{
    if (!co_nmt_master_heartbeat(master, node_id, ms))
        return false;
    /* Just configured, the consumer has no loss to end: only its timer starts. */
    co_hb_monitor_alive(&slave_of(master, node_id)->heartbeat, now);
    return true;
}

bool co_nmt_master_guard(co_nmt_master_t *master, uint8_t node_id, uint16_t guard_ms,
                         uint8_t life_time_factor, co_time_t now)
{
    if (!node_id_valid(node_id) || heartbeat_monitored(slave_of(master, node_id)))
        return false;
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    bool on = guard_ms != 0 && life_time_factor != 0;
    slave->guard_us = on ? (uint32_t)guard_ms * 1000u : 0;
    slave->life_time_factor = on ? life_time_factor : 0;
    slave->missed = 0;
    slave->requested = false;
    slave->answered = false;
    slave->guarding_lost = false;
    guarding_restart_toggle(slave);
    slave->next_request = on ? now : CO_TIME_NEVER;
    return true;
}

static void set_state(co_nmt_master_t *master, uint8_t node_id, uint8_t state)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    uint8_t old = slave->state;
    slave->state = state;
    if (old != state)
        report(master, CO_NMT_MASTER_STATE_CHANGED, node_id, old);
}

/* A heartbeat or boot-up: a sign of life for the heartbeat consumer (as on the slave side,
 * docs/error-control.md). */
static void heartbeat_alive(co_nmt_master_t *master, uint8_t node_id, co_time_t now)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    if (co_hb_monitor_alive(&slave->heartbeat, now))
        report(master, CO_NMT_MASTER_RESUMED, node_id, slave->state);
}

/* CiA 301 7.2.8.3.2: the boot-up is sent on the heartbeat COB-ID, and the node is then in
 * Pre-operational. It restarts the toggle bit of guarding; it is no guarding reply. */
static void receive_boot_up(co_nmt_master_t *master, uint8_t node_id, co_time_t now)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    uint8_t old = slave->state;
    slave->state = CO_NMT_PRE_OPERATIONAL;
    report(master, CO_NMT_MASTER_BOOT_UP, node_id, old);
    guarding_restart_toggle(slave);
    heartbeat_alive(master, node_id, now);
}

/* CiA 301 7.2.8.3.1: a reply whose toggle bit equals the previous reply's is handled as if it was
 * not received; the one after it is checked against the opposite bit again. */
static void receive_guarding_reply(co_nmt_master_t *master, uint8_t node_id, uint8_t data)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    uint8_t toggle = data & CO_GUARD_TOGGLE;
    bool valid = toggle == slave->expected_toggle;
    slave->expected_toggle = toggle ^ CO_GUARD_TOGGLE;
    if (!valid)
        return;
    slave->answered = true;
    slave->missed = 0;
    if (slave->guarding_lost) {
        slave->guarding_lost = false;
        report(master, CO_NMT_MASTER_RESUMED, node_id, slave->state);
    }
    set_state(master, node_id, data & CO_NMT_STATE_MASK);
}

static void receive_heartbeat(co_nmt_master_t *master, uint8_t node_id, uint8_t state,
                              co_time_t now)
{
    heartbeat_alive(master, node_id, now);
    set_state(master, node_id, state);
}

bool co_nmt_master_receive(co_nmt_master_t *master, const co_frame_t *frame, co_time_t now)
{
    if (frame->id <= CO_CAN_ID_ERROR_CONTROL ||
        frame->id > CO_CAN_ID_ERROR_CONTROL + CO_NMT_MASTER_NODE_ID_MAX ||
        (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF)) || frame->len != 1)
        return false;
    uint8_t node_id = (uint8_t)(frame->id - CO_CAN_ID_ERROR_CONTROL);
    uint8_t data = frame->data[0];
    if (data == BOOT_UP_STATE) {
        receive_boot_up(master, node_id, now);
        return true;
    }
    if (!state_valid(data & CO_NMT_STATE_MASK))
        return false;
    if (guarded(slave_of(master, node_id)))
        receive_guarding_reply(master, node_id, data);
    else
        receive_heartbeat(master, node_id, data & CO_NMT_STATE_MASK, now);
    return true;
}

static co_time_t heartbeat_process(co_nmt_master_t *master, uint8_t node_id, co_time_t now)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    if (co_hb_monitor_expired(&slave->heartbeat, now))
        report(master, CO_NMT_MASTER_HEARTBEAT_LOST, node_id, slave->state);
    return slave->heartbeat.deadline;
}

/* One guard time ended: count it as missed when no valid reply came, report the loss when the
 * life time factor is reached, and send the next request. Requests go on while the node is lost,
 * so that a valid reply can resume it. */
static void guarding_tick(co_nmt_master_t *master, uint8_t node_id)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    if (slave->requested && !slave->answered && !slave->guarding_lost) {
        slave->missed++;
        if (slave->missed >= slave->life_time_factor) {
            slave->guarding_lost = true;
            report(master, CO_NMT_MASTER_GUARDING_LOST, node_id, slave->state);
        }
    }
    slave->requested = true;
    slave->answered = false;
    co_frame_t request = {
        .id = CO_CAN_ID_ERROR_CONTROL + node_id, .len = GUARD_REQUEST_DLC, .flags = CO_FRAME_RTR};
    master->send(master->user, &request);
}

static co_time_t guarding_process(co_nmt_master_t *master, uint8_t node_id, co_time_t now)
{
    co_nmt_master_slave_t *slave = slave_of(master, node_id);
    if (now < slave->next_request)
        return slave->next_request;
    guarding_tick(master, node_id);
    /* On the grid of the first request; a caller later than a guard time skips requests. */
    slave->next_request += slave->guard_us;
    if (slave->next_request <= now)
        slave->next_request = now + slave->guard_us;
    return slave->next_request;
}

co_time_t co_nmt_master_process(co_nmt_master_t *master, co_time_t now)
{
    co_time_t next = CO_TIME_NEVER;
    for (uint8_t id = 1; id <= CO_NMT_MASTER_NODE_ID_MAX; id++) {
        co_nmt_master_slave_t *slave = slave_of(master, id);
        if (heartbeat_monitored(slave))
            next = co_time_min(next, heartbeat_process(master, id, now));
        else if (guarded(slave))
            next = co_time_min(next, guarding_process(master, id, now));
    }
    return next;
}

uint8_t co_nmt_master_state(const co_nmt_master_t *master, uint8_t node_id)
{
    return node_id_valid(node_id) ? master->slave[node_id - 1].state : CO_NMT_MASTER_STATE_UNKNOWN;
}

bool co_nmt_master_lost(const co_nmt_master_t *master, uint8_t node_id)
{
    if (!node_id_valid(node_id))
        return false;
    const co_nmt_master_slave_t *slave = &master->slave[node_id - 1];
    return slave->heartbeat.lost || slave->guarding_lost;
}
