#include "models.h"

#include "atv312/atv312.h"

#include <string.h>

const atv312d_model_t atv312d_models[] = {
    {"atv312", "Schneider Altivar 312 (eds/ATV312.eds)", &atv312_profile},
};

const size_t atv312d_model_count = sizeof atv312d_models / sizeof atv312d_models[0];

const atv312d_model_t *atv312d_find_model(const char *name)
{
    for (size_t i = 0; i < atv312d_model_count; i++) {
        if (strcmp(atv312d_models[i].name, name) == 0)
            return &atv312d_models[i];
    }
    return NULL;
}
