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

bool drive_reference_from_network(const drive_t *drive)
{
    return from_network(drive, &drive->profile->reference_channels);
}

/* In "not separate" mode the command comes from the reference's channel. */
bool drive_command_from_network(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    bool separate =
        drive_param_value(drive, profile->channel_mode) == profile->channel_mode_separate;
    return separate ? from_network(drive, &profile->command_channels)
                    : drive_reference_from_network(drive);
}

bool drive_local_control(const drive_t *drive)
{
    return drive->local || !drive_command_from_network(drive);
}
