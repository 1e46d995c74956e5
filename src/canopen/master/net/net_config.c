/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's description as the application gives it (co_net_master_config_t): what
 * co_net_master_init refuses before anything is sent (docs/net-master.md, "The application's
 * description"); the bit rates of the PLC300's codes, which the application's interface takes. */
#include "canopen/master/net/net_floors.h"

uint32_t co_net_master_1f80(const co_net_master_config_t *config)
{
    uint32_t value = CO_NET_1F80_NMT_MASTER;
    if (config->start == CO_NET_START_ALL)
        value |= CO_NET_1F80_START_ALL;
    else if (config->start == CO_NET_START_NONE)
        value |= CO_NET_1F80_NO_SLAVE_START;
    if (config->on_mandatory_error == CO_NET_MANDATORY_STOP_ALL)
        value |= CO_NET_1F80_STOP_ALL;
    else if (config->on_mandatory_error == CO_NET_MANDATORY_RESET_ALL)
        value |= CO_NET_1F80_RESET_ALL;
    return value;
}

bool co_net_master_config_from_1f80(co_net_master_config_t *config, uint32_t value)
{
    const uint32_t taken = CO_NET_1F80_NMT_MASTER | CO_NET_1F80_START_ALL |
                           CO_NET_1F80_NO_SLAVE_START | CO_NET_1F80_RESET_ALL |
                           CO_NET_1F80_STOP_ALL;
    if ((value & CO_NET_1F80_NMT_MASTER) == 0 || (value & ~taken) != 0)
        return false;
    if ((value & CO_NET_1F80_NO_SLAVE_START) != 0)
        config->start = CO_NET_START_NONE;
    else if ((value & CO_NET_1F80_START_ALL) != 0)
        config->start = CO_NET_START_ALL;
    else
        config->start = CO_NET_START_EACH;
    if ((value & CO_NET_1F80_STOP_ALL) != 0)
        config->on_mandatory_error = CO_NET_MANDATORY_STOP_ALL;
    else if ((value & CO_NET_1F80_RESET_ALL) != 0)
        config->on_mandatory_error = CO_NET_MANDATORY_RESET_ALL;
    else
        config->on_mandatory_error = CO_NET_MANDATORY_ALONE;
    return true;
}

uint32_t co_net_slave_1f81(const co_net_slave_config_t *slave)
{
    uint32_t value = CO_NET_1F81_SLAVE;
    if (slave->on_error == CO_NET_ON_ERROR_REBOOT)
        value |= CO_NET_1F81_BOOT;
    if (slave->mandatory)
        value |= CO_NET_1F81_MANDATORY;
    return value | (uint32_t)slave->life_time_factor << CO_NET_1F81_RETRY_SHIFT |
           (uint32_t)slave->guard_ms << CO_NET_1F81_GUARD_SHIFT;
}

bool co_net_slave_config_from_1f81(co_net_slave_config_t *slave, uint32_t value)
{
    const uint32_t taken = CO_NET_1F81_SLAVE | CO_NET_1F81_BOOT | CO_NET_1F81_MANDATORY;
    if ((value & CO_NET_1F81_SLAVE) == 0 || (value & 0xFFu & ~taken) != 0)
        return false;
    slave->on_error =
        (value & CO_NET_1F81_BOOT) != 0 ? CO_NET_ON_ERROR_REBOOT : CO_NET_ON_ERROR_REPORT;
    slave->mandatory = (value & CO_NET_1F81_MANDATORY) != 0;
    slave->life_time_factor = (uint8_t)(value >> CO_NET_1F81_RETRY_SHIFT);
    slave->guard_ms = (uint16_t)(value >> CO_NET_1F81_GUARD_SHIFT);
    return true;
}

/* 1F84h..1F88h in the order of the check bits: 1000h, then 1018h:01..04. */
static bool expected_sub(uint16_t index, unsigned *k)
{
    if (index < CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION || index > CO_NET_IDX_SERIAL_NUMBER)
        return false;
    *k = (unsigned)(index - CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION);
    return true;
}

static uint32_t *expected_value(co_net_slave_config_t *slave, unsigned k)
{
    return k == 0 ? &slave->device_type : &slave->identity[k - 1];
}

uint32_t co_net_slave_expected(const co_net_slave_config_t *slave, uint16_t index)
{
    unsigned k;
    if (!expected_sub(index, &k) || (slave->check & (CO_NET_CHECK_DEVICE_TYPE << k)) == 0)
        return 0;
    return k == 0 ? slave->device_type : slave->identity[k - 1];
}

/* CiA 302-2, 1F84h..1F88h: a value of 0 is no check of that value. */
bool co_net_slave_config_set_expected(co_net_slave_config_t *slave, uint16_t index, uint32_t value)
{
    unsigned k;
    if (!expected_sub(index, &k))
        return false;
    *expected_value(slave, k) = value;
    if (value == 0)
        slave->check &= (uint8_t) ~(CO_NET_CHECK_DEVICE_TYPE << k);
    else
        slave->check |= (uint8_t)(CO_NET_CHECK_DEVICE_TYPE << k);
    return true;
}

uint32_t co_net_bit_rate(uint8_t code)
{
    /* kbit/s by code, as the PLC300 manual's table lists them. */
    static const uint16_t kbit[] = {1000, 0, 500, 250, 125, 100, 50, 20};
    return code < sizeof kbit / sizeof kbit[0] ? kbit[code] * 1000u : 0;
}

static bool pdo_valid(const co_net_master_config_t *config, const co_net_pdo_t *pdo,
                      size_t image_size)
{
    return pdo->len >= 1 && pdo->len <= CO_FRAME_DLC_MAX &&
           (size_t)pdo->offset + pdo->len <= image_size && pdo->can_id <= CO_COB_ID_CAN_ID &&
           !co_can_id_restricted(pdo->can_id) &&
           co_net_config_index(config, pdo->node_id) < config->slave_count;
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
    if (s->concise_dcf != NULL &&
        (s->write_count > 0 || !co_concise_dcf_valid(s->concise_dcf, s->concise_dcf_len, NULL)))
        return false;
    for (size_t w = 0; w < s->write_count; w++) {
        if (s->writes[w].data == NULL || s->writes[w].len == 0)
            return false;
    }
    return true;
}

bool co_net_config_valid(const co_net_master_config_t *config)
{
    if (config == NULL || config->send == NULL || config->slaves == NULL ||
        config->slave_state == NULL || config->slave_count == 0 ||
        config->slave_count > CO_NMT_MASTER_NODE_ID_MAX ||
        config->sdo_timeout_ms < CO_NET_SDO_TIMEOUT_MIN_MS ||
        config->sdo_timeout_ms > CO_NET_SDO_TIMEOUT_MAX_MS || config->start > CO_NET_START_NONE ||
        config->on_mandatory_error > CO_NET_MANDATORY_RESET_ALL)
        return false;
    if (config->heartbeat_ms != 0 &&
        (config->node_id < 1 || config->node_id > CO_NMT_MASTER_NODE_ID_MAX ||
         co_net_config_index(config, config->node_id) != config->slave_count))
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

/* ---- the master's own objects (CiA 302-2) ------------------------------------------------------
 */

bool co_net_objects_from_config(co_net_objects_t *objects, const co_net_master_config_t *config)
{
    *objects = (co_net_objects_t){.nmt_startup = co_net_master_1f80(config),
                                  .boot_time_ms = config->boot_limit_ms};
    for (size_t i = 0; i < config->slave_count; i++) {
        const co_net_slave_config_t *s = &config->slaves[i];
        size_t n = (size_t)s->node_id - 1u;
        if (s->write_count > 0)
            return false;
        objects->slave_assignment[n] = co_net_slave_1f81(s);
        objects->consumer_heartbeat_ms[n] = s->heartbeat_ms;
        for (unsigned k = 0; k <= CO_NET_IDENTITY_SUBS; k++) {
            uint16_t index = (uint16_t)(CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION + k);
            uint32_t value = co_net_slave_expected(s, index);
            if (value == 0 && (s->check & (CO_NET_CHECK_DEVICE_TYPE << k)) != 0)
                return false;
            objects->expected[k][n] = value;
        }
        objects->concise_dcf[n] = s->concise_dcf;
        objects->concise_dcf_len[n] = s->concise_dcf_len;
    }
    return true;
}

bool co_net_config_from_objects(co_net_master_config_t *config, co_net_slave_config_t *slaves,
                                size_t max, const co_net_objects_t *objects)
{
    if (!co_net_master_config_from_1f80(config, objects->nmt_startup))
        return false;
    config->boot_limit_ms = objects->boot_time_ms;
    size_t count = 0;
    for (size_t n = 0; n < CO_NMT_MASTER_NODE_ID_MAX; n++) {
        if ((objects->slave_assignment[n] & CO_NET_1F81_SLAVE) == 0)
            continue;
        if (count == max)
            return false;
        co_net_slave_config_t *s = &slaves[count++];
        *s = (co_net_slave_config_t){.node_id = (uint8_t)(n + 1u),
                                     .heartbeat_ms = objects->consumer_heartbeat_ms[n],
                                     .concise_dcf = objects->concise_dcf[n],
                                     .concise_dcf_len = objects->concise_dcf_len[n]};
        if (!co_net_slave_config_from_1f81(s, objects->slave_assignment[n]))
            return false;
        for (unsigned k = 0; k <= CO_NET_IDENTITY_SUBS; k++)
            co_net_slave_config_set_expected(
                s, (uint16_t)(CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION + k), objects->expected[k][n]);
    }
    config->slaves = slaves;
    config->slave_count = count;
    return true;
}
