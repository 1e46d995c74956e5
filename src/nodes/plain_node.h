/* SPDX-License-Identifier: Apache-2.0 */
/* A plain node: a CANopen slave that is no drive, whose behaviour is its model's dictionary (its
 * EDS and hooks file) and the few rules of plain_model_t: what a lost heartbeat producer or life
 * guarding does to the NMT state, its LEDs, its identity's serial number. The PLC300 slave
 * (nodes/plc300/plc300.h) and the CiA 401 I/O node (nodes/io/io401.h) are plain nodes.
 * Portable like the core: no malloc, no OS calls, no globals; time is passed in. docs/plc300.md,
 * docs/io.md; where it stands among the layers: docs/architecture.md. */
#ifndef NODES_PLAIN_NODE_H
#define NODES_PLAIN_NODE_H

#include "co/co_indicators.h"
#include "co/co_node.h"

/* A model of plain node: data, no code of its own but its dictionary's hooks. */
typedef struct plain_model {
    const char *name;        /* as atv312d's --model takes it */
    const char *description; /* for --help */
    const co_od_t *od;
    uint8_t node_id_max; /* highest node-id the model takes */
    /* 1018h:04 of a node is this plus the number the application gives it (atv312d: its node-id,
     * 80h + k for the k-th node without node-id), so that every node of a bench has its own
     * serial number. */
    uint32_t serial_base;
    /* A lost heartbeat producer or life guarding enters Pre-operational from Stopped too (the
     * PLC300's manual, 6.5.2 and 6.5.3); false: only from Operational, CiA 301's error behaviour
     * where 1029h:01 is absent or 0. */
    bool loss_from_any_state;
    /* While the ERR (red) LED shows anything the RUN (green) LED is off (the PLC300's manual,
     * 2.4, whose patterns and timings are CiA 303-3's otherwise); false: both show, as CiA 303-3
     * has them. */
    bool err_over_run;
    /* The node consumes TIME (co_time_stamp.h) as its dictionary's 1012h says; false: the
     * service is not linked into the node and 1012h, if any, can neither consume nor produce. */
    bool time_stamp;
    /* The node has a CiA 305 LSS slave (docs/lss.md), and may start without node-id (FFh). */
    bool lss;
    /* The core's error behaviour (co_error_behaviour.h): its dictionary's 1029h decides what a
     * lost heartbeat producer or life guarding and a bus off recovery do, and
     * loss_from_any_state is not used; false: the service is not linked into the node and the
     * node reacts as loss_from_any_state says. */
    bool error_behaviour;
    /* The core's NMT start-up (co_nmt_startup.h): 1F80h bit 2 clear starts the node by itself;
     * false: not linked, the node waits for the master's start. */
    bool nmt_startup;
    /* Additional SDO servers (co_sdo_servers.h), 1201h.. of the dictionary, each with its own
     * buffer: 0..PLAIN_SDO_SERVERS_MAX. */
    uint8_t sdo_servers;
} plain_model_t;

/* Most additional SDO servers of a plain node: the I/O node's one. */
#define PLAIN_SDO_SERVERS_MAX 1

/* The error control event the node saw last, until the producer or the master comes back or a
 * reset (the ERR LED's double flash). */
typedef enum plain_loss {
    PLAIN_LOSS_NONE,
    PLAIN_LOSS_HEARTBEAT, /* of producer `lost_producer` */
    PLAIN_LOSS_GUARDING   /* life guarding: the master's guarding requests stopped */
} plain_loss_t;

typedef struct plain_node {
    co_node_t node; /* first: a hook's co_node_t is its plain node (plain_node_of) */
    const plain_model_t *model;
    uint32_t serial_number;
    plain_loss_t loss;
    uint8_t lost_producer;
    bool bus_warning; /* the controller at or over its warning level */
    bool bus_passive; /* error passive */
    bool bus_off;
    /* The last TIME received (model->time_stamp), kept across resets: the time is the
     * network's, not the node's. */
    co_time_of_day_t time;
    bool time_received;
    co_lss_slave_t lss; /* used when the model has LSS */
    /* The additional SDO servers, when the model has them. */
    co_sdo_servers_t sdo_servers;
    co_sdo_server_t sdo_channels[PLAIN_SDO_SERVERS_MAX];
} plain_node_t;

typedef struct plain_node_config {
    const plain_model_t *model;
    uint8_t *od_data;       /* model->od->data_size bytes owned by the application */
    uint8_t node_id;        /* 1..127, or FFh (none) for a model with LSS */
    uint32_t serial_number; /* 1018h:04 */
    /* The LSS slave's hooks when the model has LSS (NULL: none, no store); its bit timing is
     * lss_bit_timing, the index of CiA 305's table 0 the node runs at. */
    const co_lss_slave_hooks_t *lss_hooks;
    uint8_t lss_bit_timing;
    co_send_fn send;
    void *send_user;
    const co_storage_t *storage;                     /* may be NULL */
    uint32_t node_options;                           /* the core's CO_NODE_* options */
    const co_node_options_code_t *node_options_code; /* &co_node_options when options != 0 */
} plain_node_config_t;

/* The plain node of a core node initialised by plain_node_init. */
static inline plain_node_t *plain_node_of(co_node_t *node)
{
    return (plain_node_t *)(void *)node;
}

/* Prepares the node in Initialising; 0 or co_node_init's error (CO_NODE_ERR_CONFIG for a model
 * with more than PLAIN_SDO_SERVERS_MAX additional SDO servers). */
int plain_node_init(plain_node_t *plain, const plain_node_config_t *config);
void plain_node_start(plain_node_t *plain, co_time_t now);
void plain_node_receive(plain_node_t *plain, const co_frame_t *frame, co_time_t now);
co_time_t plain_node_process(plain_node_t *plain, co_time_t now);

/* A CAN condition began or ended: emcy_code 8120h (error passive) or 8140h (bus off; its end the
 * recovery); others change no LED. */
void plain_node_bus_event(plain_node_t *plain, uint16_t emcy_code, bool active);
/* The controller reached (active) or left its warning level. */
void plain_node_bus_warning(plain_node_t *plain, bool active);

/* The RUN (green) and ERR (red) LEDs, CiA 303-3's (co_indicators.h): RUN single flash Stopped,
 * blinking Pre-operational, on Operational; ERR on bus off, double flash after an error control
 * event, single flash at the warning level or error passive, otherwise off; with the model's
 * err_over_run, RUN off while ERR shows anything. */
co_led_t plain_node_run_led(const plain_node_t *plain);
co_led_t plain_node_err_led(const plain_node_t *plain);

#endif
