/* SPDX-License-Identifier: Apache-2.0 */
/* comaster time: the TIME producer of a network (CiA 301 7.2.6): one TIME frame on 100h with the
 * host's clock, or one every PERIOD milliseconds until SIGINT or SIGTERM. docs/time.md. */
#include "co/co_time_of_day.h"
#include "co_linux/loop.h"
#include "comaster/comaster.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static const char time_help[] =
    "usage: comaster time [PERIOD]\n"
    "\n"
    "Sends the TIME object (100h, CiA 301): the host's clock in UTC as a\n"
    "TIME_OF_DAY, milliseconds after midnight and days since 1984-01-01, and\n"
    "prints it ('TIME 2026-11-29 12:34:56.789'). Without PERIOD, one frame and\n"
    "exits; with PERIOD (ms, 1..3600000), one every PERIOD ms on a fixed grid\n"
    "until SIGINT or SIGTERM (exit status 0). A node consumes it when its 1012h has bit 31 set\n"
    "(the I/O node of atv312d --model io does, on 100h).\n"
    "\n"
    "Example: comaster -i vcan0 time 1000\n";

#define PERIOD_MAX_MS 3600000u

typedef struct time_job {
    comaster_bus_t *bus;
    const comaster_options_t *opts;
    co_time_t period_us; /* 0: once */
    co_time_t due;
} time_job_t;

/* The host's clock as a TIME_OF_DAY; false before 1984 or after 2163 (a clock not set). */
static bool host_time(co_time_of_day_t *time)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t ms = (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
    return co_time_of_day_from_unix_ms(ms, time);
}

static int send_time(time_job_t *job)
{
    co_time_of_day_t time;
    if (!host_time(&time))
        return comaster_fail(job->opts, EX_SOFTWARE,
                             "time: the host's clock is outside 1984..2163: is it set?");
    co_frame_t frame = {.id = CO_CAN_ID_TIME, .len = CO_TIME_OF_DAY_LEN};
    co_time_of_day_encode(&time, frame.data);
    comaster_bus_send(job->bus, &frame);
    char text[CO_TIME_OF_DAY_TEXT_SIZE];
    co_time_of_day_format(&time, text);
    if (job->opts->json)
        printf("{\"time\": \"%s\", \"ms\": %lu, \"days\": %u}\n", text, (unsigned long)time.ms,
               time.days);
    else
        printf("TIME %s\n", text);
    fflush(stdout);
    return 0;
}

static void time_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    (void)ctx, (void)frame, (void)now;
}

static co_time_t time_process(void *ctx, co_time_t now)
{
    time_job_t *job = ctx;
    if (now < job->due)
        return job->due;
    int rc = send_time(job);
    if (rc != 0) {
        comaster_bus_finish(job->bus, rc);
        return CO_TIME_NEVER;
    }
    job->due = co_time_next_period(job->due, job->period_us, now);
    return job->due;
}

int comaster_time_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, time_help, "", 0, 1);
    if (rc >= 0)
        return rc;
    unsigned long period_ms = 0;
    if (args.count == 1) {
        char *end;
        period_ms = strtoul(args.positional[0], &end, 10);
        if (*end != '\0' || period_ms < 1 || period_ms > PERIOD_MAX_MS)
            return comaster_fail(opts, EX_USAGE, "time: '%s' is no period: give 1..%u ms",
                                 args.positional[0], PERIOD_MAX_MS);
    }
    static comaster_bus_t bus;
    rc = comaster_bus_open(&bus, opts);
    if (rc != 0)
        return rc;
    static time_job_t job;
    job = (time_job_t){.bus = &bus, .opts = opts, .period_us = (co_time_t)period_ms * 1000u};
    if (period_ms == 0) {
        rc = send_time(&job);
        if (rc == 0)
            rc = comaster_bus_pause(&bus, 0); /* sends what is queued */
    } else {
        bus.signal_is_the_end = true;
        job.due = co_linux_now();
        comaster_job_t run = {.receive = time_receive, .process = time_process, .ctx = &job};
        rc = comaster_bus_run(&bus, &run);
        if (rc == CLI_EXIT_INTERRUPTED) /* the signal is how it ends */
            rc = 0;
    }
    comaster_bus_close(&bus);
    return rc;
}
