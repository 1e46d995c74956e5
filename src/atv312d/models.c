#include "models.h"

#include "atv31/atv31.h"
#include "atv312/atv312.h"

#include <string.h>

const atv312d_model_t atv312d_models[] = {
    {"atv312", "Schneider Altivar 312 (eds/ATV312.eds)", &atv312_profile},
    {"atv31", "Schneider Altivar 31, firmware V1.2 and later (eds/ATV31.eds)", &atv31_profile},
    {"atv31-v1.1", "Schneider Altivar 31 before V1.2: no heartbeat, 1016h/1017h absent",
     &atv31_v11_profile},
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
