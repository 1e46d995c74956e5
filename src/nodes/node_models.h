/* SPDX-License-Identifier: Apache-2.0 */
/* The table of plain node models by name (nodes/plain_node.h), as atv312d's --model takes them
 * beside the drive models (drive/models/models.h). Adding one is adding its folder (its EDS's
 * dictionary, its hooks, its plain_model_t) and one entry to node_models.c; atv312d shows it
 * through its row of plain surfaces (apps/atv312d/view.c). */
#ifndef NODES_NODE_MODELS_H
#define NODES_NODE_MODELS_H

#include "nodes/plain_node.h"

#include <stddef.h>

extern const plain_model_t *const plain_models[];
extern const size_t plain_model_count;

/* NULL when no plain model has that name. */
const plain_model_t *plain_model_find(const char *name);

#endif
