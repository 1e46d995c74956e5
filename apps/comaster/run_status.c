/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's status word in comaster run and boot: its bits 13-14 from the CAN
 * controller, and the names of its bits and of a slave's, which the run prints and its control
 * socket's status, disable and enable answer (docs/comaster.md "run and its control socket"). */
#include "comaster/runner.h"

#include "co_linux/conditions.h"

#include <stdio.h>

uint16_t run_bus_bits(const runner_t *r)
{
    const co_linux_bus_t *bus = &r->bus.loop.bus;
    uint16_t bits = 0;
    if (co_linux_conditions_active(&bus->conditions, CO_LINUX_EMCY_BUS_OFF))
        bits |= CO_NET_MASTER_BUS_OFF;
    if (!bus->link_up) /* D-NET-MASTER-BUS-POWER */
        bits |= CO_NET_MASTER_NO_BUS_POWER;
    return bits;
}

static const char *const slave_bits[] = {"contacted",   "configured", "error-control-started",
                                         "initialised", "init-error", "error-control-error"};
/* The PLC300's %SW3200 (bits 6 and 7 the project's own); NULL: reserved. */
static const char *const master_bits[] = {"all-contacted",
                                          "all-configured",
                                          "all-error-control-started",
                                          "init-finished",
                                          "init-error",
                                          "error-control-error",
                                          "mandatory-error",
                                          "boot-time-over",
                                          "nmt-toggle",
                                          NULL,
                                          NULL,
                                          NULL,
                                          NULL,
                                          "bus-off",
                                          "no-bus-power",
                                          "disabled"};

/* " contacted configured": the names of the bits set. */
static void bit_names(uint16_t status, const char *const *names, size_t count, char *out,
                      size_t cap)
{
    size_t used = 0;
    out[0] = '\0';
    for (size_t bit = 0; bit < count && used < cap; bit++) {
        if ((status & (1u << bit)) && names[bit] != NULL)
            used += (size_t)snprintf(out + used, cap - used, " %s", names[bit]);
    }
}

void run_slave_status_text(uint16_t status, char *out, size_t cap)
{
    bit_names(status, slave_bits, sizeof slave_bits / sizeof slave_bits[0], out, cap);
}

void run_master_status_text(uint16_t status, char *out, size_t cap)
{
    int prefix = snprintf(out, cap, "master 0x%04X", status);
    if (prefix > 0 && (size_t)prefix < cap)
        bit_names(status, master_bits, sizeof master_bits / sizeof master_bits[0], out + prefix,
                  cap - (size_t)prefix);
}
