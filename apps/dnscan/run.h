/* SPDX-License-Identifier: Apache-2.0 */
/* dnscan's bus: the runtime's loop with the scanner as its device, and per slave a sequence of
 * steps run one after the other (run.c). */
#ifndef DNSCAN_RUN_H
#define DNSCAN_RUN_H

#include "co_linux/loop.h"
#include "dnscan/dnscan.h"

/* The scanner's identity in its duplicate MAC ID check: no vendor (0), and a serial number
 * that names the tool ("DNSC"). */
#define DNSCAN_VENDOR_ID 0x0000u
#define DNSCAN_SERIAL_NUMBER 0x43534E44u

typedef enum dnscan_step_kind {
    DNSCAN_ALLOCATE,
    DNSCAN_RELEASE,
    DNSCAN_REQUEST,
    DNSCAN_POLL /* ends when the command calls dnscan_poll_done; kept with --every */
} dnscan_step_kind_t;

typedef struct dnscan_step {
    dnscan_step_kind_t kind;
    bool ucmm; /* ALLOCATE and RELEASE of the explicit connection: the UCMM's Open and Close */
    uint8_t choice;
    uint8_t service;
    uint8_t class_id;
    uint8_t instance;
    uint8_t data[DN_MESSAGE_MAX];
    uint8_t len;
} dnscan_step_t;

#define DNSCAN_STEPS_MAX 10

typedef struct dnscan_sequence {
    uint8_t mac_id;
    dnscan_step_t steps[DNSCAN_STEPS_MAX];
    uint8_t count;
    uint8_t next;
    bool done;
    /* the command's own */
    bool we_allocated;
    uint32_t polls;
    uint16_t in_assembly; /* poll: the produced assembly the answers carry, 0 unknown */
    uint16_t vendor, device_type, product_code, serial_low, serial_high;
    uint8_t revision[2];
    char name[33];
    int state; /* scan: 0 absent, 1 present, 2 owned by another master */
} dnscan_sequence_t;

typedef struct dnscan_run dnscan_run_t;

struct dnscan_run {
    dnscan_options_t *opts;
    co_linux_loop_t loop;
    co_linux_device_t device;
    dn_scanner_t scanner;
    dn_scanner_config_t config;
    dn_scanner_app_t app;
    dn_slave_t slaves[DN_MAC_ID_MAX + 1];
    dnscan_sequence_t sequences[DN_MAC_ID_MAX + 1];
    bool started;
    bool passive;           /* monitor: the scanner stays off, nothing is sent */
    bool signal_is_the_end; /* poll without --count, monitor: SIGINT ends it, no error */
    bool releasing;         /* after SIGINT or SIGTERM: the releases of what was allocated */
    int status;
    co_time_t now;
    co_time_t end; /* the command's own deadline (CO_TIME_NEVER) */
    co_time_t every_us;
    uint16_t rate_ms; /* poll: the expected packet rate set, and set again on a reconnection */
    uint8_t output[8];
    uint8_t output_len;
    /* A step's result: false stops the slave's sequence. */
    bool (*on_result)(dnscan_run_t *run, dnscan_sequence_t *seq, const dnscan_step_t *step,
                      const dn_result_t *result);
    void (*on_io)(dnscan_run_t *run, dnscan_sequence_t *seq, dn_io_kind_t kind, const uint8_t *data,
                  uint8_t len);
    void (*on_frame)(dnscan_run_t *run, const co_frame_t *frame);
    void (*on_connection)(dnscan_run_t *run, dnscan_sequence_t *seq, dn_connection_event_t event,
                          const dn_result_t *result);
    const void *command; /* the command's context */
};

void dnscan_run_init(dnscan_run_t *run, dnscan_options_t *opts);
dnscan_sequence_t *dnscan_add_slave(dnscan_run_t *run, uint8_t mac_id);
dnscan_step_t *dnscan_add_step(dnscan_sequence_t *seq, dnscan_step_kind_t kind);
/* Opens the interface and runs until the command finishes; its exit status. SIGINT or SIGTERM
 * first sends each slave whose sequence allocated (or was allocating) its release step, and
 * waits for them (each within the timeout; a second signal does not wait). */
int dnscan_run(dnscan_run_t *run);
void dnscan_finish(dnscan_run_t *run, int status);
/* Leaves out the steps before the sequence's release (after an error). */
void dnscan_skip_to_release(dnscan_run_t *run, dnscan_sequence_t *seq);
/* The poll step is over: the sequence goes on. */
void dnscan_poll_done(dnscan_run_t *run, dnscan_sequence_t *seq, co_time_t now);
co_time_t dnscan_ms(uint32_t ms);

#endif
