/* SPDX-License-Identifier: Apache-2.0 */
#include "drive/models/models.h"

#include "atv31/atv31.h"
#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "atv58/atv58.h"

#include <string.h>

const drive_model_t drive_models[] = {
    {"atv312", "Schneider Altivar 312 (eds/ATV312.eds)", &atv312_profile, CO_NODE_ID_MAX,
     &atv312_devicenet_profile},
    {"atv31", "Schneider Altivar 31, firmware V1.2 and later (eds/ATV31.eds)", &atv31_profile,
     CO_NODE_ID_MAX, NULL},
    {"atv31-v1.1", "Schneider Altivar 31 before V1.2: no heartbeat, 1016h/1017h absent",
     &atv31_v11_profile, CO_NODE_ID_MAX, NULL},
    {"atv58", "Schneider Altivar 58 + VW3-A58308 card, node-ids 1..63 (eds/ATV58.eds)",
     &atv58_profile, ATV58_NODE_ID_MAX, NULL},
};

const size_t drive_model_count = sizeof drive_models / sizeof drive_models[0];

const drive_model_t *drive_model_find(const char *name)
{
    for (size_t i = 0; i < drive_model_count; i++) {
        if (strcmp(drive_models[i].name, name) == 0)
            return &drive_models[i];
    }
    return NULL;
}
