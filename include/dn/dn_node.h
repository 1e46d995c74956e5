/* SPDX-License-Identifier: Apache-2.0 */
/* A DeviceNet slave (the predefined master/slave connection set, and the UCMM's explicit
 * connections on group 3), portable
 * like the CANopen core: no malloc, no OS calls, no globals; frames and time (microseconds, the
 * core's co_time_t) are passed in, frames leave through a send callback, and dn_node_process
 * returns the next deadline. The application allocates a dn_node_t wherever it likes.
 *
 * The library owns the link (duplicate MAC ID check, identifiers), the connections (explicit
 * instance 1 with fragmentation, polled instance 2, COS/cyclic instance 4, the acknowledge
 * handler, the explicit server instances 10-14 that the UCMM opens and closes) and the standard CIP
 * objects (Identity 0x01, Message router 0x02, DeviceNet 0x03, Assembly 0x04, Connection 0x05,
 * Acknowledge handler 0x2B). The application supplies its assemblies (a table and data callbacks)
 * and registers its own classes (a drive's 0x28, 0x29, 0x2A, 0x70+) as a table of dn_object_t
 * sorted by class, without changing the library (docs/devicenet.md). */
#ifndef DN_NODE_H
#define DN_NODE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_types.h" /* co_frame_t, co_time_t, co_send_fn: header only, no CANopen service */
#include "dn_cip.h"
#include "dn_fragment.h" /* dn_fragments_t, DN_MESSAGE_MAX */
#include "dn_link.h"

/* A CIP status: the general status in the low byte, the additional code in the high byte
 * (DN_AC_NONE when there is none); DN_OK for success. */
typedef uint16_t dn_status_t;
#define DN_OK 0u
#define DN_STATUS(general, additional) ((dn_status_t)((general) | (unsigned)(additional) << 8))
#define DN_ERROR(general) DN_STATUS(general, DN_AC_NONE)

/* The largest I/O assembly: one frame, no I/O fragmentation (docs/devicenet.md). */
#define DN_IO_MAX 8u

typedef struct dn_node dn_node_t;
typedef struct dn_object dn_object_t;

/* One explicit request as the message router hands it to an object (8/8 body format). */
typedef struct dn_request {
    uint8_t service;
    uint8_t class_id;
    uint8_t instance;   /* 0: the class */
    uint8_t attribute;  /* Get/Set_Attribute_Single only */
    uint8_t master_mac; /* the requester's MAC ID, from the message header or the group 3 CAN-ID */
    uint8_t connection; /* the explicit connection's instance (1, 10-14); 0: unconnected */
    const uint8_t *data;
    uint8_t len; /* data after the path (and the attribute) */
} dn_request_t;

/* The data of a success response, filled by an object's handler with the dn_reply_* helpers;
 * more than fits is answered with "reply data too large". */
typedef struct dn_reply {
    uint8_t len;
    bool overflow;
    uint8_t data[DN_MESSAGE_MAX - 1]; /* the service byte takes one */
} dn_reply_t;

void dn_reply_bytes(dn_reply_t *reply, const void *data, size_t len);
void dn_reply_u8(dn_reply_t *reply, uint8_t value);
void dn_reply_u16(dn_reply_t *reply, uint16_t value);
void dn_reply_u32(dn_reply_t *reply, uint32_t value);
/* A SHORT_STRING: one length byte, then the characters. */
void dn_reply_short_string(dn_reply_t *reply, const char *text);

/* An attribute of an object's table. Get_Attribute_Single and Set_Attribute_Single are checked
 * against the table before the handler runs: a missing attribute is 0x14, a Set of a Get-only
 * attribute 0x0E, a Set of another length than `size` 0x13 (shorter) or 0x15 (longer), and a
 * level (class or instance) without any attribute does not have the service (0x08). */
#define DN_GET 0x01u
#define DN_SET 0x02u
#define DN_GET_SET (DN_GET | DN_SET)
#define DN_EVERY_INSTANCE 0xFFu /* `instance` of an attribute every instance has */

typedef struct dn_attribute {
    uint8_t instance; /* 0: a class attribute; an instance number; or DN_EVERY_INSTANCE */
    uint8_t id;
    uint8_t access; /* DN_GET, DN_GET_SET */
    uint8_t size;   /* the length a Set must carry; 0: the handler checks it */
} dn_attribute_t;

/* Answers one request to its object, after the router's checks: fills `reply` and returns DN_OK,
 * or returns the refusal (0x08 for a service it does not have, 0x09 for a value it refuses, 0x16
 * for an instance that does not exist...). */
typedef dn_status_t (*dn_handler_fn)(dn_node_t *node, const dn_object_t *object,
                                     const dn_request_t *request, dn_reply_t *reply);

/* A class, or a range of classes that one handler serves (the drive's application objects
 * 0x70..0xA8). */
struct dn_object {
    uint8_t class_first;
    uint8_t class_last;
    uint8_t max_instance; /* instances 1..max_instance; the handler may refuse some with 0x16 */
    uint8_t attribute_count;
    const dn_attribute_t *attributes; /* NULL: the handler checks attributes and lengths itself */
    dn_handler_fn handler;
    void *user;
};

/* An assembly instance of the application: its data travel through the dn_app_t callbacks. */
typedef struct dn_assembly {
    uint16_t instance;
    uint8_t size;  /* 1..DN_IO_MAX */
    bool produced; /* input data, drive to scanner (70, 71, 101); else consumed (20, 21, 100) */
} dn_assembly_t;

/* What the library asks the application to keep across restarts. */
typedef struct dn_stored {
    uint16_t consumed_assembly; /* Connection class attribute 100; 0: the default */
    uint16_t produced_assembly; /* Connection class attribute 101; 0: the default */
    bool quick_connect;         /* DeviceNet attribute 10 */
} dn_stored_t;

/* What happens to the I/O connections, for the application; how a connection ends is
 * dn_connection_ended, below. */
typedef enum dn_io_event {
    DN_IO_ESTABLISHED, /* an I/O connection entered Established */
    DN_IO_RUN,         /* data after idle: the master is in run mode */
    DN_IO_IDLE,        /* a zero-length poll or COS message: the master is idle */
    DN_IO_ACK_FAILED,  /* the COS/cyclic data were not acknowledged after the retries */
    DN_IO_RELEASED     /* the last I/O connection was released */
} dn_io_event_t;

/* Why an Established connection stopped carrying the master's messages. */
typedef enum dn_end_cause {
    DN_END_TIMEOUT,  /* its inactivity watchdog expired: Timed out, deferred delete or deleted */
    DN_END_RELEASED, /* the master released it (Release Master/Slave Connection Set) */
    DN_END_BUS_OFF,  /* the controller went bus off, with or without BOI */
    DN_END_OFFLINE   /* the node left the bus or started again (dn_node_stop, dn_node_start) */
} dn_end_cause_t;

/* What the node counts of its traffic, each where it happens. The application keeps the counters
 * (dn_app_t.stats), so that they outlive a restart of the node (an Identity Reset, the bus
 * again); they wrap around at 2^32. */
typedef struct dn_stats {
    uint32_t explicit_requests; /* requests answered, on the explicit connection or message 6 */
    uint32_t error_responses;   /* of those, the ones answered with an error response (0x94) */
    uint32_t io_messages;       /* poll commands and the master's COS/cyclic data consumed, idle
                                   (zero-length) ones included; a wrong length is not */
    uint32_t fragments;         /* explicit fragments received and sent (repeats too), not their
                                   acknowledgements */
    uint32_t timeouts;          /* watchdogs expired: an I/O connection Timed out, the explicit
                                   connection deleted or in deferred delete */
} dn_stats_t;

typedef struct dn_app {
    void *user;
    co_send_fn send; /* every frame the node sends */
    /* The current data of an assembly of the table (`size` bytes). */
    void (*read_assembly)(void *user, uint16_t instance, uint8_t *data);
    /* New data for a consumed assembly, from an I/O message or a Set of attribute 3. */
    void (*write_assembly)(void *user, uint16_t instance, const uint8_t *data);
    void (*io_event)(void *user, dn_io_event_t event); /* optional */
    /* An Established connection ended: instance 1 (explicit), 2 (polled, or the master's
     * COS/cyclic data), 4 (the slave's COS/cyclic data) or 10-14 (explicit, opened by the UCMM:
     * DN_END_RELEASED is their Close), told once whatever ended it, after
     * the connection left Established; the I/O connections before the explicit one when several
     * end at once (docs/devicenet.md, "How a connection ends"). Optional. */
    void (*connection_ended)(void *user, uint8_t instance, dn_end_cause_t cause);
    /* Keeps these values across restarts; false when it could not (the Set is refused with
     * 0x19). NULL: the values are not stored and the Sets are refused. */
    bool (*store)(void *user, const dn_stored_t *stored);
    /* Identity Reset, type 0 (as a power cycle) or 1 (out-of-box values, then as a power cycle),
     * called after its response left: the application restarts the node. Optional. */
    void (*reset)(void *user, uint8_t type);
    dn_stats_t *stats; /* where the node counts its traffic; NULL: not counted */
} dn_app_t;

typedef struct dn_config {
    uint8_t mac_id;    /* 0..63 */
    uint8_t baud_rate; /* DeviceNet attribute 2: 0 125 kbit/s, 1 250 kbit/s, 2 500 kbit/s */
    /* The switches as read at start-up (attributes 6..9): a changed switch is a minor
     * recoverable fault in the Identity status. */
    uint8_t mac_switch;
    uint8_t baud_switch;
    bool mac_switch_changed;
    bool baud_switch_changed;
    /* Identity. */
    uint16_t vendor_id;
    uint16_t device_type;
    uint16_t product_code;
    uint8_t major_revision;
    uint8_t minor_revision;
    uint32_t serial_number;
    const char *product_name; /* up to 32 characters */
    bool configured;          /* Identity status bit 2: settings other than out-of-box */
    /* Assemblies: the table, the defaults and the stored selection. */
    const dn_assembly_t *assemblies;
    uint8_t assembly_count;
    uint16_t default_consumed_assembly;
    uint16_t default_produced_assembly;
    dn_stored_t stored; /* as the application loaded it; zeros: the defaults */
    /* The application's classes, sorted by class_first, not overlapping the library's. */
    const dn_object_t *objects;
    uint8_t object_count;
    const dn_app_t *app;
} dn_config_t;

typedef enum dn_link_state {
    DN_LINK_OFF,         /* not started */
    DN_LINK_DUP_CHECK_1, /* first duplicate MAC ID check request sent */
    DN_LINK_DUP_CHECK_2, /* second request sent */
    DN_LINK_ONLINE,
    DN_LINK_FAULTED /* communication faulted: duplicate MAC ID or bus off */
} dn_link_state_t;

/* The module (MS) and network (NS) status LEDs, after the manual's table. */
typedef enum dn_led {
    DN_LED_OFF,
    DN_LED_GREEN,
    DN_LED_FLASHING_GREEN,
    DN_LED_RED,
    DN_LED_FLASHING_RED
} dn_led_t;

/* One connection of the predefined set. Times in microseconds, rates in milliseconds. */
typedef struct dn_connection {
    uint8_t state;                 /* dn_conn_state_t */
    uint8_t transport;             /* attribute 3: transport class and trigger */
    uint8_t comm;                  /* attribute 6: initial communication characteristics */
    uint8_t timeout_action;        /* attribute 12 */
    uint8_t multiplier;            /* attribute 18: 0 = x4 .. 7 = x512 */
    uint16_t produced_id;          /* attribute 4, 0xFFFF: none */
    uint16_t consumed_id;          /* attribute 5, 0xFFFF: none */
    uint16_t produced_size;        /* attribute 7 */
    uint16_t consumed_size;        /* attribute 8 */
    uint16_t expected_packet_rate; /* attribute 9, ms, 0: no watchdog */
    uint16_t inhibit_time;         /* attribute 17, ms */
    uint8_t client_mac;            /* instances 10-14: the MAC ID of the client that opened it */
    co_time_t watchdog;            /* inactivity deadline, CO_TIME_NEVER when not running */
} dn_connection_t;

/* conn[0..2]: explicit (1), poll (2), COS/cyclic (4); conn[3..7]: the UCMM's 10-14. */
#define DN_CONN_COUNT 8u
/* The connections that can fragment: the explicit ones, instance 1 and the UCMM's five. I/O
 * messages never do (an assembly fits a frame: DN_IO_MAX), so they have no buffers. */
#define DN_EXPLICIT_COUNT 6u

/* An explicit connection's fragmented messages: the request coming in, the response going out. */
typedef struct dn_messages {
    dn_fragments_t rx;
    dn_fragments_t tx;
} dn_messages_t;

struct dn_node {
    const dn_config_t *config;
    dn_predefined_ids_t ids;
    dn_link_state_t link;
    co_time_t link_deadline;
    bool duplicate_mac; /* the check found another node with this MAC ID */
    /* DeviceNet object. */
    uint8_t allocation; /* allocation choice byte of the allocated connections */
    uint8_t master_mac; /* DN_MAC_ID_NONE when nothing is allocated */
    bool bus_off_interrupt;
    uint8_t bus_off_counter;
    /* Assemblies in use since the start, and what the stored attributes read. */
    uint16_t consumed_assembly;
    uint8_t consumed_size;
    uint16_t produced_assembly;
    uint8_t produced_size;
    dn_stored_t stored;
    uint16_t faults;          /* Identity status bits 8..11 the application reports */
    bool needs_commissioning; /* the application's configuration is missing or incorrect */
    co_time_t led_test_start; /* the start-up LED test's, CO_TIME_NEVER when not started */
    bool idle;                /* the last I/O message was zero-length */
    dn_connection_t conn[DN_CONN_COUNT];
    /* Acknowledge handler and the COS/cyclic production. */
    uint16_t ack_timer; /* ms */
    uint8_t retry_limit;
    uint8_t retries; /* retransmissions of the unacknowledged production */
    bool awaiting_ack;
    co_time_t ack_deadline;
    co_time_t produce_deadline; /* the next cyclic production, or the COS heartbeat */
    co_time_t inhibit_until;
    uint8_t last_produced[DN_IO_MAX];
    /* Explicit messaging: each explicit connection's fragmented messages, conn[0]'s then
     * conn[3..7]'s (dn_messages in src/devicenet/slave/dn_slave.h). */
    dn_messages_t messages[DN_EXPLICIT_COUNT];
    int16_t pending_reset; /* Identity Reset type to hand over after the response, or -1 */
    /* The explicit connection instance (1, 10-14) of the request being executed, 0 otherwise. */
    uint8_t request_connection;
    co_time_t now; /* the time of the call in progress */
};

/* dn_node_init's refusals. */
#define DN_INIT_OK 0
#define DN_INIT_BAD_MAC_ID -1
#define DN_INIT_BAD_ASSEMBLY -2 /* size 0 or over DN_IO_MAX, or a default not in the table */
#define DN_INIT_BAD_CONFIG -3   /* no send callback or assembly callbacks, objects unsorted */

/* Validates the configuration, loads the stored selection (an unknown stored assembly falls back
 * to the default) and leaves the node offline. The node keeps `config` (and what it points at):
 * it must outlive the node. An Identity Reset is the application's init and start again. */
int dn_node_init(dn_node_t *node, const dn_config_t *config);
/* Goes on the bus: the duplicate MAC ID check's first request. On a node already started, its
 * connections end first (DN_END_OFFLINE). A restart on the bus (bus off with BOI, the interface
 * back after an outage) starts so, without the LED test. */
void dn_node_start(dn_node_t *node, co_time_t now);
/* Powers up (power on, or an Identity Reset, which emulates a power cycle): the manual's start-up
 * LED test (1.25 s, the LEDs' own state after it), then dn_node_start (docs/decisions.md,
 * D-DEVICENET-LEDS). */
void dn_node_power_up(dn_node_t *node, co_time_t now);
/* Leaves the bus (the interface is gone, or the node is about to be initialised again): its
 * connections end (DN_END_OFFLINE) and it sends nothing until dn_node_start. */
void dn_node_stop(dn_node_t *node, co_time_t now);
/* The CAN-IDs of the frames dn_node_receive acts on: group 2 with the node's MAC ID, messages
 * 2, 4, 5, 6 and 7 (the predefined set's master-to-slave messages and the duplicate MAC ID
 * check), and group 3 messages 0-4 and 6 of every source MAC ID (the UCMM's requests, addressed
 * in their header, and the clients' requests on the connections it opens, whose message IDs the
 * clients choose). The group 2 ones follow the node's MAC ID, the group 3 ones are the same for
 * every node; none changes while the node runs, so a runtime can route by them once (a frame of
 * group 3 goes to every node, each keeping what is addressed to it): the others are no business
 * of this node. Returns DN_NODE_CONSUMED_IDS. */
#define DN_NODE_CONSUMED_IDS (5u + 6u * 64u)
size_t dn_node_consumed_ids(const dn_node_t *node, uint16_t ids[DN_NODE_CONSUMED_IDS]);
/* Every received frame; 29-bit and remote frames, and a length over 8, are ignored. */
void dn_node_receive(dn_node_t *node, const co_frame_t *frame, co_time_t now);
/* Runs what is due; returns the next deadline or CO_TIME_NEVER. Call it after every frame. */
co_time_t dn_node_process(dn_node_t *node, co_time_t now);
/* The CAN controller went bus off: counted (attribute 4), its connections end (DN_END_BUS_OFF);
 * with BOI set the node starts again (a new duplicate MAC ID check), else it stays faulted. */
void dn_node_bus_off(dn_node_t *node, co_time_t now);
/* The application's faults for the Identity status (DN_STATUS_MINOR_... / MAJOR_... bits). */
void dn_node_set_faults(dn_node_t *node, uint16_t faults);
/* The application's configuration is missing, incomplete or incorrect: MS flashes green (the
 * manual's "Needs commissioning"), unless an unrecoverable fault makes it red. */
void dn_node_set_commissioning(dn_node_t *node, bool needed);

uint16_t dn_node_identity_status(const dn_node_t *node);
dn_led_t dn_node_ms_led(const dn_node_t *node);
dn_led_t dn_node_ns_led(const dn_node_t *node);
/* The state (dn_conn_state_t) of connection instance 1, 2, 4 or 10-14; Non-existent for
 * another. */
uint8_t dn_node_connection_state(const dn_node_t *node, uint8_t instance);
/* The explicit connection (1, 10-14) whose request the node is executing, for the application's
 * handlers and callbacks called from it (an object's Set, an assembly's write); 0 outside a
 * request, and in an I/O message's write. */
uint8_t dn_node_request_connection(const dn_node_t *node);
/* The assembly table's entry of an instance, or NULL. */
const dn_assembly_t *dn_node_assembly(const dn_node_t *node, uint16_t instance);

#endif
