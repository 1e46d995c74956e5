/* The drive models atv312d can emulate, by the name --model takes. Adding a model is adding its
 * library (its dictionary, hooks and drive_profile_t) and one entry to the table of models.c. */
#ifndef ATV312D_MODELS_H
#define ATV312D_MODELS_H

#include "drive/drive.h"

#include <stddef.h>

typedef struct atv312d_model {
    const char *name;        /* as --model takes it */
    const char *description; /* for --help */
    const drive_profile_t *profile;
    uint8_t node_id_max; /* highest node-id the model takes (the ATV58's card: 63) */
} atv312d_model_t;

/* The models; the first is the default of a --node-id without --model. */
extern const atv312d_model_t atv312d_models[];
extern const size_t atv312d_model_count;

/* NULL when no model has that name. */
const atv312d_model_t *atv312d_find_model(const char *name);

#endif
