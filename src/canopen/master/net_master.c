/* SPDX-License-Identifier: Apache-2.0 */
/* Network master: the boot of slaves after the PLC300's section 7.3, their status words, the last
 * SDO error and EMCY, and the process image (docs/net-master.md). */
#include "co/co_net_master.h"

#include <string.h>

#define US_PER_MS 1000u
/* The bits of a slave's status word that one attempt at its initialisation builds up. */
#define SLAVE_PROGRESS                                                                             \
    (CO_NET_SLAVE_CONTACTED | CO_NET_SLAVE_CONFIGURED | CO_NET_SLAVE_EC_STARTED |                  \
     CO_NET_SLAVE_INIT_DONE)

static const co_net_slave_config_t *slave_config(const co_net_master_t *m, size_t i)
{
    return &m->config.slaves[i];
}

static co_net_slave_t *slave_at(co_net_master_t *m, size_t i)
{
    return &m->config.slave_state[i];
}

/* The position of node `node_id` in the table, slave_count when it is not there. */
static size_t config_index(const co_net_master_config_t *config, uint8_t node_id)
{
    for (size_t i = 0; i < config->slave_count; i++) {
        if (config->slaves[i].node_id == node_id)
            return i;
    }
    return config->slave_count;
}

static size_t slave_index(const co_net_master_t *m, uint8_t node_id)
{
    return config_index(&m->config, node_id);
}

static void report(co_net_master_t *m, co_net_event_kind_t kind, uint8_t node_id, size_t pdo)
{
    if (m->config.event == NULL)
        return;
    co_net_event_t event = {.kind = kind, .node_id = node_id, .pdo = pdo};
    m->config.event(m->config.user, &event);
}

static void set_step(co_net_master_t *m, size_t i, co_net_step_t step)
{
    co_net_slave_t *s = slave_at(m, i);
    if (s->step == step)
        return;
    s->step = (uint8_t)step;
    report(m, CO_NET_EVENT_STEP, slave_config(m, i)->node_id, 0);
}

static void set_status(co_net_master_t *m, size_t i, uint16_t status)
{
    co_net_slave_t *s = slave_at(m, i);
    if (s->status == status)
        return;
    s->status = status;
    report(m, CO_NET_EVENT_STATUS, slave_config(m, i)->node_id, 0);
}

static void add_status(co_net_master_t *m, size_t i, uint16_t bits)
{
    set_status(m, i, slave_at(m, i)->status | bits);
}

static void clear_status(co_net_master_t *m, size_t i, uint16_t bits)
{
    set_status(m, i, (uint16_t)(slave_at(m, i)->status & ~bits));
}

static uint32_t le32(const uint8_t *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static co_time_t after_ms(co_time_t now, uint32_t ms)
{
    return now + (co_time_t)ms * US_PER_MS;
}

static bool pdo_valid(const co_net_master_config_t *config, const co_net_pdo_t *pdo,
                      size_t image_size)
{
    return pdo->len >= 1 && pdo->len <= CO_FRAME_DLC_MAX &&
           (size_t)pdo->offset + pdo->len <= image_size && pdo->can_id <= CO_COB_ID_CAN_ID &&
           !co_can_id_restricted(pdo->can_id) &&
           config_index(config, pdo->node_id) < config->slave_count;
}

static bool pdos_valid(const co_net_master_config_t *config, const co_net_pdo_t *pdos, size_t count,
                       const uint8_t *image, size_t image_size)
{
    if ((count > 0 && pdos == NULL) || (image == NULL && (count > 0 || image_size > 0)))
        return false;
    for (size_t i = 0; i < count; i++) {
        if (!pdo_valid(config, &pdos[i], image_size))
            return false;
    }
    return true;
}

static bool slave_valid(const co_net_master_config_t *config, size_t i)
{
    const co_net_slave_config_t *s = &config->slaves[i];
    if (s->node_id < 1 || s->node_id > CO_NMT_MASTER_NODE_ID_MAX)
        return false;
    for (size_t j = 0; j < i; j++) {
        if (config->slaves[j].node_id == s->node_id)
            return false;
    }
    if (s->write_count > 0 && s->writes == NULL)
        return false;
    for (size_t w = 0; w < s->write_count; w++) {
        if (s->writes[w].data == NULL || s->writes[w].len == 0)
            return false;
    }
    return true;
}

static bool config_valid(const co_net_master_config_t *config)
{
    if (config == NULL || config->send == NULL || config->slaves == NULL ||
        config->slave_state == NULL || config->slave_count == 0 ||
        config->slave_count > CO_NMT_MASTER_NODE_ID_MAX ||
        config->sdo_timeout_ms < CO_NET_SDO_TIMEOUT_MIN_MS ||
        config->sdo_timeout_ms > CO_NET_SDO_TIMEOUT_MAX_MS || config->start > CO_NET_START_NONE)
        return false;
    if (config->heartbeat_ms != 0 &&
        (config->node_id < 1 || config->node_id > CO_NMT_MASTER_NODE_ID_MAX ||
         config_index(config, config->node_id) != config->slave_count))
        return false;
    for (size_t i = 0; i < config->slave_count; i++) {
        if (!slave_valid(config, i))
            return false;
    }
    return pdos_valid(config, config->inputs, config->input_count, config->input_image,
                      config->input_size) &&
           pdos_valid(config, config->outputs, config->output_count, config->output_image,
                      config->output_size);
}

static void fail(co_net_master_t *m, size_t i, co_net_failure_t failure);
static void finish_request(co_net_master_t *m, const co_sdo_client_result_t *result);
static bool ready(const co_net_master_t *m, const co_net_slave_t *s);
static void forward_send(void *user, const co_frame_t *frame);
static void sdo_done(void *user, const co_sdo_client_result_t *result);
static void begin_identity(co_net_master_t *m, size_t i);
static void begin_download(co_net_master_t *m, size_t i);

static void record_sdo_error(co_net_master_t *m, uint8_t node_id, const co_sdo_client_result_t *r,
                             uint8_t access, uint32_t value)
{
    m->last_sdo_error = (co_net_sdo_error_t){.node_id = node_id,
                                             .index = r->index,
                                             .subindex = r->subindex,
                                             .access = access,
                                             .value = value,
                                             .abort_code = r->abort_code};
    report(m, CO_NET_EVENT_SDO_ERROR, m->last_sdo_error.node_id, 0);
}

/* The first 4 bytes of a written value, little-endian (the PLC300's record of a write). */
static uint32_t written_value(const uint8_t *data, uint32_t len)
{
    uint8_t b[4] = {0};
    memcpy(b, data, len < 4 ? len : 4);
    return le32(b);
}

static bool read(co_net_master_t *m, uint16_t index, uint8_t subindex)
{
    memset(m->value, 0, sizeof(m->value));
    return co_sdo_client_upload(&m->sdo, index, subindex, m->value, sizeof(m->value),
                                CO_SDO_CLIENT_AUTO, m->config.sdo_timeout_ms, m->now) == 0;
}

/* The SDO client is idle whenever a slave's step starts a request, so a request can only fail
 * for a bad argument, which co_net_master_init rules out; the failure is still not ignored. */
static void begin_read(co_net_master_t *m, size_t i, uint16_t index, uint8_t subindex)
{
    if (!read(m, index, subindex))
        fail(m, i, CO_NET_FAIL_SDO);
}

static void release(co_net_master_t *m)
{
    m->current = m->config.slave_count;
}

/* A failed attempt keeps "contacted" when its identification succeeded (the attempt cleared it
 * when it began): the PLC300 (5.6.3) shows a slave that was found but refused its configuration
 * as contacted with an init error, one that was not found as an init error alone. */
static void fail(co_net_master_t *m, size_t i, co_net_failure_t failure)
{
    co_net_slave_t *s = slave_at(m, i);
    s->failure = (uint8_t)failure;
    s->deadline = after_ms(m->now, m->config.retry_delay_ms);
    s->tried = true;
    set_step(m, i, CO_NET_STEP_FAILED);
    set_status(m, i,
               (uint16_t)((s->status & ~(SLAVE_PROGRESS & ~CO_NET_SLAVE_CONTACTED)) |
                          CO_NET_SLAVE_INIT_ERROR));
    if (m->current == i)
        release(m);
}

/* The slave's transfer under way, if any, is dropped without a frame: the slave restarted (its
 * boot-up came, or the master reset it), so its server holds no transfer an abort could end. */
static void abandon_transfer(co_net_master_t *m, size_t i)
{
    if (m->current != i)
        return;
    co_sdo_client_cancel(&m->sdo);
    release(m);
}

static void begin_attempt(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = slave_at(m, i);
    co_sdo_client_config_t sdo = {.server_node_id = slave_config(m, i)->node_id,
                                  .send = forward_send,
                                  .user = m,
                                  .done = sdo_done};
    m->current = i;
    clear_status(m, i, SLAVE_PROGRESS);
    if (co_sdo_client_init(&m->sdo, &sdo) != 0) {
        fail(m, i, CO_NET_FAIL_SDO);
        return;
    }
    s->failure = CO_NET_FAIL_NONE;
    set_step(m, i, CO_NET_STEP_DEVICE_TYPE);
    begin_read(m, i, CO_IDX_DEVICE_TYPE, 0);
}

static void begin_identity(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = slave_at(m, i);
    const co_net_slave_config_t *c = slave_config(m, i);
    while (s->identity_sub < CO_NET_IDENTITY_SUBS &&
           (c->check & (CO_NET_CHECK_VENDOR << s->identity_sub)) == 0)
        s->identity_sub++;
    if (s->identity_sub == CO_NET_IDENTITY_SUBS) {
        add_status(m, i, CO_NET_SLAVE_CONTACTED);
        begin_download(m, i);
        return;
    }
    set_step(m, i, CO_NET_STEP_IDENTITY);
    begin_read(m, i, CO_IDX_IDENTITY, (uint8_t)(s->identity_sub + 1));
}

/* CiA 301's heartbeat consumer waits for the first heartbeat forever, so a slave that dies right
 * after its configuration would never be seen lost: the master expects that first heartbeat within
 * one consumer time of starting error control (the download has just set the slave's 1017h). */
static void start_error_control(co_net_master_t *m, size_t i)
{
    const co_net_slave_config_t *c = slave_config(m, i);
    if (c->heartbeat_ms != 0)
        co_nmt_master_await_heartbeat(&m->nmt, c->node_id, c->heartbeat_ms, m->now);
    else if (c->guard_ms != 0 && c->life_time_factor != 0)
        co_nmt_master_guard(&m->nmt, c->node_id, c->guard_ms, c->life_time_factor, m->now);
    add_status(m, i, CO_NET_SLAVE_EC_STARTED);
}

static void stop_error_control(co_net_master_t *m, size_t i)
{
    uint8_t node_id = slave_config(m, i)->node_id;
    co_nmt_master_heartbeat(&m->nmt, node_id, 0);
    co_nmt_master_guard(&m->nmt, node_id, 0, 0, m->now);
}

static void become_operational(co_net_master_t *m, size_t i)
{
    slave_at(m, i)->tried = true;
    set_status(m, i,
               (uint16_t)((slave_at(m, i)->status | CO_NET_SLAVE_INIT_DONE) &
                          ~(CO_NET_SLAVE_INIT_ERROR | CO_NET_SLAVE_EC_ERROR)));
    set_step(m, i, CO_NET_STEP_OPERATIONAL);
}

/* The last step of a configured slave's boot: it waits for the start of all until that is sent;
 * afterwards it is started alone (CO_NET_START_EACH, or CO_NET_START_ALL once it went out). */
static void start_slave(co_net_master_t *m, size_t i)
{
    if (m->config.start == CO_NET_START_ALL && !m->started_all) {
        slave_at(m, i)->tried = true;
        set_step(m, i, CO_NET_STEP_WAIT_START);
        return;
    }
    if (m->config.start != CO_NET_START_NONE)
        co_nmt_master_command(&m->nmt, CO_NMT_CS_START, slave_config(m, i)->node_id);
    become_operational(m, i);
}

static void finish_boot(co_net_master_t *m, size_t i)
{
    add_status(m, i, CO_NET_SLAVE_CONFIGURED);
    start_error_control(m, i);
    release(m);
    start_slave(m, i);
}

static void download_next(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = slave_at(m, i);
    const co_net_slave_config_t *c = slave_config(m, i);
    if (s->write_pos == c->write_count) {
        finish_boot(m, i);
        return;
    }
    const co_net_write_t *w = &c->writes[s->write_pos];
    if (co_sdo_client_download(&m->sdo, w->index, w->subindex, w->data, w->len, CO_SDO_CLIENT_AUTO,
                               m->config.sdo_timeout_ms, m->now) != 0)
        fail(m, i, CO_NET_FAIL_SDO);
}

static void begin_download(co_net_master_t *m, size_t i)
{
    slave_at(m, i)->write_pos = 0;
    set_step(m, i, CO_NET_STEP_DOWNLOAD);
    download_next(m, i);
}

static void identity_read(co_net_master_t *m, size_t i, uint32_t value)
{
    co_net_slave_t *s = slave_at(m, i);
    s->read_value = value;
    if (value != slave_config(m, i)->identity[s->identity_sub]) {
        fail(m, i, CO_NET_FAIL_IDENTITY);
        return;
    }
    s->identity_sub++;
    begin_identity(m, i);
}

static void device_type_read(co_net_master_t *m, size_t i, uint32_t value)
{
    const co_net_slave_config_t *c = slave_config(m, i);
    co_net_slave_t *s = slave_at(m, i);
    s->read_value = value;
    if ((c->check & CO_NET_CHECK_DEVICE_TYPE) != 0 && value != c->device_type) {
        fail(m, i, CO_NET_FAIL_DEVICE_TYPE);
        return;
    }
    s->identity_sub = 0;
    begin_identity(m, i);
}

static void sdo_done(void *user, const co_sdo_client_result_t *result)
{
    co_net_master_t *m = user;
    if (m->serving) {
        finish_request(m, result);
        return;
    }
    size_t i = m->current;
    if (i == m->config.slave_count)
        return;
    co_net_slave_t *s = slave_at(m, i);
    if (result->status != CO_SDO_CLIENT_OK) {
        uint8_t node_id = slave_config(m, i)->node_id;
        if (s->step == CO_NET_STEP_DOWNLOAD) {
            const co_net_write_t *w = &slave_config(m, i)->writes[s->write_pos];
            record_sdo_error(m, node_id, result, CO_NET_ACCESS_WRITE,
                             written_value(w->data, w->len));
        } else {
            record_sdo_error(m, node_id, result, CO_NET_ACCESS_READ, 0);
        }
        fail(m, i, CO_NET_FAIL_SDO);
        return;
    }
    switch (s->step) {
    case CO_NET_STEP_DEVICE_TYPE:
        device_type_read(m, i, le32(m->value));
        break;
    case CO_NET_STEP_IDENTITY:
        identity_read(m, i, le32(m->value));
        break;
    case CO_NET_STEP_DOWNLOAD:
        s->write_pos++;
        download_next(m, i);
        break;
    default:
        break;
    }
}

/* A slave that was reset or restarted: nothing of its boot so far holds, and its boot-up is
 * awaited (or `booted`: it came). */
static void await_boot(co_net_master_t *m, size_t i, bool booted)
{
    co_net_slave_t *s = slave_at(m, i);
    abandon_transfer(m, i);
    stop_error_control(m, i);
    clear_status(m, i, SLAVE_PROGRESS);
    s->booted = booted;
    s->deadline = after_ms(m->now, m->config.boot_time_ms);
    set_step(m, i, CO_NET_STEP_WAIT_BOOT);
}

/* Resets one slave (its communication for a boot, the whole node after an error-control loss,
 * so that it also forgets a half-applied configuration) and waits for its boot-up. */
static void reset_slave(co_net_master_t *m, size_t i, uint8_t command)
{
    co_nmt_master_command(&m->nmt, command, slave_config(m, i)->node_id);
    await_boot(m, i, false);
}

static void error_control_lost(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = slave_at(m, i);
    if (s->step != CO_NET_STEP_OPERATIONAL && s->step != CO_NET_STEP_WAIT_START)
        return;
    if (slave_config(m, i)->on_error == CO_NET_ON_ERROR_REPORT) {
        add_status(m, i, CO_NET_SLAVE_EC_ERROR);
        set_step(m, i, CO_NET_STEP_LOST);
        return;
    }
    set_status(m, i, (uint16_t)((s->status & ~SLAVE_PROGRESS) | CO_NET_SLAVE_EC_ERROR));
    reset_slave(m, i, CO_NMT_CS_RESET_NODE);
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
    co_net_slave_t *s = slave_at(m, i);
    if (s->step == CO_NET_STEP_IDLE)
        return;
    if (awaited_boot_up(s)) {
        s->booted = true;
        return;
    }
    await_boot(m, i, true);
}

/* A slave lost under CO_NET_ON_ERROR_REPORT is heard again (any heartbeat, or a valid guarding
 * reply): it returns to where it was lost, running (bit 3 set) or waiting for the start of all,
 * which may have been sent meanwhile. */
static void resumed(co_net_master_t *m, size_t i)
{
    if (slave_at(m, i)->step != CO_NET_STEP_LOST)
        return;
    clear_status(m, i, CO_NET_SLAVE_EC_ERROR);
    if ((slave_at(m, i)->status & CO_NET_SLAVE_INIT_DONE) != 0)
        set_step(m, i, CO_NET_STEP_OPERATIONAL);
    else
        start_slave(m, i);
}

static void nmt_event(void *user, const co_nmt_master_event_t *event)
{
    co_net_master_t *m = user;
    size_t i = slave_index(m, event->node_id);
    if (i == m->config.slave_count)
        return;
    switch (event->kind) {
    case CO_NMT_MASTER_BOOT_UP:
        booted_up(m, i);
        break;
    case CO_NMT_MASTER_HEARTBEAT_LOST:
    case CO_NMT_MASTER_GUARDING_LOST:
        error_control_lost(m, i);
        break;
    case CO_NMT_MASTER_RESUMED:
        resumed(m, i);
        break;
    default: /* a state change: the state of a slave is not checked (docs/net-master.md) */
        break;
    }
}

static void emcy_received(void *user, co_emcy_decode_t result, const co_emcy_message_t *msg,
                          co_time_t now)
{
    (void)now;
    co_net_master_t *m = user;
    if (result != CO_EMCY_DECODE_OK)
        return;
    m->last_emcy = *msg;
    report(m, CO_NET_EVENT_EMCY, msg->node_id, 0);
}

static void send(co_net_master_t *m, const co_frame_t *frame)
{
    m->config.send(m->config.user, frame);
}

/* The send callback of the NMT master and the SDO client, whose `user` is the master itself (it
 * also receives their events). */
static void forward_send(void *user, const co_frame_t *frame)
{
    send(user, frame);
}

static void send_output(co_net_master_t *m, size_t p)
{
    const co_net_pdo_t *pdo = &m->config.outputs[p];
    co_frame_t frame = {.id = pdo->can_id, .len = pdo->len};
    memcpy(frame.data, m->config.output_image + pdo->offset, pdo->len);
    send(m, &frame);
}

static bool output_live(const co_net_master_t *m, size_t p)
{
    size_t i = slave_index(m, m->config.outputs[p].node_id);
    return m->config.slave_state[i].step == CO_NET_STEP_OPERATIONAL;
}

bool co_net_master_init(co_net_master_t *master, const co_net_master_config_t *config)
{
    if (!config_valid(config))
        return false;
    *master = (co_net_master_t){.config = *config};
    co_nmt_master_init(&master->nmt, &(co_nmt_master_config_t){
                                         .send = forward_send, .user = master, .event = nmt_event});
    co_emcy_consumer_init(&master->emcy, emcy_received, master);
    for (size_t i = 0; i < config->slave_count; i++) {
        config->slave_state[i] = (co_net_slave_t){.step = CO_NET_STEP_IDLE};
        co_emcy_consumer_watch(&master->emcy, config->slaves[i].node_id, true);
    }
    master->sync.next = CO_TIME_NEVER;
    master->next_heartbeat = CO_TIME_NEVER;
    if (config->sync_period_us != 0)
        co_sync_producer_init(&master->sync, CO_CAN_ID_SYNC, config->sync_period_us, 0);
    release(master);
    return true;
}

void co_net_master_start(co_net_master_t *master, co_time_t now)
{
    master->now = now;
    master->started = true;
    master->started_all = false;
    if (master->config.heartbeat_ms != 0)
        master->next_heartbeat = now;
    if (master->config.reset_all)
        co_nmt_master_command(&master->nmt, CO_NMT_CS_RESET_COMMUNICATION, CO_NMT_MASTER_ALL_NODES);
    for (size_t i = 0; i < master->config.slave_count; i++) {
        slave_at(master, i)->tried = false;
        set_status(master, i, 0);
        if (master->config.reset_all)
            await_boot(master, i, false);
        else
            reset_slave(master, i, CO_NMT_CS_RESET_COMMUNICATION);
    }
}

/* ---- NMT commands of the application, confirmed by the state the nodes report -------------- */

/* Node-id n is bit n % 32 of awaited[n / 32]. */
static uint32_t awaited_bit(uint8_t node_id)
{
    return 1u << (node_id % 32u);
}

static bool nmt_awaits(const co_net_nmt_request_t *r, uint8_t node_id)
{
    return r->pending && (r->awaited[node_id / 32u] & awaited_bit(node_id)) != 0;
}

static void nmt_await(co_net_nmt_request_t *r, uint8_t node_id)
{
    r->awaited[node_id / 32u] |= awaited_bit(node_id);
}

static bool nmt_awaits_any(const co_net_nmt_request_t *r)
{
    return (r->awaited[0] | r->awaited[1] | r->awaited[2] | r->awaited[3]) != 0;
}

static void finish_nmt(co_net_master_t *m)
{
    m->nmt_request.pending = false;
    report(m, CO_NET_EVENT_NMT_DONE, m->nmt_request.node_id, 0);
}

static void confirm_nmt(co_net_master_t *m, uint8_t node_id, uint8_t state)
{
    co_net_nmt_request_t *r = &m->nmt_request;
    if (!nmt_awaits(r, node_id) || state != r->expected)
        return;
    r->awaited[node_id / 32u] &= ~awaited_bit(node_id);
    if (!nmt_awaits_any(r))
        finish_nmt(m);
}

/* The state a node reports after the command: a reset ends with its boot-up. */
static bool nmt_expected_state(uint8_t command, uint8_t *state)
{
    switch (command) {
    case CO_NMT_CS_START:
        *state = CO_NMT_OPERATIONAL;
        return true;
    case CO_NMT_CS_STOP:
        *state = CO_NMT_STOPPED;
        return true;
    case CO_NMT_CS_ENTER_PRE_OPERATIONAL:
        *state = CO_NMT_PRE_OPERATIONAL;
        return true;
    case CO_NMT_CS_RESET_NODE:
    case CO_NMT_CS_RESET_COMMUNICATION:
        *state = CO_NMT_INITIALISING;
        return true;
    default:
        return false;
    }
}

/* A node whose heartbeat the master consumes, or which it guards, tells its state by itself; any
 * other is asked once by a guarding request (its reply carries the state). */
static void ask_state(co_net_master_t *m, uint8_t node_id)
{
    const co_nmt_master_slave_t *n = &m->nmt.slave[node_id - 1u];
    if (n->heartbeat.time_us != 0 || n->guard_us != 0)
        return;
    co_frame_t rtr = {.id = CO_CAN_ID_ERROR_CONTROL + node_id, .len = 1, .flags = CO_FRAME_RTR};
    send(m, &rtr);
}

bool co_net_master_nmt(co_net_master_t *master, uint8_t command, uint8_t node_id,
                       uint32_t timeout_ms, co_time_t now)
{
    co_net_nmt_request_t *r = &master->nmt_request;
    uint8_t expected;
    if (master->disabled || r->pending || node_id > CO_NMT_MASTER_NODE_ID_MAX ||
        !nmt_expected_state(command, &expected))
        return false;
    master->now = now;
    *r = (co_net_nmt_request_t){.pending = true,
                                .command = command,
                                .node_id = node_id,
                                .expected = expected,
                                .deadline = after_ms(now, timeout_ms)};
    if (node_id != CO_NMT_MASTER_ALL_NODES)
        nmt_await(r, node_id);
    for (size_t i = 0; node_id == CO_NMT_MASTER_ALL_NODES && i < master->config.slave_count; i++)
        nmt_await(r, slave_config(master, i)->node_id);
    co_nmt_master_command(&master->nmt, command, node_id);
    master->nmt_toggle ^= CO_NET_MASTER_NMT_TOGGLE;
    for (unsigned id = 1; expected != CO_NMT_INITIALISING && id <= CO_NMT_MASTER_NODE_ID_MAX;
         id++) {
        if (nmt_awaits(r, (uint8_t)id))
            ask_state(master, (uint8_t)id);
    }
    return true;
}

bool co_net_master_nmt_awaited(const co_net_master_t *master, uint8_t node_id)
{
    return node_id <= CO_NMT_MASTER_NODE_ID_MAX &&
           (master->nmt_request.awaited[node_id / 32u] & awaited_bit(node_id)) != 0;
}

/* ---- SDO requests of the application on the master's client --------------------------------- */

static bool client_free(const co_net_master_t *m)
{
    return m->current == m->config.slave_count && !m->serving;
}

/* Ends the first request (under way, or dropped before it started) with `result`. */
static void finish_request(co_net_master_t *m, const co_sdo_client_result_t *result)
{
    co_net_request_t request = m->requests[0];
    m->request_count--;
    memmove(&m->requests[0], &m->requests[1], m->request_count * sizeof m->requests[0]);
    m->serving = false;
    if (result->status != CO_SDO_CLIENT_OK)
        record_sdo_error(m, request.node_id, result,
                         request.write ? CO_NET_ACCESS_WRITE : CO_NET_ACCESS_READ,
                         request.write ? written_value(request.data, request.len) : 0);
    request.done(request.user, &request, result);
}

static co_sdo_client_result_t request_failed(const co_net_request_t *r, uint32_t abort_code)
{
    return (co_sdo_client_result_t){.status = CO_SDO_CLIENT_CLIENT_ABORT,
                                    .abort_code = abort_code,
                                    .index = r->index,
                                    .subindex = r->subindex};
}

/* A slave of the table that was reset and whose boot-up has not come yet (nor its boot time
 * ended) would not answer, or answer after its reset: a request to it waits. */
static bool resetting(const co_net_master_t *m, uint8_t node_id)
{
    size_t i = slave_index(m, node_id);
    if (i == m->config.slave_count)
        return false;
    const co_net_slave_t *s = &m->config.slave_state[i];
    return s->step == CO_NET_STEP_WAIT_BOOT && !ready(m, s);
}

/* Starts the first request waiting, when no slave's boot holds the client. */
static void serve_request(co_net_master_t *m)
{
    if (!client_free(m) || m->request_count == 0 || resetting(m, m->requests[0].node_id))
        return;
    const co_net_request_t *r = &m->requests[0];
    co_sdo_client_config_t sdo = {
        .server_node_id = r->node_id, .send = forward_send, .user = m, .done = sdo_done};
    m->serving = true;
    int rc = co_sdo_client_init(&m->sdo, &sdo);
    if (rc == 0 && r->write)
        rc = co_sdo_client_download(&m->sdo, r->index, r->subindex, r->data, r->len,
                                    CO_SDO_CLIENT_AUTO, m->config.sdo_timeout_ms, m->now);
    else if (rc == 0)
        rc = co_sdo_client_upload(&m->sdo, r->index, r->subindex, r->data, r->len,
                                  CO_SDO_CLIENT_AUTO, m->config.sdo_timeout_ms, m->now);
    if (rc != 0) {
        co_sdo_client_result_t result = request_failed(r, CO_SDO_ABORT_GENERAL);
        finish_request(m, &result);
    }
}

bool co_net_master_sdo(co_net_master_t *master, const co_net_request_t *request, co_time_t now)
{
    if (master->disabled || master->request_count == CO_NET_REQUEST_MAX || request == NULL ||
        request->node_id < 1 || request->node_id > CO_NMT_MASTER_NODE_ID_MAX ||
        request->data == NULL || request->len == 0 || request->done == NULL)
        return false;
    master->now = now;
    master->requests[master->request_count++] = *request;
    return true;
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
    if (master->serving)
        co_sdo_client_cancel(&master->sdo);
    for (size_t i = 0; i < master->config.slave_count; i++) {
        co_net_slave_t *s = slave_at(master, i);
        abandon_transfer(master, i);
        stop_error_control(master, i);
        s->booted = false;
        s->tried = false;
        set_status(master, i, 0);
        set_step(master, i, CO_NET_STEP_IDLE);
    }
    while (master->request_count > 0) {
        co_sdo_client_result_t result = request_failed(&master->requests[0], CO_SDO_ABORT_TIMEOUT);
        finish_request(master, &result);
    }
    master->last_sdo_error = (co_net_sdo_error_t){0};
    master->last_emcy = (co_emcy_message_t){0};
    master->nmt_toggle = 0;
    if (master->nmt_request.pending)
        finish_nmt(master);
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

static bool receive_input(co_net_master_t *m, const co_frame_t *frame)
{
    bool used = false;
    for (size_t p = 0; p < m->config.input_count; p++) {
        const co_net_pdo_t *pdo = &m->config.inputs[p];
        /* CiA 301: a PDO shorter than its mapping is not used; a longer one is (its first bytes
         * are the mapped ones). */
        if (pdo->can_id != frame->id || frame->len < pdo->len)
            continue;
        memcpy(m->config.input_image + pdo->offset, frame->data, pdo->len);
        report(m, CO_NET_EVENT_INPUT, pdo->node_id, p);
        used = true;
    }
    return used;
}

bool co_net_master_receive(co_net_master_t *master, const co_frame_t *frame, co_time_t now)
{
    master->now = now;
    /* A master consumes no remote or 29-bit frame (CiA 301 uses neither for what it receives);
     * a disabled one none at all. */
    if ((frame->flags & (CO_FRAME_EFF | CO_FRAME_RTR)) != 0 || master->disabled)
        return false;
    if (co_nmt_master_receive(&master->nmt, frame, now)) {
        confirm_nmt(master, (uint8_t)(frame->id - CO_CAN_ID_ERROR_CONTROL),
                    (uint8_t)(frame->data[0] & CO_NMT_STATE_MASK));
        return true;
    }
    if (co_sdo_client_busy(&master->sdo) && co_sdo_client_receive(&master->sdo, frame, now))
        return true;
    if (co_emcy_consumer_receive(&master->emcy, frame, now))
        return true;
    return receive_input(master, frame);
}

/* A slave waiting for its boot-up is ready for its identification when the boot-up came or the
 * boot time ended; it then waits only for the SDO client, which a frame or a timeout of the slave
 * holding it frees, never a time of its own. */
static bool ready(const co_net_master_t *m, const co_net_slave_t *s)
{
    return s->step == CO_NET_STEP_WAIT_BOOT && (s->booted || m->now >= s->deadline);
}

/* The next slave whose turn has come, searched from next_pick so that a slave that just failed is
 * tried again only after the others. */
static size_t next_ready(co_net_master_t *m)
{
    size_t n = m->config.slave_count;
    for (size_t k = 0; k < n; k++) {
        size_t i = (m->next_pick + k) % n;
        if (ready(m, slave_at(m, i)))
            return i;
    }
    return n;
}

static void retry_failed(co_net_master_t *m)
{
    for (size_t i = 0; i < m->config.slave_count; i++) {
        const co_net_slave_t *s = slave_at(m, i);
        if (s->step == CO_NET_STEP_FAILED && m->now >= s->deadline)
            reset_slave(m, i, CO_NMT_CS_RESET_COMMUNICATION);
    }
}

static bool network_ready(const co_net_master_t *m)
{
    for (size_t i = 0; i < m->config.slave_count; i++) {
        const co_net_slave_t *s = &m->config.slave_state[i];
        if (!s->tried)
            return false;
        if (m->config.slaves[i].mandatory && s->step != CO_NET_STEP_WAIT_START)
            return false;
    }
    return true;
}

static void start_all(co_net_master_t *m)
{
    if (m->config.start != CO_NET_START_ALL || m->started_all || !network_ready(m))
        return;
    m->started_all = true;
    co_nmt_master_command(&m->nmt, CO_NMT_CS_START, CO_NMT_MASTER_ALL_NODES);
    report(m, CO_NET_EVENT_STARTED, 0, 0);
    for (size_t i = 0; i < m->config.slave_count; i++) {
        if (slave_at(m, i)->step == CO_NET_STEP_WAIT_START)
            become_operational(m, i);
    }
}

static void produce_sync(co_net_master_t *m)
{
    co_frame_t frame;
    if (!co_sync_producer_take(&m->sync, m->now, &frame))
        return;
    send(m, &frame);
    for (size_t p = 0; p < m->config.output_count; p++) {
        if (output_live(m, p))
            send_output(m, p);
    }
}

/* The end of a boot time not yet reached, or of a retry delay (retry_failed has just run the
 * ones that ended). */
static co_time_t slave_deadline(const co_net_master_t *m)
{
    co_time_t next = CO_TIME_NEVER;
    for (size_t i = 0; i < m->config.slave_count; i++) {
        const co_net_slave_t *s = &m->config.slave_state[i];
        if ((s->step == CO_NET_STEP_WAIT_BOOT && !ready(m, s)) || s->step == CO_NET_STEP_FAILED)
            next = co_time_min(next, s->deadline);
    }
    return next;
}

/* The master's own heartbeat: Operational (it runs the network), on the grid of its start. */
static co_time_t produce_heartbeat(co_net_master_t *m)
{
    if (m->next_heartbeat > m->now)
        return m->next_heartbeat;
    co_frame_t beat = {
        .id = CO_CAN_ID_ERROR_CONTROL + m->config.node_id, .len = 1, .data = {CO_NMT_OPERATIONAL}};
    send(m, &beat);
    m->next_heartbeat = co_time_next_period(m->next_heartbeat,
                                            (co_time_t)m->config.heartbeat_ms * US_PER_MS, m->now);
    return m->next_heartbeat;
}

static co_time_t nmt_deadline(co_net_master_t *m)
{
    if (!m->nmt_request.pending)
        return CO_TIME_NEVER;
    if (m->now >= m->nmt_request.deadline)
        finish_nmt(m);
    return m->nmt_request.pending ? m->nmt_request.deadline : CO_TIME_NEVER;
}

co_time_t co_net_master_process(co_net_master_t *master, co_time_t now)
{
    master->now = now;
    if (master->disabled)
        return CO_TIME_NEVER;
    co_time_t next = co_nmt_master_process(&master->nmt, now);
    next = co_time_min(next, co_sdo_client_process(&master->sdo, now));
    next = co_time_min(next, nmt_deadline(master));
    if (!master->started) {
        serve_request(master);
        return co_time_min(next, co_sdo_client_process(&master->sdo, now));
    }
    next = co_time_min(next, produce_heartbeat(master));
    retry_failed(master);
    while (client_free(master)) {
        size_t i = next_ready(master);
        if (i == master->config.slave_count)
            break;
        master->next_pick = (i + 1) % master->config.slave_count;
        begin_attempt(master, i);
    }
    start_all(master);
    if (master->config.sync_period_us != 0) {
        if (master->sync.next == CO_TIME_NEVER)
            co_sync_producer_start(&master->sync, now);
        produce_sync(master);
        next = co_time_min(next, master->sync.next);
    }
    serve_request(master);
    if (!client_free(master))
        next = co_time_min(next, co_sdo_client_process(&master->sdo, now));
    return co_time_min(next, slave_deadline(master));
}

/* Sends output PDO `p` with the bytes offset..offset+len replaced by `data`, when they change
 * its content (the image itself is updated after every PDO was looked at). */
static void send_changed_output(co_net_master_t *m, size_t p, size_t offset, const uint8_t *data,
                                size_t len)
{
    const co_net_pdo_t *pdo = &m->config.outputs[p];
    co_frame_t frame = {.id = pdo->can_id, .len = pdo->len};
    memcpy(frame.data, m->config.output_image + pdo->offset, pdo->len);
    bool changed = false;
    for (size_t k = 0; k < pdo->len; k++) {
        size_t at = (size_t)pdo->offset + k;
        if (at >= offset && at < offset + len && frame.data[k] != data[at - offset]) {
            frame.data[k] = data[at - offset];
            changed = true;
        }
    }
    if (changed)
        send(m, &frame);
}

bool co_net_master_write_output(co_net_master_t *master, size_t offset, const uint8_t *data,
                                size_t len)
{
    if (data == NULL || master->config.output_image == NULL ||
        offset > master->config.output_size || len > master->config.output_size - offset)
        return false;
    for (size_t p = 0; p < master->config.output_count; p++) {
        if (output_live(master, p))
            send_changed_output(master, p, offset, data, len);
    }
    memcpy(master->config.output_image + offset, data, len);
    return true;
}

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
    return all | some | own;
}

const co_net_slave_t *co_net_master_slave(const co_net_master_t *master, uint8_t node_id)
{
    size_t i = slave_index(master, node_id);
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
