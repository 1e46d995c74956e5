/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/conditions.h"
#include "co_linux/log.h"

static const char *const names[CO_LINUX_CONDITIONS] = {
    "CAN overrun (frames lost)", "CAN error passive", "CAN bus off", "CAN error warning level"};

void co_linux_conditions_init(co_linux_conditions_t *c)
{
    *c = (co_linux_conditions_t){0};
    c->items[CO_LINUX_COND_OVERRUN].emcy_code = CO_LINUX_EMCY_CAN_OVERRUN;
    c->items[CO_LINUX_COND_PASSIVE].emcy_code = CO_LINUX_EMCY_CAN_PASSIVE;
    c->items[CO_LINUX_COND_BUS_OFF].emcy_code = CO_LINUX_EMCY_BUS_OFF;
    c->items[CO_LINUX_COND_WARNING].emcy_code = CO_LINUX_EMCY_NONE;
}

void co_linux_conditions_set(co_linux_conditions_t *c, const char *iface,
                             co_linux_condition_kind_t which, bool active)
{
    co_linux_condition_t *item = &c->items[which];
    if (item->wanted == active)
        return;
    item->wanted = active;
    if (which == CO_LINUX_COND_OVERRUN)
        c->traffic_since_overrun = false;
    if (which == CO_LINUX_COND_BUS_OFF && active)
        c->bus_offs++;
    co_log_level_t level = active ? CO_LOG_WARN : CO_LOG_INFO;
    const char *change = active ? "active" : "cleared";
    if (item->emcy_code == CO_LINUX_EMCY_NONE)
        co_log(level, "%s: %s (no EMCY) %s", iface, names[which], change);
    else
        co_log(level, "%s: %s (EMCY %04X %s)", iface, names[which], item->emcy_code, change);
}

void co_linux_conditions_restart(co_linux_conditions_t *c)
{
    for (int i = 0; i < CO_LINUX_CONDITIONS; i++)
        c->items[i].wanted = false;
}

void co_linux_conditions_end_overrun(co_linux_conditions_t *c, const char *iface, size_t queued)
{
    const co_linux_condition_t *overrun = &c->items[CO_LINUX_COND_OVERRUN];
    if (overrun->wanted && overrun->reported && queued == 0 && c->traffic_since_overrun)
        co_linux_conditions_set(c, iface, CO_LINUX_COND_OVERRUN, false);
}

bool co_linux_conditions_take(co_linux_conditions_t *c, co_linux_condition_kind_t which,
                              size_t queued, size_t capacity)
{
    co_linux_condition_t *item = &c->items[which];
    if (item->wanted == item->reported)
        return false;
    if (which == CO_LINUX_COND_OVERRUN && item->wanted && queued >= capacity)
        return false;
    item->reported = item->wanted;
    return true;
}

bool co_linux_conditions_active(const co_linux_conditions_t *c, uint16_t emcy_code)
{
    for (int i = 0; i < CO_LINUX_CONDITIONS; i++) {
        if (c->items[i].emcy_code == emcy_code)
            return c->items[i].wanted;
    }
    return false;
}

bool co_linux_conditions_warning(const co_linux_conditions_t *c)
{
    return c->items[CO_LINUX_COND_WARNING].wanted;
}
