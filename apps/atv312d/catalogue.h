/* SPDX-License-Identifier: Apache-2.0 */
/* The models atv312d hosts, each with its kind: the drives of drive/models/models.h (a CiA 402
 * drive, some with a DeviceNet card), then the plain nodes of nodes/node_models.h (a PLC300
 * slave, a CiA 401 I/O node). What --model takes, what --help lists, what the surfaces say a
 * node is (docs/architecture.md, "The daemon, atv312d"). */
#ifndef ATV312D_CATALOGUE_H
#define ATV312D_CATALOGUE_H

#include "drive/models/models.h"
#include "nodes/node_models.h"

#include <stdbool.h>
#include <stddef.h>

typedef enum atv312d_kind {
    ATV312D_KIND_DRIVE, /* a drive_t: the drive commands, its CiA 402 state */
    ATV312D_KIND_NODE   /* a plain_node_t: its model's commands (marker, input, analog) */
} atv312d_kind_t;

/* One model; exactly one of drive and node is set, after kind. */
typedef struct atv312d_model {
    atv312d_kind_t kind;
    const char *name; /* as --model takes it; the same pointer for every node of the model */
    const char *description;
    uint8_t node_id_max;
    const drive_model_t *drive;
    const plain_model_t *node;
} atv312d_model_t;

/* Models in --help's order, drives first; model 0 is the default of a --node-id alone. */
size_t atv312d_model_count(void);
atv312d_model_t atv312d_model_at(size_t i);
/* False when no model has that name. */
bool atv312d_model_find(const char *name, atv312d_model_t *model);
/* "drive" or "node", as the status JSON's "kind" says it. */
const char *atv312d_kind_name(atv312d_kind_t kind);

#endif
