/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's floors: its internal interface, for the files of this folder and never an
 * application's. A section per file from the ground floor up (net_records.c, net_config.c,
 * net_image.c, net_boot.c, net_supervision.c, net_requests.c); a file calls only the sections
 * above its own. net_master.c, the composition root, calls any: it owns the public entry points
 * of include/co/co_net_master.h that act on the whole master (init, start, receive, process,
 * disable, the status words). docs/net-master.md. */
#ifndef NET_FLOORS_H
#define NET_FLOORS_H

#include "co/co_net_master.h"

#define CO_NET_US_PER_MS 1000u
/* The bits of a slave's status word that one attempt at its initialisation builds up. */
#define CO_NET_SLAVE_PROGRESS                                                                      \
    (CO_NET_SLAVE_CONTACTED | CO_NET_SLAVE_CONFIGURED | CO_NET_SLAVE_EC_STARTED |                  \
     CO_NET_SLAVE_INIT_DONE)

static inline const co_net_slave_config_t *co_net_slave_config(const co_net_master_t *m, size_t i)
{
    return &m->config.slaves[i];
}

static inline co_net_slave_t *co_net_slave_at(co_net_master_t *m, size_t i)
{
    return &m->config.slave_state[i];
}

static inline co_time_t co_net_after_ms(co_time_t now, uint32_t ms)
{
    return now + (co_time_t)ms * CO_NET_US_PER_MS;
}

/* The records (net_records.c): the slaves' steps and status words, the events that tell the
 * application of their changes, the last SDO error, the frames out. */
/* The position of node `node_id` in the table, slave_count when it is not there. */
size_t co_net_config_index(const co_net_master_config_t *config, uint8_t node_id);
size_t co_net_slave_index(const co_net_master_t *m, uint8_t node_id);
void co_net_report(co_net_master_t *m, co_net_event_kind_t kind, uint8_t node_id, size_t pdo);
/* Each reports its change (CO_NET_EVENT_STEP, _STATUS), nothing when nothing changed; a status
 * without bit 5 also clears the slave's ec_error. */
void co_net_set_step(co_net_master_t *m, size_t i, co_net_step_t step);
void co_net_set_status(co_net_master_t *m, size_t i, uint16_t status);
void co_net_add_status(co_net_master_t *m, size_t i, uint16_t bits);
void co_net_clear_status(co_net_master_t *m, size_t i, uint16_t bits);
/* The PLC300's last SDO error (5.6.4), reported; `value` is a write's (co_net_written_value). */
void co_net_record_sdo_error(co_net_master_t *m, uint8_t node_id, const co_sdo_client_result_t *r,
                             uint8_t access, uint32_t value);
uint32_t co_net_written_value(const uint8_t *data, uint32_t len);
void co_net_send(co_net_master_t *m, const co_frame_t *frame);
/* The send callback of the NMT master and the SDO client, whose `user` is the master itself (it
 * also receives their events). */
void co_net_forward_send(void *user, const co_frame_t *frame);

/* The application's description (net_config.c): what co_net_master_init refuses. */
bool co_net_config_valid(const co_net_master_config_t *config);

/* The process image (net_image.c). A received frame on an input PDO's CAN-ID: true when used. */
bool co_net_image_receive(co_net_master_t *m, const co_frame_t *frame);
/* The SYNC when due, and every output PDO of an operational slave after it. */
void co_net_image_sync(co_net_master_t *m);

/* The boot of the slaves (net_boot.c): identification, configuration download, error control,
 * start, one slave at a time on the master's SDO client. */
/* No slave's boot holds the SDO client, nor an application's request. */
bool co_net_client_free(const co_net_master_t *m);
/* No slave holds the SDO client. */
void co_net_release(co_net_master_t *m);
/* The slave's transfer under way, if any, is dropped without a frame (docs/net-master.md). */
void co_net_abandon_transfer(co_net_master_t *m, size_t i);
void co_net_stop_error_control(co_net_master_t *m, size_t i);
/* A slave that was reset or restarted: nothing of its boot so far holds, and its boot-up is
 * awaited (or `booted`: it came). */
void co_net_await_boot(co_net_master_t *m, size_t i, bool booted);
/* Sends `command` (reset node or communication) to the slave and awaits its boot-up. */
void co_net_reset_slave(co_net_master_t *m, size_t i, uint8_t command);
/* The network's boot from its beginning, the master's start or CiA 302-2's reset of all: no start
 * of all sent yet, the boot time 1F89h running, every slave untried and awaiting its boot-up after
 * `command` (reset node or communication), sent at once to all nodes (`to_all`) or to each slave
 * alone. `afresh` (the start) also clears the slaves' status words and boot errors; a reset of
 * all keeps them, so that the lost slave shows bit 5 until its boot succeeds. */
void co_net_boot_network(co_net_master_t *m, uint8_t command, bool to_all, bool afresh);
/* The last step of a configured slave's boot: NMT start, or the wait for the start of all. */
void co_net_start_slave(co_net_master_t *m, size_t i);
/* The slave waits for its boot-up and its turn has come: the boot-up came or the boot time
 * ended. */
bool co_net_ready(const co_net_master_t *m, const co_net_slave_t *s);
/* Retries the failed slaves whose delay ended, starts the boot of the slaves whose turn came
 * while the client is free, sends the start of all when the network is ready. */
void co_net_boot_run(co_net_master_t *m);
/* CiA 302-2's boot time 1F89h runs from now (the network's boot begins); status bit 7 clear. */
void co_net_begin_boot_time(co_net_master_t *m);
/* The end of a boot time not yet reached, of a retry delay, or of the boot time 1F89h. */
co_time_t co_net_boot_deadline(const co_net_master_t *m);

/* The supervision of the slaves (net_supervision.c): their error control, boot-ups and EMCYs,
 * the master's own heartbeat. The NMT master's and the EMCY consumer's callbacks. */
void co_net_nmt_event(void *user, const co_nmt_master_event_t *event);
void co_net_emcy_received(void *user, co_emcy_decode_t result, const co_emcy_message_t *msg,
                          co_time_t now);
/* Sends the master's heartbeat when due; its next time. */
co_time_t co_net_heartbeat(co_net_master_t *m);

/* The application's requests (net_requests.c): NMT commands confirmed by the nodes' states, SDO
 * transfers queued behind the boot. */
/* A node reported `state`: it may confirm the NMT command awaited. */
void co_net_confirm_nmt(co_net_master_t *m, uint8_t node_id, uint8_t state);
void co_net_finish_nmt(co_net_master_t *m);
/* Ends the NMT command whose deadline passed; the deadline still awaited, or CO_TIME_NEVER. */
co_time_t co_net_nmt_deadline(co_net_master_t *m);
/* Starts the first request waiting, when no slave's boot holds the client. */
void co_net_serve_request(co_net_master_t *m);
/* Ends every request waiting, under way or not, with 0x05040000. */
void co_net_drop_requests(co_net_master_t *m);

#endif
