/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the CiA 305 LSS slave (src/canopen/slave/lss_slave.c) in the CiA 401 I/O
 * node, which has LSS: the input plays the LSS master and the NMT master, frame by frame and time
 * step by time step, and the harness holds the slave to CiA 305 after every step
 * (docs/fuzzing.md, "Invariants"): an answer on 7E4h only to a request that has one, with that
 * request's answer specifier; no node-id, active or pending, outside 1..127 and FFh; the LSS state
 * waiting or configuration; a node without node-id in Initialising, sending nothing but LSS
 * answers; a node with one never in Initialising after its start. Input: one byte, bit 0 the node
 * starts without node-id (else with node-id 1 + bits 1-7 mod 127), then steps of 9 bytes:
 *
 *     control:   bits 0-3 the frame's length (mod 9), bit 4 a remote frame, bit 5 a time step
 *                of data[0] ms instead of a frame, bit 6 the frame on 000h (NMT) instead of 7E5h
 *     data:      8 bytes
 *
 * fuzz/corpus/lss_slave holds the seeds: every service of docs/lss.md, a fastscan, NMT resets. */
#include "co/co_lss.h"
#include "nodes/io/io401.h"
#include "rig.h"

#include "io401_od.h"

#include <string.h>

#define STEP_SIZE 9
#define CONTROL_LEN 0x0Fu
#define CONTROL_RTR 0x10u
#define CONTROL_TIME 0x20u
#define CONTROL_NMT 0x40u
#define US_PER_MS 1000u
#define SENT_MAX 32

static plain_node_t io;
static uint8_t od_data[IO401_OD_DATA_SIZE];
static co_frame_t sent[SENT_MAX];
static size_t sent_count;

static void capture(void *user, const co_frame_t *frame)
{
    (void)user;
    if (sent_count < SENT_MAX)
        sent[sent_count] = *frame;
    sent_count++;
}

static bool valid_node_id(uint8_t id)
{
    return (id >= 1 && id <= CO_NODE_ID_MAX) || id == CO_LSS_NODE_ID_UNCONFIGURED;
}

/* The specifier CiA 305 answers a request's with, 0 for a request without answer. */
static uint8_t answer_of(uint8_t cs)
{
    switch (cs) {
    case CO_LSS_CS_CONFIGURE_NODE_ID:
    case CO_LSS_CS_CONFIGURE_BIT_TIMING:
    case CO_LSS_CS_STORE:
        return cs;
    case CO_LSS_CS_SWITCH_SELECTIVE_SERIAL:
        return CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE;
    case CO_LSS_CS_IDENTIFY_VENDOR:
    case CO_LSS_CS_IDENTIFY_PRODUCT:
    case CO_LSS_CS_IDENTIFY_REVISION_LOW:
    case CO_LSS_CS_IDENTIFY_REVISION_HIGH:
    case CO_LSS_CS_IDENTIFY_SERIAL_LOW:
    case CO_LSS_CS_IDENTIFY_SERIAL_HIGH:
    case CO_LSS_CS_FASTSCAN:
        return CO_LSS_CS_IDENTIFY_SLAVE;
    case CO_LSS_CS_IDENTIFY_NON_CONFIGURED:
        return CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE;
    case CO_LSS_CS_INQUIRE_VENDOR:
    case CO_LSS_CS_INQUIRE_PRODUCT:
    case CO_LSS_CS_INQUIRE_REVISION:
    case CO_LSS_CS_INQUIRE_SERIAL:
    case CO_LSS_CS_INQUIRE_NODE_ID:
        return cs;
    default:
        return 0;
    }
}

/* The frames one step made, and the state after it. `request` is the LSS request delivered,
 * NULL for a time step or an NMT frame. */
static void check_step(const co_frame_t *request, uint8_t node_id_before)
{
    const co_node_t *node = &io.node;
    const co_lss_slave_t *lss = &io.lss;
    size_t answers = 0;
    for (size_t i = 0; i < sent_count && i < SENT_MAX; i++) {
        const co_frame_t *f = &sent[i];
        if (node_id_before == CO_LSS_NODE_ID_UNCONFIGURED &&
            node->node_id == CO_LSS_NODE_ID_UNCONFIGURED)
            rig_check(f->id == CO_LSS_ID_SLAVE, "a node without node-id sent no LSS answer");
        if (f->id != CO_LSS_ID_SLAVE)
            continue;
        answers++;
        rig_check(f->len == CO_LSS_FRAME_LEN, "an LSS answer of 8 bytes");
        rig_check(request != NULL, "an LSS answer to no LSS request");
        uint8_t want = request ? answer_of(request->data[0]) : 0;
        rig_check(want != 0 && f->data[0] == want, "the answer specifier of the request");
        if (f->data[0] == CO_LSS_CS_INQUIRE_NODE_ID)
            rig_check(valid_node_id(f->data[1]), "inquire node-id answers 1..127 or FFh");
    }
    rig_check(answers <= 1, "one answer to one request");
    rig_check(valid_node_id(node->node_id), "active node-id 1..127 or FFh");
    rig_check(valid_node_id(lss->pending_node_id), "pending node-id 1..127 or FFh");
    rig_check(lss->state == CO_LSS_WAITING || lss->state == CO_LSS_CONFIGURATION,
              "LSS state waiting or configuration");
    rig_check(lss->bit_timing <= CO_LSS_BIT_TIMING_INDEX_MAX, "bit timing an index of table 0");
    rig_check((node->node_id == CO_LSS_NODE_ID_UNCONFIGURED) ==
                  (node->nmt_state == CO_NMT_INITIALISING),
              "Initialising exactly while without node-id");
}

int LLVMFuzzerTestOneInput(const uint8_t *input, size_t size)
{
    if (size < 1)
        return 0;
    uint8_t node_id = (input[0] & 1u) ? CO_LSS_NODE_ID_UNCONFIGURED
                                      : (uint8_t)(1u + (input[0] >> 1) % CO_NODE_ID_MAX);
    memset(&io, 0, sizeof io);
    plain_node_config_t config = {
        .model = &io401_model,
        .od_data = od_data,
        .node_id = node_id,
        .serial_number = io401_model.serial_base + 0x81u,
        .lss_bit_timing = CO_LSS_BIT_TIMING_AUTO,
        .send = capture,
    };
    rig_check(plain_node_init(&io, &config) == 0, "the I/O node initialises");
    co_time_t now = 0;
    sent_count = 0;
    plain_node_start(&io, now);
    check_step(NULL, CO_LSS_NODE_ID_UNCONFIGURED);
    for (size_t at = 1; at + STEP_SIZE <= size; at += STEP_SIZE) {
        const uint8_t *step = input + at;
        uint8_t before = io.node.node_id;
        sent_count = 0;
        if (step[0] & CONTROL_TIME) {
            now += (co_time_t)step[1] * US_PER_MS;
            plain_node_process(&io, now);
            check_step(NULL, before);
            continue;
        }
        co_frame_t frame = {
            .id = (step[0] & CONTROL_NMT) ? CO_CAN_ID_NMT : CO_LSS_ID_MASTER,
            .len = (uint8_t)((step[0] & CONTROL_LEN) % (CO_LSS_FRAME_LEN + 1u)),
            .flags = (step[0] & CONTROL_RTR) ? CO_FRAME_RTR : 0u,
        };
        memcpy(frame.data, step + 1, CO_LSS_FRAME_LEN);
        plain_node_receive(&io, &frame, now);
        plain_node_process(&io, now);
        check_step(frame.id == CO_LSS_ID_MASTER ? &frame : NULL, before);
    }
    return 0;
}
