/* SPDX-License-Identifier: Apache-2.0 */
/* The boot of the network master's slaves after the PLC300's section 7.3: each slave reset, then
 * one at a time on the master's single SDO client identified (1000h, the checked 1018h subs),
 * configured (the application's writes), its error control started and the slave started, or
 * left waiting for the start of all; a failed slave retried after the others
 * (docs/net-master.md, "The boot of a slave"). */
#include "canopen/master/net/net_floors.h"

#include <string.h>

static bool read(co_net_master_t *m, uint16_t index, uint8_t subindex)
{
    memset(m->value, 0, sizeof(m->value));
    return co_sdo_client_upload(&m->sdo, index, subindex, m->value, sizeof(m->value),
                                CO_SDO_CLIENT_AUTO, m->config.sdo_timeout_ms, m->now) == 0;
}

void co_net_release(co_net_master_t *m)
{
    m->current = m->config.slave_count;
}

/* CiA 302-2's error status of the step that failed: the read of 1000h (B, or C for another
 * value), of a 1018h sub (its own letter, whether the value differs or could not be read: either
 * way the slave is not shown to be the one expected), the download (J). */
static uint8_t boot_error(const co_net_slave_t *s, co_net_failure_t failure)
{
    static const uint8_t identity_errors[CO_NET_IDENTITY_SUBS] = {
        CO_NET_BOOT_ERROR_D, CO_NET_BOOT_ERROR_M, CO_NET_BOOT_ERROR_N, CO_NET_BOOT_ERROR_O};
    if (failure == CO_NET_FAIL_DEVICE_TYPE)
        return CO_NET_BOOT_ERROR_C;
    if (s->step == CO_NET_STEP_IDENTITY)
        return identity_errors[s->identity_sub];
    return s->step == CO_NET_STEP_DOWNLOAD ? CO_NET_BOOT_ERROR_J : CO_NET_BOOT_ERROR_B;
}

/* A failed attempt keeps "contacted" when its identification succeeded (the attempt cleared it
 * when it began): the PLC300 (5.6.3) shows a slave that was found but refused its configuration
 * as contacted with an init error, one that was not found as an init error alone. */
static void fail(co_net_master_t *m, size_t i, co_net_failure_t failure)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    s->failure = (uint8_t)failure;
    s->boot_error = boot_error(s, failure);
    s->deadline = co_net_after_ms(m->now, m->config.retry_delay_ms);
    s->tried = true;
    co_net_set_step(m, i, CO_NET_STEP_FAILED);
    co_net_set_status(m, i,
                      (uint16_t)((s->status & ~(CO_NET_SLAVE_PROGRESS & ~CO_NET_SLAVE_CONTACTED)) |
                                 CO_NET_SLAVE_INIT_ERROR));
    if (m->current == i)
        co_net_release(m);
}

/* The SDO client is idle whenever a slave's step starts a request, so a request can only fail
 * for a bad argument, which co_net_master_init rules out; the failure is still not ignored. */
static void begin_read(co_net_master_t *m, size_t i, uint16_t index, uint8_t subindex)
{
    if (!read(m, index, subindex))
        fail(m, i, CO_NET_FAIL_SDO);
}

/* The slave restarted (its boot-up came, or the master reset it), so its server holds no
 * transfer an abort could end. */
void co_net_abandon_transfer(co_net_master_t *m, size_t i)
{
    if (m->current != i)
        return;
    co_sdo_client_cancel(&m->sdo);
    co_net_release(m);
}

/* CiA 301's heartbeat consumer waits for the first heartbeat forever, so a slave that dies right
 * after its configuration would never be seen lost: the master expects that first heartbeat within
 * one consumer time of starting error control (the download has just set the slave's 1017h). */
static void start_error_control(co_net_master_t *m, size_t i)
{
    const co_net_slave_config_t *c = co_net_slave_config(m, i);
    if (c->heartbeat_ms != 0)
        co_nmt_master_await_heartbeat(&m->nmt, c->node_id, c->heartbeat_ms, m->now);
    else if (c->guard_ms != 0 && c->life_time_factor != 0)
        co_nmt_master_guard(&m->nmt, c->node_id, c->guard_ms, c->life_time_factor, m->now);
    co_net_add_status(m, i, CO_NET_SLAVE_EC_STARTED);
}

void co_net_stop_error_control(co_net_master_t *m, size_t i)
{
    uint8_t node_id = co_net_slave_config(m, i)->node_id;
    co_nmt_master_heartbeat(&m->nmt, node_id, 0);
    co_nmt_master_guard(&m->nmt, node_id, 0, 0, m->now);
}

static void become_operational(co_net_master_t *m, size_t i)
{
    co_net_slave_at(m, i)->tried = true;
    co_net_set_status(m, i,
                      (uint16_t)((co_net_slave_at(m, i)->status | CO_NET_SLAVE_INIT_DONE) &
                                 ~(CO_NET_SLAVE_INIT_ERROR | CO_NET_SLAVE_EC_ERROR)));
    co_net_set_step(m, i, CO_NET_STEP_OPERATIONAL);
}

/* It waits for the start of all until that is sent; afterwards it is started alone
 * (CO_NET_START_EACH, or CO_NET_START_ALL once it went out). */
void co_net_start_slave(co_net_master_t *m, size_t i)
{
    if (m->config.start == CO_NET_START_ALL && !m->started_all) {
        co_net_slave_at(m, i)->tried = true;
        co_net_set_step(m, i, CO_NET_STEP_WAIT_START);
        return;
    }
    if (m->config.start != CO_NET_START_NONE)
        co_nmt_master_command(&m->nmt, CO_NMT_CS_START, co_net_slave_config(m, i)->node_id);
    become_operational(m, i);
}

static void finish_boot(co_net_master_t *m, size_t i)
{
    co_net_slave_at(m, i)->boot_error = CO_NET_BOOT_ERROR_NONE;
    co_net_add_status(m, i, CO_NET_SLAVE_CONFIGURED);
    start_error_control(m, i);
    co_net_release(m);
    co_net_start_slave(m, i);
}

/* The write at the slave's cursor write_pos (an index into writes, or a concise DCF's byte
 * offset) into *w; returns the cursor past it, or 0 (no write's cursor) past the last one. */
static size_t current_write(const co_net_master_t *m, size_t i, co_net_write_t *w)
{
    size_t pos = m->config.slave_state[i].write_pos;
    const co_net_slave_config_t *c = &m->config.slaves[i];
    if (c->concise_dcf == NULL) {
        if (pos == c->write_count)
            return 0;
        *w = c->writes[pos];
        return pos + 1;
    }
    co_concise_dcf_entry_t e;
    if (!co_concise_dcf_next(c->concise_dcf, c->concise_dcf_len, &pos, &e))
        return 0;
    *w = (co_net_write_t){e.index, e.subindex, e.data, e.len};
    return pos;
}

static void download_next(co_net_master_t *m, size_t i)
{
    co_net_write_t w;
    if (current_write(m, i, &w) == 0) {
        finish_boot(m, i);
        return;
    }
    if (co_sdo_client_download(&m->sdo, w.index, w.subindex, w.data, w.len, CO_SDO_CLIENT_AUTO,
                               m->config.sdo_timeout_ms, m->now) != 0)
        fail(m, i, CO_NET_FAIL_SDO);
}

/* The write just confirmed: on to the next. */
static void download_done(co_net_master_t *m, size_t i)
{
    co_net_write_t w;
    co_net_slave_at(m, i)->write_pos = current_write(m, i, &w);
    download_next(m, i);
}

static void begin_download(co_net_master_t *m, size_t i)
{
    co_net_slave_at(m, i)->write_pos =
        co_net_slave_config(m, i)->concise_dcf == NULL ? 0 : CO_CONCISE_DCF_HEADER;
    co_net_set_step(m, i, CO_NET_STEP_DOWNLOAD);
    download_next(m, i);
}

static void begin_identity(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    const co_net_slave_config_t *c = co_net_slave_config(m, i);
    while (s->identity_sub < CO_NET_IDENTITY_SUBS &&
           (c->check & (CO_NET_CHECK_VENDOR << s->identity_sub)) == 0)
        s->identity_sub++;
    if (s->identity_sub == CO_NET_IDENTITY_SUBS) {
        co_net_add_status(m, i, CO_NET_SLAVE_CONTACTED);
        begin_download(m, i);
        return;
    }
    co_net_set_step(m, i, CO_NET_STEP_IDENTITY);
    begin_read(m, i, CO_IDX_IDENTITY, (uint8_t)(s->identity_sub + 1));
}

static void identity_read(co_net_master_t *m, size_t i, uint32_t value)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    s->read_value = value;
    if (value != co_net_slave_config(m, i)->identity[s->identity_sub]) {
        fail(m, i, CO_NET_FAIL_IDENTITY);
        return;
    }
    s->identity_sub++;
    begin_identity(m, i);
}

static void device_type_read(co_net_master_t *m, size_t i, uint32_t value)
{
    const co_net_slave_config_t *c = co_net_slave_config(m, i);
    co_net_slave_t *s = co_net_slave_at(m, i);
    s->read_value = value;
    if ((c->check & CO_NET_CHECK_DEVICE_TYPE) != 0 && value != c->device_type) {
        fail(m, i, CO_NET_FAIL_DEVICE_TYPE);
        return;
    }
    s->identity_sub = 0;
    begin_identity(m, i);
}

/* The SDO client's callback while a slave's boot holds it. */
static void sdo_done(void *user, const co_sdo_client_result_t *result)
{
    co_net_master_t *m = user;
    size_t i = m->current;
    if (i == m->config.slave_count)
        return;
    co_net_slave_t *s = co_net_slave_at(m, i);
    if (result->status != CO_SDO_CLIENT_OK) {
        uint8_t node_id = co_net_slave_config(m, i)->node_id;
        co_net_write_t w;
        if (s->step == CO_NET_STEP_DOWNLOAD && current_write(m, i, &w) != 0) {
            co_net_record_sdo_error(m, node_id, result, CO_NET_ACCESS_WRITE,
                                    co_net_written_value(w.data, w.len));
        } else {
            co_net_record_sdo_error(m, node_id, result, CO_NET_ACCESS_READ, 0);
        }
        fail(m, i, CO_NET_FAIL_SDO);
        return;
    }
    switch (s->step) {
    case CO_NET_STEP_DEVICE_TYPE:
        device_type_read(m, i, co_get_u32(m->value));
        break;
    case CO_NET_STEP_IDENTITY:
        identity_read(m, i, co_get_u32(m->value));
        break;
    case CO_NET_STEP_DOWNLOAD:
        download_done(m, i);
        break;
    default:
        break;
    }
}

static void begin_attempt(co_net_master_t *m, size_t i)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    co_sdo_client_config_t sdo = {.server_node_id = co_net_slave_config(m, i)->node_id,
                                  .send = co_net_forward_send,
                                  .user = m,
                                  .done = sdo_done};
    m->current = i;
    co_net_clear_status(m, i, CO_NET_SLAVE_PROGRESS);
    if (co_sdo_client_init(&m->sdo, &sdo) != 0) {
        fail(m, i, CO_NET_FAIL_SDO);
        return;
    }
    s->failure = CO_NET_FAIL_NONE;
    co_net_set_step(m, i, CO_NET_STEP_DEVICE_TYPE);
    begin_read(m, i, CO_IDX_DEVICE_TYPE, 0);
}

void co_net_await_boot(co_net_master_t *m, size_t i, bool booted)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    co_net_abandon_transfer(m, i);
    co_net_stop_error_control(m, i);
    co_net_clear_status(m, i, CO_NET_SLAVE_PROGRESS);
    s->booted = booted;
    s->deadline = co_net_after_ms(m->now, m->config.boot_time_ms);
    co_net_set_step(m, i, CO_NET_STEP_WAIT_BOOT);
}

/* Communication for a boot, the whole node after an error-control loss, so that it also forgets
 * a half-applied configuration. */
void co_net_reset_slave(co_net_master_t *m, size_t i, uint8_t command)
{
    co_nmt_master_command(&m->nmt, command, co_net_slave_config(m, i)->node_id);
    co_net_await_boot(m, i, false);
}

void co_net_boot_network(co_net_master_t *m, uint8_t command, bool to_all, bool afresh)
{
    m->started_all = false;
    co_net_begin_boot_time(m);
    if (to_all)
        co_nmt_master_command(&m->nmt, command, CO_NMT_MASTER_ALL_NODES);
    for (size_t i = 0; i < m->config.slave_count; i++) {
        co_net_slave_t *s = co_net_slave_at(m, i);
        s->tried = false;
        if (afresh) {
            s->boot_error = CO_NET_BOOT_ERROR_NONE;
            co_net_set_status(m, i, 0);
        }
        if (to_all)
            co_net_await_boot(m, i, false);
        else
            co_net_reset_slave(m, i, command);
    }
}

/* It then waits only for the SDO client, which a frame or a timeout of the slave holding it
 * frees, never a time of its own. */
bool co_net_ready(const co_net_master_t *m, const co_net_slave_t *s)
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
        if (co_net_ready(m, co_net_slave_at(m, i)))
            return i;
    }
    return n;
}

static void retry_failed(co_net_master_t *m)
{
    for (size_t i = 0; i < m->config.slave_count; i++) {
        const co_net_slave_t *s = co_net_slave_at(m, i);
        if (s->step == CO_NET_STEP_FAILED && m->now >= s->deadline)
            co_net_reset_slave(m, i, CO_NMT_CS_RESET_COMMUNICATION);
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
    co_net_report(m, CO_NET_EVENT_STARTED, 0, 0);
    for (size_t i = 0; i < m->config.slave_count; i++) {
        if (co_net_slave_at(m, i)->step == CO_NET_STEP_WAIT_START)
            become_operational(m, i);
    }
}

void co_net_begin_boot_time(co_net_master_t *m)
{
    m->boot_time_over = false;
    m->boot_limit = m->config.boot_limit_ms == 0 ? CO_TIME_NEVER
                                                 : co_net_after_ms(m->now, m->config.boot_limit_ms);
}

static bool mandatory_configured(const co_net_master_t *m)
{
    for (size_t i = 0; i < m->config.slave_count; i++) {
        uint8_t step = m->config.slave_state[i].step;
        if (m->config.slaves[i].mandatory && step != CO_NET_STEP_WAIT_START &&
            step != CO_NET_STEP_OPERATIONAL)
            return false;
    }
    return true;
}

/* CiA 302-2's boot time 1F89h: it ends once, when every mandatory slave is configured or, first,
 * at its end, which the application is told; the boot of the missing ones goes on, as the PLC300
 * retries a failed slave (docs/decisions.md, D-NET-MASTER-BOOT-TIME). */
static void check_boot_time(co_net_master_t *m)
{
    if (m->boot_limit == CO_TIME_NEVER)
        return;
    if (mandatory_configured(m)) {
        m->boot_limit = CO_TIME_NEVER;
    } else if (m->now >= m->boot_limit) {
        m->boot_limit = CO_TIME_NEVER;
        m->boot_time_over = true;
        co_net_report(m, CO_NET_EVENT_BOOT_TIME, 0, 0);
    }
}

bool co_net_client_free(const co_net_master_t *m)
{
    return m->current == m->config.slave_count && !m->serving;
}

void co_net_boot_run(co_net_master_t *m)
{
    retry_failed(m);
    while (co_net_client_free(m)) {
        size_t i = next_ready(m);
        if (i == m->config.slave_count)
            break;
        m->next_pick = (i + 1) % m->config.slave_count;
        begin_attempt(m, i);
    }
    start_all(m);
    check_boot_time(m);
}

/* retry_failed has just run the retries whose delay ended, check_boot_time the boot time. */
co_time_t co_net_boot_deadline(const co_net_master_t *m)
{
    co_time_t next = m->boot_limit;
    for (size_t i = 0; i < m->config.slave_count; i++) {
        const co_net_slave_t *s = &m->config.slave_state[i];
        if ((s->step == CO_NET_STEP_WAIT_BOOT && !co_net_ready(m, s)) ||
            s->step == CO_NET_STEP_FAILED)
            next = co_time_min(next, s->deadline);
    }
    return next;
}
