/* SPDX-License-Identifier: Apache-2.0 */
/* The one view of a node that every surface shows (the control socket's `state`, the status
 * file and SIGUSR1, the web's API and events), in text and in JSON: its bus state (NMT, or the
 * DeviceNet card's LEDs and supervisor), CiA 402 state, speed, current, torque, front panel,
 * fault, communication loss, frame and service counters and inputs; the drive's fixed data for
 * the web's bench; the CAN controller's state. It reads the drives and writes text; it calls
 * no surface. docs/atv312d.md, "Control surface" and "Status". */
#ifndef ATV312D_VIEW_H
#define ATV312D_VIEW_H

#include "atv312d/catalogue.h"
#include "atv312d/counters.h"
#include "cli/json.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/drive_devicenet.h"
#include "nodes/plain_node.h"

#include <stdbool.h>
#include <stddef.h>

/* One node as the surfaces see it (named after the control surface, which came first): a drive,
 * or a plain node (a PLC300, an I/O node) whose view is its NMT state, LEDs, error control event,
 * counters and its model's data (docs/atv312d.md, "Plain nodes"). */
typedef struct atv312d_control_node {
    uint8_t id;        /* what NODE names: the node-id on CANopen, the MAC ID on DeviceNet (a plain
                        * node's: atv312d_node_id) */
    const char *model; /* its --model name, "atv312" */
    drive_t *drive;    /* a drive's; NULL for a plain node */
    plain_node_t *plain;         /* a plain node's; NULL for a drive */
    const drive_dn_t *devicenet; /* its DeviceNet card; NULL on CANopen */
    co_linux_device_t *device;   /* processed after a command changed the drive; its frame counts */
    const atv312d_counters_t *counters;
} atv312d_control_node_t;

/* A drive, or a plain node: what its plain pointer says. */
static inline atv312d_kind_t atv312d_node_kind(const atv312d_control_node_t *node)
{
    return node->plain != NULL ? ATV312D_KIND_NODE : ATV312D_KIND_DRIVE;
}

/* The id NODE names now: a plain node's is its node-id of the moment, which LSS may give it
 * (FFh: none yet, a node of --unconfigured). */
static inline uint8_t atv312d_node_id(const atv312d_control_node_t *node)
{
    return node->plain ? node->plain->node.node_id : node->id;
}

/* Text appended to a buffer: what does not fit is cut, the text stays NUL-terminated. */
typedef struct atv312d_text {
    char *buf;
    size_t len, used;
} atv312d_text_t;

void atv312d_text_put(atv312d_text_t *text, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* The CAN controller as the loop sees it: "down" (the interface), "bus-off", "error-passive",
 * "error-warning" (an error counter at or over the warning limit, 96) or "error-active". */
const char *atv312d_can_state(const co_linux_loop_t *loop);

/* A value of an analogue input of `kind` in the unit the control surface takes: "-2.500 V",
 * "12.000 mA", "50.5 %". */
void atv312d_format_analog(drive_analog_kind_t kind, int32_t value, char *buf, size_t len);

/* One node's state as `state` reports it: "node 4: nmt ..., fault none" (on DeviceNet "node 25:
 * ms ..., ns ..., supervisor ..., cia402 ...") or its JSON object. */
void atv312d_format_state(const atv312d_control_node_t *node, bool json, char *buf, size_t len);
/* The same line appended to text. */
void atv312d_state_text(atv312d_text_t *text, const atv312d_control_node_t *node);

/* What the surfaces show and take of a plain node of one model: the commands it takes (for a
 * refusal), its model's data in the state text and in the JSON. */
typedef struct atv312d_plain_surface {
    const plain_model_t *model;
    const char *commands;
    void (*text)(const plain_node_t *plain, atv312d_text_t *text);
    void (*json)(cli_json_t *json, const plain_node_t *plain);
} atv312d_plain_surface_t;

/* The row of a model of src/nodes/node_models.c; NULL for a model without one (its state shows
 * what every plain node has, and it takes `state` alone). */
const atv312d_plain_surface_t *atv312d_plain_surface(const plain_model_t *model);
/* The same JSON object as a value of the document being written. */
void atv312d_state_json(cli_json_t *json, const atv312d_control_node_t *node);

/* The node's fixed data for the web's bench, as a value of the document being written: node,
 * model, faults, inputs and LEDs (docs/web.md, GET /api/bench); a plain node's has "kind":
 * "node", no faults and no inputs. */
void atv312d_bench_drive_json(cli_json_t *json, const atv312d_control_node_t *node);

#endif
