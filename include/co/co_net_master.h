/* SPDX-License-Identifier: Apache-2.0 */
/* Network master (the PLC300's master mode, its manual section 7.3; the "boot slave" process of
 * CiA 302-2): boots a table of slaves (reset communication, identify by 1000h and 1018h, download
 * the configuration, start error control, NMT start), retries a failed slave after the others,
 * re-boots a slave whose error control fails, keeps the PLC300's status words (its section 5.6.3),
 * the last SDO error and the last EMCY (5.6.4, 5.6.5), and exchanges a process image with the
 * slaves by PDO. Built on co_sdo_client_t (one, reused slave after slave as the PLC300's single
 * client), co_nmt_master_t, co_emcy_consumer_t and co_sync_producer_t; owns none of their
 * protocols. Passive like the rest of the core: frames and time are passed in, frames go out
 * through the send callback, no malloc, no globals. Behaviour and decisions: docs/net-master.md. */
#ifndef CO_NET_MASTER_H
#define CO_NET_MASTER_H

#include "co_concise_dcf.h"
#include "co_emcy_consumer.h"
#include "co_nmt_master.h"
#include "co_sdo_client.h"
#include "co_sync.h"

/* Status word of one slave, bits of the PLC300's %SW3202..%SW3454 (5.6.3). */
#define CO_NET_SLAVE_CONTACTED 0x0001u  /* bit 0: 1000h read (and identity matched) */
#define CO_NET_SLAVE_CONFIGURED 0x0002u /* bit 1: every configuration write done */
#define CO_NET_SLAVE_EC_STARTED 0x0004u /* bit 2: error control started (or none) */
#define CO_NET_SLAVE_INIT_DONE 0x0008u  /* bit 3: initialisation finished successfully */
#define CO_NET_SLAVE_INIT_ERROR 0x0010u /* bit 4: the last initialisation failed */
#define CO_NET_SLAVE_EC_ERROR 0x0020u   /* bit 5: error control detected a failure */
/* Status word of the master, bits of the PLC300's %SW3200 (5.6.3); bit 6 is the project's own. */
#define CO_NET_MASTER_ALL_CONTACTED 0x0001u   /* bit 0: every slave has bit 0 */
#define CO_NET_MASTER_ALL_CONFIGURED 0x0002u  /* bit 1: every slave has bit 1 */
#define CO_NET_MASTER_ALL_EC_STARTED 0x0004u  /* bit 2: every slave has bit 2 */
#define CO_NET_MASTER_INIT_FINISHED 0x0008u   /* bit 3: every slave's first attempt ended */
#define CO_NET_MASTER_INIT_ERROR 0x0010u      /* bit 4: some slave has bit 4 */
#define CO_NET_MASTER_EC_ERROR 0x0020u        /* bit 5: some slave has bit 5 */
#define CO_NET_MASTER_MANDATORY_ERROR 0x0040u /* bit 6: some mandatory slave has bit 4 */
#define CO_NET_MASTER_BOOT_TIME_OVER                                                               \
    0x0080u                                /* bit 7 (the project's own): CiA 302-2's boot          \
                                            * time 1F89h ended before every mandatory slave        \
                                            * was configured */
#define CO_NET_MASTER_NMT_TOGGLE 0x0100u   /* bit 8: flips after each co_net_master_nmt */
#define CO_NET_MASTER_BUS_OFF 0x2000u      /* bit 13: the controller is bus off */
#define CO_NET_MASTER_NO_BUS_POWER 0x4000u /* bit 14: the interface has no bus power */
#define CO_NET_MASTER_DISABLED                                                                     \
    0x8000u /* bit 15: communication disabled (by the                                              \
             * application, bus off or no bus power) */

/* The CANopen protocol state, the PLC300's %SB3180 (its section 8.1, reading system markers; 1 is
 * reserved): its two error codes tell a node guarding failure from a heartbeat failure, which the
 * status words' bit 5 does not (docs/decisions.md, D-NET-MASTER-EC-KIND). */
#define CO_NET_PROTOCOL_DISABLED 0u        /* communication disabled (status bit 15) */
#define CO_NET_PROTOCOL_ENABLED 2u         /* CANopen enabled, no slave under error control */
#define CO_NET_PROTOCOL_EC_ENABLED 3u      /* error control of some slave started */
#define CO_NET_PROTOCOL_GUARDING_ERROR 4u  /* a slave failed node guarding */
#define CO_NET_PROTOCOL_HEARTBEAT_ERROR 5u /* a slave's heartbeat failed */

/* Which identity values are compared with the expected ones (co_net_slave_config_t.check). */
#define CO_NET_CHECK_DEVICE_TYPE 0x01u /* 1000h */
#define CO_NET_CHECK_VENDOR 0x02u      /* 1018h:01 */
#define CO_NET_CHECK_PRODUCT 0x04u     /* 1018h:02 */
#define CO_NET_CHECK_REVISION 0x08u    /* 1018h:03 */
#define CO_NET_CHECK_SERIAL 0x10u      /* 1018h:04 */
#define CO_NET_IDENTITY_SUBS 4u

/* CiA 302-2's expected identity objects of an NMT master, each an array whose sub-index is the
 * slave's node-id (co_net_slave_expected, co_net_slave_config_set_expected); 0: not checked. */
#define CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION 0x1F84u /* 1000h */
#define CO_NET_IDX_VENDOR_IDENTIFICATION 0x1F85u      /* 1018h:01 */
#define CO_NET_IDX_PRODUCT_CODE 0x1F86u               /* 1018h:02 */
#define CO_NET_IDX_REVISION_NUMBER 0x1F87u            /* 1018h:03 */
#define CO_NET_IDX_SERIAL_NUMBER 0x1F88u              /* 1018h:04 */
/* CiA 302-2's boot time 1F89h (UNSIGNED32, ms; 0: no limit): co_net_master_config_t.boot_limit_ms.
 */
#define CO_NET_IDX_BOOT_TIME 0x1F89u

/* CiA 302-2's error status of a failed "boot slave" (co_net_slave_t.boot_error), the letters of
 * its table that this master can give. */
#define CO_NET_BOOT_ERROR_NONE 0u
#define CO_NET_BOOT_ERROR_B 'B' /* no answer to the read of 1000h (an abort or a timeout) */
#define CO_NET_BOOT_ERROR_C 'C' /* 1000h differs from 1F84h */
#define CO_NET_BOOT_ERROR_D 'D' /* 1018h:01 differs from 1F85h (or could not be read) */
#define CO_NET_BOOT_ERROR_J 'J' /* the configuration download failed */
#define CO_NET_BOOT_ERROR_M 'M' /* 1018h:02 differs from 1F86h (or could not be read) */
#define CO_NET_BOOT_ERROR_N 'N' /* 1018h:03 differs from 1F87h (or could not be read) */
#define CO_NET_BOOT_ERROR_O 'O' /* 1018h:04 differs from 1F88h (or could not be read) */

/* The PLC300's CAN baud rate codes, its %CB3055 and Setup menu's BAUD RATE (section 8.2; 1 is
 * reserved, and 800 and 10 kbit/s have none): the master's bit rate marker, which the application
 * sets its controller to (docs/decisions.md, D-NET-MASTER-MARKERS). */
#define CO_NET_BIT_RATE_1M 0u
#define CO_NET_BIT_RATE_500K 2u
#define CO_NET_BIT_RATE_250K 3u
#define CO_NET_BIT_RATE_125K 4u
#define CO_NET_BIT_RATE_100K 5u
#define CO_NET_BIT_RATE_50K 6u
#define CO_NET_BIT_RATE_20K 7u

/* The PLC300's SDO timeout range (its CO_SDORead block, 5-5000 ms). */
#define CO_NET_SDO_TIMEOUT_MIN_MS 5u
#define CO_NET_SDO_TIMEOUT_MAX_MS 5000u

/* One configuration write: `len` bytes at `data` (application memory that outlives the master). */
typedef struct co_net_write {
    uint16_t index;
    uint8_t subindex;
    const uint8_t *data;
    uint32_t len;
} co_net_write_t;

/* What to do when error control of a configured slave fails (a boot-up, whatever this says, boots
 * the slave again: docs/net-master.md). */
typedef enum co_net_on_error {
    CO_NET_ON_ERROR_REBOOT = 0, /* reset node, then boot it again from the start */
    CO_NET_ON_ERROR_REPORT      /* only set bit 5 and step LOST; heard again, the slave returns to
                                 * the step it was lost from and bit 5 is cleared */
} co_net_on_error_t;

typedef struct co_net_slave_config {
    uint8_t node_id; /* 1..127, each at most once */
    bool mandatory;  /* NMT start all waits for it; its init error sets master bit 6 */
    uint8_t check;   /* CO_NET_CHECK_* */
    uint32_t device_type;
    uint32_t identity[CO_NET_IDENTITY_SUBS]; /* expected 1018h:01..04 */
    const co_net_write_t *writes;
    size_t write_count;
    /* Or the configuration as CiA 302's concise DCF (1F22h, sub-index the node-id:
     * co_concise_dcf.h), its entries downloaded in order as the writes would be; application memory
     * that outlives the master. Not both. */
    const uint8_t *concise_dcf;
    size_t concise_dcf_len;
    uint16_t heartbeat_ms; /* consumer time, 0: no heartbeat monitoring */
    uint16_t guard_ms;     /* node guarding when heartbeat_ms is 0 and this is not */
    uint8_t life_time_factor;
    co_net_on_error_t on_error;
} co_net_slave_config_t;

/* CiA 302-2's NMT slave assignment 1F81h (its sub-index is the slave's node-id), bit by bit. */
#define CO_NET_1F81_SLAVE 0x01u /* bit 0: an NMT slave of this master */
#define CO_NET_1F81_BOOT 0x04u  /* bit 2: an error control event configures and starts it again */
#define CO_NET_1F81_MANDATORY 0x08u  /* bit 3: the network does not start without it */
#define CO_NET_1F81_KEEP_ALIVE 0x10u /* bit 4: not reset by the master's boot when Operational */
#define CO_NET_1F81_RETRY_SHIFT 8u   /* bits 8..15: the retry factor (life time factor) */
#define CO_NET_1F81_GUARD_SHIFT 16u  /* bits 16..31: the guard time, ms */

/* When the master sends NMT start. */
typedef enum co_net_start {
    CO_NET_START_EACH = 0, /* each slave as soon as it is configured */
    CO_NET_START_ALL,      /* all at once (node 0) when every mandatory slave is configured and
                            * every first attempt ended; a slave booted after that starts alone */
    CO_NET_START_NONE      /* never: the application starts them */
} co_net_start_t;

/* What an error control failure of a mandatory slave does to the network: CiA 302-2's NMT
 * start-up (1F80h) bits 4 and 6. */
typedef enum co_net_mandatory_error {
    CO_NET_MANDATORY_ALONE = 0, /* the slave alone, as its on_error says */
    CO_NET_MANDATORY_STOP_ALL,  /* NMT stop to all nodes (000#0200), the master stopped too: no
                                 * SYNC, no output PDO, its heartbeat 04h, until the application's
                                 * NMT start to all or a new start; the slave LOST */
    CO_NET_MANDATORY_RESET_ALL  /* NMT reset node to all (000#8100), then the whole network
                                 * booted again from its boot-ups */
} co_net_mandatory_error_t;

/* CiA 302-2's NMT start-up object 1F80h (UNSIGNED32) of an NMT master, bit by bit. */
#define CO_NET_1F80_NMT_MASTER 0x01u     /* bit 0: the device is the NMT master */
#define CO_NET_1F80_START_ALL 0x02u      /* bit 1: start all nodes by one NMT start to node 0 */
#define CO_NET_1F80_NO_SELF_START 0x04u  /* bit 2: the master does not enter Operational itself */
#define CO_NET_1F80_NO_SLAVE_START 0x08u /* bit 3: the master starts no slave: the application */
#define CO_NET_1F80_RESET_ALL                                                                      \
    0x10u                               /* bit 4: a mandatory slave's error control event resets   \
                                         * all nodes */
#define CO_NET_1F80_FLYING_MASTER 0x20u /* bit 5: takes part in the flying master process */
#define CO_NET_1F80_STOP_ALL 0x40u      /* bit 6: ... stops all nodes (before bit 4) */

/* One PDO of the process image: the frame's bytes are image[offset .. offset + len). Inputs are
 * the slaves' TPDOs, outputs the RPDOs the master sends them. */
typedef struct co_net_pdo {
    uint8_t node_id; /* the slave it comes from or goes to */
    uint16_t can_id; /* 11-bit */
    uint8_t len;     /* 1..8 */
    uint16_t offset;
} co_net_pdo_t;

/* How many SDO requests of the application wait for the master's client at once. */
#define CO_NET_REQUEST_MAX 4u

/* An SDO transfer the application asks of the master's own client (co_net_master_sdo): it runs
 * when no slave's boot holds the client, one at a time in the order asked. */
typedef struct co_net_request co_net_request_t;
typedef void (*co_net_request_fn)(void *user, const co_net_request_t *request,
                                  const co_sdo_client_result_t *result);
struct co_net_request {
    uint8_t node_id; /* 1..127, in the table or not */
    uint16_t index;
    uint8_t subindex;
    bool write;
    uint8_t *data; /* write: the bytes (which stay valid until done); read: the buffer */
    uint32_t len;  /* write: the bytes to write; read: the buffer's size */
    co_net_request_fn done;
    void *user; /* passed to done */
};

/* What a co_net_master_nmt command confirms: the state each addressed node reports after it. */
typedef struct co_net_nmt_request {
    bool pending;
    uint8_t command;  /* CO_NMT_CS_* */
    uint8_t node_id;  /* 0: every slave of the table */
    uint8_t expected; /* the state awaited: 05h, 04h, 7Fh, or 00h (boot-up) for a reset */
    co_time_t deadline;
    uint32_t awaited[4]; /* node-id n at bit n % 32 of word n / 32: not confirmed yet */
} co_net_nmt_request_t;

typedef enum co_net_event_kind {
    CO_NET_EVENT_STEP,      /* the slave entered another step */
    CO_NET_EVENT_STATUS,    /* the slave's status word changed */
    CO_NET_EVENT_SDO_ERROR, /* last_sdo_error was updated */
    CO_NET_EVENT_EMCY,      /* last_emcy was updated */
    CO_NET_EVENT_INPUT,     /* a TPDO updated the input image (`pdo` is its index) */
    CO_NET_EVENT_STARTED,   /* NMT start all was sent */
    CO_NET_EVENT_BOOT_TIME, /* the boot time 1F89h ended with a mandatory slave not configured
                             * (node_id 0; master status bit 7) */
    CO_NET_EVENT_NMT_DONE   /* the co_net_master_nmt command ended: every addressed node
                             * confirmed, or its deadline passed (master.nmt_request says who) */
} co_net_event_kind_t;

/* Where a slave is in its boot. */
typedef enum co_net_step {
    CO_NET_STEP_IDLE = 0,    /* before co_net_master_start */
    CO_NET_STEP_WAIT_BOOT,   /* reset sent: waiting for its boot-up (or the boot time) */
    CO_NET_STEP_DEVICE_TYPE, /* reading 1000h */
    CO_NET_STEP_IDENTITY,    /* reading the checked 1018h subs */
    CO_NET_STEP_DOWNLOAD,    /* writing the configuration */
    CO_NET_STEP_WAIT_START,  /* configured, waiting for NMT start all */
    CO_NET_STEP_OPERATIONAL, /* initialised (and started, unless CO_NET_START_NONE) */
    CO_NET_STEP_FAILED,      /* init error: retried after the retry delay, after the others */
    CO_NET_STEP_LOST         /* error control failed, CO_NET_ON_ERROR_REPORT: from WAIT_START
                              * (bit 3 clear) or OPERATIONAL (bit 3 set) */
} co_net_step_t;

/* Which error control found a slave silent: what its status bit 5 stands for. */
typedef enum co_net_ec_error {
    CO_NET_EC_ERROR_NONE = 0, /* bit 5 clear */
    CO_NET_EC_ERROR_GUARDING, /* node guarding: no valid reply for life time factor x guard time */
    CO_NET_EC_ERROR_HEARTBEAT /* no heartbeat within the consumer time (or no first one) */
} co_net_ec_error_t;

/* Why the last initialisation of a slave failed. */
typedef enum co_net_failure {
    CO_NET_FAIL_NONE = 0,
    CO_NET_FAIL_SDO,         /* an SDO transfer failed: see last_sdo_error */
    CO_NET_FAIL_DEVICE_TYPE, /* 1000h differs from the expected value */
    CO_NET_FAIL_IDENTITY     /* a checked 1018h sub differs */
} co_net_failure_t;

typedef struct co_net_event {
    co_net_event_kind_t kind;
    uint8_t node_id; /* 0 for CO_NET_EVENT_STARTED */
    size_t pdo;      /* CO_NET_EVENT_INPUT */
} co_net_event_t;

typedef void (*co_net_event_fn)(void *user, const co_net_event_t *event);

/* The PLC300's last SDO error record (5.6.4). */
#define CO_NET_ACCESS_READ 1u
#define CO_NET_ACCESS_WRITE 2u
typedef struct co_net_sdo_error {
    uint8_t node_id; /* 0: none yet */
    uint16_t index;
    uint8_t subindex;
    uint8_t access; /* CO_NET_ACCESS_* */
    uint32_t value; /* a write's value (its first 4 bytes, little-endian) */
    uint32_t abort_code;
} co_net_sdo_error_t;

/* What the master knows of one slave. */
typedef struct co_net_slave {
    uint8_t step;        /* co_net_step_t */
    uint16_t status;     /* CO_NET_SLAVE_* */
    uint8_t failure;     /* co_net_failure_t of the last failed attempt */
    uint8_t ec_error;    /* co_net_ec_error_t of the last loss while bit 5 is set, else NONE */
    uint8_t boot_error;  /* CiA 302-2's CO_NET_BOOT_ERROR_* of the last failed attempt; as bit 4,
                          * kept until an attempt configures the slave or the master starts */
    uint32_t read_value; /* the value of the failed identity check (or the last one read) */
    bool booted;         /* the boot-up awaited since its last reset came */
    bool tried;          /* an attempt at its initialisation ended (successfully or not) */
    size_t write_pos;    /* the write being downloaded: its index in writes, or for a concise
                          * DCF the byte offset of its entry */
    uint8_t identity_sub;
    co_time_t deadline; /* WAIT_BOOT: the end of the boot time; FAILED: the retry */
} co_net_slave_t;

typedef struct co_net_master_config {
    co_send_fn send;                     /* required */
    void *user;                          /* passed to send and event */
    co_net_event_fn event;               /* may be NULL */
    const co_net_slave_config_t *slaves; /* booted in this order */
    co_net_slave_t *slave_state;         /* as many as slaves, the application's memory */
    size_t slave_count;                  /* 1..127 */
    uint16_t sdo_timeout_ms;             /* 5..5000 */
    uint32_t boot_time_ms;   /* the wait for a boot-up after a reset; identification starts
                              * anyway when it ends */
    uint32_t retry_delay_ms; /* before a failed slave is tried again */
    co_net_start_t start;
    bool reset_all;          /* begin with NMT reset communication to all nodes (PLC300 step 1);
                              * otherwise each slave is reset alone */
    uint32_t sync_period_us; /* 0: no SYNC; otherwise SYNC on 080h, no counter */
    const co_net_pdo_t *inputs;
    size_t input_count;
    uint8_t *input_image;
    size_t input_size;
    const co_net_pdo_t *outputs;
    size_t output_count;
    uint8_t *output_image;
    size_t output_size;
    /* The master's own heartbeat (the PLC300's 1017h): 700h + node_id [05h] every heartbeat_ms
     * from co_net_master_start; 0: none. node_id 1..127, no slave's, when heartbeat_ms is set. */
    uint8_t node_id;
    uint16_t heartbeat_ms;
    co_net_mandatory_error_t on_mandatory_error;
    /* CiA 302-2's boot time 1F89h: from co_net_master_start (or a reset of all), the time every
     * mandatory slave has to be configured in, else CO_NET_EVENT_BOOT_TIME and master status bit
     * 7; the boot goes on. 0: no limit. */
    uint32_t boot_limit_ms;
} co_net_master_config_t;

typedef struct co_net_master {
    co_net_master_config_t config;
    co_nmt_master_t nmt;
    co_sdo_client_t sdo;
    co_emcy_consumer_t emcy;
    co_sync_producer_t sync;
    size_t current;       /* the slave using the SDO client, config.slave_count when none */
    size_t next_pick;     /* where the search for the next slave to boot starts */
    bool started;         /* co_net_master_start was called */
    bool started_all;     /* CO_NET_START_ALL: the start all was sent */
    bool stopped_all;     /* CO_NET_MANDATORY_STOP_ALL stopped every node, the master too */
    bool boot_time_over;  /* the boot time 1F89h ended first: status bit 7 */
    co_time_t boot_limit; /* its end, CO_TIME_NEVER once over or every mandatory slave is in */
    co_time_t now;        /* of the call under way, for requests started from callbacks */
    uint8_t value[4];     /* an identity value being read */
    co_net_sdo_error_t last_sdo_error;
    co_emcy_message_t last_emcy; /* node_id 0: none yet */
    co_time_t next_heartbeat;    /* CO_TIME_NEVER: none produced */
    bool disabled;               /* co_net_master_disable: no frame in or out */
    uint16_t bus;                /* CO_NET_MASTER_BUS_OFF, _NO_BUS_POWER as the runtime says */
    uint16_t nmt_toggle;         /* CO_NET_MASTER_NMT_TOGGLE or 0 */
    co_net_nmt_request_t nmt_request;
    co_net_request_t requests[CO_NET_REQUEST_MAX]; /* the SDO requests waiting, the first one
                                                    * under way when `serving` */
    size_t request_count;
    bool serving;
} co_net_master_t;

/* Checks and copies the configuration (the tables it points at are the application's and must
 * outlive the master); every slave idle. False, and nothing sent, for: no send callback, no slave
 * or more than 127, a node-id outside 1..127 or twice, a write without data, a concise DCF that is
 * not one (or with writes too), an SDO timeout
 * outside 5..5000 ms, a PDO of length 0 or above 8, outside its image or for a node not in the
 * table, a restricted CAN-ID, an image size or a PDO without an image. Sends nothing. */
bool co_net_master_init(co_net_master_t *master, const co_net_master_config_t *config);

/* Starts the boot of the whole network at `now`: NMT reset communication to all (or to each
 * slave), every slave waits for its boot-up. */
void co_net_master_start(co_net_master_t *master, co_time_t now);

/* Handles a received frame; true when the master used it (boot-up, heartbeat, guarding reply,
 * SDO response of the client, EMCY of a slave, input PDO). */
bool co_net_master_receive(co_net_master_t *master, const co_frame_t *frame, co_time_t now);

/* Runs what is due (timeouts, boot steps, retries, guarding, SYNC and the output PDOs it
 * triggers) and returns the next deadline: always later than `now`, or CO_TIME_NEVER. */
co_time_t co_net_master_process(co_net_master_t *master, co_time_t now);

/* Writes `len` bytes of the output image at `offset` and sends at once every output PDO whose
 * bytes changed and whose slave is operational. False (nothing changed) outside the image, and
 * always for a master without an output image. */
bool co_net_master_write_output(co_net_master_t *master, size_t offset, const uint8_t *data,
                                size_t len);

/* Queues an SDO transfer on the master's own client, behind the boot of the slaves: it starts
 * when no slave's identification or download holds the client, and `done` is called once at its
 * end (with the master's SDO timeout, and 0x05040000 for a transfer the disabling of the master
 * dropped). False, and nothing queued, when the queue is full, the node-id is outside 1..127, the
 * data or the callback is missing, or the master is disabled. */
bool co_net_master_sdo(co_net_master_t *master, const co_net_request_t *request, co_time_t now);

/* Sends the NMT command (CO_NMT_CS_START, _STOP, _ENTER_PRE_OPERATIONAL, _RESET_NODE,
 * _RESET_COMMUNICATION) to node_id, or to all (0), flips status bit 8 and awaits the state the
 * command leads to from the node (from every slave of the table for 0): its heartbeat, guarding
 * reply or boot-up; a node the master does not supervise is asked by one guarding request
 * (700h + id, RTR). CO_NET_EVENT_NMT_DONE ends it, at the latest at now + timeout_ms. False, and
 * nothing sent, for another command, a node-id above 127, a command still awaited, or a disabled
 * master. A slave of the table that boots up after a reset is booted again by the master, as any
 * slave that restarts. */
bool co_net_master_nmt(co_net_master_t *master, uint8_t command, uint8_t node_id,
                       uint32_t timeout_ms, co_time_t now);
/* CiA 302-2's configuration request 1F25h (UNSIGNED32, write only): its value "conf" written to
 * sub-index node-id configures that slave again, to sub-index 128 every slave of the table: each
 * reset (communication) and booted again, its configuration downloaded anew. False, and nothing
 * sent, for another value or sub-index, a node not in the table, a master not started or
 * disabled. */
#define CO_NET_IDX_CONFIGURATION_REQUEST 0x1F25u
#define CO_NET_1F25_ALL 128u
#define CO_NET_1F25_SIGNATURE 0x666E6F63u /* "conf" */
bool co_net_master_request_configuration(co_net_master_t *master, uint8_t subindex, uint32_t value,
                                         co_time_t now);

/* Whether node_id is still awaited by the NMT command (false once it confirmed). */
bool co_net_master_nmt_awaited(const co_net_master_t *master, uint8_t node_id);

/* The PLC300's "disable communication": the master sends nothing more (no heartbeat, SYNC, PDO,
 * NMT or SDO), takes no frame, stops supervising the slaves and, as the PLC300 does, clears the
 * status words, the last SDO error and EMCY (status bit 15 set); a transfer under way and the
 * queued requests end with 0x05040000, an NMT command awaited ends. co_net_master_enable boots
 * the network again from its start (co_net_master_start). */
void co_net_master_disable(co_net_master_t *master, co_time_t now);
void co_net_master_enable(co_net_master_t *master, co_time_t now);

/* What the runtime knows of the controller: CO_NET_MASTER_BUS_OFF and/or _NO_BUS_POWER (status
 * bits 13 and 14; either also sets bit 15, as the PLC300's CommDisabled). */
void co_net_master_set_bus(co_net_master_t *master, uint16_t bus);

/* The status word of the master (CO_NET_MASTER_*), and of the slave with node-id `node_id`
 * (CO_NET_SLAVE_*; 0 for a node not in the table). */
uint16_t co_net_master_status(const co_net_master_t *master);
uint16_t co_net_master_slave_status(const co_net_master_t *master, uint8_t node_id);
/* The protocol state (CO_NET_PROTOCOL_*): disabled with status bit 15; else the error of the
 * first slave of the table whose bit 5 is set, node guarding or heartbeat; else error control
 * enabled when some slave has bit 2 and an error control configured; else enabled. */
uint8_t co_net_master_protocol_state(const co_net_master_t *master);
/* The slave's record, NULL for a node not in the table. */
const co_net_slave_t *co_net_master_slave(const co_net_master_t *master, uint8_t node_id);

/* CiA 302-2's 1F80h of the master's start and on_mandatory_error (bit 0 always set), and the
 * reverse: false, and `config` untouched, for a value this master does not take (bit 0 clear:
 * no NMT master; bit 2: the master is Operational by itself, D-NET-MASTER-HEARTBEAT; bit 5, no
 * flying master; a reserved bit 7..31). Bit 3 wins over bit 1, bit 6 over bit 4. */
uint32_t co_net_master_1f80(const co_net_master_config_t *config);
bool co_net_master_config_from_1f80(co_net_master_config_t *config, uint32_t value);

/* CiA 302-2's 1F81h of a slave of the table (bits 0 and 2 from on_error, 3, the guard time and
 * factor), and the reverse: false, and `slave` untouched, for a value this master does not take
 * (bit 0 clear; bit 1, reserved; bit 4, keep alive: the master resets every slave at its start;
 * bits 5..7, software version check and update, restore). Bit 2 clear is on_error "report"
 * (docs/net-master.md, "NMT slave assignment 1F81h"). */
uint32_t co_net_slave_1f81(const co_net_slave_config_t *slave);
bool co_net_slave_config_from_1f81(co_net_slave_config_t *slave, uint32_t value);

/* The slave's expected identity object (CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION .. _SERIAL_NUMBER)
 * as CiA 302-2 holds it: the value checked, 0 when not checked (and for another index); and the
 * reverse: the value and its check set, or the check cleared by 0; false, and `slave` untouched,
 * for another index. An expected value of 0 cannot be checked: CiA 302-2's 0 means none. */
uint32_t co_net_slave_expected(const co_net_slave_config_t *slave, uint16_t index);
bool co_net_slave_config_set_expected(co_net_slave_config_t *slave, uint16_t index, uint32_t value);

/* CiA 302-2's objects of an NMT master that describe its network, as a plain struct the
 * application owns (static, in RAM or const in flash; no malloc, no dictionary needed): element
 * n - 1 of each array is node-id n, as the objects' sub-index n is. A firmware may hold its
 * master's objects here and serve them by SDO from it; co_net_config_from_objects makes the
 * master's configuration of them, co_net_objects_from_config the objects of a configuration
 * (docs/net-master.md, "The master's own objects"; D-NET-MASTER-OBJECTS). 4,328 bytes on a
 * Cortex-M. */
typedef struct co_net_objects {
    uint32_t nmt_startup;                                      /* 1F80h */
    uint32_t boot_time_ms;                                     /* 1F89h */
    uint32_t slave_assignment[CO_NMT_MASTER_NODE_ID_MAX];      /* 1F81h; bit 0 clear: none */
    uint16_t consumer_heartbeat_ms[CO_NMT_MASTER_NODE_ID_MAX]; /* 1016h's entry of the node */
    /* 1F84h + k, k = 0..4: device type, vendor-ID, product code, revision, serial number */
    uint32_t expected[CO_NET_IDENTITY_SUBS + 1][CO_NMT_MASTER_NODE_ID_MAX];
    const uint8_t *concise_dcf[CO_NMT_MASTER_NODE_ID_MAX]; /* 1F22h, NULL: none */
    size_t concise_dcf_len[CO_NMT_MASTER_NODE_ID_MAX];
} co_net_objects_t;

/* The objects of `config` (its start, reaction, boot time and table of slaves). False, and
 * `objects` left partly written, for a table these objects cannot hold: a slave configured by
 * writes (not a concise DCF) or expecting an identity value of 0. */
bool co_net_objects_from_config(co_net_objects_t *objects, const co_net_master_config_t *config);

/* The master's configuration of its objects: start and reaction (1F80h), boot time, and a slave in
 * `slaves` (up to `max`) for each node-id whose 1F81h has bit 0, in node-id order; config->slaves
 * and slave_count are set, its other members left as they were. False for a 1F80h or 1F81h the
 * master does not take or more slaves than `max` (config then undefined in those members). */
bool co_net_config_from_objects(co_net_master_config_t *config, co_net_slave_config_t *slaves,
                                size_t max, const co_net_objects_t *objects);

/* The bit rate of a CO_NET_BIT_RATE_* code in bit/s; 0 for the reserved code 1 and above 7. */
uint32_t co_net_bit_rate(uint8_t code);

/* "idle", "wait boot-up", ... and "SDO error", "device type mismatch", ... for printing. */
const char *co_net_step_text(co_net_step_t step);
const char *co_net_failure_text(co_net_failure_t failure);
/* CiA 302-2's meaning of a CO_NET_BOOT_ERROR_* letter: "no answer to 1000h", ...; "none" for 0. */
const char *co_net_boot_error_text(uint8_t boot_error);
/* "none", "node guarding error", "heartbeat error"; "disabled", "CANopen enabled", "error control
 * enabled", and the two error texts for a protocol state: the PLC300's words. */
const char *co_net_ec_error_text(co_net_ec_error_t error);
const char *co_net_protocol_state_text(uint8_t state);

#endif
