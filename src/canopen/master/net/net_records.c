/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's records: each slave's step and status word (the PLC300's 5.6.3), the
 * events that tell the application of their changes, the last SDO error (5.6.4), and the way out
 * of every frame the master sends. The ground floor of net_floors.h. */
#include "canopen/master/net/net_floors.h"

#include <string.h>

size_t co_net_config_index(const co_net_master_config_t *config, uint8_t node_id)
{
    for (size_t i = 0; i < config->slave_count; i++) {
        if (config->slaves[i].node_id == node_id)
            return i;
    }
    return config->slave_count;
}

size_t co_net_slave_index(const co_net_master_t *m, uint8_t node_id)
{
    return co_net_config_index(&m->config, node_id);
}

void co_net_report(co_net_master_t *m, co_net_event_kind_t kind, uint8_t node_id, size_t pdo)
{
    if (m->config.event == NULL)
        return;
    co_net_event_t event = {.kind = kind, .node_id = node_id, .pdo = pdo};
    m->config.event(m->config.user, &event);
}

void co_net_set_step(co_net_master_t *m, size_t i, co_net_step_t step)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    if (s->step == step)
        return;
    s->step = (uint8_t)step;
    co_net_report(m, CO_NET_EVENT_STEP, co_net_slave_config(m, i)->node_id, 0);
}

void co_net_set_status(co_net_master_t *m, size_t i, uint16_t status)
{
    co_net_slave_t *s = co_net_slave_at(m, i);
    /* The kind of error control failure is what bit 5 stands for: none once it is clear. */
    if ((status & CO_NET_SLAVE_EC_ERROR) == 0)
        s->ec_error = CO_NET_EC_ERROR_NONE;
    if (s->status == status)
        return;
    s->status = status;
    co_net_report(m, CO_NET_EVENT_STATUS, co_net_slave_config(m, i)->node_id, 0);
}

void co_net_add_status(co_net_master_t *m, size_t i, uint16_t bits)
{
    co_net_set_status(m, i, co_net_slave_at(m, i)->status | bits);
}

void co_net_clear_status(co_net_master_t *m, size_t i, uint16_t bits)
{
    co_net_set_status(m, i, (uint16_t)(co_net_slave_at(m, i)->status & ~bits));
}

void co_net_record_sdo_error(co_net_master_t *m, uint8_t node_id, const co_sdo_client_result_t *r,
                             uint8_t access, uint32_t value)
{
    m->last_sdo_error = (co_net_sdo_error_t){.node_id = node_id,
                                             .index = r->index,
                                             .subindex = r->subindex,
                                             .access = access,
                                             .value = value,
                                             .abort_code = r->abort_code};
    co_net_report(m, CO_NET_EVENT_SDO_ERROR, m->last_sdo_error.node_id, 0);
}

/* The first 4 bytes of a written value, little-endian (the PLC300's record of a write). */
uint32_t co_net_written_value(const uint8_t *data, uint32_t len)
{
    uint8_t b[4] = {0};
    memcpy(b, data, len < 4 ? len : 4);
    return co_get_u32(b);
}

void co_net_send(co_net_master_t *m, const co_frame_t *frame)
{
    m->config.send(m->config.user, frame);
}

void co_net_forward_send(void *user, const co_frame_t *frame)
{
    co_net_send(user, frame);
}
