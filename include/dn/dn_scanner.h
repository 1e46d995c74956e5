/* SPDX-License-Identifier: Apache-2.0 */
/* A DeviceNet scanner (the master side of the predefined master/slave connection set), portable
 * like the slave library: no malloc, no OS calls, no globals; frames and time (microseconds) are
 * passed in, frames leave through a send callback, and dn_scanner_process returns the next
 * deadline. The application allocates the scanner and one dn_slave_t per slave it talks to (up
 * to 63 at once: a scan, or a bus of polled drives).
 *
 * The scanner checks its own MAC ID (the duplicate MAC ID check as a client, and answers other
 * nodes' checks), allocates and releases a slave's connections through the Group 2 only
 * unconnected port, runs explicit requests (Get/Set_Attribute_Single or any service) on the
 * explicit connection with fragmentation both ways, polls the polled connection (instance 2)
 * once or at a period, and takes and acknowledges the slave's COS/cyclic data (instance 4).
 * Every request ends in one result: success, the CIP error response (general status and
 * additional code), or a timeout (docs/devicenet.md, "The scanner"). A polled connection kept
 * with dn_scanner_keep_polling is re-established when the slave stops answering
 * (docs/decisions.md, D-DEVICENET-RECONNECT). */
#ifndef DN_SCANNER_H
#define DN_SCANNER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_types.h"
#include "dn_cip.h"
#include "dn_fragment.h"
#include "dn_link.h"

/* The scanner's MAC ID when the application gives none (the usual scanner address). */
#define DN_SCANNER_MAC_DEFAULT 0u
/* How long a request waits for its response, or a fragment for its acknowledgement. */
#define DN_SCANNER_TIMEOUT_DEFAULT_US 1000000u

/* The supervision of a kept polled connection (dn_scanner_keep_polling, D-DEVICENET-RECONNECT):
 * this many polls in a row unanswered, the time the slave's own watchdog takes (4 x the expected
 * packet rate), and the connection is lost; ... */
#define DN_SCANNER_LOST_AFTER_MISSED 4u
/* ... re-established by tries of Release, Allocate and the expected packet rate: this many, one
 * second apart, then (reported as DN_CONNECTION_FAILED) one every ten seconds until one succeeds
 * or polling stops. */
#define DN_SCANNER_RECONNECT_TRIES 3u
#define DN_SCANNER_RECONNECT_INTERVAL_US 1000000u
#define DN_SCANNER_RECONNECT_SLOW_US 10000000u

/* How a request ended. */
typedef enum dn_result_status {
    DN_RESULT_OK,             /* the success response: data, len */
    DN_RESULT_CIP_ERROR,      /* the error response 0x94: general, additional */
    DN_RESULT_TIMEOUT,        /* no response, or no acknowledgement of a fragment, in time */
    DN_RESULT_FRAGMENT_ERROR, /* a fragment acknowledged with an error status (additional) */
    DN_RESULT_FRAGMENT_LOST,  /* a response fragment out of sequence: the response is lost */
    DN_RESULT_BAD_RESPONSE    /* a response of another service, or empty */
} dn_result_status_t;

typedef struct dn_result {
    uint8_t mac_id;  /* the slave's */
    uint8_t service; /* the request's */
    dn_result_status_t status;
    uint8_t general; /* CIP general status: 0 unless DN_RESULT_CIP_ERROR */
    uint8_t
        additional; /* the additional code (DN_AC_NONE when none); a refused fragment's status */
    uint8_t len;
    const uint8_t *data; /* the response after its service byte; valid during the callback */
} dn_result_t;

/* What the polled connection or the COS/cyclic connection brought. */
typedef enum dn_io_kind {
    DN_IO_POLL_RESPONSE, /* the answer to the poll command awaiting one */
    DN_IO_POLL_MISSED,   /* no answer to a poll command before its timeout or the next poll */
    DN_IO_POLL_LATE,     /* an answer while no poll awaits one: its poll was counted missed */
    DN_IO_COS_DATA       /* the slave's COS/cyclic data (acknowledged unless suppressed) */
} dn_io_kind_t;

/* What became of a kept polled connection (dn_scanner_keep_polling). */
typedef enum dn_connection_event {
    DN_CONNECTION_LOST,     /* DN_SCANNER_LOST_AFTER_MISSED polls in a row unanswered: polls stop,
                             * the first try starts */
    DN_CONNECTION_RESTORED, /* a try went through: polling goes on */
    DN_CONNECTION_FAILED    /* the DN_SCANNER_RECONNECT_TRIES quick tries failed, the last as
                             * `result` says: one try every DN_SCANNER_RECONNECT_SLOW_US now */
} dn_connection_event_t;

/* The steps of a try to re-establish a polled connection. */
typedef enum dn_recovery {
    DN_RECOVERY_NONE,     /* the connection is up (or not kept) */
    DN_RECOVERY_WAITING,  /* the next try at next_try, once no request is in progress */
    DN_RECOVERY_RELEASE,  /* what is left of the old connections released */
    DN_RECOVERY_ALLOCATE, /* the set allocated again */
    DN_RECOVERY_RATE      /* the expected packet rate of instance 2: Established again */
} dn_recovery_t;

typedef struct dn_scanner_app {
    void *user;
    co_send_fn send;
    /* A request of dn_scanner_allocate, _release or _request ended; the slave takes the next. */
    void (*done)(void *user, const dn_result_t *result);
    /* I/O data of a slave (len 0 for DN_IO_POLL_MISSED). Optional. */
    void (*io)(void *user, uint8_t mac_id, dn_io_kind_t kind, const uint8_t *data, uint8_t len);
    /* A kept polled connection lost, re-established, or not re-established in its quick tries
     * (`result`: the failed step's, NULL for the other events). Optional. */
    void (*connection)(void *user, uint8_t mac_id, dn_connection_event_t event,
                       const dn_result_t *result);
} dn_scanner_app_t;

/* One slave the scanner talks to. */
typedef struct dn_slave {
    uint8_t mac_id;
    dn_predefined_ids_t ids;
    uint8_t allocated; /* the allocation choice bits the slave granted this scanner */
    /* The request in progress (one at a time: the explicit and the unconnected ports share the
     * slave's response identifier). */
    bool busy;
    uint8_t service;
    uint8_t xid;          /* the transaction bit of the last request: a late response is ignored */
    uint8_t choice;       /* Allocate/Release: the choice asked */
    bool to_ucmm;         /* sent to the UCMM: 4B/4C are Open/Close, not Allocate/Release */
    uint16_t response_id; /* the CAN-ID its answer comes on */
    co_time_t deadline;
    dn_fragments_t tx;
    dn_fragments_t rx;
    /* The explicit connection the UCMM opened (dn_scanner_ucmm_open), which the explicit
     * requests use instead of the predefined set's while it is open (ucmm_instance not 0). */
    uint16_t ucmm_instance; /* the slave's connection instance, 10..14; 0: none */
    uint8_t ucmm_message;   /* the scanner's group 3 message ID on it, 0..4 */
    uint16_t ucmm_response; /* the slave's CAN-ID on it */
    /* The polled connection. */
    uint8_t output[DN_FRAME_BODY + 1];
    uint8_t output_len;
    co_time_t poll_period; /* microseconds; 0: on demand only */
    co_time_t next_poll;
    co_time_t poll_deadline; /* CO_TIME_NEVER: no poll awaiting its response */
    /* Each poll sent is answered or missed, once: polls = responses + missed + (1 while one
     * awaits its answer). An answer while none awaits is late, counted apart. */
    uint32_t polls;
    uint32_t responses;
    uint32_t missed;
    uint32_t late;
    uint8_t missed_in_row;
    /* The supervision of a kept polled connection (dn_scanner_keep_polling). */
    uint8_t keep_choice; /* the connections re-allocated; 0: not kept */
    uint16_t keep_rate_ms;
    dn_recovery_t recovery;
    bool recovering_request; /* the request in progress is a step of the recovery's */
    uint8_t tries;           /* since the connection was lost */
    co_time_t next_try;
    uint32_t lost;     /* times the connection was found lost */
    uint32_t restored; /* times it was re-established */
} dn_slave_t;

/* The scanner's duplicate MAC ID check. */
typedef enum dn_scanner_link {
    DN_SCANNER_OFF,
    DN_SCANNER_CHECKING, /* the two requests, a second apart, then a second of silence */
    DN_SCANNER_ONLINE,
    DN_SCANNER_DUPLICATE /* another node has the scanner's MAC ID: nothing is sent */
} dn_scanner_link_t;

typedef struct dn_scanner_config {
    uint8_t mac_id; /* the scanner's, 0..63 */
    uint16_t vendor_id;
    uint32_t serial_number;
    co_time_t timeout; /* microseconds; 0: DN_SCANNER_TIMEOUT_DEFAULT_US */
    dn_slave_t *slaves;
    uint8_t slave_count; /* up to DN_MAC_ID_MAX + 1 */
    const dn_scanner_app_t *app;
} dn_scanner_config_t;

typedef struct dn_scanner {
    const dn_scanner_config_t *config;
    co_time_t timeout;
    dn_scanner_link_t link;
    uint8_t checks_sent;
    co_time_t link_deadline;
    uint8_t slave_index[DN_MAC_ID_MAX + 1]; /* position in config->slaves by MAC ID, 0xFF none */
    co_time_t now;
} dn_scanner_t;

/* dn_scanner_init's refusals. */
#define DN_SCANNER_INIT_OK 0
#define DN_SCANNER_INIT_BAD_MAC_ID -1 /* the scanner's or a slave's above 63, or a slave twice */
#define DN_SCANNER_INIT_BAD_CONFIG -2 /* no send or done callback */

/* Validates the configuration and clears the slaves' state; the scanner is off. */
int dn_scanner_init(dn_scanner_t *scanner, const dn_scanner_config_t *config);
/* Goes on the bus: the duplicate MAC ID check's first request. */
void dn_scanner_start(dn_scanner_t *scanner, co_time_t now);
/* Online at once, without the check (a scanner whose MAC ID is known to be free). */
void dn_scanner_start_online(dn_scanner_t *scanner, co_time_t now);
/* Every received frame (29-bit, remote and over-long frames are ignored). */
void dn_scanner_receive(dn_scanner_t *scanner, const co_frame_t *frame, co_time_t now);
/* Runs what is due (the check, timeouts, retries, periodic polls); returns the next deadline. */
co_time_t dn_scanner_process(dn_scanner_t *scanner, co_time_t now);

/* The slave of a MAC ID, or NULL when it is not in the configuration. */
dn_slave_t *dn_scanner_slave(dn_scanner_t *scanner, uint8_t mac_id);

/* The requests; each returns false (nothing sent) when the scanner is not online, the slave
 * unknown or busy with another request, or the request does not fit; otherwise the slave's
 * `done` callback reports its end. */
bool dn_scanner_allocate(dn_scanner_t *scanner, uint8_t mac_id, uint8_t choice, co_time_t now);
bool dn_scanner_release(dn_scanner_t *scanner, uint8_t mac_id, uint8_t choice, co_time_t now);
/* Any service on the explicit connection: the path class/instance, then `data` (for
 * Get/Set_Attribute_Single the attribute first). Up to DN_MESSAGE_MAX bytes in all. */
bool dn_scanner_request(dn_scanner_t *scanner, uint8_t mac_id, uint8_t service, uint8_t class_id,
                        uint8_t instance, const uint8_t *data, uint8_t len, co_time_t now);
bool dn_scanner_get(dn_scanner_t *scanner, uint8_t mac_id, uint8_t class_id, uint8_t instance,
                    uint8_t attribute, co_time_t now);
bool dn_scanner_set(dn_scanner_t *scanner, uint8_t mac_id, uint8_t class_id, uint8_t instance,
                    uint8_t attribute, const uint8_t *value, uint8_t len, co_time_t now);
/* Set_Attribute_Single of a connection's expected packet rate (Connection 0x05, attribute 9);
 * the result's data are the rate the slave uses (UINT, ms). */
bool dn_scanner_set_expected_packet_rate(dn_scanner_t *scanner, uint8_t mac_id, uint8_t connection,
                                         uint16_t ms, co_time_t now);

/* Open Explicit Messaging Connection on the slave's UCMM (group 3 message 6), the scanner's
 * group 3 message ID the lowest no other slave's UCMM connection uses or Open in flight asks
 * for (false when all five are taken); on success the explicit requests go over that connection, no
 * Allocate needed. The result's data: body format, message IDs, instance (UINT). */
bool dn_scanner_ucmm_open(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now);
/* Close of that connection on the UCMM; from then on the predefined set's again, whatever the
 * answer (an error: the slave's watchdog deleted it already) or none. */
bool dn_scanner_ucmm_close(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now);

/* The output data of the slave's poll commands (0..8 bytes; 0 is the idle poll). */
bool dn_scanner_set_output(dn_scanner_t *scanner, uint8_t mac_id, const uint8_t *data, uint8_t len);
/* One poll command now (the polled connection must be allocated and established). */
bool dn_scanner_poll(dn_scanner_t *scanner, uint8_t mac_id, co_time_t now);
/* Poll commands every `period_us` from now on (0 stops them, and the supervision of
 * dn_scanner_keep_polling with any try in progress). */
bool dn_scanner_poll_every(dn_scanner_t *scanner, uint8_t mac_id, co_time_t period_us,
                           co_time_t now);
/* Poll commands every `period_us`, and the connection kept: DN_SCANNER_LOST_AFTER_MISSED polls
 * in a row unanswered, it is re-established (D-DEVICENET-RECONNECT): Release and Allocate of the
 * connections allocated now (explicit and polled at least, else false), then the expected packet
 * rate `rate_ms` of instance 2, the tries as DN_SCANNER_RECONNECT_* say; the `connection`
 * callback tells. Requests of the application's wait for no try, and a try waits for them. */
bool dn_scanner_keep_polling(dn_scanner_t *scanner, uint8_t mac_id, co_time_t period_us,
                             uint16_t rate_ms, co_time_t now);
/* Drops the request in progress without a result (its late answer is ignored): a program that
 * stops sends its Release at once. */
void dn_scanner_abandon(dn_scanner_t *scanner, uint8_t mac_id);

#endif
