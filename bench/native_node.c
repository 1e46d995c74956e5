/* SPDX-License-Identifier: Apache-2.0 */
/* The daemon's side of bench/native: one emulated drive of atv312d's (the ATV312 model) on the
 * runtime loop, co_linux_loop_run, over a socket it inherits (one end of an AF_UNIX
 * SOCK_SEQPACKET socketpair carrying struct can_frame: co_linux_loop_open_fd), so that the loop
 * and the drive can be timed on a native kernel that has no vcan.
 *
 *   native_node FD NODE-ID
 *
 * The device operations are the daemon's (apps/atv312d/drives.c) without its logging: atv312d also
 * compares the NMT and CiA 402 states after each call into the drive and looks up 1014h for each
 * frame it sends, to log state changes and emergencies. Runs until the peer hangs up or SIGTERM,
 * then prints the loop's counters as one JSON line on standard output. */
#include "co_linux/log.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/models/models.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

typedef struct {
    drive_t drive;
    co_linux_device_t device;
} bench_drive_t;

static void send_frame(void *user, const co_frame_t *frame)
{
    bench_drive_t *d = user;
    co_linux_device_send(&d->device, frame);
}

static void start(void *ctx, co_time_t now)
{
    drive_start(&((bench_drive_t *)ctx)->drive, now);
}

static void receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    drive_receive(&((bench_drive_t *)ctx)->drive, frame, now);
}

static co_time_t process(void *ctx, co_time_t now)
{
    return drive_process(&((bench_drive_t *)ctx)->drive, now);
}

static void bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    drive_bus_event(&((bench_drive_t *)ctx)->drive, emcy_code, active);
}

static const co_node_t *node_of(void *ctx)
{
    return &((bench_drive_t *)ctx)->drive.node;
}

/* Never called: a given socket has no link that goes down and comes back. */
static void restart(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
}

static const co_linux_device_ops_t ops = {.start = start,
                                          .restart = restart,
                                          .receive = receive,
                                          .process = process,
                                          .bus_event = bus_event,
                                          .node = node_of};

static long parse(const char *arg, long max)
{
    char *end = NULL;
    long value = strtol(arg, &end, 10);
    return *end == '\0' && end != arg && value >= 0 && value <= max ? value : -1;
}

int main(int argc, char **argv)
{
    long fd = argc == 3 ? parse(argv[1], 1023) : -1;
    long node_id = argc == 3 ? parse(argv[2], 127) : -1;
    if (fd < 0 || node_id < 1) {
        fprintf(stderr, "usage: native_node FD NODE-ID (1-127)\n");
        return EX_USAGE;
    }
    co_log_setup("native_node", CO_LOG_WARN);
    static co_linux_loop_t loop;
    co_linux_loop_config_t config = {.iface = "socketpair"};
    if (co_linux_loop_open_fd(&loop, &config, (int)fd) != CO_LINUX_OPEN_OK) {
        fprintf(stderr, "native_node: %s: %s\n", loop.open_call, strerror(loop.open_errno));
        return EX_OSERR;
    }
    const drive_model_t *model = drive_model_find("atv312");
    static bench_drive_t bench;
    uint8_t *od_data = calloc(1, model->profile->od->data_size);
    drive_config_t dc = {.profile = model->profile,
                         .od_data = od_data,
                         .node_id = (uint8_t)node_id,
                         .send = send_frame,
                         .send_user = &bench};
    if (od_data == NULL || drive_init(&bench.drive, &dc) != 0) {
        fprintf(stderr, "native_node: the drive cannot be initialised\n");
        return EX_SOFTWARE;
    }
    co_linux_loop_add(&loop, &bench.device, &ops, &bench);
    int rc = co_linux_loop_run(&loop);
    printf("{\"wakeups\": %llu, \"rx\": %llu, \"tx\": %llu, \"tx_calls\": %llu, \"tx_dropped\": "
           "%llu}\n",
           loop.stats.wakeups, loop.stats.rx, loop.stats.tx, loop.stats.tx_calls,
           loop.stats.tx_dropped);
    co_linux_loop_close(&loop);
    free(od_data);
    return rc;
}
