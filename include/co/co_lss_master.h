/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS master: every LSS service from the master's side on 7E5h/7E4h, fastscan included.
 * A passive state machine like the SDO client, which needs no co_node_t: the application feeds it
 * the frames of 7E4h and the monotonic time, it sends through a callback and reports the end of
 * each confirmed service through another; one request at a time. Behaviour: docs/lss.md. */
#ifndef CO_LSS_MASTER_H
#define CO_LSS_MASTER_H

#include "co_lss.h"

/* How a request ends. */
typedef enum co_lss_master_status {
    CO_LSS_MASTER_OK = 0,  /* the answer came (for identify and fastscan: at least one) */
    CO_LSS_MASTER_TIMEOUT, /* no answer within the timeout (fastscan: no slave found) */
} co_lss_master_status_t;

typedef struct co_lss_master_result {
    uint8_t service; /* the request's command specifier (fastscan: CO_LSS_CS_FASTSCAN) */
    co_lss_master_status_t status;
    uint8_t error;    /* configure, store: the slave's error code (CO_LSS_OK, ...) */
    uint8_t specific; /* with error CO_LSS_SPECIFIC_ERROR: the device's own code */
    uint32_t value;   /* inquire: the vendor-ID, product code, revision, serial or node-id */
    /* identify: the answers that came within the timeout; fastscan ended in TIMEOUT: the answers
     * to its first frame, so that a scan that lost its slave (an answer later than the timeout)
     * tells itself from one that found none (0) */
    uint16_t answers;
    co_lss_address_t address; /* fastscan: the address of the slave found, now configuring */
} co_lss_master_result_t;

/* Called once at the end of every confirmed request, from co_lss_master_receive() or
 * co_lss_master_process(); the master is idle again, so the callback may start the next one. */
typedef void (*co_lss_master_done_fn)(void *user, const co_lss_master_result_t *result);

typedef struct co_lss_master_config {
    co_send_fn send;
    void *user; /* passed to send and done */
    co_lss_master_done_fn done;
} co_lss_master_config_t;

/* Fastscan: the parts of the address the master already knows (bit n of `known` for part n,
 * co_lss_part_t), each checked with one frame instead of 32, and those it guesses (bit n of
 * `guessed`: for instance the last slave's, the same device), each tried with one frame and
 * scanned bit by bit when no slave has it; NULL scans all four. */
typedef struct co_lss_fastscan_known {
    uint8_t known;
    uint8_t guessed;
    co_lss_address_t address;
} co_lss_fastscan_known_t;

typedef struct co_lss_master {
    co_send_fn send;
    void *user;
    co_lss_master_done_fn done;
    uint8_t step;   /* what the master waits for (lss_master.c) */
    uint8_t expect; /* the command specifier of the answer awaited */
    co_time_t timeout_us;
    co_time_t deadline;
    co_lss_master_result_t result;
    /* fastscan */
    co_lss_fastscan_known_t known;
    uint8_t part;           /* the part under scan, or inquired */
    uint8_t bit;            /* the bit checked by the frame in flight */
    bool confirming;        /* the frame in flight moves the slave to the next part */
    bool guessing;          /* ... and its part is a guess, scanned when nobody answers */
    uint16_t reset_answers; /* the answers to the scan's first frame */
    co_time_t min_wait_us;  /* the shortest wait of a frame after the reset */
    co_time_t sent_at;      /* when the frame in flight was sent */
    co_time_t slowest_us;   /* the longest time from a frame of this scan to an answer */
} co_lss_master_t;

/* Results of co_lss_master_init and the requests; 0 when the request was sent. */
#define CO_LSS_MASTER_ERR_CONFIG 1 /* no send or done callback */
#define CO_LSS_MASTER_ERR_BUSY 2   /* a request is under way: nothing was sent */
#define CO_LSS_MASTER_ERR_ARG 3    /* timeout 0, a value outside its range: nothing was sent */

int co_lss_master_init(co_lss_master_t *master, const co_lss_master_config_t *config);

/* Unconfirmed services: sent at once, no `done` call. */
int co_lss_master_switch_global(co_lss_master_t *master, co_lss_state_t state);
/* Switch delay in ms (CiA 305: the slaves keep still for twice this around the switch). */
int co_lss_master_activate_bit_timing(co_lss_master_t *master, uint16_t delay_ms);

/* Confirmed services: each waits timeout_us for its answer. */
int co_lss_master_switch_selective(co_lss_master_t *master, const co_lss_address_t *address,
                                   co_time_t timeout_us, co_time_t now);
/* node_id 1..127 or CO_LSS_NODE_ID_UNCONFIGURED. */
int co_lss_master_configure_node_id(co_lss_master_t *master, uint8_t node_id, co_time_t timeout_us,
                                    co_time_t now);
int co_lss_master_configure_bit_timing(co_lss_master_t *master, uint8_t table, uint8_t index,
                                       co_time_t timeout_us, co_time_t now);
int co_lss_master_store(co_lss_master_t *master, co_time_t timeout_us, co_time_t now);
/* cs: CO_LSS_CS_INQUIRE_VENDOR .. CO_LSS_CS_INQUIRE_NODE_ID. */
int co_lss_master_inquire(co_lss_master_t *master, uint8_t cs, co_time_t timeout_us, co_time_t now);
/* Every slave with low's vendor-ID and product code, a revision and a serial within low..high
 * (bounds included) answers; the request ends at its timeout with the count. */
int co_lss_master_identify_remote(co_lss_master_t *master, const co_lss_address_t *low,
                                  const co_lss_address_t *high, co_time_t timeout_us,
                                  co_time_t now);
int co_lss_master_identify_non_configured(co_lss_master_t *master, co_time_t timeout_us,
                                          co_time_t now);
/* Finds one non-configured slave in the waiting state and leaves it in the configuration state,
 * its address in the result, checked by inquiring its four parts (5Ah..5Dh, each waiting up to
 * timeout_us); TIMEOUT when there is none (answers 0), or when a slave answered the first frame
 * and a later frame or inquiry went unanswered or the inquiry gave another address (answers > 0:
 * switch all to waiting and scan again, with longer waits).
 * Each frame waits until its wait ends, an answer never ending it, since several slaves may
 * answer one frame: the reset timeout_us, every later frame twice the slowest answer of the scan
 * (from a frame's sending), at least min_wait_us (1..timeout_us; timeout_us: each frame waits the
 * whole timeout) and at most timeout_us (docs/lss.md, "Fastscan"; docs/decisions.md,
 * D-LSS-FASTSCAN-WAIT). */
int co_lss_master_fastscan(co_lss_master_t *master, const co_lss_fastscan_known_t *known,
                           co_time_t timeout_us, co_time_t min_wait_us, co_time_t now);

/* Handles a frame; returns whether it was on 7E4h. */
bool co_lss_master_receive(co_lss_master_t *master, const co_frame_t *frame, co_time_t now);

/* Runs the timeout; returns the next deadline, CO_TIME_NEVER when idle. */
co_time_t co_lss_master_process(co_lss_master_t *master, co_time_t now);

bool co_lss_master_busy(const co_lss_master_t *master);

#endif
