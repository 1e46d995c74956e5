/* SPDX-License-Identifier: Apache-2.0 */
#include "nodes/node_models.h"

#include "nodes/io/io401.h"
#include "nodes/plc300/plc300.h"

#include <string.h>

const plain_model_t *const plain_models[] = {&plc300_model, &io401_model};

const size_t plain_model_count = sizeof plain_models / sizeof plain_models[0];

const plain_model_t *plain_model_find(const char *name)
{
    for (size_t i = 0; i < plain_model_count; i++) {
        if (strcmp(plain_models[i]->name, name) == 0)
            return plain_models[i];
    }
    return NULL;
}
