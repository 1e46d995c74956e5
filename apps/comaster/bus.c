/* SPDX-License-Identifier: Apache-2.0 */
/* The bus of comaster: the runtime's epoll loop with one device, on which the commands run their
 * jobs one after the other. Each job ends the loop's run with comaster_bus_finish; the deadlines
 * come from the core's process calls, so nothing sleeps. */
#include "comaster/comaster.h"

#include "cli/co_cli.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* The status a job's run returns when a signal ended it: the loop's own status for SIGINT/SIGTERM
 * is 0, so jobs finish with their status + FINISHED_OFFSET to tell the two apart. */
#define FINISHED_OFFSET 1000

static void device_start(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
}

static void device_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    comaster_bus_t *bus = ctx;
    if (bus->job && bus->job->receive)
        bus->job->receive(bus->job->ctx, frame, now);
}

static co_time_t device_process(void *ctx, co_time_t now)
{
    comaster_bus_t *bus = ctx;
    if (!bus->job || !bus->job->process)
        return CO_TIME_NEVER;
    return bus->job->process(bus->job->ctx, now);
}

static const co_linux_device_ops_t device_ops = {
    .start = device_start,
    .restart = device_start,
    .receive = device_receive,
    .process = device_process,
};

static int report_open_error(const comaster_bus_t *bus, const comaster_options_t *opts,
                             co_linux_open_result_t result)
{
    char message[512];
    int status = cli_open_error_text(&bus->loop, result, "COMASTER_IFACE", message, sizeof message);
    return comaster_fail(opts, status, "%s", message);
}

int comaster_bus_open(comaster_bus_t *bus, const comaster_options_t *opts)
{
    memset(bus, 0, sizeof *bus);
    co_linux_loop_config_t config = {.iface = opts->iface};
    co_linux_open_result_t opened = co_linux_loop_open(&bus->loop, &config);
    if (opened != CO_LINUX_OPEN_OK)
        return report_open_error(bus, opts, opened);
    co_linux_loop_add(&bus->loop, &bus->device, &device_ops, bus);
    bus->opened = true;
    bus->opts = opts;
    return 0;
}

void comaster_bus_close(comaster_bus_t *bus)
{
    if (bus->opened)
        co_linux_loop_close(&bus->loop);
    bus->opened = false;
}

int comaster_bus_run(comaster_bus_t *bus, const comaster_job_t *job)
{
    bus->job = job;
    int rc = co_linux_loop_run(&bus->loop);
    bus->job = NULL;
    if (rc >= FINISHED_OFFSET)
        return rc - FINISHED_OFFSET;
    if (rc != 0)
        return rc;
    if (!bus->signal_is_the_end)
        comaster_fail(bus->opts, CLI_EXIT_INTERRUPTED,
                      "interrupted by a signal before the command finished");
    return CLI_EXIT_INTERRUPTED;
}

void comaster_bus_finish(comaster_bus_t *bus, int status)
{
    co_linux_loop_stop(&bus->loop, status + FINISHED_OFFSET);
}

void comaster_bus_send(void *bus, const co_frame_t *frame)
{
    comaster_bus_t *b = bus;
    co_linux_device_send(&b->device, frame);
}

/* ---- a pause: the loop runs (and flushes what was sent) until a deadline ----------------------
 */

typedef struct pause_job {
    comaster_bus_t *bus;
    co_time_t until;
} pause_job_t;

static co_time_t pause_process(void *ctx, co_time_t now)
{
    pause_job_t *p = ctx;
    if (now >= p->until) {
        comaster_bus_finish(p->bus, 0);
        return CO_TIME_NEVER;
    }
    return p->until;
}

int comaster_bus_pause(comaster_bus_t *bus, uint32_t ms)
{
    pause_job_t pause = {bus, co_linux_now() + (co_time_t)ms * 1000u};
    comaster_job_t job = {.process = pause_process, .ctx = &pause};
    return comaster_bus_run(bus, &job);
}

/* ---- one SDO transfer ---------------------------------------------------------------------------
 */

typedef struct sdo_job {
    comaster_bus_t *bus;
    co_sdo_client_t client;
    co_sdo_client_result_t *result;
} sdo_job_t;

static void sdo_send(void *user, const co_frame_t *frame)
{
    sdo_job_t *s = user;
    comaster_bus_send(s->bus, frame);
}

static void sdo_done(void *user, const co_sdo_client_result_t *result)
{
    sdo_job_t *s = user;
    *s->result = *result;
    comaster_bus_finish(s->bus, 0);
}

static void sdo_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    sdo_job_t *s = ctx;
    co_sdo_client_receive(&s->client, frame, now);
}

static co_time_t sdo_process(void *ctx, co_time_t now)
{
    sdo_job_t *s = ctx;
    return co_sdo_client_process(&s->client, now);
}

static void sdo_job_init(sdo_job_t *s, comaster_bus_t *bus, uint8_t node,
                         co_sdo_client_result_t *result)
{
    memset(s, 0, sizeof *s);
    s->bus = bus;
    s->result = result;
    co_sdo_client_config_t config = {
        .server_node_id = node, .send = sdo_send, .user = s, .done = sdo_done};
    co_sdo_client_init(&s->client, &config);
}

static int sdo_run(sdo_job_t *s, int started)
{
    if (started != 0)
        return comaster_fail(s->bus->opts, EX_SOFTWARE,
                             "internal error: the SDO client did not start the transfer (%d)",
                             started);
    comaster_job_t job = {.receive = sdo_receive, .process = sdo_process, .ctx = s};
    return comaster_bus_run(s->bus, &job);
}

int comaster_sdo_upload(comaster_bus_t *bus, uint8_t node, uint16_t index, uint8_t sub,
                        uint8_t *buf, uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                        co_sdo_client_result_t *result)
{
    sdo_job_t s;
    sdo_job_init(&s, bus, node, result);
    return sdo_run(&s, co_sdo_client_upload(&s.client, index, sub, buf, cap, mode, timeout_ms,
                                            co_linux_now()));
}

int comaster_sdo_download(comaster_bus_t *bus, uint8_t node, uint16_t index, uint8_t sub,
                          const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                          uint32_t timeout_ms, co_sdo_client_result_t *result)
{
    sdo_job_t s;
    sdo_job_init(&s, bus, node, result);
    return sdo_run(&s, co_sdo_client_download(&s.client, index, sub, data, len, mode, timeout_ms,
                                              co_linux_now()));
}

int comaster_sdo_status(const comaster_options_t *opts, uint8_t node,
                        const co_sdo_client_result_t *result)
{
    if (result->status == CO_SDO_CLIENT_OK)
        return CLI_EXIT_OK;
    if (result->status == CO_SDO_CLIENT_CLIENT_ABORT && result->abort_code == CO_SDO_ABORT_TIMEOUT)
        return comaster_fail(opts, CLI_EXIT_TIMEOUT,
                             "node %u, %04X:%02X: no answer within %u ms: is the node on %s and "
                             "its node-id %u? (--timeout MS waits longer)",
                             node, result->index, result->subindex, opts->timeout_ms, opts->iface,
                             node);
    return comaster_fail(opts, CLI_EXIT_REFUSED, "node %u, %04X:%02X: %s abort 0x%08X: %s", node,
                         result->index, result->subindex,
                         result->status == CO_SDO_CLIENT_SERVER_ABORT ? "SDO" : "client",
                         result->abort_code, co_sdo_abort_text(result->abort_code));
}
