/* SPDX-License-Identifier: Apache-2.0 */
/* The application's requests to the network master: NMT commands, confirmed by the state each
 * addressed node reports next (D-NET-MASTER-NMT-CONFIRM), and SDO transfers on the master's own
 * client, queued behind the boot of the slaves (D-NET-MASTER-REQUESTS). docs/net-master.md,
 * "Requests of the application". */
#include "canopen/master/net/net_floors.h"

#include <string.h>

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

void co_net_finish_nmt(co_net_master_t *m)
{
    m->nmt_request.pending = false;
    co_net_report(m, CO_NET_EVENT_NMT_DONE, m->nmt_request.node_id, 0);
}

void co_net_confirm_nmt(co_net_master_t *m, uint8_t node_id, uint8_t state)
{
    co_net_nmt_request_t *r = &m->nmt_request;
    if (!nmt_awaits(r, node_id) || state != r->expected)
        return;
    r->awaited[node_id / 32u] &= ~awaited_bit(node_id);
    if (!nmt_awaits_any(r))
        co_net_finish_nmt(m);
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
    co_net_send(m, &rtr);
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
                                .deadline = co_net_after_ms(now, timeout_ms)};
    if (node_id != CO_NMT_MASTER_ALL_NODES)
        nmt_await(r, node_id);
    for (size_t i = 0; node_id == CO_NMT_MASTER_ALL_NODES && i < master->config.slave_count; i++)
        nmt_await(r, co_net_slave_config(master, i)->node_id);
    co_nmt_master_command(&master->nmt, command, node_id);
    master->nmt_toggle ^= CO_NET_MASTER_NMT_TOGGLE;
    /* The application starts the nodes the master stopped (1F80h bit 6), the master with them. */
    if (command == CO_NMT_CS_START && node_id == CO_NMT_MASTER_ALL_NODES)
        master->stopped_all = false;
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

co_time_t co_net_nmt_deadline(co_net_master_t *m)
{
    if (!m->nmt_request.pending)
        return CO_TIME_NEVER;
    if (m->now >= m->nmt_request.deadline)
        co_net_finish_nmt(m);
    return m->nmt_request.pending ? m->nmt_request.deadline : CO_TIME_NEVER;
}

/* ---- SDO requests of the application on the master's client --------------------------------- */

/* Ends the first request (under way, or dropped before it started) with `result`. */
static void finish_request(co_net_master_t *m, const co_sdo_client_result_t *result)
{
    co_net_request_t request = m->requests[0];
    m->request_count--;
    memmove(&m->requests[0], &m->requests[1], m->request_count * sizeof m->requests[0]);
    m->serving = false;
    if (result->status != CO_SDO_CLIENT_OK)
        co_net_record_sdo_error(
            m, request.node_id, result, request.write ? CO_NET_ACCESS_WRITE : CO_NET_ACCESS_READ,
            request.write ? co_net_written_value(request.data, request.len) : 0);
    request.done(request.user, &request, result);
}

/* The SDO client's callback while a request holds it. */
static void sdo_done(void *user, const co_sdo_client_result_t *result)
{
    finish_request(user, result);
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
    size_t i = co_net_slave_index(m, node_id);
    if (i == m->config.slave_count)
        return false;
    const co_net_slave_t *s = &m->config.slave_state[i];
    return s->step == CO_NET_STEP_WAIT_BOOT && !co_net_ready(m, s);
}

void co_net_serve_request(co_net_master_t *m)
{
    if (!co_net_client_free(m) || m->request_count == 0 || resetting(m, m->requests[0].node_id))
        return;
    const co_net_request_t *r = &m->requests[0];
    co_sdo_client_config_t sdo = {
        .server_node_id = r->node_id, .send = co_net_forward_send, .user = m, .done = sdo_done};
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

void co_net_drop_requests(co_net_master_t *m)
{
    while (m->request_count > 0) {
        co_sdo_client_result_t result = request_failed(&m->requests[0], CO_SDO_ABORT_TIMEOUT);
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

/* ---- configuration request 1F25h --------------------------------------------------------------
 */

/* CiA 302-2: the slave is configured again, which here is its whole boot (reset communication,
 * identification, download, error control, start), so that nothing of its old configuration or
 * state is taken for granted (docs/net-master.md, "Configuration request 1F25h"). */
bool co_net_master_request_configuration(co_net_master_t *master, uint8_t subindex, uint32_t value,
                                         co_time_t now)
{
    size_t n = master->config.slave_count;
    size_t i = subindex == CO_NET_1F25_ALL ? 0 : co_net_slave_index(master, subindex);
    if (value != CO_NET_1F25_SIGNATURE || !master->started || master->disabled || i == n)
        return false;
    master->now = now;
    for (; i < n; i++) {
        co_net_reset_slave(master, i, CO_NMT_CS_RESET_COMMUNICATION);
        if (subindex != CO_NET_1F25_ALL)
            break;
    }
    return true;
}
