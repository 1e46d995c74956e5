/* SPDX-License-Identifier: Apache-2.0 */
/* A CANopen node: one instance of the portable core. The application owns the co_node_t and its
 * object dictionary data block, feeds received frames and the current monotonic time in, and gets
 * frames out through its send callback. co_node_process() runs what is due and returns the next
 * deadline, so a runtime sleeps exactly until then. No malloc, no OS calls, no globals. */
#ifndef CO_NODE_H
#define CO_NODE_H

#include "co_config.h"
#include "co_emcy.h"
#include "co_error_behaviour.h"
#include "co_guarding.h"
#include "co_heartbeat.h"
#include "co_lss_slave.h"
#include "co_nmt.h"
#include "co_nmt_startup.h"
#include "co_od.h"
#include "co_pdo.h"
#include "co_sdo.h"
#include "co_sdo_clients.h"
#include "co_sdo_servers.h"
#include "co_store.h"
#include "co_sync.h"
#include "co_time_stamp.h"
#include "co_types.h"

/* Application callbacks; any of them may be NULL. */
typedef struct co_app_hooks {
    void (*nmt_state)(co_node_t *node, co_nmt_state_t state);
    /* Before the reset of the given scope restores the dictionary (reset node: the application
     * resets its own state too, and the EMCY producer forgets the errors it raised; reset
     * communication keeps them). */
    void (*reset)(co_node_t *node, co_nmt_reset_t scope);
    /* An RPDO (number 1..) was applied to the dictionary. */
    void (*rpdo)(co_node_t *node, uint16_t pdo_number);
    void (*sync)(co_node_t *node, uint8_t counter);
    /* A monitored heartbeat producer was lost (lost = true) or came back (lost = false). A reset
     * restarts monitoring without a call: no lost = false follows a loss then. */
    void (*heartbeat)(co_node_t *node, uint8_t producer, bool lost);
    /* Life guarding: the master stopped guarding this node (lost = true) or resumed; a reset
     * restarts it without a call, as for heartbeat. */
    void (*guarding)(co_node_t *node, bool lost);
    /* A TIME frame was received (co_time_stamp.h: a node given the service, 1012h bit 31). */
    void (*time_stamp)(co_node_t *node, const co_time_of_day_t *time);
    /* An entry was written by SDO or PDO and stored. */
    void (*od_written)(co_node_t *node, const co_od_entry_t *entry, co_od_origin_t origin);
} co_app_hooks_t;

/* Behaviour options of one node (co_node_config_t.options), most for a device of an older profile
 * than CiA 301 v4.2 (DS301 V4.0 devices with pre-V4 habits); 0 is plain
 * CiA 301. A model chooses those, an application the heartbeat grid; each service consults its
 * own (docs/architecture.md, "Node options"). Their code is in co_node_options, which a node
 * with any option must be given (co_node_config_t.options_code), so that a firmware without
 * options does not link it. */
/* Every frame the node sends has DLC 8, its unused bytes 0; NMT commands of DLC 2..8, guarding
 * RTRs of any DLC and RPDOs of DLC 8 (longer than their mapping) are accepted. */
#define CO_NODE_PAD_DLC8 0x01u
/* The SDO server does expedited transfers only: segmented and block initiates abort with
 * 0x05040001, an upload of a value that is not 1..4 bytes with 0x06010000. */
#define CO_NODE_SDO_EXPEDITED_ONLY 0x02u
/* An expedited write longer than its fixed-size object is taken when the extra bytes are 0 (a
 * 4-byte write, 0x23, of a 16-bit object). */
#define CO_NODE_SDO_LONG_EXPEDITED 0x04u
/* Abort frames in the DS301 V3 layout: bytes 4-5 (the additional code) 0, byte 6 the error code,
 * byte 7 the error class, one of four: 2/6 no object, 9/6 no sub-index, 3/5 request not
 * supported (command specifiers), 1/6 access not supported (every other refusal). */
#define CO_NODE_SDO_ERROR_CLASS 0x08u
/* NMT command 3, Disconnect remote node (DS301 before V4): the node enters Stopped. */
#define CO_NODE_NMT_DISCONNECT 0x10u
/* The heartbeat producer's beats fall on the multiples of its period (1017h) from time 0 of the
 * clock passed in, the first at most one period after the boot-up or the 1017h write, so that
 * the nodes of one runtime send their heartbeats in the same wake-ups (a runtime's choice, not a
 * profile's: docs/error-control.md). */
#define CO_NODE_HEARTBEAT_GRID 0x20u
/* 1001h, and byte 2 of every EMCY the node sends whoever raises it (the core's RPDO and SYNC
 * length errors too), is the generic bit alone: 1 while an error is active, 0 otherwise, without
 * CiA 301's class bits (a device whose manual prints the error register as "error (1) or no error
 * (0)"). */
#define CO_NODE_ERROR_REGISTER_GENERIC 0x40u
/* The inhibit time (18xxh:03) of an asynchronous TPDO (types 254/255) is taken while the TPDO is
 * valid, where CiA 301 table 72 takes it only while invalid (a device whose manual says "in
 * asynchronous mode "Inhibit time" and "Event timer" can be modified"); the new value governs from
 * the next transmission. */
#define CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE 0x80u

/* The code of the options (src/canopen/slave/node_options.c), one function for each option that
 * needs more than a test of its flag. */
typedef struct co_node_options_code {
    /* CO_NODE_PAD_DLC8: sends a data frame padded to DLC 8 with zeros. */
    void (*send_padded)(co_node_t *node, const co_frame_t *frame);
    /* CO_NODE_SDO_EXPEDITED_ONLY: whether the server refuses an initiate of this command byte. */
    bool (*sdo_refused_initiate)(uint8_t command);
    /* CO_NODE_SDO_LONG_EXPEDITED: the length of an expedited write of `len` bytes to `entry`
     * (NULL when absent) once its zero extension is dropped. */
    size_t (*sdo_expedited_length)(const co_od_entry_t *entry, const uint8_t *value, size_t len);
    /* CO_NODE_SDO_ERROR_CLASS: the abort code sent for a CiA 301 abort code. */
    uint32_t (*sdo_abort_code)(uint32_t code);
    /* CO_NODE_HEARTBEAT_GRID: the producer's first beat after `now`. */
    co_time_t (*beat_on_grid)(co_time_t now, co_time_t period);
} co_node_options_code_t;

/* The options' code, for co_node_config_t.options_code. */
extern const co_node_options_code_t co_node_options;

typedef struct co_node_config {
    uint8_t node_id; /* 1..127; CO_LSS_NODE_ID_UNCONFIGURED (FFh) too for a node with LSS */
    const co_od_t *od;
    uint8_t *od_data; /* od->data_size bytes owned by the application */
    co_send_fn send;
    void *user;
    const co_app_hooks_t *hooks; /* may be NULL */
    const co_storage_t *storage; /* may be NULL: 1010h/1011h then abort 0x08000020 */
    /* SDO transfer buffer, which several nodes may share (co_sdo_buffer_t). NULL: the node's own
     * CO_CONFIG_SDO_BUFFER bytes; required when CO_CONFIG_SDO_BUFFER is 0. */
    co_sdo_buffer_t *sdo_buffer;
    /* The additional SDO server channels 1201h.. (co_sdo_servers.h), which the application owns
     * and has prepared with co_sdo_servers_init (else CO_NODE_ERR_CONFIG); NULL: the default
     * channel 1200h alone. */
    co_sdo_servers_t *sdo_servers;
    /* The SDO client channels 1280h.. (co_sdo_clients.h), which the application owns and has
     * prepared with co_sdo_clients_init (else CO_NODE_ERR_CONFIG); NULL: none. */
    co_sdo_clients_t *sdo_clients;
    uint32_t options; /* CO_NODE_* behaviour options, 0 for plain CiA 301 */
    /* &co_node_options when options is not 0 (else co_node_init refuses the node with
     * CO_NODE_ERR_OPTIONS); NULL links none of the options' code. */
    const co_node_options_code_t *options_code;
    /* CiA 305 LSS slave (co_lss_slave_init), NULL for none; the application owns it. */
    co_lss_slave_t *lss;
    /* &co_time_stamp: the TIME consumer and the rules of 1012h (co_time_stamp.h); NULL links
     * none of it, and 1012h then refuses bits 31 and 30. */
    const co_time_stamp_code_t *time_stamp;
    /* &co_error_behaviour: 1029h decides what a communication error (a heartbeat producer or life
     * guarding lost) does to the NMT state, and the application raises device errors and bus off
     * recoveries through it (co_error_behaviour.h); NULL links none of it, and the core then
     * leaves the NMT state to the application's heartbeat and guarding hooks. */
    const co_error_behaviour_code_t *error_behaviour;
    /* &co_nmt_startup: the node starts itself into Operational as 1F80h bit 2 says
     * (co_nmt_startup.h); NULL links none of it. */
    const co_nmt_startup_code_t *nmt_startup;
    /* The TPDOs whose inhibit time (18xxh:03) counts in 1 ms instead of CiA 301's 100 us, bit n
     * for TPDO n+1 (TPDOs 1..32), as a device's manual prints the unit of each row (the ATV312's
     * TPDO1, docs/decisions.md D-INHIBIT-TIME); 0 for plain CiA 301. */
    uint32_t tpdo_inhibit_ms;
} co_node_config_t;

struct co_node {
    uint8_t node_id;
    co_nmt_state_t nmt_state;
    const co_od_t *od;
    uint8_t *od_data;
    co_send_fn send;
    void *user;
    const co_app_hooks_t *hooks;
    const co_storage_t *storage;
    uint32_t options;             /* CO_NODE_* */
    co_lss_slave_t *lss;          /* CiA 305 LSS slave, NULL for none */
    co_time_t now;                /* time of the frame or process call being handled */
    uint32_t consumer_generation; /* co_consumers.h */
    /* The options' code, beside a 32-bit member so that a 32-bit processor pads nothing. */
    const co_node_options_code_t *options_code;
    /* co_node_process: the earliest deadline of the services other than the PDOs, valid while
     * schedule_changed is false (co_node_reschedule). */
    co_time_t services_due;
    bool schedule_changed;
    /* The services' rules for the communication parameters 1000h..1FFFh (node.c), which
     * co_od_write applies after its generic checks: 0 to store the value, CO_OD_HANDLED when the
     * service stored it, or an abort code. A pointer, so that the dictionary calls no service;
     * after schedule_changed, in what was padding before the 8-byte aligned service states. */
    uint32_t (*parameter_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                size_t len);
    const co_time_stamp_code_t *time_stamp; /* co_node_config_t.time_stamp */
    /* co_node_config_t.sdo_servers: on a 32-bit processor in what was padding before the 8-byte
     * aligned service states, so that a node keeps its size (docs/footprint.md). */
    co_sdo_servers_t *sdo_servers;

    co_sdo_server_t sdo; /* the default channel, 1200h */
    co_pdo_t pdo;
    co_sync_t sync;
    co_emcy_t emcy;
    co_heartbeat_t heartbeat;
    co_guarding_t guarding;
    /* Last, so that the services' states keep their offsets, and the short load instructions
     * that reach them, whether a firmware uses these or not. */
    const co_error_behaviour_code_t *error_behaviour; /* co_node_config_t.error_behaviour */
    const co_nmt_startup_code_t *nmt_startup;         /* co_node_config_t.nmt_startup */
    /* 1012h as the TIME service keeps it (co_time_stamp_code_t.reset and its write rules), so
     * that a received frame is matched without a dictionary look-up; 0 without the service. */
    uint32_t time_cob_id;
    /* co_node_config_t.sdo_clients: on a 32-bit processor in what was the padding after
     * time_cob_id, so that a node keeps its size (docs/footprint.md). */
    co_sdo_clients_t *sdo_clients;
};

/* Results of co_node_init besides the object dictionary's own validation errors. */
/* node-id outside 1..127, and not FFh of a node with LSS */
#define CO_NODE_ERR_NODE_ID 0x100
/* missing od, data block, send callback or SDO buffer; SDO servers or clients not prepared */
#define CO_NODE_ERR_CONFIG 0x101
/* The dictionary has more RPDOs or TPDOs than co_config.h gives a node (CO_CONFIG_RPDO_MAX,
 * CO_CONFIG_TPDO_MAX). */
#define CO_NODE_ERR_TABLES 0x102
/* Options (co_node_config_t.options) without their code (options_code NULL). */
#define CO_NODE_ERR_OPTIONS 0x103

/* Prepares a node in Initialising: validates the dictionary and loads its defaults. Sends
 * nothing. Returns 0, a co_od_error_t, or a CO_NODE_ERR_* code. */
int co_node_init(co_node_t *node, const co_node_config_t *config);

/* Leaves Initialising: applies stored parameters, sends the boot-up frame, enters
 * Pre-operational. A node without a node-id (FFh, LSS) stays in Initialising, answering LSS only,
 * until LSS gives it one (docs/lss.md). */
void co_node_start(co_node_t *node, co_time_t now);

/* Handles one received frame. Malformed or foreign frames are ignored. */
void co_node_receive(co_node_t *node, const co_frame_t *frame, co_time_t now);

/* Runs every timer that is due at `now` and returns the next deadline (CO_TIME_NEVER when none).
 * Call it after every received frame and every change the application makes to mapped data. */
co_time_t co_node_process(co_node_t *node, co_time_t now);

/* A service's schedule may have changed outside co_node_process() (a frame it consumed, a
 * parameter written, an NMT state change, an EMCY queued): the next process call runs every
 * service instead of returning the kept deadline (used by the services). Inline: it sets one
 * flag, and a service that calls it then calls no function of the node. */
static inline void co_node_reschedule(co_node_t *node)
{
    node->schedule_changed = true;
}
/* A communication error (1029h:01, CiA 301 7.5.2.32): a heartbeat producer or life guarding
 * lost, an RPDO time-out, the recovery from bus off. The NMT state changes as 1029h:01 says on a
 * node with the error behaviour service; a node without it keeps its state (its application
 * keeps CiA 301's behaviour without 1029h). Inline: one test and one call. */
static inline void co_node_communication_error(co_node_t *node)
{
    if (node->error_behaviour != NULL)
        node->error_behaviour->raise(node, CO_ERROR_CLASS_COMMUNICATION);
}

/* The name of release 0.1, which stays for one more release: use co_node_reschedule. */
#define co_node_changed co_node_reschedule

/* Sends a frame through the node's callback, padded to DLC 8 under CO_NODE_PAD_DLC8 (used by the
 * services; src/canopen/common/frame_output.c). */
void co_node_send(co_node_t *node, const co_frame_t *frame);

/* Sends the one data byte of an error control frame (CiA 301 7.2.8.3): a boot-up, a heartbeat, a
 * node guarding reply. */
void co_node_send_byte(co_node_t *node, uint32_t id, uint8_t byte);

#endif
