/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 312 card's assemblies with the field names of its DeviceNet manual's tables
 * (cip_assembly.h). */
#include "trace/cip_assembly.h"

#include <ctype.h>

static const cip_field_t basic_output[] = {
    {"Run fwd", CIP_FIELD_BIT, 0, 0},
    {"Fault reset", CIP_FIELD_BIT, 0, 2},
    {"Speed reference", CIP_FIELD_RPM, 2, 0},
};
static const cip_field_t extended_output[] = {
    {"Run fwd", CIP_FIELD_BIT, 0, 0},     {"Run rev", CIP_FIELD_BIT, 0, 1},
    {"Fault reset", CIP_FIELD_BIT, 0, 2}, {"NetCtrl", CIP_FIELD_BIT, 0, 5},
    {"NetRef", CIP_FIELD_BIT, 0, 6},      {"Speed reference", CIP_FIELD_RPM, 2, 0},
};
static const cip_field_t transparent_output[] = {
    {"Control word", CIP_FIELD_CONTROL_WORD, 0, 0},
    {"Reference speed", CIP_FIELD_RPM, 2, 0},
};
static const cip_field_t basic_input[] = {
    {"Faulted", CIP_FIELD_BIT, 0, 0},
    {"Running1", CIP_FIELD_BIT, 0, 2},
    {"Speed actual", CIP_FIELD_RPM, 2, 0},
};
static const cip_field_t extended_input[] = {
    {"Faulted", CIP_FIELD_BIT, 0, 0},       {"Warning", CIP_FIELD_BIT, 0, 1},
    {"Running1", CIP_FIELD_BIT, 0, 2},      {"Running2", CIP_FIELD_BIT, 0, 3},
    {"Ready", CIP_FIELD_BIT, 0, 4},         {"Ctrl from net", CIP_FIELD_BIT, 0, 5},
    {"Ref from net", CIP_FIELD_BIT, 0, 6},  {"At reference", CIP_FIELD_BIT, 0, 7},
    {"Drive state", CIP_FIELD_STATE, 1, 0}, {"Speed actual", CIP_FIELD_RPM, 2, 0},
};
static const cip_field_t transparent_input[] = {
    {"Status word", CIP_FIELD_STATUS_WORD, 0, 0},
    {"Output speed", CIP_FIELD_RPM, 2, 0},
};

#define FIELDS(table) (uint8_t)(sizeof(table) / sizeof(table[0])), table

static const cip_assembly_t assemblies[] = {
    {20, "Basic speed control output", false, FIELDS(basic_output)},
    {21, "Extended speed control output", false, FIELDS(extended_output)},
    {100, "Transparent output", false, FIELDS(transparent_output)},
    {70, "Basic speed control input", true, FIELDS(basic_input)},
    {71, "Extended speed control input", true, FIELDS(extended_input)},
    {101, "Transparent input", true, FIELDS(transparent_input)},
};

const cip_assembly_t *cip_assembly(uint16_t instance)
{
    for (size_t i = 0; i < sizeof(assemblies) / sizeof(assemblies[0]); i++)
        if (assemblies[i].instance == instance)
            return &assemblies[i];
    return NULL;
}

static uint16_t word_at(const uint8_t *data)
{
    return (uint16_t)(data[0] | data[1] << 8);
}

int32_t cip_field_get(const cip_field_t *field, const uint8_t *data)
{
    const uint8_t *at = &data[field->byte];
    switch (field->kind) {
    case CIP_FIELD_BIT:
        return (*at >> field->bit) & 1;
    case CIP_FIELD_STATE:
        return *at;
    case CIP_FIELD_RPM:
        return (int16_t)word_at(at);
    case CIP_FIELD_CONTROL_WORD:
    case CIP_FIELD_STATUS_WORD:
        break;
    }
    return word_at(at);
}

static bool same_name(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = *a == '_' ? ' ' : (char)tolower((unsigned char)*a);
        char y = *b == '_' ? ' ' : (char)tolower((unsigned char)*b);
        if (x != y)
            return false;
    }
    return *a == *b;
}

const cip_field_t *cip_field_by_name(const cip_assembly_t *assembly, const char *name)
{
    for (uint8_t i = 0; i < assembly->field_count; i++)
        if (same_name(assembly->fields[i].name, name))
            return &assembly->fields[i];
    return NULL;
}

bool cip_field_set(const cip_field_t *field, long value, uint8_t *data)
{
    uint8_t *at = &data[field->byte];
    switch (field->kind) {
    case CIP_FIELD_BIT:
        if (value < 0 || value > 1)
            return false;
        *at = (uint8_t)((*at & ~(1u << field->bit)) | (unsigned)value << field->bit);
        return true;
    case CIP_FIELD_STATE:
        if (value < 0 || value > UINT8_MAX)
            return false;
        *at = (uint8_t)value;
        return true;
    case CIP_FIELD_RPM:
    case CIP_FIELD_CONTROL_WORD:
    case CIP_FIELD_STATUS_WORD:
        break;
    }
    if (value < INT16_MIN || value > UINT16_MAX)
        return false;
    at[0] = (uint8_t)value;
    at[1] = (uint8_t)((unsigned long)value >> 8);
    return true;
}

const char *cip_supervisor_state_name(uint8_t state)
{
    static const char *const states[] = {"Vendor specific", "Startup",  "Not_Ready",  "Ready",
                                         "Enabled",         "Stopping", "Fault_Stop", "Faulted"};
    return state < sizeof states / sizeof states[0] ? states[state] : "reserved";
}
