/* SPDX-License-Identifier: Apache-2.0 */
/* The daemon's models by kind (catalogue.h): the two tables read as one. */
#include "atv312d/catalogue.h"

#include <string.h>

size_t atv312d_model_count(void)
{
    return drive_model_count + plain_model_count;
}

atv312d_model_t atv312d_model_at(size_t i)
{
    if (i < drive_model_count) {
        const drive_model_t *d = &drive_models[i];
        return (atv312d_model_t){ATV312D_KIND_DRIVE, d->name, d->description,
                                 d->node_id_max,     d,       NULL};
    }
    const plain_model_t *n = plain_models[i - drive_model_count];
    return (atv312d_model_t){ATV312D_KIND_NODE, n->name, n->description, n->node_id_max, NULL, n};
}

bool atv312d_model_find(const char *name, atv312d_model_t *model)
{
    for (size_t i = 0; i < atv312d_model_count(); i++) {
        *model = atv312d_model_at(i);
        if (strcmp(model->name, name) == 0)
            return true;
    }
    return false;
}

const char *atv312d_kind_name(atv312d_kind_t kind)
{
    return kind == ATV312D_KIND_NODE ? "node" : "drive";
}
