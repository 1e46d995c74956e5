/* SPDX-License-Identifier: Apache-2.0 */
/* dnscan's bus and sequences: the Linux runtime's loop with the scanner as its one device; each
 * slave of a command runs a sequence of steps (allocate, requests, polls, release) one after the
 * other, all slaves at once, and the command ends when every sequence has. */
#include "dnscan/run.h"

#include "cli/co_cli.h"

#include <stdio.h>
#include <string.h>

/* The loop returns 0 for SIGINT/SIGTERM: a command's own end is its status + FINISHED. */
#define FINISHED 1000
#define US_PER_MS 1000u

void dnscan_finish(dnscan_run_t *run, int status)
{
    co_linux_loop_stop(&run->loop, status + FINISHED);
}

static void start_step(dnscan_run_t *run, dnscan_sequence_t *seq, co_time_t now);

static void next_step(dnscan_run_t *run, dnscan_sequence_t *seq, co_time_t now)
{
    seq->next++;
    if (seq->next < seq->count) {
        start_step(run, seq, now);
        return;
    }
    seq->done = true;
    for (uint8_t i = 0; i < run->config.slave_count; i++)
        if (!run->sequences[i].done)
            return;
    dnscan_finish(run, run->status);
}

static void start_step(dnscan_run_t *run, dnscan_sequence_t *seq, co_time_t now)
{
    const dnscan_step_t *step = &seq->steps[seq->next];
    dn_scanner_t *s = &run->scanner;
    bool started = false;
    switch (step->kind) {
    case DNSCAN_ALLOCATE:
        started = step->ucmm ? dn_scanner_ucmm_open(s, seq->mac_id, now)
                             : dn_scanner_allocate(s, seq->mac_id, step->choice, now);
        break;
    case DNSCAN_RELEASE:
        started = step->ucmm ? dn_scanner_ucmm_close(s, seq->mac_id, now)
                             : dn_scanner_release(s, seq->mac_id, step->choice, now);
        break;
    case DNSCAN_REQUEST:
        started = dn_scanner_request(s, seq->mac_id, step->service, step->class_id, step->instance,
                                     step->data, step->len, now);
        break;
    case DNSCAN_POLL:
        dn_scanner_set_output(s, seq->mac_id, run->output, run->output_len);
        started = run->every_us
                      ? dn_scanner_keep_polling(s, seq->mac_id, run->every_us, run->rate_ms, now)
                      : dn_scanner_poll(s, seq->mac_id, now);
        break;
    }
    if (!started)
        dnscan_finish(run, dnscan_fail(run->opts, EX_SOFTWARE,
                                       "internal error: MAC ID %u: the scanner did not start the "
                                       "request",
                                       seq->mac_id));
}

void dnscan_skip_to_release(dnscan_run_t *run, dnscan_sequence_t *seq)
{
    (void)run;
    while (seq->next + 1 < seq->count && seq->steps[seq->next + 1].kind != DNSCAN_RELEASE)
        seq->next++;
}

void dnscan_poll_done(dnscan_run_t *run, dnscan_sequence_t *seq, co_time_t now)
{
    if (seq->done || seq->steps[seq->next].kind != DNSCAN_POLL)
        return; /* a signal sent the sequence to its release: the last poll's end changes nothing */
    dn_scanner_poll_every(&run->scanner, seq->mac_id, 0, now);
    next_step(run, seq, now);
}

static dnscan_sequence_t *sequence_of(dnscan_run_t *run, uint8_t mac_id)
{
    for (uint8_t i = 0; i < run->config.slave_count; i++)
        if (run->sequences[i].mac_id == mac_id)
            return &run->sequences[i];
    return NULL;
}

static void on_send(void *user, const co_frame_t *frame)
{
    dnscan_run_t *run = user;
    co_linux_device_send(&run->device, frame);
}

static void on_done(void *user, const dn_result_t *result)
{
    dnscan_run_t *run = user;
    dnscan_sequence_t *seq = sequence_of(run, result->mac_id);
    if (seq == NULL || seq->done)
        return;
    const dnscan_step_t *step = &seq->steps[seq->next];
    if (!run->on_result(run, seq, step, result)) {
        seq->next = seq->count; /* stop here */
    }
    next_step(run, seq, run->now);
}

static void on_io(void *user, uint8_t mac_id, dn_io_kind_t kind, const uint8_t *data, uint8_t len)
{
    dnscan_run_t *run = user;
    dnscan_sequence_t *seq = sequence_of(run, mac_id);
    if (seq && run->on_io)
        run->on_io(run, seq, kind, data, len);
}

static void on_connection(void *user, uint8_t mac_id, dn_connection_event_t event,
                          const dn_result_t *result)
{
    dnscan_run_t *run = user;
    dnscan_sequence_t *seq = sequence_of(run, mac_id);
    if (seq && run->on_connection)
        run->on_connection(run, seq, event, result);
}

static void device_start(void *ctx, co_time_t now)
{
    dnscan_run_t *run = ctx;
    run->now = now;
    if (run->passive || run->releasing)
        return; /* the loop runs again for the releases: the scanner goes on as it is */
    if (run->opts->no_check)
        dn_scanner_start_online(&run->scanner, now);
    else
        dn_scanner_start(&run->scanner, now);
}

static void device_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    dnscan_run_t *run = ctx;
    run->now = now;
    if (run->on_frame)
        run->on_frame(run, frame);
    if (!run->passive)
        dn_scanner_receive(&run->scanner, frame, now);
}

static co_time_t device_process(void *ctx, co_time_t now)
{
    dnscan_run_t *run = ctx;
    run->now = now;
    if (run->passive)
        return run->end;
    if (now >= run->end) {
        dnscan_finish(run, run->status);
        return CO_TIME_NEVER;
    }
    co_time_t next = dn_scanner_process(&run->scanner, now);
    if (run->scanner.link == DN_SCANNER_DUPLICATE) {
        dnscan_finish(run, dnscan_fail(run->opts, CLI_EXIT_MAC_ID_IN_USE,
                                       "MAC ID %u is in use on %s: give the scanner another "
                                       "with --mac-id N",
                                       run->opts->mac_id, run->opts->iface));
        return CO_TIME_NEVER;
    }
    if (run->scanner.link == DN_SCANNER_ONLINE && !run->started) {
        run->started = true;
        for (uint8_t i = 0; i < run->config.slave_count; i++)
            start_step(run, &run->sequences[i], now);
        next = dn_scanner_process(&run->scanner, now);
    }
    return co_time_min(next, run->end);
}

static const co_linux_device_ops_t device_ops = {
    .start = device_start,
    .restart = device_start,
    .receive = device_receive,
    .process = device_process,
};

static int open_error(const dnscan_run_t *run, co_linux_open_result_t result)
{
    char message[512];
    int status = cli_open_error_text(&run->loop, result, "DNSCAN_IFACE", message, sizeof message);
    return dnscan_fail(run->opts, status, "%s", message);
}

void dnscan_run_init(dnscan_run_t *run, dnscan_options_t *opts)
{
    memset(run, 0, sizeof *run);
    run->opts = opts;
    run->end = CO_TIME_NEVER;
    run->app = (dn_scanner_app_t){run, on_send, on_done, on_io, on_connection};
}

dnscan_sequence_t *dnscan_add_slave(dnscan_run_t *run, uint8_t mac_id)
{
    uint8_t i = run->config.slave_count++;
    run->slaves[i].mac_id = mac_id;
    run->sequences[i].mac_id = mac_id;
    return &run->sequences[i];
}

dnscan_step_t *dnscan_add_step(dnscan_sequence_t *seq, dnscan_step_kind_t kind)
{
    dnscan_step_t *step = &seq->steps[seq->count++];
    memset(step, 0, sizeof *step);
    step->kind = kind;
    return step;
}

/* The release step still ahead of a sequence that allocated or is allocating, or -1. */
static int release_ahead(const dnscan_sequence_t *seq)
{
    for (int i = seq->next; i < seq->count; i++)
        if (seq->steps[i].kind == DNSCAN_RELEASE)
            return i;
    return -1;
}

/* SIGINT or SIGTERM: each sequence not done stops (polls, a request in progress dropped) and
 * goes to its release at once, or ends when it has none (what `allocate` leaves allocated, a
 * UCMM connection whose Open is unanswered);
 * true when a release is under way. */
static bool release_on_signal(dnscan_run_t *run)
{
    if (!run->started)
        return false;
    co_time_t now = co_linux_now();
    run->now = now;
    bool any = false;
    for (uint8_t i = 0; i < run->config.slave_count; i++) {
        dnscan_sequence_t *seq = &run->sequences[i];
        if (seq->done)
            continue;
        int release = release_ahead(seq);
        if (release == seq->next) {
            any = true; /* already on its way */
            continue;
        }
        dn_scanner_poll_every(&run->scanner, seq->mac_id, 0, now);
        dn_scanner_abandon(&run->scanner, seq->mac_id);
        if (release >= 0 && seq->steps[release].ucmm &&
            dn_scanner_slave(&run->scanner, seq->mac_id)->ucmm_instance == 0)
            release = -1; /* its Open was not answered: no connection to close */
        if (release < 0) {
            seq->done = true;
            continue;
        }
        any = true;
        seq->next = (uint8_t)release;
        start_step(run, seq, now);
    }
    return any;
}

int dnscan_run(dnscan_run_t *run)
{
    run->config = (dn_scanner_config_t){run->opts->mac_id,
                                        DNSCAN_VENDOR_ID,
                                        DNSCAN_SERIAL_NUMBER,
                                        (co_time_t)run->opts->timeout_ms * US_PER_MS,
                                        run->slaves,
                                        run->config.slave_count,
                                        &run->app};
    if (dn_scanner_init(&run->scanner, &run->config) != DN_SCANNER_INIT_OK)
        return dnscan_fail(run->opts, EX_SOFTWARE,
                           "internal error: the scanner refused its configuration");
    co_linux_loop_config_t config = {.iface = run->opts->iface};
    co_linux_open_result_t opened = co_linux_loop_open(&run->loop, &config);
    if (opened != CO_LINUX_OPEN_OK)
        return open_error(run, opened);
    co_linux_loop_add(&run->loop, &run->device, &device_ops, run);
    int rc = co_linux_loop_run(&run->loop);
    if (rc == 0 && release_on_signal(run)) {
        run->releasing = true;
        int released = co_linux_loop_run(&run->loop);
        if (released != 0 && released < FINISHED)
            rc = released; /* the loop failed */
    }
    co_linux_loop_close(&run->loop);
    if (rc >= FINISHED)
        return rc - FINISHED;
    if (rc != 0)
        return rc;
    if (run->signal_is_the_end)
        return run->status;
    return dnscan_fail(run->opts, CLI_EXIT_INTERRUPTED,
                       "interrupted by a signal before the command finished");
}

co_time_t dnscan_ms(uint32_t ms)
{
    return (co_time_t)ms * US_PER_MS;
}
