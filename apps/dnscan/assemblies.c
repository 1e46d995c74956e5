/* The ATV312's assemblies 20, 21, 100 (consumed) and 70, 71, 101 (produced), 4 bytes each, with
 * the field names of the Altivar 312 DeviceNet manual's tables. */
#include "assemblies.h"

#include <ctype.h>

static const dnscan_field_t basic_output[] = {
    {"Run fwd", 0, 0},
    {"Fault reset", 0, 2},
    {"Speed reference", 2, DNSCAN_FIELD_WORD},
};
static const dnscan_field_t extended_output[] = {
    {"Run fwd", 0, 0}, {"Run rev", 0, 1}, {"Fault reset", 0, 2},
    {"NetCtrl", 0, 5}, {"NetRef", 0, 6},  {"Speed reference", 2, DNSCAN_FIELD_WORD},
};
static const dnscan_field_t transparent_output[] = {
    {"Control word", 0, DNSCAN_FIELD_WORD},
    {"Reference speed", 2, DNSCAN_FIELD_WORD},
};
static const dnscan_field_t basic_input[] = {
    {"Faulted", 0, 0},
    {"Running1", 0, 2},
    {"Speed actual", 2, DNSCAN_FIELD_WORD},
};
static const dnscan_field_t extended_input[] = {
    {"Faulted", 0, 0},
    {"Warning", 0, 1},
    {"Running1", 0, 2},
    {"Running2", 0, 3},
    {"Ready", 0, 4},
    {"Ctrl from net", 0, 5},
    {"Ref from net", 0, 6},
    {"At reference", 0, 7},
    {"Drive state", 1, DNSCAN_FIELD_BYTE},
    {"Speed actual", 2, DNSCAN_FIELD_WORD},
};
static const dnscan_field_t transparent_input[] = {
    {"Status word", 0, DNSCAN_FIELD_WORD},
    {"Output speed", 2, DNSCAN_FIELD_WORD},
};

#define FIELDS(table) (uint8_t)(sizeof(table) / sizeof(table[0])), table

static const dnscan_assembly_t assemblies[] = {
    {20, "Basic speed control output", false, FIELDS(basic_output)},
    {21, "Extended speed control output", false, FIELDS(extended_output)},
    {100, "Transparent output", false, FIELDS(transparent_output)},
    {70, "Basic speed control input", true, FIELDS(basic_input)},
    {71, "Extended speed control input", true, FIELDS(extended_input)},
    {101, "Transparent input", true, FIELDS(transparent_input)},
};

const dnscan_assembly_t *dnscan_assembly(uint16_t instance)
{
    for (size_t i = 0; i < sizeof(assemblies) / sizeof(assemblies[0]); i++)
        if (assemblies[i].instance == instance)
            return &assemblies[i];
    return NULL;
}

int32_t dnscan_field_get(const dnscan_field_t *field, const uint8_t *data)
{
    if (field->bit == DNSCAN_FIELD_WORD)
        return (int16_t)(data[field->byte] | data[field->byte + 1] << 8);
    if (field->bit == DNSCAN_FIELD_BYTE)
        return data[field->byte];
    return (data[field->byte] >> field->bit) & 1;
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

const dnscan_field_t *dnscan_field_by_name(const dnscan_assembly_t *assembly, const char *name)
{
    for (uint8_t i = 0; i < assembly->field_count; i++)
        if (same_name(assembly->fields[i].name, name))
            return &assembly->fields[i];
    return NULL;
}

bool dnscan_field_set(const dnscan_field_t *field, long value, uint8_t *data)
{
    if (field->bit == DNSCAN_FIELD_WORD) {
        if (value < INT16_MIN || value > UINT16_MAX)
            return false;
        data[field->byte] = (uint8_t)value;
        data[field->byte + 1] = (uint8_t)((unsigned long)value >> 8);
    } else if (field->bit == DNSCAN_FIELD_BYTE) {
        if (value < 0 || value > UINT8_MAX)
            return false;
        data[field->byte] = (uint8_t)value;
    } else {
        if (value < 0 || value > 1)
            return false;
        data[field->byte] =
            (uint8_t)((data[field->byte] & ~(1u << field->bit)) | (unsigned)value << field->bit);
    }
    return true;
}
