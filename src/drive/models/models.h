/* SPDX-License-Identifier: Apache-2.0 */
/* The table of drive models by name, as a program's --model takes it (atv312d), with what its
 * --help says of each. Adding a model is adding its library (its dictionary, hooks and
 * drive_profile_t, docs/drive.md) and one entry to the table of models.c. */
#ifndef DRIVE_MODELS_H
#define DRIVE_MODELS_H

#include "drive/drive.h"
#include "drive/drive_devicenet.h"

#include <stddef.h>

typedef struct drive_model {
    const char *name;        /* as --model takes it */
    const char *description; /* for --help */
    const drive_profile_t *profile;
    uint8_t node_id_max; /* highest node-id the model takes (the ATV58's card: 63) */
    /* Its DeviceNet card's data (drive_devicenet.h), NULL when the model has none here: only
     * such a model runs on a DeviceNet bus (atv312d --devicenet). */
    const drive_dn_profile_t *devicenet;
} drive_model_t;

/* The models; the first is the default of a --node-id without --model. */
extern const drive_model_t drive_models[];
extern const size_t drive_model_count;

/* NULL when no model has that name. */
const drive_model_t *drive_model_find(const char *name);

#endif
