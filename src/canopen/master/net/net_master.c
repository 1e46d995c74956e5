/* SPDX-License-Identifier: Apache-2.0 */
/* Network master: the boot of slaves after the PLC300's section 7.3, their status words, the last
 * SDO error and EMCY, and the process image (docs/net-master.md). The composition root of the
 * floors of net_floors.h: the entry points that act on the whole master. */
#include "canopen/master/net/net_floors.h"

bool co_net_master_init(co_net_master_t *master, const co_net_master_config_t *config)
{
    if (!co_net_config_valid(config))
        return false;
    *master = (co_net_master_t){.config = *config};
    co_nmt_master_init(&master->nmt, &(co_nmt_master_config_t){.send = co_net_forward_send,
                                                               .user = master,
                                                               .event = co_net_nmt_event});
    co_emcy_consumer_init(&master->emcy, co_net_emcy_received, master);
    for (size_t i = 0; i < config->slave_count; i++) {
        config->slave_state[i] = (co_net_slave_t){.step = CO_NET_STEP_IDLE};
        co_emcy_consumer_watch(&master->emcy, config->slaves[i].node_id, true);
    }
    master->sync.next = CO_TIME_NEVER;
    master->next_heartbeat = CO_TIME_NEVER;
    master->boot_limit = CO_TIME_NEVER;
    if (config->sync_period_us != 0)
        co_sync_producer_init(&master->sync, CO_CAN_ID_SYNC, config->sync_period_us, 0);
    co_net_release(master);
    return true;
}

void co_net_master_start(co_net_master_t *master, co_time_t now)
{
    master->now = now;
    master->started = true;
    master->stopped_all = false;
    if (master->config.heartbeat_ms != 0)
        master->next_heartbeat = now;
    co_net_boot_network(master, CO_NMT_CS_RESET_COMMUNICATION, master->config.reset_all, true);
}

/* ---- disabling communication, the controller's state --------------------------------------- */

void co_net_master_disable(co_net_master_t *master, co_time_t now)
{
    if (master->disabled)
        return;
    master->now = now;
    master->disabled = true;
    master->started = false;
    master->started_all = false;
    master->next_heartbeat = CO_TIME_NEVER;
    master->sync.next = CO_TIME_NEVER;
    master->boot_limit = CO_TIME_NEVER;
    master->boot_time_over = false;
    if (master->serving)
        co_sdo_client_cancel(&master->sdo);
    for (size_t i = 0; i < master->config.slave_count; i++) {
        co_net_slave_t *s = co_net_slave_at(master, i);
        co_net_abandon_transfer(master, i);
        co_net_stop_error_control(master, i);
        s->booted = false;
        s->tried = false;
        s->boot_error = CO_NET_BOOT_ERROR_NONE;
        co_net_set_status(master, i, 0);
        co_net_set_step(master, i, CO_NET_STEP_IDLE);
    }
    co_net_drop_requests(master);
    master->last_sdo_error = (co_net_sdo_error_t){0};
    master->last_emcy = (co_emcy_message_t){0};
    master->nmt_toggle = 0;
    if (master->nmt_request.pending)
        co_net_finish_nmt(master);
}

void co_net_master_enable(co_net_master_t *master, co_time_t now)
{
    if (!master->disabled)
        return;
    master->disabled = false;
    co_net_master_start(master, now);
}

void co_net_master_set_bus(co_net_master_t *master, uint16_t bus)
{
    master->bus = bus & (CO_NET_MASTER_BUS_OFF | CO_NET_MASTER_NO_BUS_POWER);
}

/* ---- frames and time ---------------------------------------------------------------------- */

bool co_net_master_receive(co_net_master_t *master, const co_frame_t *frame, co_time_t now)
{
    master->now = now;
    /* A master consumes no remote or 29-bit frame (CiA 301 uses neither for what it receives);
     * a disabled one none at all. */
    if ((frame->flags & (CO_FRAME_EFF | CO_FRAME_RTR)) != 0 || master->disabled)
        return false;
    if (co_nmt_master_receive(&master->nmt, frame, now)) {
        co_net_confirm_nmt(master, (uint8_t)(frame->id - CO_CAN_ID_ERROR_CONTROL),
                           (uint8_t)(frame->data[0] & CO_NMT_STATE_MASK));
        return true;
    }
    if (co_sdo_client_busy(&master->sdo) && co_sdo_client_receive(&master->sdo, frame, now))
        return true;
    if (co_emcy_consumer_receive(&master->emcy, frame, now))
        return true;
    return co_net_image_receive(master, frame);
}

co_time_t co_net_master_process(co_net_master_t *master, co_time_t now)
{
    master->now = now;
    if (master->disabled)
        return CO_TIME_NEVER;
    co_time_t next = co_nmt_master_process(&master->nmt, now);
    next = co_time_min(next, co_sdo_client_process(&master->sdo, now));
    next = co_time_min(next, co_net_nmt_deadline(master));
    if (!master->started) {
        co_net_serve_request(master);
        return co_time_min(next, co_sdo_client_process(&master->sdo, now));
    }
    next = co_time_min(next, co_net_heartbeat(master));
    co_net_boot_run(master);
    if (master->config.sync_period_us != 0) {
        if (master->sync.next == CO_TIME_NEVER)
            co_sync_producer_start(&master->sync, now);
        co_net_image_sync(master);
        next = co_time_min(next, master->sync.next);
    }
    co_net_serve_request(master);
    if (!co_net_client_free(master))
        next = co_time_min(next, co_sdo_client_process(&master->sdo, now));
    return co_time_min(next, co_net_boot_deadline(master));
}

/* ---- what the application reads ------------------------------------------------------------ */

uint16_t co_net_master_status(const co_net_master_t *master)
{
    uint16_t own = master->nmt_toggle | master->bus;
    if (master->disabled || master->bus != 0)
        own |= CO_NET_MASTER_DISABLED;
    uint16_t all = CO_NET_MASTER_ALL_CONTACTED | CO_NET_MASTER_ALL_CONFIGURED |
                   CO_NET_MASTER_ALL_EC_STARTED | CO_NET_MASTER_INIT_FINISHED;
    uint16_t some = 0;
    for (size_t i = 0; i < master->config.slave_count; i++) {
        const co_net_slave_t *s = &master->config.slave_state[i];
        uint16_t progress = s->status & (CO_NET_SLAVE_CONTACTED | CO_NET_SLAVE_CONFIGURED |
                                         CO_NET_SLAVE_EC_STARTED);
        if (s->tried)
            progress |= CO_NET_MASTER_INIT_FINISHED;
        all &= progress;
        some |= s->status & (CO_NET_SLAVE_INIT_ERROR | CO_NET_SLAVE_EC_ERROR);
        if (master->config.slaves[i].mandatory && (s->status & CO_NET_SLAVE_INIT_ERROR) != 0)
            some |= CO_NET_MASTER_MANDATORY_ERROR;
    }
    if (master->boot_time_over)
        some |= CO_NET_MASTER_BOOT_TIME_OVER;
    return all | some | own;
}

/* Error control is configured for the slave: a heartbeat consumed, or node guarding. */
static bool supervised(const co_net_slave_config_t *c)
{
    return c->heartbeat_ms != 0 || (c->guard_ms != 0 && c->life_time_factor != 0);
}

uint8_t co_net_master_protocol_state(const co_net_master_t *master)
{
    if ((co_net_master_status(master) & CO_NET_MASTER_DISABLED) != 0)
        return CO_NET_PROTOCOL_DISABLED;
    uint8_t state = CO_NET_PROTOCOL_ENABLED;
    for (size_t i = 0; i < master->config.slave_count; i++) {
        const co_net_slave_t *s = &master->config.slave_state[i];
        if (s->ec_error == CO_NET_EC_ERROR_GUARDING)
            return CO_NET_PROTOCOL_GUARDING_ERROR;
        if (s->ec_error == CO_NET_EC_ERROR_HEARTBEAT)
            return CO_NET_PROTOCOL_HEARTBEAT_ERROR;
        if ((s->status & CO_NET_SLAVE_EC_STARTED) != 0 && supervised(&master->config.slaves[i]))
            state = CO_NET_PROTOCOL_EC_ENABLED;
    }
    return state;
}

const co_net_slave_t *co_net_master_slave(const co_net_master_t *master, uint8_t node_id)
{
    size_t i = co_net_slave_index(master, node_id);
    return i == master->config.slave_count ? NULL : &master->config.slave_state[i];
}

uint16_t co_net_master_slave_status(const co_net_master_t *master, uint8_t node_id)
{
    const co_net_slave_t *s = co_net_master_slave(master, node_id);
    return s == NULL ? 0 : s->status;
}

const char *co_net_step_text(co_net_step_t step)
{
    switch (step) {
    case CO_NET_STEP_IDLE:
        return "idle";
    case CO_NET_STEP_WAIT_BOOT:
        return "wait boot-up";
    case CO_NET_STEP_DEVICE_TYPE:
        return "read device type";
    case CO_NET_STEP_IDENTITY:
        return "read identity";
    case CO_NET_STEP_DOWNLOAD:
        return "download configuration";
    case CO_NET_STEP_WAIT_START:
        return "wait start all";
    case CO_NET_STEP_OPERATIONAL:
        return "operational";
    case CO_NET_STEP_FAILED:
        return "init error";
    case CO_NET_STEP_LOST:
        return "error control lost";
    }
    return "unknown step";
}

const char *co_net_failure_text(co_net_failure_t failure)
{
    switch (failure) {
    case CO_NET_FAIL_NONE:
        return "none";
    case CO_NET_FAIL_SDO:
        return "SDO error";
    case CO_NET_FAIL_DEVICE_TYPE:
        return "device type mismatch";
    case CO_NET_FAIL_IDENTITY:
        return "identity mismatch";
    }
    return "unknown failure";
}

const char *co_net_boot_error_text(uint8_t boot_error)
{
    switch (boot_error) {
    case CO_NET_BOOT_ERROR_NONE:
        return "none";
    case CO_NET_BOOT_ERROR_B:
        return "no answer to the read of 1000h";
    case CO_NET_BOOT_ERROR_C:
        return "device type differs from 1F84h";
    case CO_NET_BOOT_ERROR_D:
        return "vendor-ID differs from 1F85h";
    case CO_NET_BOOT_ERROR_J:
        return "configuration download failed";
    case CO_NET_BOOT_ERROR_M:
        return "product code differs from 1F86h";
    case CO_NET_BOOT_ERROR_N:
        return "revision number differs from 1F87h";
    case CO_NET_BOOT_ERROR_O:
        return "serial number differs from 1F88h";
    default:
        return "unknown boot error";
    }
}

const char *co_net_ec_error_text(co_net_ec_error_t error)
{
    switch (error) {
    case CO_NET_EC_ERROR_NONE:
        return "none";
    case CO_NET_EC_ERROR_GUARDING:
        return "node guarding error";
    case CO_NET_EC_ERROR_HEARTBEAT:
        return "heartbeat error";
    }
    return "unknown error control error";
}

const char *co_net_protocol_state_text(uint8_t state)
{
    switch (state) {
    case CO_NET_PROTOCOL_DISABLED:
        return "disabled";
    case CO_NET_PROTOCOL_ENABLED:
        return "CANopen enabled";
    case CO_NET_PROTOCOL_EC_ENABLED:
        return "error control enabled";
    case CO_NET_PROTOCOL_GUARDING_ERROR:
        return co_net_ec_error_text(CO_NET_EC_ERROR_GUARDING);
    case CO_NET_PROTOCOL_HEARTBEAT_ERROR:
        return co_net_ec_error_text(CO_NET_EC_ERROR_HEARTBEAT);
    default:
        return "reserved";
    }
}
