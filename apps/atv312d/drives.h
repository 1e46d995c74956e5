/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's nodes on the bus as runtime devices: each emulated drive, a CANopen node of its own
 * or behind its DeviceNet card, and each plain node (a PLC300 slave, a CiA 401 I/O node:
 * nodes/plain_node.h), a device of the daemon's loop (co_linux/device.h) whose callbacks count
 * its frames (counters.h), log its state changes, boot-up, emergencies and LEDs, and keep its
 * parameters in the --store file. Built from the command line (options.h). */
#ifndef ATV312D_DRIVES_H
#define ATV312D_DRIVES_H

#include "atv312d/counters.h"
#include "atv312d/options.h"
#include "co_linux/file_store.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/drive_devicenet.h"
#include "nodes/plain_node.h"

#include <stddef.h>

/* One node of the bench, a drive or a plain node, and what the runtime and the logs need around
 * it (a slot of the bench). */
typedef struct atv312d_drive {
    drive_t drive;       /* a drive's; unused by a plain node */
    plain_node_t *plain; /* a plain node's (its model's kind ATV312D_KIND_NODE); NULL: a drive */
    uint8_t *od_data;    /* the node's dictionary data block, of its model's size */
    uint8_t id; /* node-id on CANopen (a node with LSS: the one it has now, FFh: none), MAC ID on
                 * DeviceNet */
    /* Its records' key in the --store file: its node-id as given, or for the k-th node of
     * --unconfigured CO_FILE_STORE_UNCONFIGURED_KEY + k, whatever node-id LSS gives it. */
    uint8_t key;
    drive_dn_t *dn; /* its DeviceNet card, NULL on CANopen */
    co_file_store_t *store;
    co_linux_device_t device;
    co_file_store_node_t store_node;
    co_storage_t storage;
    co_nmt_state_t nmt_state; /* last logged */
    const char *cia402_state; /* last logged */
    dn_led_t ms_led, ns_led;  /* last logged, DeviceNet */
    plain_loss_t plain_loss;  /* last logged, a plain node */
    atv312d_counters_t counters;
} atv312d_drive_t;

/* Initialises the opts->node_count nodes of `slots` (zeroed), each on its node-id or MAC ID
 * and model, bound to `store` (NULL: no --store), and adds each to the loop. 0, or an exit
 * status after logging why. */
int atv312d_drives_init(atv312d_drive_t *slots, const atv312d_options_t *opts,
                        co_file_store_t *store, co_linux_loop_t *loop);

/* Frees the nodes' memory and unbinds them from the store, then frees `slots` (NULL: nothing). */
void atv312d_drives_free(atv312d_drive_t *slots, size_t count);

#endif
