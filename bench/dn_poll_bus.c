/* SPDX-License-Identifier: Apache-2.0 */
/* The scanner of bench/devicenet: a bus of DeviceNet drives polled at a period, as a PLC's
 * scanner polls its scan list, on the portable scanner library and the Linux runtime's loop.
 *
 *   dn_poll_bus [--spread] IFACE FIRST-LAST PERIOD-MS
 *
 * IFACE may be --fd=FD: a socket the scanner inherits, one struct can_frame per datagram
 * (bench/native-devicenet: one end of an AF_UNIX SOCK_SEQPACKET socketpair, on a kernel without
 * CAN; co_linux_loop_open_fd).
 * The scanner (MAC ID 0, online at once: the drives' MAC IDs are FIRST..LAST, 1..63) allocates
 * the explicit and polled connections of every slave, sets the polled connection's expected
 * packet rate to PERIOD-MS (the slave's watchdog is 4 times it) and, once every slave's is set,
 * polls them all every PERIOD-MS from that moment on, in one scan cycle as a PLC's scanner does,
 * with 4 bytes of zeros (an assembly 21 that neither runs nor stops the drive); with --spread the
 * slaves' polls are spread evenly over the period instead (slave i at i x PERIOD / N), one frame at
 * a time as a scan cycle's frames follow one another on a real bus, where a burst written at once
 * on a socketpair reaches the slaves' side in one read. Then it prints
 * "polling N" on a line of its own, so that the measurement starts with the whole bus polled; a
 * slave that refuses or does not answer its allocation ends the program with status 1, saying
 * which. SIGUSR1 prints one JSON line of counts: the polls sent, the responses and the polls
 * missed (no response before the next poll or within the scanner's timeout of 1 s), in all, and
 * the fewest responses of a slave. SIGINT or SIGTERM ends the polling: the counts once more, and
 * it exits 0. */
#include "co_linux/log.h"
#include "co_linux/loop.h"
#include "dn/dn_scanner.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <unistd.h>

enum {
    SCANNER_MAC_ID = 0,
    POLL_COMMAND_LEN = 4, /* the output assemblies of the Altivar 312 are 4 bytes */
    US_PER_MS = 1000,
    PERIOD_MS_MAX = 10000,
    EXIT_USAGE = 64,
};

/* Where each slave is on its way to being polled. */
typedef enum slave_step { ALLOCATING, SETTING_RATE, POLLING } slave_step_t;

typedef struct poll_bus {
    co_linux_loop_t loop;
    co_linux_device_t device;
    dn_scanner_t scanner;
    dn_scanner_config_t config;
    dn_scanner_app_t app;
    dn_slave_t slaves[DN_MAC_ID_MAX + 1];
    slave_step_t steps[DN_MAC_ID_MAX + 1];
    uint8_t polling; /* slaves at POLLING */
    uint16_t period_ms;
    bool spread; /* the polls spread over the period, not in one burst */
    co_time_t now;
    int status;
} poll_bus_t;

static void on_send(void *user, const co_frame_t *frame)
{
    poll_bus_t *bus = user;
    co_linux_device_send(&bus->device, frame);
}

static void fail(poll_bus_t *bus, const dn_result_t *result, const char *what)
{
    fprintf(stderr,
            "dn_poll_bus: MAC ID %u, %s: result %d, general status 0x%02X, additional 0x%02X\n",
            result->mac_id, what, (int)result->status, result->general, result->additional);
    bus->status = 1;
    co_linux_loop_stop(&bus->loop, 1);
}

/* Allocate done: the expected packet rate next; rate done: polling from now on. */
static void on_done(void *user, const dn_result_t *result)
{
    poll_bus_t *bus = user;
    uint8_t i = 0;
    while (bus->slaves[i].mac_id != result->mac_id)
        i++;
    if (result->status != DN_RESULT_OK) {
        fail(bus, result, bus->steps[i] == ALLOCATING ? "allocate" : "expected packet rate");
        return;
    }
    if (bus->steps[i] == ALLOCATING) {
        bus->steps[i] = SETTING_RATE;
        dn_scanner_set_expected_packet_rate(&bus->scanner, result->mac_id, DN_CONN_POLL,
                                            bus->period_ms, bus->now);
        return;
    }
    bus->steps[i] = POLLING;
    if (++bus->polling < bus->config.slave_count)
        return;
    co_time_t period_us = (co_time_t)bus->period_ms * US_PER_MS;
    for (i = 0; i < bus->config.slave_count; i++) {
        co_time_t offset = bus->spread ? period_us * i / bus->config.slave_count : 0;
        dn_scanner_poll_every(&bus->scanner, bus->slaves[i].mac_id, period_us, bus->now + offset);
    }
    printf("polling %u\n", bus->polling);
    fflush(stdout);
}

static void device_start(void *ctx, co_time_t now)
{
    poll_bus_t *bus = ctx;
    bus->now = now;
    dn_scanner_start_online(&bus->scanner, now);
    static const uint8_t zeros[POLL_COMMAND_LEN] = {0};
    for (uint8_t i = 0; i < bus->config.slave_count; i++) {
        dn_scanner_set_output(&bus->scanner, bus->slaves[i].mac_id, zeros, sizeof zeros);
        dn_scanner_allocate(&bus->scanner, bus->slaves[i].mac_id,
                            DN_ALLOC_EXPLICIT | DN_ALLOC_POLLED, now);
    }
}

static void device_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    poll_bus_t *bus = ctx;
    bus->now = now;
    dn_scanner_receive(&bus->scanner, frame, now);
}

static co_time_t device_process(void *ctx, co_time_t now)
{
    poll_bus_t *bus = ctx;
    bus->now = now;
    return dn_scanner_process(&bus->scanner, now);
}

static const co_linux_device_ops_t device_ops = {
    .start = device_start,
    .restart = device_start,
    .receive = device_receive,
    .process = device_process,
};

static void print_counts(const poll_bus_t *bus)
{
    unsigned long long polls = 0, responses = 0, missed = 0;
    uint32_t fewest = UINT32_MAX;
    for (uint8_t i = 0; i < bus->config.slave_count; i++) {
        const dn_slave_t *slave = &bus->slaves[i];
        polls += slave->polls;
        responses += slave->responses;
        missed += slave->missed;
        if (slave->responses < fewest)
            fewest = slave->responses;
    }
    printf("{\"slaves\": %u, \"polling\": %u, \"polls\": %llu, \"responses\": %llu, \"missed\": "
           "%llu, \"fewest_responses\": %lu}\n",
           bus->config.slave_count, bus->polling, polls, responses, missed, (unsigned long)fewest);
    fflush(stdout);
}

static void counts_asked(void *ctx, int fd)
{
    struct signalfd_siginfo info;
    if (read(fd, &info, sizeof info) == (ssize_t)sizeof info)
        print_counts(ctx);
}

/* SIGUSR1, read from a signalfd the loop watches: the counts while the polling goes on. */
static int watch_sigusr1(poll_bus_t *bus)
{
    sigset_t usr1;
    sigemptyset(&usr1);
    sigaddset(&usr1, SIGUSR1);
    int fd = -1;
    if (sigprocmask(SIG_BLOCK, &usr1, NULL) != 0 ||
        (fd = signalfd(-1, &usr1, SFD_NONBLOCK | SFD_CLOEXEC)) < 0 ||
        co_linux_loop_watch(&bus->loop, fd, counts_asked, bus) != 0) {
        perror("dn_poll_bus: SIGUSR1");
        return -1;
    }
    return fd;
}

/* The interface, or the inherited socket of --fd=FD. */
static co_linux_open_result_t open_bus(co_linux_loop_t *loop, const co_linux_loop_config_t *config)
{
    if (strncmp(config->iface, "--fd=", 5) != 0)
        return co_linux_loop_open(loop, config);
    char *end = NULL;
    long fd = strtol(config->iface + 5, &end, 10);
    if (*end != '\0' || end == config->iface + 5 || fd < 0 || fd > 1023)
        return CO_LINUX_OPEN_OS_ERROR;
    return co_linux_loop_open_fd(loop, config, (int)fd);
}

static bool parse_range(const char *text, unsigned *first, unsigned *last)
{
    char extra;
    return sscanf(text, "%u-%u%c", first, last, &extra) == 2 && *first <= *last &&
           *last <= DN_MAC_ID_MAX && *first != SCANNER_MAC_ID;
}

int main(int argc, char **argv)
{
    static poll_bus_t bus;
    unsigned first = 0, last = 0;
    char *end = NULL;
    bus.spread = argc > 1 && strcmp(argv[1], "--spread") == 0;
    argc -= bus.spread;
    argv += bus.spread;
    unsigned long period = argc == 4 ? strtoul(argv[3], &end, 10) : 0;
    if (argc != 4 || !parse_range(argv[2], &first, &last) || *end != '\0' || period < 1 ||
        period > PERIOD_MS_MAX) {
        fprintf(stderr,
                "usage: dn_poll_bus [--spread] IFACE FIRST-LAST (MAC IDs 1..63) PERIOD-MS (1-%d)\n",
                PERIOD_MS_MAX);
        return EXIT_USAGE;
    }
    bus.period_ms = (uint16_t)period;
    for (unsigned mac_id = first; mac_id <= last; mac_id++)
        bus.slaves[mac_id - first].mac_id = (uint8_t)mac_id;
    bus.app = (dn_scanner_app_t){.user = &bus, .send = on_send, .done = on_done};
    bus.config = (dn_scanner_config_t){.mac_id = SCANNER_MAC_ID,
                                       .slaves = bus.slaves,
                                       .slave_count = (uint8_t)(last - first + 1),
                                       .app = &bus.app};
    if (dn_scanner_init(&bus.scanner, &bus.config) != DN_SCANNER_INIT_OK)
        return 1;
    co_log_setup("dn_poll_bus", CO_LOG_WARN);
    co_linux_loop_config_t config = {.iface = argv[1]};
    if (open_bus(&bus.loop, &config) != CO_LINUX_OPEN_OK) {
        fprintf(stderr, "dn_poll_bus: cannot open %s\n", argv[1]);
        return 1;
    }
    co_linux_loop_add(&bus.loop, &bus.device, &device_ops, &bus);
    int usr1 = watch_sigusr1(&bus);
    if (usr1 < 0)
        return 1;
    int rc = co_linux_loop_run(&bus.loop);
    co_linux_loop_unwatch(&bus.loop, usr1);
    close(usr1);
    co_linux_loop_close(&bus.loop);
    if (rc != 0 || bus.status != 0)
        return 1;
    print_counts(&bus);
    return 0;
}
