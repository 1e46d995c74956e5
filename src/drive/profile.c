/* SPDX-License-Identifier: Apache-2.0 */
/* The ground floor of the drive layer: the profile's parameters read through the model's
 * dictionary (the entries found once at init, a parameter's value) and the units they convert
 * between (0.1 Hz and rpm, through the nominal frequency and speed). Every other file of the layer
 * reads through it; it calls none of them. */
#include "drive/drive_floors.h"

#include <stddef.h>

drive_t *drive_of(co_node_t *node)
{
    return (drive_t *)(void *)((char *)node - offsetof(drive_t, node));
}

uint32_t drive_param_value(const drive_t *drive, drive_param_t param)
{
    if (param.index == 0)
        return param.fixed;
    return (uint32_t)co_od_value(&drive->node, param.index, param.subindex);
}

bool drive_is_param(const co_od_entry_t *entry, drive_param_t param)
{
    return param.index != 0 && entry->index == param.index && entry->subindex == param.subindex;
}

static char lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

bool drive_same_code(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        if (lower(*a) != lower(*b))
            return false;
    }
    return *a == *b;
}

int64_t drive_entry_value(const drive_t *drive, const co_od_entry_t *entry)
{
    return entry != NULL ? co_od_get(&drive->node, entry) : 0;
}

/* Held within the entry's limits (co_od_saturate), so that whatever the drive publishes a client
 * can write back: 6044h stays at 32767 rpm above it, rather than wrapping round. */
void drive_entry_set(drive_t *drive, const co_od_entry_t *entry, int64_t value)
{
    if (entry != NULL)
        co_od_set(&drive->node, entry, co_od_saturate(entry, value));
}

static const co_od_entry_t *param_entry(const drive_t *drive, drive_param_t param)
{
    return co_od_find(drive->profile->od, param.index, param.subindex);
}

void drive_entries_find(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    const co_od_t *od = profile->od;
    drive->entries = (drive_entries_t){
        .error_code = co_od_find(od, CIA402_IDX_ERROR_CODE, 0),
        .control_word = co_od_find(od, CIA402_IDX_CONTROLWORD, 0),
        .status_word = co_od_find(od, CIA402_IDX_STATUSWORD, 0),
        .target_velocity = co_od_find(od, CIA402_IDX_TARGET_VELOCITY, 0),
        .velocity_demand = co_od_find(od, CIA402_IDX_VELOCITY_DEMAND, 0),
        .velocity_actual = co_od_find(od, CIA402_IDX_VELOCITY_ACTUAL, 0),
        .acceleration = param_entry(drive, profile->acceleration),
        .deceleration = param_entry(drive, profile->deceleration),
        .low_speed = param_entry(drive, profile->low_speed),
        .high_speed = param_entry(drive, profile->high_speed),
        .nominal_frequency = param_entry(drive, profile->nominal_frequency),
        .nominal_speed = param_entry(drive, profile->nominal_speed),
        .nominal_current = param_entry(drive, profile->nominal_current),
        .motor_current = param_entry(drive, profile->motor_current),
        .motor_torque = param_entry(drive, profile->motor_torque),
        .control_word_copy = param_entry(drive, profile->control_word_copy),
        .status_word_copy = param_entry(drive, profile->status_word_copy),
        .output_frequency = param_entry(drive, profile->output_frequency),
        .frequency_reference = param_entry(drive, profile->frequency_reference),
        .stop_type = param_entry(drive, profile->stop_type),
        .acceleration_2 = param_entry(drive, profile->acceleration_2),
        .deceleration_2 = param_entry(drive, profile->deceleration_2),
    };
    for (uint8_t i = 0; i < profile->analog_input_count && i < DRIVE_ANALOG_MAX; i++) {
        drive->entries.analog_low[i] = param_entry(drive, profile->analog_inputs[i].low);
        drive->entries.analog_high[i] = param_entry(drive, profile->analog_inputs[i].high);
    }
}

/* A setting the model's dictionary lacks reads as its fixed value (DRIVE_FIXED), as
 * drive_param_value does. */
uint32_t drive_entry_param(const drive_t *drive, const co_od_entry_t *entry, drive_param_t param)
{
    return entry != NULL ? (uint32_t)co_od_get(&drive->node, entry) : param.fixed;
}

uint32_t drive_frequency_to_rpm(const drive_t *drive, uint32_t decihertz)
{
    uint32_t frs = drive_entry_param(drive, drive->entries.nominal_frequency,
                                     drive->profile->nominal_frequency);
    uint32_t nsp =
        drive_entry_param(drive, drive->entries.nominal_speed, drive->profile->nominal_speed);
    return frs ? (decihertz * nsp + frs / 2) / frs : 0;
}

uint32_t drive_rpm_to_frequency(const drive_t *drive, uint32_t rpm)
{
    uint64_t frs = drive_entry_param(drive, drive->entries.nominal_frequency,
                                     drive->profile->nominal_frequency);
    uint64_t nsp =
        drive_entry_param(drive, drive->entries.nominal_speed, drive->profile->nominal_speed);
    uint64_t decihertz = nsp ? ((uint64_t)rpm * frs + nsp / 2) / nsp : 0;
    return decihertz > UINT32_MAX ? UINT32_MAX : (uint32_t)decihertz;
}

int32_t drive_signed_rpm_to_frequency(const drive_t *drive, int32_t rpm)
{
    uint32_t decihertz = drive_rpm_to_frequency(drive, (uint32_t)(rpm < 0 ? -rpm : rpm));
    int32_t magnitude = decihertz > INT32_MAX ? INT32_MAX : (int32_t)decihertz;
    return rpm < 0 ? -magnitude : magnitude;
}

int32_t drive_signed_frequency_to_rpm(const drive_t *drive, int32_t decihertz)
{
    uint32_t magnitude = (uint32_t)(decihertz < 0 ? -decihertz : decihertz);
    int32_t rpm = (int32_t)drive_frequency_to_rpm(drive, magnitude);
    return decihertz < 0 ? -rpm : rpm;
}
