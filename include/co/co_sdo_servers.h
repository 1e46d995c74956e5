/* SPDX-License-Identifier: Apache-2.0 */
/* The additional SDO server channels of a node, 1201h..127Fh (CiA 301 7.5.2.34, "SDO server
 * parameter"): their states, which the application owns and gives the node
 * (co_node_config_t.sdo_servers) once co_sdo_servers_init has prepared them; a node given none
 * links none of this module. Channel n (0..count-1) is 1201h + n of the dictionary: its
 * client -> server (sub-index 1) and server -> client (sub-index 2) COB-IDs are read at every
 * reset and whenever they are written, and it takes requests while both are valid. Each channel
 * runs its own transfer (co_sdo.h), so that several clients talk to the node at once; the
 * protocol timeout is the node's (co_sdo_set_timeout). docs/sdo.md, "Several SDO servers". */
#ifndef CO_SDO_SERVERS_H
#define CO_SDO_SERVERS_H

#include "co_sdo.h"

typedef struct co_sdo_servers {
    co_sdo_server_t *channels; /* `count` states */
    uint8_t count;             /* 1..CO_CONFIG_SDO_SERVERS_MAX */
    /* The module's entries, set by co_sdo_servers_init, so that the node calls them through these
     * and a node without additional channels does not link them: a frame for the valid channel
     * of its CAN-ID (false: none), the reset, the timeouts, the rules of 1201h..127Fh (0 to
     * store, an abort code, or CO_OD_HANDLED once a COB-ID is stored and taken). */
    bool (*receive)(co_node_t *node, const co_frame_t *frame);
    void (*reset)(co_node_t *node);
    co_time_t (*process)(co_node_t *node, co_time_t now);
    uint32_t (*od_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
} co_sdo_servers_t;

/* Prepares `count` channel states for a node, before co_node_init. Their transfer buffer:
 * `buffer`, one for all of them (and whoever else shares it: co_sdo_buffer_t), or NULL for each
 * its own CO_CONFIG_SDO_BUFFER bytes in its state (docs/decisions.md D-SDO-CHANNEL-BUFFER).
 * Returns 0, or -1 for no states, a count outside 1..CO_CONFIG_SDO_SERVERS_MAX or no buffer
 * when CO_CONFIG_SDO_BUFFER is 0. */
int co_sdo_servers_init(co_sdo_servers_t *servers, co_sdo_server_t *channels, uint8_t count,
                        co_sdo_buffer_t *buffer);

#endif
