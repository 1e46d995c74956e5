/* SPDX-License-Identifier: Apache-2.0 */
/* Where the commands and the reference come from (include/drive/drive.h, the profile's channel
 * fields), and which ramp pair runs: the network, or a channel at the drive, chosen by switches
 * whose sources are logic inputs or control word bits. An update says whether the command channel
 * changed; the composition root (drive.c) has local control react to it. */
#include "drive/drive_floors.h"

static bool network_bit(const drive_t *drive, uint32_t bit)
{
    const co_od_entry_t *word = drive->entries.control_word;
    return word != NULL && ((co_od_get(&drive->node, word) >> bit) & 1u) != 0;
}

bool drive_source_is_bit(uint32_t code)
{
    uint32_t kind = code / 100u;
    uint32_t bit = code % 100u;
    return (kind == DRIVE_SOURCE_NETWORK_BIT(0) / 100u ||
            kind == DRIVE_SOURCE_COMMAND_BIT(0) / 100u) &&
           bit >= DRIVE_SOURCE_BIT_FIRST && bit <= DRIVE_SOURCE_BIT_LAST;
}

static bool source_is_input(const drive_t *drive, uint32_t code)
{
    return code > DRIVE_SOURCE_INPUT(0) && code <= DRIVE_SOURCE_INPUT(drive->profile->logic_inputs);
}

bool drive_source_valid(const drive_t *drive, uint32_t code)
{
    return drive_source_is_bit(code) || source_is_input(drive, code);
}

bool drive_mode_separate(const drive_profile_t *profile, uint32_t mode)
{
    return mode == profile->channel_mode_separate ||
           (profile->channel_mode_io != 0 && mode == profile->channel_mode_io);
}

bool drive_access_full(const drive_t *drive)
{
    return drive_param_value(drive, drive->profile->access_level) >=
           drive->profile->access_level_full;
}

/* The control word bit a switch's value takes over, or 0; below the full access level none. */
static uint16_t assigned_bit(const drive_t *drive, uint32_t code)
{
    return drive_source_is_bit(code) && drive_access_full(drive) ? (uint16_t)(1u << (code % 100u))
                                                                 : 0u;
}

/* A Cd bit reads the word of the command channel active before this evaluation: the network's
 * while it commands, none (0) while a channel at the drive does. */
static bool source_active(const drive_t *drive, uint32_t code)
{
    if (assigned_bit(drive, code) != 0u)
        return (code < DRIVE_SOURCE_COMMAND_BIT(0) || drive->command_from_network) &&
               network_bit(drive, code % 100u);
    return source_is_input(drive, code) &&
           drive_input(drive, (uint8_t)(code - DRIVE_SOURCE_INPUT(0)));
}

static bool second_selected(const drive_t *drive, const drive_channels_t *channels)
{
    uint32_t select = drive_param_value(drive, channels->select);
    return select == channels->select_second ||
           (select > channels->select_second && source_active(drive, select));
}

/* The code of the pair's active channel. */
static uint32_t active_channel(const drive_t *drive, const drive_channels_t *channels)
{
    bool second = second_selected(drive, channels);
    return drive_param_value(drive, second ? channels->second : channels->first);
}

static bool from_network(const drive_t *drive, const drive_channels_t *channels)
{
    return active_channel(drive, channels) == channels->network;
}

/* The analogue input whose code the active reference channel holds, or -1. */
static int8_t analog_of_reference(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    uint32_t channel = active_channel(drive, &profile->reference_channels);
    for (uint8_t i = 0; i < profile->analog_input_count; i++) {
        if (profile->analog_inputs[i].channel == channel)
            return (int8_t)i;
    }
    return -1;
}

/* In "not separate" mode the command comes from the reference's channel. Below the full access
 * level the channels are managed by priority: the network, the highest channel the emulation
 * has after forced local control, commands and gives the reference. */
bool drive_channels_update(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    bool was_from_network = drive->command_from_network;
    drive->assigned_bits =
        (uint16_t)(assigned_bit(drive, drive_param_value(drive, profile->command_channels.select)) |
                   assigned_bit(drive,
                                drive_param_value(drive, profile->reference_channels.select)) |
                   assigned_bit(drive, drive_param_value(drive, profile->ramp_switch)));
    drive->second_ramp = source_active(drive, drive_param_value(drive, profile->ramp_switch));
    uint32_t mode = drive_param_value(drive, profile->channel_mode);
    drive->io_mode = profile->channel_mode_io != 0 && mode == profile->channel_mode_io;
    drive->reference_analog = -1;
    drive->command_from_terminals = false;
    if (!drive_access_full(drive)) {
        drive->reference_from_network = true;
        drive->command_from_network = true;
    } else {
        bool reference = from_network(drive, &profile->reference_channels);
        bool separate = drive_mode_separate(profile, mode);
        drive->reference_from_network = reference;
        if (!reference)
            drive->reference_analog = analog_of_reference(drive);
        drive->command_from_network =
            separate ? from_network(drive, &profile->command_channels) : reference;
        drive->command_from_terminals =
            profile->terminals != 0 &&
            (separate ? active_channel(drive, &profile->command_channels) == profile->terminals
                      : drive->reference_analog >= 0);
    }
    return drive->command_from_network != was_from_network;
}

static bool channels_parameter(const drive_channels_t *channels, const co_od_entry_t *entry)
{
    return drive_is_param(entry, channels->first) || drive_is_param(entry, channels->second) ||
           drive_is_param(entry, channels->select);
}

bool drive_channel_parameter(const drive_t *drive, const co_od_entry_t *entry)
{
    const drive_profile_t *profile = drive->profile;
    return drive_is_param(entry, profile->channel_mode) ||
           drive_is_param(entry, profile->access_level) ||
           drive_is_param(entry, profile->ramp_switch) ||
           channels_parameter(&profile->command_channels, entry) ||
           channels_parameter(&profile->reference_channels, entry);
}

bool drive_reference_from_network(const drive_t *drive)
{
    return drive->reference_from_network;
}

const drive_analog_input_t *drive_reference_analog(const drive_t *drive)
{
    return drive->reference_analog >= 0 ? &drive->profile->analog_inputs[drive->reference_analog]
                                        : NULL;
}
