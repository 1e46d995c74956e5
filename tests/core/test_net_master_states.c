/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's boot manager, every event in every situation of a slave: one row per
 * (situation, event) gives the step, the status word, the frames the master sends and the deadline
 * it returns after the event (docs/net-master.md, "Every event in every step", says why each
 * reaction is the one CiA 302-2 and the PLC300 call for). No slave node: the test plays node 4
 * (and node 5, the other slave some situations need) frame by frame, with injected time, and every
 * deadline the master returns must be in the future or never. The table is followed by the frame-
 * exact cases of issue 22's items 2 to 4. */
#include "check_main.h"
#include "co/co_net_master.h"
#include "test_bus.h"

#include <stdio.h>
#include <string.h>

#define MS 1000u
#define HEARTBEAT_MS 100u /* the master's consumer time for node 4 */
#define SDO_TIMEOUT_MS 200u
#define BOOT_TIME_MS 300u
#define RETRY_DELAY_MS 400u
#define QUIET_MS 1000u   /* how long a timeout waits when the master asks for no deadline */
#define NEVER UINT32_MAX /* a row's deadline: CO_TIME_NEVER */
#define FRAMES_MAX 64u
#define FRAMES_TEXT 256u

/* The steps by shorter names, so that a row of the table fits a line. */
#define IDLE CO_NET_STEP_IDLE
#define WAIT_BOOT CO_NET_STEP_WAIT_BOOT
#define DEVICE_TYPE CO_NET_STEP_DEVICE_TYPE
#define IDENTITY CO_NET_STEP_IDENTITY
#define DOWNLOAD CO_NET_STEP_DOWNLOAD
#define WAIT_START CO_NET_STEP_WAIT_START
#define OPERATIONAL CO_NET_STEP_OPERATIONAL
#define FAILED CO_NET_STEP_FAILED
#define LOST CO_NET_STEP_LOST

static struct {
    co_frame_t frame[FRAMES_MAX];
    size_t count;
    size_t next; /* the first frame the current check has not looked at */
    co_time_t now;
    co_time_t deadline; /* returned by the last co_net_master_process */
} bus;

static co_net_master_t master;
static co_net_master_config_t config;
static co_net_slave_config_t table[2];
static co_net_slave_t state[2];

/* Node 4 is checked (1000h, 1018h:01) and configured (1017h = 100 ms) and its heartbeat is
 * consumed; node 5 is only read (1000h) and configured. */
static const uint8_t heartbeat_100ms[] = {0x64, 0x00};
static const co_net_write_t writes[] = {{0x1017, 0, heartbeat_100ms, sizeof(heartbeat_100ms)}};

static void master_send(void *user, const co_frame_t *frame)
{
    ck_assert_ptr_eq(user, &bus);
    ck_assert_uint_lt(bus.count, FRAMES_MAX);
    bus.frame[bus.count++] = *frame;
}

/* Runs the master at the current time; a runtime sleeps until the deadline it returns, so that
 * deadline is never in the past nor now (or the runtime spins). */
static void run(void)
{
    bus.deadline = co_net_master_process(&master, bus.now);
    ck_assert_msg(bus.deadline > bus.now,
                  "at %llu us the master returned the deadline %llu us, not in the future",
                  (unsigned long long)bus.now, (unsigned long long)bus.deadline);
}

static void deliver(const char *text)
{
    co_frame_t frame = test_frame(text);
    co_net_master_receive(&master, &frame, bus.now);
    run();
}

/* Time passes to `until`, the master running at every deadline on the way. */
static void advance_to(co_time_t until)
{
    while (bus.deadline <= until) {
        bus.now = bus.deadline;
        run();
    }
    bus.now = until;
    run();
}

static void start(void)
{
    co_net_master_start(&master, bus.now);
    run();
}

static void configure_network(co_net_on_error_t on_error, co_net_start_t start_mode, size_t slaves,
                              co_net_mandatory_error_t on_mandatory_error)
{
    memset(&bus, 0, sizeof(bus));
    table[0] = (co_net_slave_config_t){
        .node_id = 4,
        .mandatory = true,
        .check = CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR,
        .device_type = 0x00010192,
        .identity = {0x5F},
        .writes = writes,
        .write_count = 1,
        .heartbeat_ms = HEARTBEAT_MS,
        .on_error = on_error,
    };
    table[1] = (co_net_slave_config_t){.node_id = 5, .writes = writes, .write_count = 1};
    config = (co_net_master_config_t){
        .send = master_send,
        .user = &bus,
        .slaves = table,
        .slave_state = state,
        .slave_count = slaves,
        .sdo_timeout_ms = SDO_TIMEOUT_MS,
        .boot_time_ms = BOOT_TIME_MS,
        .retry_delay_ms = RETRY_DELAY_MS,
        .start = start_mode,
        .on_mandatory_error = on_mandatory_error,
    };
    ck_assert(co_net_master_init(&master, &config));
    run();
}

static void configure(co_net_on_error_t on_error, co_net_start_t start_mode, size_t slaves)
{
    configure_network(on_error, start_mode, slaves, CO_NET_MANDATORY_ALONE);
}

/* ---- the situations: how node 4 gets there (all at time 0 unless said) ---------------------- */

/* Reset communication sent, boot-up received: the master reads 1000h. */
static void boot_to_device_type(void)
{
    start();
    deliver("704#00");
}

static void boot_to_identity(void)
{
    boot_to_device_type();
    deliver("584#4300100092010100");
}

static void boot_to_download(void)
{
    boot_to_identity();
    deliver("584#431810015F000000");
}

static void boot_to_end(void)
{
    boot_to_download();
    deliver("584#6017100000000000");
}

static void enter_idle(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
}

static void enter_wait_boot(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    start();
}

/* Node 5 booted first and holds the SDO client (its 1017h write, sent at 150 ms, times out at
 * 350 ms) when node 4's boot time ends at 300 ms without a boot-up: node 4 waits for the client. */
static void enter_wait_client(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 2);
    start();
    deliver("705#00");
    advance_to(150 * MS);
    deliver("585#4300100092010100");
    advance_to(BOOT_TIME_MS * MS);
}

static void enter_device_type(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    boot_to_device_type();
}

/* The boot time ended without a boot-up: the master reads 1000h anyway, at 300 ms. */
static void enter_device_type_no_boot_up(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    start();
    advance_to(BOOT_TIME_MS * MS);
}

static void enter_identity(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    boot_to_identity();
}

static void enter_download(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    boot_to_download();
}

/* Start all: node 4 (mandatory) configured, node 5 still waits for its boot-up (its boot time
 * ends at 300 ms), so the start of all is not yet sent. Node 4's first heartbeat came. */
static void enter_wait_start_reboot(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_ALL, 2);
    boot_to_end();
    deliver("704#7F");
}

static void enter_wait_start_report(void)
{
    configure(CO_NET_ON_ERROR_REPORT, CO_NET_START_ALL, 2);
    boot_to_end();
    deliver("704#7F");
}

static void enter_operational_reboot(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    boot_to_end();
    deliver("704#05");
}

static void enter_operational_report(void)
{
    configure(CO_NET_ON_ERROR_REPORT, CO_NET_START_EACH, 1);
    boot_to_end();
    deliver("704#05");
}

/* 1F80h bit 6 or 4: node 4, mandatory, running; its loss is the network's. */
static void enter_operational_stop_all(void)
{
    configure_network(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1, CO_NET_MANDATORY_STOP_ALL);
    boot_to_end();
    deliver("704#05");
}

static void enter_operational_reset_all(void)
{
    configure_network(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1, CO_NET_MANDATORY_RESET_ALL);
    boot_to_end();
    deliver("704#05");
}

/* Its silence stopped every node at 100 ms: node 4 lost, the network stopped. */
static void enter_stopped_all(void)
{
    enter_operational_stop_all();
    advance_to(HEARTBEAT_MS * MS);
}

/* Started, heard once, then silent: lost at 100 ms. */
static void enter_lost(void)
{
    enter_operational_report();
    advance_to(HEARTBEAT_MS * MS);
}

/* Not started by the master (CO_NET_START_NONE) and never heard: lost at 100 ms, while the master
 * still knows it Pre-operational from its boot-up. */
static void enter_lost_first_heartbeat(void)
{
    configure(CO_NET_ON_ERROR_REPORT, CO_NET_START_NONE, 1);
    boot_to_end();
    advance_to(HEARTBEAT_MS * MS);
}

/* Lost at 100 ms while waiting for the start of all. */
static void enter_lost_waiting_start(void)
{
    enter_wait_start_report();
    advance_to(HEARTBEAT_MS * MS);
}

/* Its 1000h refused: retried at 400 ms. */
static void enter_failed(void)
{
    configure(CO_NET_ON_ERROR_REBOOT, CO_NET_START_EACH, 1);
    boot_to_device_type();
    deliver("584#8000100000000206");
}

static const char *sdo_abort(uint8_t step);

/* Found, then its configuration refused: contacted with the init error (D-NET-MASTER-CONTACTED),
 * retried at 400 ms from the refusal. */
static void enter_failed_found(void)
{
    enter_download();
    deliver(sdo_abort(DOWNLOAD));
}

typedef enum situation {
    S_IDLE,
    S_WAIT_BOOT,
    S_WAIT_CLIENT,
    S_DEVICE_TYPE,
    S_DEVICE_TYPE_NO_BOOT_UP,
    S_IDENTITY,
    S_DOWNLOAD,
    S_WAIT_START,
    S_WAIT_START_REPORT,
    S_OPERATIONAL,
    S_OPERATIONAL_REPORT,
    S_OPERATIONAL_STOP_ALL,
    S_OPERATIONAL_RESET_ALL,
    S_STOPPED_ALL,
    S_LOST,
    S_LOST_FIRST_HEARTBEAT,
    S_LOST_WAITING_START,
    S_FAILED,
    S_FAILED_FOUND,
    SITUATIONS
} situation_t;

static const struct {
    const char *name;
    void (*enter)(void);
    uint8_t step; /* node 4's, once there */
    uint16_t status;
} situations[SITUATIONS] = {
    [S_IDLE] = {"idle", enter_idle, IDLE, 0x00},
    [S_WAIT_BOOT] = {"wait boot-up", enter_wait_boot, WAIT_BOOT, 0x00},
    [S_WAIT_CLIENT] = {"boot time over, client busy", enter_wait_client, WAIT_BOOT, 0x00},
    [S_DEVICE_TYPE] = {"read device type", enter_device_type, DEVICE_TYPE, 0x00},
    [S_DEVICE_TYPE_NO_BOOT_UP] = {"read device type, no boot-up yet", enter_device_type_no_boot_up,
                                  DEVICE_TYPE, 0x00},
    [S_IDENTITY] = {"read identity", enter_identity, IDENTITY, 0x00},
    [S_DOWNLOAD] = {"download", enter_download, DOWNLOAD, 0x01},
    [S_WAIT_START] = {"wait start all (reboot)", enter_wait_start_reboot, WAIT_START, 0x07},
    [S_WAIT_START_REPORT] = {"wait start all (report)", enter_wait_start_report, WAIT_START, 0x07},
    [S_OPERATIONAL] = {"operational (reboot)", enter_operational_reboot, OPERATIONAL, 0x0F},
    [S_OPERATIONAL_REPORT] = {"operational (report)", enter_operational_report, OPERATIONAL, 0x0F},
    [S_OPERATIONAL_STOP_ALL] = {"operational (stop all)", enter_operational_stop_all, OPERATIONAL,
                                0x0F},
    [S_OPERATIONAL_RESET_ALL] = {"operational (reset all)", enter_operational_reset_all,
                                 OPERATIONAL, 0x0F},
    [S_STOPPED_ALL] = {"lost, all stopped", enter_stopped_all, LOST, 0x2F},
    [S_LOST] = {"lost", enter_lost, LOST, 0x2F},
    [S_LOST_FIRST_HEARTBEAT] = {"lost, never heard", enter_lost_first_heartbeat, LOST, 0x2F},
    [S_LOST_WAITING_START] = {"lost waiting start all", enter_lost_waiting_start, LOST, 0x27},
    [S_FAILED] = {"init error", enter_failed, FAILED, 0x10},
    [S_FAILED_FOUND] = {"init error, found", enter_failed_found, FAILED, 0x11},
};

/* ---- the events ------------------------------------------------------------------------------ */

typedef enum event {
    E_BOOT_UP,   /* 704#00 */
    E_HB_PREOP,  /* heartbeat 704#7F */
    E_HB_OP,     /* heartbeat 704#05 */
    E_HB_STOP,   /* heartbeat 704#04 */
    E_SILENCE,   /* one consumer time (100 ms) without a frame of node 4: a heartbeat loss where
                  * the master consumes its heartbeat */
    E_SDO_DONE,  /* node 4 answers the request under way (a 1000h answer when there is none) */
    E_SDO_ABORT, /* node 4 aborts it (a 1000h abort when there is none) */
    E_TIMEOUT,   /* time reaches the deadline the master returned (1 s on when it was never) */
    E_START,     /* the application calls co_net_master_start */
    EVENTS
} event_t;

static const char *const event_names[EVENTS] = {
    "boot-up",    "heartbeat 7F", "heartbeat 05", "heartbeat 04", "silence",
    "SDO answer", "SDO abort",    "timeout",      "start",
};

/* What node 4 answers to the request of the step it is in. */
static const char *sdo_answer(uint8_t step)
{
    switch (step) {
    case IDENTITY:
        return "584#431810015F000000";
    case DOWNLOAD:
        return "584#6017100000000000";
    default:
        return "584#4300100092010100";
    }
}

static const char *sdo_abort(uint8_t step)
{
    switch (step) {
    case IDENTITY:
        return "584#8018100111000906"; /* 0x06090011 */
    case DOWNLOAD:
        return "584#8017100030000906"; /* 0x06090030 */
    default:
        return "584#8000100000000206"; /* 0x06020000 */
    }
}

static void happen(event_t event)
{
    static const char *const heartbeats[] = {"704#7F", "704#05", "704#04"};
    uint8_t step = co_net_master_slave(&master, 4)->step;
    switch (event) {
    case E_BOOT_UP:
        deliver("704#00");
        break;
    case E_HB_PREOP:
    case E_HB_OP:
    case E_HB_STOP:
        deliver(heartbeats[event - E_HB_PREOP]);
        break;
    case E_SILENCE:
        advance_to(bus.now + HEARTBEAT_MS * MS);
        break;
    case E_SDO_DONE:
        deliver(sdo_answer(step));
        break;
    case E_SDO_ABORT:
        deliver(sdo_abort(step));
        break;
    case E_TIMEOUT:
        advance_to(bus.deadline == CO_TIME_NEVER ? bus.now + QUIET_MS * MS : bus.deadline);
        break;
    case E_START:
        start();
        break;
    case EVENTS:
        break;
    }
}

/* The frames sent since bus.next, as "a b c" (cut at FRAMES_TEXT - 1 characters). */
static const char *frames_sent(char *text)
{
    char one[32];
    size_t used = 0;
    text[0] = '\0';
    for (size_t i = bus.next; i < bus.count && used < FRAMES_TEXT; i++)
        used += (size_t)snprintf(text + used, FRAMES_TEXT - used, "%s%s", i > bus.next ? " " : "",
                                 test_format(&bus.frame[i], one));
    return text;
}

/* ---- the table ------------------------------------------------------------------------------- */

typedef struct row {
    situation_t situation;
    event_t event;
    uint8_t step;         /* node 4's step after the event */
    uint16_t status;      /* its status word */
    const char *frames;   /* the master's frames during the event */
    uint32_t deadline_ms; /* the deadline returned after it, from the event's end; NEVER */
} row_t;

#define BOOT_AGAIN "604#4000100000000000" /* a new boot: the request for 1000h */

static const row_t rows[] = {
    /* Before co_net_master_start nothing happens. */
    {S_IDLE, E_BOOT_UP, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_HB_PREOP, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_HB_OP, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_HB_STOP, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_SILENCE, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_SDO_DONE, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_SDO_ABORT, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_TIMEOUT, IDLE, 0x00, "", NEVER},
    {S_IDLE, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Waiting for the boot-up: it, or the end of the boot time, starts the identification. */
    {S_WAIT_BOOT, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_WAIT_BOOT, E_HB_PREOP, WAIT_BOOT, 0x00, "", 300},
    {S_WAIT_BOOT, E_HB_OP, WAIT_BOOT, 0x00, "", 300},
    {S_WAIT_BOOT, E_HB_STOP, WAIT_BOOT, 0x00, "", 300},
    {S_WAIT_BOOT, E_SILENCE, WAIT_BOOT, 0x00, "", 200},
    {S_WAIT_BOOT, E_SDO_DONE, WAIT_BOOT, 0x00, "", 300},
    {S_WAIT_BOOT, E_SDO_ABORT, WAIT_BOOT, 0x00, "", 300},
    {S_WAIT_BOOT, E_TIMEOUT, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_WAIT_BOOT, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Ready, waiting for node 5 to release the SDO client: the deadline is node 5's timeout. */
    {S_WAIT_CLIENT, E_BOOT_UP, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_HB_PREOP, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_HB_OP, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_HB_STOP, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_SILENCE, DEVICE_TYPE, 0x00, "605#8017100000000405 " BOOT_AGAIN, 150},
    {S_WAIT_CLIENT, E_SDO_DONE, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_SDO_ABORT, WAIT_BOOT, 0x00, "", 50},
    {S_WAIT_CLIENT, E_TIMEOUT, DEVICE_TYPE, 0x00, "605#8017100000000405 " BOOT_AGAIN, 200},
    {S_WAIT_CLIENT, E_START, WAIT_BOOT, 0x00, "000#8204 000#8205", 300},
    /* Identification and download: a boot-up means the slave restarted and lost what it was
     * given, so its boot starts again; heartbeats are not watched yet. */
    {S_DEVICE_TYPE, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_DEVICE_TYPE, E_HB_PREOP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE, E_HB_OP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE, E_HB_STOP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE, E_SILENCE, DEVICE_TYPE, 0x00, "", 100},
    {S_DEVICE_TYPE, E_SDO_DONE, IDENTITY, 0x00, "604#4018100100000000", 200},
    {S_DEVICE_TYPE, E_SDO_ABORT, FAILED, 0x10, "", 400},
    {S_DEVICE_TYPE, E_TIMEOUT, FAILED, 0x10, "604#8000100000000405", 400},
    {S_DEVICE_TYPE, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* The boot-up awaited since the reset comes late: it is that one, not a restart, as long as
     * the slave has not answered (a node sends its boot-up before it serves SDO). */
    {S_DEVICE_TYPE_NO_BOOT_UP, E_BOOT_UP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_HB_PREOP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_HB_OP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_HB_STOP, DEVICE_TYPE, 0x00, "", 200},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_SILENCE, DEVICE_TYPE, 0x00, "", 100},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_SDO_DONE, IDENTITY, 0x00, "604#4018100100000000", 200},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_SDO_ABORT, FAILED, 0x10, "", 400},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_TIMEOUT, FAILED, 0x10, "604#8000100000000405", 400},
    {S_DEVICE_TYPE_NO_BOOT_UP, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_IDENTITY, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_IDENTITY, E_HB_PREOP, IDENTITY, 0x00, "", 200},
    {S_IDENTITY, E_HB_OP, IDENTITY, 0x00, "", 200},
    {S_IDENTITY, E_HB_STOP, IDENTITY, 0x00, "", 200},
    {S_IDENTITY, E_SILENCE, IDENTITY, 0x00, "", 100},
    {S_IDENTITY, E_SDO_DONE, DOWNLOAD, 0x01, "604#2B17100064000000", 200},
    {S_IDENTITY, E_SDO_ABORT, FAILED, 0x10, "", 400},
    {S_IDENTITY, E_TIMEOUT, FAILED, 0x10, "604#8018100100000405", 400},
    {S_IDENTITY, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_DOWNLOAD, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_DOWNLOAD, E_HB_PREOP, DOWNLOAD, 0x01, "", 200},
    {S_DOWNLOAD, E_HB_OP, DOWNLOAD, 0x01, "", 200},
    {S_DOWNLOAD, E_HB_STOP, DOWNLOAD, 0x01, "", 200},
    {S_DOWNLOAD, E_SILENCE, DOWNLOAD, 0x01, "", 100},
    {S_DOWNLOAD, E_SDO_DONE, OPERATIONAL, 0x0F, "000#0104", 100}, /* first heartbeat due */
    {S_DOWNLOAD, E_SDO_ABORT, FAILED, 0x11, "", 400},             /* contacted stays */
    {S_DOWNLOAD, E_TIMEOUT, FAILED, 0x11, "604#8017100000000405", 400},
    {S_DOWNLOAD, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Configured, waiting for the start of all; the heartbeat is watched. */
    {S_WAIT_START, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_WAIT_START, E_HB_PREOP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START, E_HB_OP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START, E_HB_STOP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START, E_SILENCE, WAIT_BOOT, 0x20, "000#8104", 200}, /* node 5's boot time */
    {S_WAIT_START, E_SDO_DONE, WAIT_START, 0x07, "", 100},
    {S_WAIT_START, E_SDO_ABORT, WAIT_START, 0x07, "", 100},
    {S_WAIT_START, E_TIMEOUT, WAIT_BOOT, 0x20, "000#8104", 200},
    {S_WAIT_START, E_START, WAIT_BOOT, 0x00, "000#8204 000#8205", 300},
    {S_WAIT_START_REPORT, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_WAIT_START_REPORT, E_HB_PREOP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START_REPORT, E_HB_OP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START_REPORT, E_HB_STOP, WAIT_START, 0x07, "", 100},
    {S_WAIT_START_REPORT, E_SILENCE, LOST, 0x27, "", 200},
    {S_WAIT_START_REPORT, E_SDO_DONE, WAIT_START, 0x07, "", 100},
    {S_WAIT_START_REPORT, E_SDO_ABORT, WAIT_START, 0x07, "", 100},
    {S_WAIT_START_REPORT, E_TIMEOUT, LOST, 0x27, "", 200},
    {S_WAIT_START_REPORT, E_START, WAIT_BOOT, 0x00, "000#8204 000#8205", 300},
    /* Running: whatever on_error says, a boot-up boots it again (its configuration is gone); a
     * loss resets it (reboot) or is only reported (report). */
    {S_OPERATIONAL, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_OPERATIONAL, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL, E_SILENCE, WAIT_BOOT, 0x20, "000#8104", 300},
    {S_OPERATIONAL, E_SDO_DONE, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL, E_SDO_ABORT, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL, E_TIMEOUT, WAIT_BOOT, 0x20, "000#8104", 300},
    {S_OPERATIONAL, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_OPERATIONAL_REPORT, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_OPERATIONAL_REPORT, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_REPORT, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_REPORT, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_REPORT, E_SILENCE, LOST, 0x2F, "", NEVER},
    {S_OPERATIONAL_REPORT, E_SDO_DONE, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_REPORT, E_SDO_ABORT, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_REPORT, E_TIMEOUT, LOST, 0x2F, "", NEVER},
    {S_OPERATIONAL_REPORT, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* A mandatory slave under 1F80h bit 6 or 4: its loss stops all nodes (the slave lost, not
     * reset) or resets all and boots the network again; anything else as in OPERATIONAL. */
    {S_OPERATIONAL_STOP_ALL, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_OPERATIONAL_STOP_ALL, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_STOP_ALL, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_STOP_ALL, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_STOP_ALL, E_SILENCE, LOST, 0x2F, "000#0200", NEVER},
    {S_OPERATIONAL_STOP_ALL, E_SDO_DONE, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_STOP_ALL, E_SDO_ABORT, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_STOP_ALL, E_TIMEOUT, LOST, 0x2F, "000#0200", NEVER},
    {S_OPERATIONAL_STOP_ALL, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_OPERATIONAL_RESET_ALL, E_BOOT_UP, DEVICE_TYPE, 0x00, BOOT_AGAIN, 200},
    {S_OPERATIONAL_RESET_ALL, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_RESET_ALL, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_RESET_ALL, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_RESET_ALL, E_SILENCE, WAIT_BOOT, 0x20, "000#8100", 300},
    {S_OPERATIONAL_RESET_ALL, E_SDO_DONE, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_RESET_ALL, E_SDO_ABORT, OPERATIONAL, 0x0F, "", 100},
    {S_OPERATIONAL_RESET_ALL, E_TIMEOUT, WAIT_BOOT, 0x20, "000#8100", 300},
    {S_OPERATIONAL_RESET_ALL, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Every node stopped by the loss: a heartbeat resumes the slave (the network stays stopped
     * until the application starts it); a boot-up boots it again. */
    {S_STOPPED_ALL, E_BOOT_UP, DEVICE_TYPE, 0x20, BOOT_AGAIN, 200},
    {S_STOPPED_ALL, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_STOPPED_ALL, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_STOPPED_ALL, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_STOPPED_ALL, E_SILENCE, LOST, 0x2F, "", NEVER},
    {S_STOPPED_ALL, E_SDO_DONE, LOST, 0x2F, "", NEVER},
    {S_STOPPED_ALL, E_SDO_ABORT, LOST, 0x2F, "", NEVER},
    {S_STOPPED_ALL, E_TIMEOUT, LOST, 0x2F, "", NEVER},
    {S_STOPPED_ALL, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Lost (report): any heartbeat resumes it where it was lost from; a boot-up boots it. */
    {S_LOST, E_BOOT_UP, DEVICE_TYPE, 0x20, BOOT_AGAIN, 200},
    {S_LOST, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST, E_SILENCE, LOST, 0x2F, "", NEVER},
    {S_LOST, E_SDO_DONE, LOST, 0x2F, "", NEVER},
    {S_LOST, E_SDO_ABORT, LOST, 0x2F, "", NEVER},
    {S_LOST, E_TIMEOUT, LOST, 0x2F, "", NEVER},
    {S_LOST, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_LOST_FIRST_HEARTBEAT, E_BOOT_UP, DEVICE_TYPE, 0x20, BOOT_AGAIN, 200},
    {S_LOST_FIRST_HEARTBEAT, E_HB_PREOP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST_FIRST_HEARTBEAT, E_HB_OP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST_FIRST_HEARTBEAT, E_HB_STOP, OPERATIONAL, 0x0F, "", 100},
    {S_LOST_FIRST_HEARTBEAT, E_SILENCE, LOST, 0x2F, "", NEVER},
    {S_LOST_FIRST_HEARTBEAT, E_SDO_DONE, LOST, 0x2F, "", NEVER},
    {S_LOST_FIRST_HEARTBEAT, E_SDO_ABORT, LOST, 0x2F, "", NEVER},
    {S_LOST_FIRST_HEARTBEAT, E_TIMEOUT, LOST, 0x2F, "", NEVER},
    {S_LOST_FIRST_HEARTBEAT, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    {S_LOST_WAITING_START, E_BOOT_UP, DEVICE_TYPE, 0x20, BOOT_AGAIN, 200},
    {S_LOST_WAITING_START, E_HB_PREOP, WAIT_START, 0x07, "", 100},
    {S_LOST_WAITING_START, E_HB_OP, WAIT_START, 0x07, "", 100},
    {S_LOST_WAITING_START, E_HB_STOP, WAIT_START, 0x07, "", 100},
    {S_LOST_WAITING_START, E_SILENCE, LOST, 0x27, "", 100},
    {S_LOST_WAITING_START, E_SDO_DONE, LOST, 0x27, "", 200},
    {S_LOST_WAITING_START, E_SDO_ABORT, LOST, 0x27, "", 200},
    {S_LOST_WAITING_START, E_TIMEOUT, LOST, 0x27, "605#4000100000000000", 200}, /* node 5 */
    {S_LOST_WAITING_START, E_START, WAIT_BOOT, 0x00, "000#8204 000#8205", 300},
    /* Init error: a boot-up boots it at once, otherwise the retry delay runs; bit 4 stays. */
    {S_FAILED, E_BOOT_UP, DEVICE_TYPE, 0x10, BOOT_AGAIN, 200},
    {S_FAILED, E_HB_PREOP, FAILED, 0x10, "", 400},
    {S_FAILED, E_HB_OP, FAILED, 0x10, "", 400},
    {S_FAILED, E_HB_STOP, FAILED, 0x10, "", 400},
    {S_FAILED, E_SILENCE, FAILED, 0x10, "", 300},
    {S_FAILED, E_SDO_DONE, FAILED, 0x10, "", 400},
    {S_FAILED, E_SDO_ABORT, FAILED, 0x10, "", 400},
    {S_FAILED, E_TIMEOUT, WAIT_BOOT, 0x10, "000#8204", 300},
    {S_FAILED, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
    /* Found, then refused: as above; contacted holds until the slave restarts or is reset. */
    {S_FAILED_FOUND, E_BOOT_UP, DEVICE_TYPE, 0x10, BOOT_AGAIN, 200},
    {S_FAILED_FOUND, E_HB_PREOP, FAILED, 0x11, "", 400},
    {S_FAILED_FOUND, E_HB_OP, FAILED, 0x11, "", 400},
    {S_FAILED_FOUND, E_HB_STOP, FAILED, 0x11, "", 400},
    {S_FAILED_FOUND, E_SILENCE, FAILED, 0x11, "", 300},
    {S_FAILED_FOUND, E_SDO_DONE, FAILED, 0x11, "", 400},
    {S_FAILED_FOUND, E_SDO_ABORT, FAILED, 0x11, "", 400},
    {S_FAILED_FOUND, E_TIMEOUT, WAIT_BOOT, 0x10, "000#8204", 300},
    {S_FAILED_FOUND, E_START, WAIT_BOOT, 0x00, "000#8204", 300},
};

#define ROWS (sizeof(rows) / sizeof(rows[0]))

START_TEST(every_event_in_every_situation)
{
    const row_t *row = &rows[_i];
    const char *where = situations[row->situation].name;
    const char *what = event_names[row->event];
    situations[row->situation].enter();
    const co_net_slave_t *s = co_net_master_slave(&master, 4);
    ck_assert_msg(s->step == situations[row->situation].step &&
                      s->status == situations[row->situation].status,
                  "%s: reached step %s, status 0x%02X", where, co_net_step_text(s->step),
                  s->status);
    bus.next = bus.count;
    happen(row->event);
    char sent[FRAMES_TEXT];
    ck_assert_msg(strcmp(frames_sent(sent), row->frames) == 0, "%s, %s: sent \"%s\", not \"%s\"",
                  where, what, sent, row->frames);
    ck_assert_msg(s->step == row->step, "%s, %s: step %s, not %s", where, what,
                  co_net_step_text(s->step), co_net_step_text(row->step));
    ck_assert_msg(s->status == row->status, "%s, %s: status 0x%02X, not 0x%02X", where, what,
                  s->status, row->status);
    co_time_t deadline =
        row->deadline_ms == NEVER ? CO_TIME_NEVER : bus.now + (co_time_t)row->deadline_ms * MS;
    ck_assert_msg(bus.deadline == deadline, "%s, %s: deadline %lld us from now, not %lld", where,
                  what, (long long)(bus.deadline - bus.now), (long long)(deadline - bus.now));
}
END_TEST

/* Every situation meets every event, each once. */
START_TEST(the_table_is_complete)
{
    bool seen[SITUATIONS][EVENTS] = {{false}};
    for (size_t r = 0; r < ROWS; r++) {
        ck_assert_msg(!seen[rows[r].situation][rows[r].event], "row %zu twice", r);
        seen[rows[r].situation][rows[r].event] = true;
    }
    ck_assert_uint_eq(ROWS, (size_t)SITUATIONS * EVENTS);
}
END_TEST

/* ---- issue 22, frame by frame ---------------------------------------------------------------- */

#define expect(text) expect_at(text, __LINE__)
static void expect_at(const char *text, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(bus.next < bus.count, "line %d: expected %s, the master sent nothing", line,
                  want);
    test_format(&bus.frame[bus.next++], got);
    ck_assert_msg(strcmp(want, got) == 0, "line %d: expected %s, got %s", line, want, got);
}

/* Item 2: a slave that restarts while its configuration is written has lost the writes already
 * made; its boot starts again from 1000h and it is configured anew before it is reported so. */
START_TEST(reboot_during_download_boots_again)
{
    enter_download();
    bus.next = bus.count;
    bus.now = 20 * MS;
    deliver("704#00"); /* instead of the answer to the 1017h write */
    expect("604#4000100000000000");
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x00);
    ck_assert_uint_eq(bus.deadline, (20 + SDO_TIMEOUT_MS) * MS);
    deliver("584#4300100092010100");
    expect("604#4018100100000000");
    deliver("584#431810015F000000");
    expect("604#2B17100064000000");
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x01);
    deliver("584#6017100000000000");
    expect("000#0104");
    ck_assert_uint_eq(bus.count, bus.next);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(bus.deadline, (20 + HEARTBEAT_MS) * MS);
}
END_TEST

/* Item 3: with the report reaction and no start by the master, a slave lost for lack of its first
 * heartbeat resumes with the first one, though it reports the state the master already knew. */
START_TEST(lost_before_its_first_heartbeat_resumes)
{
    enter_lost_first_heartbeat();
    ck_assert_uint_eq(co_net_master_status(&master), 0x2F);
    bus.now = 250 * MS;
    deliver("704#7F");
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, OPERATIONAL);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
    ck_assert_uint_eq(bus.deadline, (250 + HEARTBEAT_MS) * MS);
    advance_to(350 * MS); /* and is watched again */
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x2F);
}
END_TEST

/* Item 4: start all with the report reaction; the mandatory slave is late with its heartbeat while
 * it waits for the start. Heard again, it waits again, and the start of all goes out when node 5
 * is configured. */
START_TEST(late_heartbeat_while_waiting_does_not_block_start_all)
{
    enter_lost_waiting_start();
    bus.next = bus.count;
    bus.now = 150 * MS;
    deliver("704#7F");
    ck_assert_uint_eq(co_net_master_slave(&master, 4)->step, WAIT_START);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x07);
    deliver("705#00");
    expect("605#4000100000000000");
    deliver("585#4300100092010100");
    expect("605#2B17100064000000");
    deliver("585#6017100000000000");
    expect("000#0100");
    ck_assert_uint_eq(bus.count, bus.next);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 4), 0x0F);
    ck_assert_uint_eq(co_net_master_slave_status(&master, 5), 0x0F);
    ck_assert_uint_eq(co_net_master_status(&master), 0x0F);
}
END_TEST

static Suite *net_master_states_suite(void)
{
    Suite *s = suite_create("net_master_states");
    TCase *tc = tcase_create("net_master_states");
    tcase_add_loop_test(tc, every_event_in_every_situation, 0, (int)ROWS);
    tcase_add_test(tc, the_table_is_complete);
    tcase_add_test(tc, reboot_during_download_boots_again);
    tcase_add_test(tc, lost_before_its_first_heartbeat_resumes);
    tcase_add_test(tc, late_heartbeat_while_waiting_does_not_block_start_all);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(net_master_states_suite());
}
