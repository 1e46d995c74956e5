/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the network master (src/canopen/master/net/, with the SDO client
 * and the NMT master under it): a master of up to three slaves, nodes 1..3, configured by the
 * input's header, fed the slaves' frames (boot-ups, heartbeats, guarding replies, SDO answers,
 * EMCYs, input PDOs) and time steps (steps.h), driven the way a runtime drives it (process after
 * every frame and at every deadline), and held to invariants of its own (docs/fuzzing.md).
 * Input: a header of 9 bytes, then steps:
 *
 *     header[0]:  bits 0-1 the start (0 each, 1 all, 2 none, 3 each), bit 2 reset all, bit 3 SYNC
 *                 every 10 ms, bit 4 a process image, bits 5-6 the slaves (1 + value mod 3), bit 7
 *                 a mandatory slave's error control event is the network's (1F80h bit 6, stop
 *                 all, or with header[1] bit 7 bit 4, reset all)
 *     header[1]:  bits 0-6 the boot time, header[2] the retry delay, both in 50 ms
 *     per slave:  flags (bit 0 mandatory, bit 1 "report" (else "reboot"), bits 2-3 error
 *                 control (0 none, 1 and 3 heartbeat, 2 guarding), bits 4-5 how many of the
 *                 three configuration writes, bits 6-7 the identity checked (0 nothing, 1 the
 *                 device type, 2 and vendor and product, 3 and revision and serial)), then the
 *                 heartbeat consumer time or guard time in 10 ms (0: none)
 *     E0h..EBh:   co_net_master_write_output: (tag & 0Fh) bytes at the offset in the next byte,
 *                 the bytes following
 *     ECh, EDh:   co_net_master_disable, co_net_master_enable
 *     EEh:        co_net_master_nmt: the command (a byte: its index in start, stop, preop, reset
 *                 node, reset communication, mod 5), the node (a byte: 0 all, else a slave of
 *                 the table), a timeout of (byte + 1) x 10 ms
 *     EFh:        co_net_master_sdo: a slave of the table (a byte), read (bit 0 of the next byte
 *                 clear) of 1018h:01, or write of 6060h = 2, each of 4 bytes
 *
 * The start and the network's reaction reach the master as its 1F80h, each slave's assignment,
 * guard time and factor as its 1F81h (co_net_master_config_from_1f80, _slave_config_from_1f81).
 * fuzz/seeds.py writes the seeds from readable frames. */
#include "co/co_net_master.h"
#include "rig.h"
#include "steps.h"

#include <string.h>

#define SLAVES_MAX 3
#define MASTER_HEADER 3
#define SLAVE_HEADER 2
#define HEADER_SIZE (MASTER_HEADER + SLAVES_MAX * SLAVE_HEADER)
/* header[0] */
#define START_MASK 0x03u
#define RESET_ALL 0x04u
#define SYNC 0x08u
#define PROCESS_IMAGE 0x10u
#define SLAVES_SHIFT 5
#define NETWORK_REACTION 0x80u
/* header[1] */
#define REACTION_RESET_ALL 0x80u
#define BOOT_TIME_MASK 0x7Fu
/* A slave's flags. */
#define MANDATORY 0x01u
#define REPORT 0x02u
#define CONTROL_SHIFT 2
#define WRITES_SHIFT 4
#define CHECK_SHIFT 6
#define SDO_TIMEOUT_MS 50
#define SLOW_UNIT_MS 50u /* boot time, retry delay */
#define FAST_UNIT_MS 10u /* heartbeat and guard times */
#define LIFE_TIME_FACTOR 3
#define SYNC_PERIOD_US 10000u
#define IMAGE_SIZE 8
#define STATUS_PROGRESS                                                                            \
    (CO_NET_SLAVE_CONTACTED | CO_NET_SLAVE_CONFIGURED | CO_NET_SLAVE_EC_STARTED |                  \
     CO_NET_SLAVE_INIT_DONE)
/* As in rig.c, deadlines handled one by one within a time step, then the rig wakes up late; fewer:
 * each call runs the NMT master over its 127 nodes. */
#define DEADLINES_PER_STEP 16
/* The commands of the application above the writes of the output image (tag & 0Fh). */
#define COMMAND_DISABLE 0x0Cu
#define COMMAND_ENABLE 0x0Du
#define COMMAND_NMT 0x0Eu
#define COMMAND_SDO 0x0Fu

enum { EC_NONE, EC_HEARTBEAT, EC_GUARDING };

static const uint32_t device_type = 0x00020192;
static const uint32_t identity[CO_NET_IDENTITY_SUBS] = {0x5F, 0x312, 0x00010001, 0x12345678};
static const uint8_t checks[4] = {
    0,
    CO_NET_CHECK_DEVICE_TYPE,
    CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR | CO_NET_CHECK_PRODUCT,
    CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR | CO_NET_CHECK_PRODUCT | CO_NET_CHECK_REVISION |
        CO_NET_CHECK_SERIAL,
};
static const uint8_t heartbeat_100ms[] = {0x64, 0x00};
static const uint8_t velocity_mode[] = {0x02};
static const uint8_t long_value[] = "ATV312 dcf"; /* 11 bytes: a segmented download */
static const co_net_write_t writes[] = {
    {0x1017, 0, heartbeat_100ms, sizeof heartbeat_100ms},
    {0x6060, 0, velocity_mode, sizeof velocity_mode},
    {0x2001, 0, long_value, sizeof long_value},
};
static const co_net_pdo_t input_pdos[SLAVES_MAX] = {
    {1, 0x181, 2, 0}, {2, 0x182, 4, 2}, {3, 0x183, 2, 6}};
static const co_net_pdo_t output_pdos[SLAVES_MAX] = {
    {1, 0x201, 2, 0}, {2, 0x202, 4, 2}, {3, 0x203, 3, 5}};

static struct harness {
    co_net_master_t master;
    co_net_master_config_t config;
    co_net_slave_config_t slaves[SLAVES_MAX];
    co_net_slave_t state[SLAVES_MAX];
    uint8_t error_control[SLAVES_MAX];
    uint8_t input_image[IMAGE_SIZE];
    uint8_t output_image[IMAGE_SIZE];
    co_time_t now;
    /* What the harness saw of each slave. */
    uint8_t step[SLAVES_MAX];     /* as the last STEP event told it */
    uint16_t status[SLAVES_MAX];  /* as the last STATUS event told it */
    bool started[SLAVES_MAX];     /* an NMT start reached it since its last reset or boot-up */
    bool rebooted[SLAVES_MAX];    /* it booted (lost its writes) since its first write went out */
    bool started_all;             /* the start-all command was sent */
    bool application_started_all; /* the application's own start of all was sent */
    co_time_t heard[SLAVES_MAX];  /* heartbeat: error control started, or its last heartbeat */
    /* co_net_master_write_output under way: the frames it must send. */
    bool writing;
    co_frame_t expected[SLAVES_MAX];
    size_t expected_count, matched;
    /* The application's requests. */
    size_t requests_queued, requests_done;
    uint8_t request_buffer[CO_NET_REQUEST_MAX][4];
} h;

/* The slave of `node_id`, SLAVES_MAX when it is not one. */
static size_t slave_of(uint32_t node_id)
{
    for (size_t i = 0; i < h.config.slave_count; i++) {
        if (h.slaves[i].node_id == node_id)
            return i;
    }
    return SLAVES_MAX;
}

static bool configuring(uint8_t step)
{
    return step == CO_NET_STEP_DEVICE_TYPE || step == CO_NET_STEP_IDENTITY ||
           step == CO_NET_STEP_DOWNLOAD;
}

/* The command of co_net_master_nmt under way, sent just now. */
static bool application_nmt(uint8_t command, uint8_t node_id)
{
    const co_net_nmt_request_t *r = &h.master.nmt_request;
    return r->pending && r->command == command && r->node_id == node_id;
}

static void check_nmt_command(const co_frame_t *frame)
{
    uint8_t command = frame->data[0], node_id = frame->data[1];
    rig_check(frame->len == 2, "an NMT command that is not 2 bytes");
    /* The application's own command: a start starts; after any other the master, which does not
     * check the state a slave reports, keeps it where it was. */
    if (application_nmt(command, node_id)) {
        for (size_t i = 0; i < h.config.slave_count; i++) {
            if (node_id == CO_NMT_MASTER_ALL_NODES || node_id == h.slaves[i].node_id)
                h.started[i] = h.started[i] || command == CO_NMT_CS_START;
        }
        /* The same frame as the master's own start of all: either one has started them. */
        if (command == CO_NMT_CS_START && node_id == CO_NMT_MASTER_ALL_NODES)
            h.application_started_all = true;
        return;
    }
    rig_check(command == CO_NMT_CS_START || command == CO_NMT_CS_STOP ||
                  command == CO_NMT_CS_RESET_NODE || command == CO_NMT_CS_RESET_COMMUNICATION,
              "an NMT command the master has no use for");
    /* Only 1F80h's reaction to a mandatory slave's loss stops all nodes or resets them all. */
    rig_check(command != CO_NMT_CS_STOP ||
                  (node_id == CO_NMT_MASTER_ALL_NODES &&
                   h.config.on_mandatory_error == CO_NET_MANDATORY_STOP_ALL),
              "an NMT stop without 1F80h bit 6");
    rig_check(command != CO_NMT_CS_RESET_NODE || node_id != CO_NMT_MASTER_ALL_NODES ||
                  h.config.on_mandatory_error == CO_NET_MANDATORY_RESET_ALL,
              "a reset of all nodes without 1F80h bit 4");
    /* ... which boots the network again: a new start of all may go. */
    if (command == CO_NMT_CS_RESET_NODE && node_id == CO_NMT_MASTER_ALL_NODES)
        h.started_all = h.application_started_all = false;
    rig_check(node_id == CO_NMT_MASTER_ALL_NODES || slave_of(node_id) < SLAVES_MAX,
              "an NMT command to a node not in the table");
    if (command == CO_NMT_CS_START) {
        rig_check(h.config.start != CO_NET_START_NONE,
                  "an NMT start with the start left to the user");
        rig_check(node_id != CO_NMT_MASTER_ALL_NODES || h.config.start == CO_NET_START_ALL,
                  "a start of all nodes without CO_NET_START_ALL");
        rig_check(node_id != CO_NMT_MASTER_ALL_NODES || !h.started_all, "two starts of all nodes");
        h.started_all = h.started_all || node_id == CO_NMT_MASTER_ALL_NODES;
    }
    /* A stop leaves a slave's start standing: the master keeps its step (docs/net-master.md). */
    for (size_t i = 0; i < h.config.slave_count && command != CO_NMT_CS_STOP; i++) {
        if (node_id == CO_NMT_MASTER_ALL_NODES || node_id == h.slaves[i].node_id)
            h.started[i] = command == CO_NMT_CS_START;
    }
}

/* An SDO request goes to the slave being configured; an abort may end the transfer of one that
 * left that step. A download of the first write starts the slave's configuration over. */
static void check_sdo_request(const co_frame_t *frame, size_t i)
{
    uint8_t ccs = frame->data[0] & CO_SDO_CS_MASK;
    rig_check(frame->len == 8, "an SDO request that is not 8 bytes");
    if (frame->data[0] == CO_SDO_COMMAND(CO_SDO_CS_ABORT))
        return;
    if (h.master.serving) {
        rig_check(h.master.requests[0].node_id == h.slaves[i].node_id,
                  "an SDO request of the application to another node than asked");
        return;
    }
    rig_check(configuring(h.state[i].step),
              "an SDO request to a slave that is not being configured");
    bool download = ccs == CO_SDO_COMMAND(CO_SDO_CCS_DOWNLOAD_INITIATE) ||
                    ccs == CO_SDO_COMMAND(CO_SDO_CCS_BLOCK_DOWNLOAD);
    if (download && co_get_u16(&frame->data[1]) == writes[0].index &&
        frame->data[3] == writes[0].subindex)
        h.rebooted[i] = false;
}

static bool same_frame(const co_frame_t *a, const co_frame_t *b)
{
    return a->id == b->id && a->len == b->len && a->flags == b->flags &&
           memcmp(a->data, b->data, a->len) == 0;
}

/* An output PDO: to an operational slave, the bytes of the output image (or, inside
 * co_net_master_write_output, the ones the write makes). */
static bool check_output(const co_frame_t *frame)
{
    for (size_t p = 0; p < h.config.output_count; p++) {
        const co_net_pdo_t *pdo = &h.config.outputs[p];
        if (pdo->can_id != frame->id)
            continue;
        rig_check(h.state[slave_of(pdo->node_id)].step == CO_NET_STEP_OPERATIONAL,
                  "an output PDO to a slave that is not operational");
        rig_check(!h.master.stopped_all, "an output PDO from a master stopped with all nodes");
        rig_check(frame->len == pdo->len, "an output PDO of another length than its own");
        if (h.writing) {
            rig_check(h.matched < h.expected_count && same_frame(frame, &h.expected[h.matched]),
                      "an output PDO whose bytes did not change, or with other bytes");
            h.matched++;
        } else {
            rig_check(memcmp(frame->data, h.output_image + pdo->offset, pdo->len) == 0,
                      "an output PDO that is not the output image");
        }
        return true;
    }
    return false;
}

static void on_send(void *user, const co_frame_t *frame)
{
    (void)user;
    rig_check(frame->len <= CO_FRAME_DLC_MAX && frame->id <= CO_COB_ID_CAN_ID &&
                  !(frame->flags & CO_FRAME_EFF),
              "a frame that is not a classic 11-bit CAN frame");
    bool rtr = (frame->flags & CO_FRAME_RTR) != 0;
    size_t sdo = slave_of(frame->id - CO_CAN_ID_SDO_RX);
    size_t guarded = slave_of(frame->id - CO_CAN_ID_ERROR_CONTROL);
    rig_check(!h.master.disabled, "a frame while the communication is disabled");
    if (guarded < SLAVES_MAX && rtr && h.error_control[guarded] != EC_GUARDING) {
        rig_check(co_net_master_nmt_awaited(&h.master, h.slaves[guarded].node_id) &&
                      frame->len == 1,
                  "a guarding request to a slave neither guarded nor asked for its state");
    } else if (frame->id == CO_CAN_ID_NMT && !rtr) {
        check_nmt_command(frame);
    } else if (sdo < SLAVES_MAX && !rtr) {
        check_sdo_request(frame, sdo);
    } else if (guarded < SLAVES_MAX && rtr) {
        rig_check(h.error_control[guarded] == EC_GUARDING && frame->len == 1,
                  "a guarding request to a slave that is not guarded");
    } else if (frame->id == CO_CAN_ID_SYNC && !rtr) {
        rig_check(h.config.sync_period_us != 0 && frame->len == 0, "a SYNC not configured");
        rig_check(!h.master.stopped_all, "a SYNC from a master stopped with all nodes");
    } else {
        rig_check(!rtr && check_output(frame), "a frame the master has no reason to send");
    }
}

static void on_event(void *user, const co_net_event_t *event)
{
    (void)user;
    if (event->kind == CO_NET_EVENT_NMT_DONE) {
        rig_check(!h.master.nmt_request.pending, "an NMT command ended that still awaits");
        return;
    }
    if (event->kind == CO_NET_EVENT_STARTED) {
        rig_check((h.started_all || h.application_started_all) && event->node_id == 0,
                  "a start-all event without the command");
        return;
    }
    size_t i = slave_of(event->node_id);
    rig_check(i < SLAVES_MAX, "an event of a node not in the table");
    const co_net_slave_t *s = &h.state[i];
    switch (event->kind) {
    case CO_NET_EVENT_STEP:
        rig_check(s->step != h.step[i], "a step event without a new step");
        h.step[i] = s->step;
        break;
    case CO_NET_EVENT_STATUS:
        rig_check(s->status != h.status[i], "a status event without a new status");
        if ((s->status & CO_NET_SLAVE_EC_STARTED) && !(h.status[i] & CO_NET_SLAVE_EC_STARTED))
            h.heard[i] = h.now;
        h.status[i] = s->status;
        break;
    case CO_NET_EVENT_SDO_ERROR:
        rig_check(h.master.last_sdo_error.node_id == event->node_id &&
                      (h.master.last_sdo_error.access == CO_NET_ACCESS_READ ||
                       h.master.last_sdo_error.access == CO_NET_ACCESS_WRITE),
                  "an SDO error event without its record");
        break;
    case CO_NET_EVENT_EMCY:
        rig_check(h.master.last_emcy.node_id == event->node_id, "an EMCY event without its record");
        break;
    case CO_NET_EVENT_INPUT:
        rig_check(event->pdo < h.config.input_count &&
                      h.config.inputs[event->pdo].node_id == event->node_id,
                  "an input event of another PDO");
        break;
    default:
        rig_check(false, "an event of an unknown kind");
    }
}

/* The status word says what the step is (docs/net-master.md, "Status words"). */
static void check_slave(size_t i)
{
    const co_net_slave_t *s = &h.state[i];
    uint16_t st = s->status;
    rig_check(s->step == h.step[i] && st == h.status[i], "a step or status change not reported");
    rig_check(s->step != CO_NET_STEP_IDLE || h.master.disabled,
              "a slave idle after the start, communication enabled");
    rig_check(!(st & CO_NET_SLAVE_CONFIGURED) || (st & CO_NET_SLAVE_CONTACTED),
              "configured without being contacted");
    rig_check(!(st & CO_NET_SLAVE_EC_STARTED) || (st & CO_NET_SLAVE_CONFIGURED),
              "error control started before the configuration");
    rig_check(!(st & CO_NET_SLAVE_INIT_DONE) || (st & STATUS_PROGRESS) == STATUS_PROGRESS,
              "init done without contact, configuration and error control");
    rig_check(!(st & CO_NET_SLAVE_INIT_DONE) || !(st & CO_NET_SLAVE_INIT_ERROR),
              "init done and init error at once");
    switch (s->step) {
    case CO_NET_STEP_IDLE:
        rig_check(st == 0, "a slave idle with status bits (disabling clears them)");
        break;
    case CO_NET_STEP_WAIT_BOOT:
    case CO_NET_STEP_DEVICE_TYPE:
    case CO_NET_STEP_IDENTITY:
        rig_check(!(st & STATUS_PROGRESS), "a slave booting with the bits of an earlier boot");
        break;
    case CO_NET_STEP_DOWNLOAD:
        rig_check((st & STATUS_PROGRESS) == CO_NET_SLAVE_CONTACTED,
                  "a slave being configured that is not just contacted");
        break;
    case CO_NET_STEP_WAIT_START:
        rig_check((st & STATUS_PROGRESS) == (STATUS_PROGRESS & ~CO_NET_SLAVE_INIT_DONE),
                  "a slave waiting for the start that is not configured, or already done");
        break;
    case CO_NET_STEP_OPERATIONAL:
        rig_check((st & CO_NET_SLAVE_INIT_DONE) != 0, "operational without init done");
        rig_check(h.config.start == CO_NET_START_NONE || h.started[i],
                  "operational without an NMT start since its reset or boot-up");
        break;
    case CO_NET_STEP_FAILED:
        /* Contacted may stay: found, then its configuration failed (D-NET-MASTER-CONTACTED). */
        rig_check((st & CO_NET_SLAVE_INIT_ERROR) &&
                      !(st & STATUS_PROGRESS & ~CO_NET_SLAVE_CONTACTED),
                  "a failed slave without init error, or with the bits of progress");
        break;
    case CO_NET_STEP_LOST:
        rig_check((st & CO_NET_SLAVE_EC_ERROR) && (st & CO_NET_SLAVE_CONFIGURED),
                  "a lost slave without the error control error, or not configured");
        break;
    default:
        rig_check(false, "a slave in an unknown step");
    }
    rig_check(!h.rebooted[i] || !(st & CO_NET_SLAVE_CONFIGURED),
              "configured without every write since its boot-up");
    /* Bit 5 says that the slave's error control failed, ec_error which one: its own
     * (D-NET-MASTER-EC-KIND), and none while the bit is clear. */
    uint8_t kind =
        h.error_control[i] == EC_GUARDING ? CO_NET_EC_ERROR_GUARDING : CO_NET_EC_ERROR_HEARTBEAT;
    rig_check(s->ec_error == ((st & CO_NET_SLAVE_EC_ERROR) ? kind : CO_NET_EC_ERROR_NONE),
              "the kind of error control failure is not that of the slave's bit 5");
}

/* A slave under heartbeat whose consumer time passed in silence is not reported healthy. */
static void check_heard(size_t i)
{
    const co_net_slave_t *s = &h.state[i];
    bool running = s->step == CO_NET_STEP_OPERATIONAL || s->step == CO_NET_STEP_WAIT_START;
    if (h.error_control[i] != EC_HEARTBEAT || !running || (s->status & CO_NET_SLAVE_EC_ERROR))
        return;
    co_time_t consumer_us = (co_time_t)h.slaves[i].heartbeat_ms * 1000u;
    rig_check(h.now < h.heard[i] + consumer_us, "a slave silent past its heartbeat time not lost");
}

/* After a process: the SDO client is not left idle while a slave waits for it (a transfer of the
 * application under way may hold it). */
static void check_sdo_client_used(void)
{
    if (h.master.serving)
        return;
    for (size_t i = 0; i < h.config.slave_count; i++) {
        if (configuring(h.state[i].step))
            return;
    }
    for (size_t i = 0; i < h.config.slave_count; i++) {
        const co_net_slave_t *s = &h.state[i];
        rig_check(s->step != CO_NET_STEP_WAIT_BOOT || (!s->booted && h.now < s->deadline),
                  "a slave whose turn came waits with the SDO client free");
    }
}

static void check_master(void)
{
    size_t busy = 0;
    for (size_t i = 0; i < h.config.slave_count; i++) {
        check_slave(i);
        if (configuring(h.state[i].step)) {
            busy++;
            rig_check(co_sdo_client_busy(&h.master.sdo) &&
                          h.master.sdo.request_id == CO_CAN_ID_SDO_RX + h.slaves[i].node_id,
                      "a slave being configured without the SDO client");
        }
    }
    rig_check(busy <= 1, "two slaves configured at once over one SDO client");
    rig_check(busy == 0 || !h.master.serving, "a slave configured during a request's transfer");
    rig_check(h.requests_done + h.master.request_count == h.requests_queued,
              "a request of the application lost, or ended twice");
    rig_check(!h.master.disabled || co_net_master_status(&h.master) == CO_NET_MASTER_DISABLED,
              "a disabled master with another status than bit 15");
    rig_check(h.master.last_sdo_error.node_id == 0 ||
                  slave_of(h.master.last_sdo_error.node_id) < SLAVES_MAX,
              "an SDO error of a node not in the table");
    rig_check(h.master.last_emcy.node_id == 0 || slave_of(h.master.last_emcy.node_id) < SLAVES_MAX,
              "an EMCY recorded of a node not in the table");
}

/* As the runtime does after every frame and at every deadline: it sleeps until the deadline. */
static co_time_t process(void)
{
    co_time_t next = co_net_master_process(&h.master, h.now);
    rig_check(next > h.now, "a deadline not in the future");
    check_master();
    check_sdo_client_used();
    for (size_t i = 0; i < h.config.slave_count; i++)
        check_heard(i);
    return next;
}

static bool boot_up(const co_frame_t *frame, size_t i)
{
    return i < SLAVES_MAX && frame->len == 1 && frame->data[0] == 0 && !frame->flags;
}

static bool heartbeat(const co_frame_t *frame, size_t i)
{
    uint8_t state = frame->data[0] & CO_NMT_STATE_MASK;
    return i < SLAVES_MAX && h.error_control[i] == EC_HEARTBEAT && frame->len == 1 &&
           !frame->flags &&
           (state == CO_NMT_STOPPED || state == CO_NMT_OPERATIONAL ||
            state == CO_NMT_PRE_OPERATIONAL);
}

/* A slave's boot-up says that it lost the writes of its configuration and its start. */
static void note_boot_up(size_t i)
{
    h.rebooted[i] = h.slaves[i].write_count > 0;
    h.started[i] = false;
}

static void deliver(const co_frame_t *frame)
{
    size_t from = slave_of(frame->id - CO_CAN_ID_ERROR_CONTROL);
    bool lost = from < SLAVES_MAX && h.state[from].step == CO_NET_STEP_LOST;
    if (boot_up(frame, from))
        note_boot_up(from);
    if (boot_up(frame, from) || heartbeat(frame, from))
        h.heard[from] = h.now;
    co_net_master_receive(&h.master, frame, h.now);
    /* A lost slave heard again is no longer lost (docs/net-master.md, "report"). */
    if (lost && heartbeat(frame, from))
        rig_check(h.state[from].step != CO_NET_STEP_LOST &&
                      !(h.state[from].status & CO_NET_SLAVE_EC_ERROR),
                  "a lost slave still lost when its heartbeat comes again");
    for (size_t p = 0; p < h.config.input_count && !h.master.disabled; p++) {
        const co_net_pdo_t *pdo = &h.config.inputs[p];
        if (pdo->can_id == frame->id && frame->len >= pdo->len && !frame->flags)
            rig_check(memcmp(h.input_image + pdo->offset, frame->data, pdo->len) == 0,
                      "an input PDO not copied to the input image");
    }
}

static void advance(co_time_t us, co_time_t *deadline)
{
    co_time_t end = h.now + us;
    for (int i = 0; i < DEADLINES_PER_STEP && *deadline <= end; i++) {
        h.now = *deadline;
        *deadline = process();
    }
    h.now = end;
    *deadline = process();
}

/* The frames co_net_master_write_output must send: each output PDO of an operational slave whose
 * bytes the write changes, with the new bytes. */
static void expect_outputs(size_t offset, const uint8_t *data, size_t len)
{
    h.expected_count = h.matched = 0;
    for (size_t p = 0; p < h.config.output_count && !h.master.stopped_all; p++) {
        const co_net_pdo_t *pdo = &h.config.outputs[p];
        if (h.state[slave_of(pdo->node_id)].step != CO_NET_STEP_OPERATIONAL)
            continue;
        co_frame_t frame = {.id = pdo->can_id, .len = pdo->len};
        memcpy(frame.data, h.output_image + pdo->offset, pdo->len);
        for (size_t k = 0; k < pdo->len; k++) {
            size_t at = (size_t)pdo->offset + k;
            if (at >= offset && at < offset + len)
                frame.data[k] = data[at - offset];
        }
        if (memcmp(frame.data, h.output_image + pdo->offset, pdo->len) != 0)
            h.expected[h.expected_count++] = frame;
    }
}

static void write_output(size_t offset, const uint8_t *data, size_t len)
{
    bool fits = h.config.output_image != NULL && offset <= h.config.output_size &&
                len <= h.config.output_size - offset;
    uint8_t before[IMAGE_SIZE];
    memcpy(before, h.output_image, sizeof before);
    if (fits)
        expect_outputs(offset, data, len);
    else
        h.expected_count = h.matched = 0;
    h.writing = true;
    bool written = co_net_master_write_output(&h.master, offset, data, len);
    h.writing = false;
    rig_check(written == fits, "a write of the output image refused inside it, or done outside it");
    rig_check(h.matched == h.expected_count, "an output PDO whose bytes changed not sent");
    if (fits && len > 0)
        memcpy(before + offset, data, len);
    rig_check(memcmp(before, h.output_image, sizeof before) == 0,
              "an output image other than the one written");
    check_master();
}

static void configure_slave(size_t i, const uint8_t *header)
{
    uint8_t flags = header[0], time = header[1];
    uint8_t control = (flags >> CONTROL_SHIFT) & 3u;
    h.error_control[i] = time == 0 || control == EC_NONE ? EC_NONE
                         : control == EC_GUARDING        ? EC_GUARDING
                                                         : EC_HEARTBEAT;
    uint32_t ms = time * FAST_UNIT_MS;
    uint32_t assignment = CO_NET_1F81_SLAVE | ((flags & REPORT) ? 0 : CO_NET_1F81_BOOT) |
                          ((flags & MANDATORY) ? CO_NET_1F81_MANDATORY : 0) |
                          (uint32_t)LIFE_TIME_FACTOR << CO_NET_1F81_RETRY_SHIFT |
                          (h.error_control[i] == EC_GUARDING ? ms : 0) << CO_NET_1F81_GUARD_SHIFT;
    h.slaves[i] = (co_net_slave_config_t){
        .node_id = (uint8_t)(i + 1),
        .heartbeat_ms = h.error_control[i] == EC_HEARTBEAT ? (uint16_t)ms : 0,
        .writes = writes,
        .write_count = (flags >> WRITES_SHIFT) & 3u,
        .check = checks[flags >> CHECK_SHIFT],
        .device_type = device_type,
    };
    memcpy(h.slaves[i].identity, identity, sizeof identity);
    rig_check(co_net_slave_config_from_1f81(&h.slaves[i], assignment) &&
                  co_net_slave_1f81(&h.slaves[i]) == assignment,
              "a slave's 1F81h refused, or not given back");
}

/* The master's 1F80h: the start and the reaction to a mandatory slave's loss. */
static uint32_t startup(const uint8_t *header)
{
    static const uint32_t starts[] = {0, CO_NET_1F80_START_ALL, CO_NET_1F80_NO_SLAVE_START, 0};
    uint32_t reaction = !(header[0] & NETWORK_REACTION)    ? 0
                        : (header[1] & REACTION_RESET_ALL) ? CO_NET_1F80_RESET_ALL
                                                           : CO_NET_1F80_STOP_ALL;
    return CO_NET_1F80_NMT_MASTER | starts[header[0] & START_MASK] | reaction;
}

static void configure(const uint8_t *header)
{
    uint8_t flags = header[0];
    size_t count = 1 + ((flags >> SLAVES_SHIFT) & 3u) % SLAVES_MAX;
    bool image = (flags & PROCESS_IMAGE) != 0;
    for (size_t i = 0; i < count; i++)
        configure_slave(i, header + MASTER_HEADER + i * SLAVE_HEADER);
    h.config = (co_net_master_config_t){
        .send = on_send,
        .event = on_event,
        .slaves = h.slaves,
        .slave_state = h.state,
        .slave_count = count,
        .sdo_timeout_ms = SDO_TIMEOUT_MS,
        .boot_time_ms = (header[1] & BOOT_TIME_MASK) * SLOW_UNIT_MS,
        .retry_delay_ms = header[2] * SLOW_UNIT_MS,
        .reset_all = (flags & RESET_ALL) != 0,
        .sync_period_us = (flags & SYNC) ? SYNC_PERIOD_US : 0,
        .inputs = image ? input_pdos : NULL,
        .input_count = image ? count : 0,
        .input_image = image ? h.input_image : NULL,
        .input_size = image ? sizeof h.input_image : 0,
        .outputs = image ? output_pdos : NULL,
        .output_count = image ? count : 0,
        .output_image = image ? h.output_image : NULL,
        .output_size = image ? sizeof h.output_image : 0,
    };
    uint32_t value = startup(header);
    rig_check(co_net_master_config_from_1f80(&h.config, value) &&
                  co_net_master_1f80(&h.config) == value,
              "the master's 1F80h refused, or not given back");
}

static void request_done(void *user, const co_net_request_t *request,
                         const co_sdo_client_result_t *result)
{
    (void)user;
    rig_check(request->done == request_done && h.requests_done < h.requests_queued,
              "a request ended that was not queued");
    rig_check(result->status == CO_SDO_CLIENT_OK || result->abort_code != 0,
              "a failed request without its abort code");
    h.requests_done++;
}

/* The application's NMT command: mod 5 of the commands, to all or to a slave of the table. */
static void request_nmt(const uint8_t *args)
{
    static const uint8_t commands[] = {CO_NMT_CS_START, CO_NMT_CS_STOP,
                                       CO_NMT_CS_ENTER_PRE_OPERATIONAL, CO_NMT_CS_RESET_NODE,
                                       CO_NMT_CS_RESET_COMMUNICATION};
    uint8_t node = args[1] == 0 ? 0 : h.slaves[args[1] % h.config.slave_count].node_id;
    bool busy = h.master.nmt_request.pending || h.master.disabled;
    bool sent = co_net_master_nmt(&h.master, commands[args[0] % 5], node,
                                  (args[2] + 1u) * FAST_UNIT_MS, h.now);
    rig_check(sent != busy, "an NMT command refused when it may go, or sent when it may not");
}

/* The application's SDO transfer on the master's client: 1018h:01 read, or 6060h written. */
static void request_sdo(const uint8_t *args)
{
    co_net_request_t request = {
        .node_id = h.slaves[args[0] % h.config.slave_count].node_id,
        .index = (args[1] & 1u) ? 0x6060 : CO_IDX_IDENTITY,
        .subindex = (args[1] & 1u) ? 0 : 1,
        .write = (args[1] & 1u) != 0,
        .data = h.request_buffer[h.requests_queued % CO_NET_REQUEST_MAX],
        .len = 4,
        .done = request_done,
    };
    bool room = !h.master.disabled && h.master.request_count < CO_NET_REQUEST_MAX;
    bool queued = co_net_master_sdo(&h.master, &request, h.now);
    rig_check(queued == room, "an SDO request refused with room, or queued without");
    h.requests_queued += queued;
}

/* A command of the application; false when the input ended in its arguments. */
static bool command(fuzz_input_t *input, uint8_t tag)
{
    const uint8_t *args;
    switch (tag) {
    case COMMAND_DISABLE:
        co_net_master_disable(&h.master, h.now);
        return true;
    case COMMAND_ENABLE:
        /* Enabling a disabled master boots the network again: a new start of all may go. */
        h.started_all = h.started_all && !h.master.disabled;
        h.application_started_all = h.application_started_all && !h.master.disabled;
        co_net_master_enable(&h.master, h.now);
        return true;
    case COMMAND_NMT:
        args = fuzz_take(input, 3);
        if (args)
            request_nmt(args);
        return args != NULL;
    case COMMAND_SDO:
        args = fuzz_take(input, 2);
        if (args)
            request_sdo(args);
        return args != NULL;
    default: {
        const uint8_t *offset = fuzz_take(input, 1);
        const uint8_t *bytes = offset ? fuzz_take(input, tag) : NULL;
        if (bytes)
            write_output(*offset, bytes, tag);
        return bytes != NULL;
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input_t input = {data, size};
    const uint8_t *header = fuzz_take(&input, HEADER_SIZE);
    if (header == NULL)
        return 0;
    memset(&h, 0, sizeof h);
    configure(header);
    rig_check(co_net_master_init(&h.master, &h.config), "init refused a valid configuration");
    co_net_master_start(&h.master, h.now);
    co_time_t deadline = process();
    fuzz_step_t step;
    while (fuzz_next_step(&input, true, &step)) {
        if (step.kind == FUZZ_STEP_TIME) {
            advance(step.us, &deadline);
        } else if (step.kind == FUZZ_STEP_FRAME) {
            deliver(&step.frame);
            deadline = process();
        } else {
            if (!command(&input, step.command))
                break;
            deadline = process();
        }
    }
    return 0;
}
