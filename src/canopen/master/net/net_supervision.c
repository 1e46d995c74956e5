/* SPDX-License-Identifier: Apache-2.0 */
/* The supervision of the network master's slaves once booted: a loss of their error control
 * (heartbeat or node guarding) and the reaction the slave's on_error asks, a boot-up that says a
 * slave restarted, a lost slave heard again, their EMCYs (the PLC300's last EMCY, 5.6.5); and the
 * master's own heartbeat, which lets the slaves supervise it (docs/net-master.md). */
#include "canopen/master/net/net_floors.h"

/* The kind is recorded before bit 5 is set, so that the event of the new status finds it. A
 * mandatory slave's loss is the network's when 1F80h says so (bits 6 and 4); any other the slave's
 * alone, as its on_error says. */
static void error_control_lost(co_net_master_t *m, size_t i, co_net_ec_error_t kind)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    if (s->step != CO_NET_STEP_OPERATIONAL && s->step != CO_NET_STEP_WAIT_START)
        return;
    s->ec_error = (uint8_t)kind;
    co_net_mandatory_error_t network = co_net_slave_config(m, i)->mandatory
                                           ? m->config.on_mandatory_error
                                           : CO_NET_MANDATORY_ALONE;
    if (network == CO_NET_MANDATORY_STOP_ALL) {
        co_nmt_master_command(&m->nmt, CO_NMT_CS_STOP, CO_NMT_MASTER_ALL_NODES);
        m->stopped_all = true;
    }
    if (network == CO_NET_MANDATORY_STOP_ALL ||
        (network == CO_NET_MANDATORY_ALONE &&
         co_net_slave_config(m, i)->on_error == CO_NET_ON_ERROR_REPORT)) {
        co_net_add_status(m, i, CO_NET_SLAVE_EC_ERROR);
        co_net_set_step(m, i, CO_NET_STEP_LOST);
        return;
    }
    co_net_set_status(m, i,
                      (uint16_t)((s->status & ~CO_NET_SLAVE_PROGRESS) | CO_NET_SLAVE_EC_ERROR));
    /* CiA 302-2's 1F80h bit 4: every node reset, the network booted again from the boot-ups. */
    if (network == CO_NET_MANDATORY_RESET_ALL)
        co_net_boot_network(m, CO_NMT_CS_RESET_NODE, true, false);
    else
        co_net_reset_slave(m, i, CO_NMT_CS_RESET_NODE);
}

/* The boot-up the master awaits after its reset: in WAIT_BOOT, or late, once the boot time ended,
 * while the slave has not answered the read of 1000h yet (a node sends its boot-up before it
 * serves any SDO, so a slave that answered has booted already). */
static bool awaited_boot_up(const co_net_slave_t *s)
{
    return s->step == CO_NET_STEP_WAIT_BOOT || (s->step == CO_NET_STEP_DEVICE_TYPE && !s->booted);
}

/* Any other boot-up says that the slave restarted (a reset, a power cycle) and lost what the
 * master gave it so far: identity checked, writes, error control. Its boot then starts again
 * from the beginning, at once, whatever its step and its on_error (CiA 302-2 boots a slave on its
 * boot-up; on_error is the reaction to a silence). A boot-up before co_net_master_start is nothing
 * to the master, whose start resets every slave. */
static void booted_up(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    if (s->step == CO_NET_STEP_IDLE)
        return;
    if (awaited_boot_up(s)) {
        s->booted = true;
        return;
    }
    co_net_await_boot(m, i, true);
}

/* A slave lost under CO_NET_ON_ERROR_REPORT is heard again (any heartbeat, or a valid guarding
 * reply): it returns to where it was lost, running (bit 3 set) or waiting for the start of all,
 * which may have been sent meanwhile. */
static void resumed(co_net_master_t *m, size_t i)
{
    if (co_net_slave_at(m, i)->step != CO_NET_STEP_LOST)
        return;
    co_net_clear_status(m, i, CO_NET_SLAVE_EC_ERROR);
    if ((co_net_slave_at(m, i)->status & CO_NET_SLAVE_INIT_DONE) != 0)
        co_net_set_step(m, i, CO_NET_STEP_OPERATIONAL);
    else
        co_net_start_slave(m, i);
}

void co_net_nmt_event(void *user, const co_nmt_master_event_t *event)
{
    co_net_master_t *m = user;
    size_t i = co_net_slave_index(m, event->node_id);
    if (i == m->config.slave_count)
        return;
    switch (event->kind) {
    case CO_NMT_MASTER_BOOT_UP:
        booted_up(m, i);
        break;
    case CO_NMT_MASTER_HEARTBEAT_LOST:
        error_control_lost(m, i, CO_NET_EC_ERROR_HEARTBEAT);
        break;
    case CO_NMT_MASTER_GUARDING_LOST:
        error_control_lost(m, i, CO_NET_EC_ERROR_GUARDING);
        break;
    case CO_NMT_MASTER_RESUMED:
        resumed(m, i);
        break;
    default: /* a state change: the state of a slave is not checked (docs/net-master.md) */
        break;
    }
}

void co_net_emcy_received(void *user, co_emcy_decode_t result, const co_emcy_message_t *msg,
                          co_time_t now)
{
    (void)now;
    co_net_master_t *m = user;
    if (result != CO_EMCY_DECODE_OK)
        return;
    m->last_emcy = *msg;
    co_net_report(m, CO_NET_EVENT_EMCY, msg->node_id, 0);
}

/* Operational (it runs the network), Stopped once it stopped all nodes; on the grid of its start.
 */
co_time_t co_net_heartbeat(co_net_master_t *m)
{
    if (m->next_heartbeat > m->now)
        return m->next_heartbeat;
    co_frame_t beat = {.id = CO_CAN_ID_ERROR_CONTROL + m->config.node_id,
                       .len = 1,
                       .data = {m->stopped_all ? CO_NMT_STOPPED : CO_NMT_OPERATIONAL}};
    co_net_send(m, &beat);
    m->next_heartbeat = co_time_next_period(
        m->next_heartbeat, (co_time_t)m->config.heartbeat_ms * CO_NET_US_PER_MS, m->now);
    return m->next_heartbeat;
}
