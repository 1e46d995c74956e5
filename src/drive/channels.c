/* Where the commands and the reference come from (include/drive/drive.h, the profile's channel
 * fields): the network, or a channel at the drive. */
#include "drive_internal.h"

static uint32_t active_channel(const drive_t *drive, const drive_channels_t *channels)
{
    bool second = drive_param_value(drive, channels->select) == channels->select_second;
    return drive_param_value(drive, second ? channels->second : channels->first);
}

static bool from_network(const drive_t *drive, const drive_channels_t *channels)
{
    return active_channel(drive, channels) == channels->network;
}

/* In "not separate" mode the command comes from the reference's channel. */
void drive_channels_update(drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    bool reference = from_network(drive, &profile->reference_channels);
    bool separate =
        drive_param_value(drive, profile->channel_mode) == profile->channel_mode_separate;
    drive->reference_from_network = reference;
    drive->command_from_network =
        separate ? from_network(drive, &profile->command_channels) : reference;
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
           channels_parameter(&profile->command_channels, entry) ||
           channels_parameter(&profile->reference_channels, entry);
}

bool drive_reference_from_network(const drive_t *drive)
{
    return drive->reference_from_network;
}

bool drive_local_control(const drive_t *drive)
{
    return drive->local || !drive->command_from_network;
}
