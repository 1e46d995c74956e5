/* SPDX-License-Identifier: Apache-2.0 */
/* The SDO client channels of a node, 1280h..12FFh (CiA 301, "SDO client parameter"):
 * their states, which the application owns and gives the node (co_node_config_t.sdo_clients)
 * once co_sdo_clients_init has prepared them; a node given none links none of this module.
 * Channel n (0..count-1) is 1280h + n of the dictionary: its client -> server (sub-index 1) and
 * server -> client (sub-index 2) COB-IDs are read at every reset and whenever they are written,
 * and it may run a transfer while both are valid. Each channel is one co_sdo_client_t (the
 * protocol is co_sdo_client.h's); the node sends its requests, routes the frames of its
 * server -> client COB-ID to it, lists that COB-ID among those it consumes (co_consumers.h) and
 * runs its timeout in co_node_process. docs/sdo.md, "SDO client objects". */
#ifndef CO_SDO_CLIENTS_H
#define CO_SDO_CLIENTS_H

#include "co_sdo_client.h"

typedef struct co_sdo_clients co_sdo_clients_t;

/* One channel. `done` and `user` get its results (co_sdo_client_init's callback and its
 * argument); co_sdo_clients_init gives every channel the same, which the application may change
 * channel by channel before a transfer. */
typedef struct co_sdo_client_channel {
    co_sdo_client_t client;
    co_sdo_client_done_fn done;
    void *user;
    co_sdo_clients_t *clients; /* its set, which knows the node */
    bool valid;                /* both COB-IDs of its object are valid */
} co_sdo_client_channel_t;

struct co_sdo_clients {
    co_sdo_client_channel_t *channels; /* `count` states */
    uint8_t count;                     /* 1..CO_CONFIG_SDO_CLIENTS_MAX */
    co_node_t *node;                   /* set by the node's reset */
    /* The module's entries, set by co_sdo_clients_init, so that the node calls them through these
     * and a node without client channels does not link them: a frame on the server -> client
     * COB-ID of a valid channel (false: none), the reset, the timeouts, the rules of
     * 1280h..12FFh (an abort code, or CO_OD_HANDLED once a value is stored and taken). */
    bool (*receive)(co_node_t *node, const co_frame_t *frame);
    void (*reset)(co_node_t *node);
    co_time_t (*process)(co_node_t *node, co_time_t now);
    uint32_t (*od_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
};

/* Prepares `count` channel states for a node, before co_node_init, each reporting to done(user).
 * Returns 0, or -1 for no states, no callback, or a count outside 1..CO_CONFIG_SDO_CLIENTS_MAX. */
int co_sdo_clients_init(co_sdo_clients_t *clients, co_sdo_client_channel_t *channels, uint8_t count,
                        co_sdo_client_done_fn done, void *user);

/* Result of the requests below besides co_sdo_client.h's: the node has no such channel. */
#define CO_SDO_CLIENT_ERR_CHANNEL 6

/* Reads index:subindex of the server of channel `channel` (1280h + channel) into buf (cap
 * bytes), as co_sdo_client_upload does. Returns 0 when the request was sent,
 * CO_SDO_CLIENT_ERR_CHANNEL, CO_SDO_CLIENT_ERR_INVALID while the channel is not valid or the node
 * is neither Pre-operational nor Operational (CiA 301 table 74), or co_sdo_client_upload's
 * errors. */
int co_node_sdo_upload(co_node_t *node, uint8_t channel, uint16_t index, uint8_t subindex,
                       uint8_t *buf, uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                       co_time_t now);

/* Writes len bytes of data (valid until the transfer ends) to index:subindex of the server of
 * channel `channel`, as co_sdo_client_download does; the same results. */
int co_node_sdo_download(co_node_t *node, uint8_t channel, uint16_t index, uint8_t subindex,
                         const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                         uint32_t timeout_ms, co_time_t now);

#endif
