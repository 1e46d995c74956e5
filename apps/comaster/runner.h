/* SPDX-License-Identifier: Apache-2.0 */
/* comaster run: the runner, its state shared by the network master on the bus (run_cmd.c, the
 * commands run and boot on top), the requests of its control socket that act on the bus
 * (run_requests.c: NMT commands, SDO through the master's client, disable and enable, the
 * controller's state) and, below both, the master's status word (run_status.c).
 * docs/comaster.md "run and its control socket". */
#ifndef COMASTER_RUNNER_H
#define COMASTER_RUNNER_H

#include "comaster/comaster.h"
#include "comaster/network.h"
#include "comaster/run_control.h"
#include "comaster/value.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The largest value read or written through the run: a string such as 1008h fits. */
#define RUN_SDO_VALUE_MAX 256u

/* An SDO request of a client, waiting in the master's queue: its reply goes to the connection of
 * `ticket` when the transfer ends. */
struct runner;

typedef struct run_sdo {
    struct runner *runner;
    bool used;
    uint32_t ticket;
    bool json;
    uint8_t node;
    comaster_object_t object;
    const comaster_type_t *type;
    uint32_t len; /* write: the bytes written */
    uint8_t data[RUN_SDO_VALUE_MAX];
} run_sdo_t;

typedef struct runner {
    comaster_bus_t bus;
    comaster_network_t *net;
    co_net_master_t master;
    bool started;
    uint16_t master_status; /* as last printed */
    uint8_t protocol_state; /* co_net_master_protocol_state as last printed */
    bool boot_only;         /* comaster boot: finish when the slave is operational or failed */
    comaster_control_t control;
    uint32_t nmt_ticket; /* the client awaiting the NMT command's confirmation */
    bool nmt_json;
    uint32_t nmt_timeout_ms;
    run_sdo_t sdo[CO_NET_REQUEST_MAX];
} runner_t;

/* The requests of run_requests.c: true when `field[0]` is one of them (nmt, read, write,
 * disable, enable, can), the reply then written or deferred (*deferred: a ticket was taken and
 * the reply comes later). */
bool run_request(runner_t *r, char **field, size_t count, bool json, char *reply, size_t cap,
                 bool *deferred);

/* The master's NMT command ended (CO_NET_EVENT_NMT_DONE): its reply to the client. */
void run_nmt_done(runner_t *r);

/* The status word of run_status.c. The controller's state as the master's status bits 13-14
 * (the runtime's conditions and link). */
uint16_t run_bus_bits(const runner_t *r);

/* "master 0x000F all-contacted ...": the master's status word and its bits by name. */
void run_master_status_text(uint16_t status, char *out, size_t cap);

/* " contacted configured": the bits of a slave's status word set, by name. */
void run_slave_status_text(uint16_t status, char *out, size_t cap);

#endif
