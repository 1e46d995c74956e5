/* SPDX-License-Identifier: Apache-2.0 */
/* Dictionary hooks a model's hooks file names on the entries its profile points at: the rules of
 * the drive's own parameters, and the CiA 402 objects that are views of them (6046h of the speed
 * limits, 6048h/6049h of the ramps). */
#include "drive/drive_floors.h"

/* Motor data are configuration parameters (ATV312 DeviceNet manual, drive state machine): they
 * change only with the motor stopped, and a change returns the drive to Switch on disabled. */
static uint32_t configuration_write(co_node_t *node, const co_od_entry_t *entry,
                                    const uint8_t *data, size_t len, co_od_origin_t origin)
{
    (void)entry, (void)data, (void)len, (void)origin;
    drive_t *drive = drive_of(node);
    drive_motor_advance(&drive->motor, node->now);
    if (drive_motor_running(&drive->motor))
        return CO_SDO_ABORT_DATA_STATE;
    cia402_configuration_changed(&drive->cia402);
    return CO_SDO_OK;
}

const co_od_hook_t drive_configuration_parameter = {configuration_write, NULL};

/* The value a hook is given, of an unsigned entry of 1, 2 or 4 bytes. */
static uint32_t written_value(const uint8_t *data, size_t len)
{
    return len == 4 ? co_get_u32(data) : len == 2 ? co_get_u16(data) : data[0];
}

/* The internal control word suspends the cross checks (a configuration transfer under way). */
static bool checks_suspended(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    return profile->internal_control.index != 0 &&
           (drive_param_value(drive, profile->internal_control) &
            profile->internal_control_no_check) != 0;
}

/* The model's fault of an inconsistent configuration, or -1. */
static int inconsistent_fault(const drive_t *drive)
{
    const char *code = drive->profile->inconsistent_fault;
    return code ? drive_fault_find(drive, code) : -1;
}

/* The configuration's cross check: a low speed above the high speed is the inconsistent
 * configuration fault (CFI), consistent limits end its cause. */
static void check_configuration(drive_t *drive, uint32_t low, uint32_t high, co_time_t now)
{
    int fault = inconsistent_fault(drive);
    if (fault < 0)
        return;
    if (low > high)
        drive_fault_inject(drive, (uint8_t)fault, now);
    else if (drive_fault_cause_present(drive, (uint8_t)fault))
        drive_fault_remove_cause(drive, (uint8_t)fault, now);
}

/* The low speed may not exceed the high speed (CiA 301 abort "maximum value is less than minimum
 * value"), unless the check is suspended; a write that makes them consistent again ends the
 * inconsistent configuration fault's cause. */
static uint32_t speed_limit_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                  size_t len, co_od_origin_t origin)
{
    (void)origin;
    drive_t *drive = drive_of(node);
    const drive_profile_t *profile = drive->profile;
    uint32_t value = written_value(data, len);
    bool is_high = drive_is_param(entry, profile->high_speed);
    uint32_t other = drive_param_value(drive, is_high ? profile->low_speed : profile->high_speed);
    uint32_t low = is_high ? other : value;
    uint32_t high = is_high ? value : other;
    if (checks_suspended(drive))
        return CO_SDO_OK;
    if (low > high)
        return CO_SDO_ABORT_MAX_LESS_MIN;
    check_configuration(drive, low, high, node->now);
    return CO_SDO_OK;
}

/* The internal control word (ATV312 DeviceNet manual, "Switch on disabled": "disable the
 * consistency check during the transfer: CMI W8504, bit 15 = 1 ... After the transfer,
 * re-enable it: CMI W8504, bit 15 = 0"): the check bit back to 0 checks what was loaded: an
 * inconsistent configuration is the inconsistent configuration fault (CFI), a consistent one
 * ends the fault an earlier transfer left. */
static uint32_t internal_control_write(co_node_t *node, const co_od_entry_t *entry,
                                       const uint8_t *data, size_t len, co_od_origin_t origin)
{
    (void)entry, (void)origin;
    drive_t *drive = drive_of(node);
    const drive_profile_t *profile = drive->profile;
    if (checks_suspended(drive) && !(written_value(data, len) & profile->internal_control_no_check))
        check_configuration(drive, drive_param_value(drive, profile->low_speed),
                            drive_param_value(drive, profile->high_speed), node->now);
    return CO_SDO_OK;
}

const co_od_hook_t drive_speed_limit = {speed_limit_write, NULL};
const co_od_hook_t drive_internal_control = {internal_control_write, NULL};

/* A view's write goes through the full write path of the parameter it stands for (its limits,
 * its hook), so the view refuses what the parameter refuses, with the same abort code. */
static uint32_t write_param(co_node_t *node, drive_param_t param, uint64_t value)
{
    const co_od_entry_t *entry;
    uint32_t abort = co_od_lookup(node->od, param.index, param.subindex, &entry);
    if (abort != CO_SDO_OK)
        return abort;
    uint8_t bytes[8];
    if (entry->size > sizeof bytes ||
        (entry->size < sizeof bytes && value >> (8u * entry->size) != 0))
        return CO_SDO_ABORT_VALUE_HIGH;
    co_put_u32(bytes, (uint32_t)value);
    co_put_u32(bytes + 4, (uint32_t)(value >> 32));
    abort = co_od_write(node, param.index, param.subindex, bytes, entry->size, CO_OD_ORIGIN_APP);
    return abort == CO_SDO_OK ? CO_OD_HANDLED : abort;
}

/* 6046h sub 1 (min) is the low speed and sub 2 (max) the high speed, converted to rpm. */
static drive_param_t limit_of(const drive_t *drive, const co_od_entry_t *entry)
{
    return entry->subindex == 1 ? drive->profile->low_speed : drive->profile->high_speed;
}

/* Held within 6046h's limits: a speed beyond its HighLimit (500.0 Hz at 32767 rpm per 10.0 Hz,
 * motor data no motor has) reads as the HighLimit. */
static int64_t velocity_limit_reported(const drive_t *drive, const co_od_entry_t *entry)
{
    uint32_t decihertz = drive_param_value(drive, limit_of(drive, entry));
    return co_od_saturate(entry, drive_frequency_to_rpm(drive, decihertz));
}

static uint32_t velocity_limits_read(co_node_t *node, const co_od_entry_t *entry)
{
    co_od_set(node, entry, velocity_limit_reported(drive_of(node), entry));
    return CO_SDO_OK;
}

/* The speed the view reads, written back, leaves its parameter as it is: rpm converted back may
 * land on another 0.1 Hz (a motor of less than 1 rpm per 0.1 Hz), and a speed read as the
 * HighLimit stands for any beyond it. */
static uint32_t velocity_limits_write(co_node_t *node, const co_od_entry_t *entry,
                                      const uint8_t *data, size_t len, co_od_origin_t origin)
{
    (void)origin;
    drive_t *drive = drive_of(node);
    uint32_t rpm = written_value(data, len);
    if (rpm == velocity_limit_reported(drive, entry))
        return CO_OD_HANDLED;
    return write_param(node, limit_of(drive, entry), drive_rpm_to_frequency(drive, rpm));
}

const co_od_hook_t drive_velocity_limits = {.write = velocity_limits_write,
                                            .read = velocity_limits_read};

/* 6048h is the acceleration and 6049h the deceleration: delta speed / delta time = nominal speed /
 * ramp time. The view reads the pair last written or read while it still stands for the ramp,
 * else the reduced fraction (nominal speed x 10) / ramp, which represents any ramp time exactly,
 * or, when its terms exceed the objects' HighLimits (NSP 4131 rpm, ACC 7.7 s: 41310 / 77, delta
 * speed at most 32767), the fraction within them nearest to it, which writes back to the same
 * ramp time while the rate is at most the HighLimit of delta speed per second (32726 / 61;
 * docs/decisions.md, D-VIEW-LIMITS). */
static drive_param_t ramp_of(const drive_t *drive, const co_od_entry_t *entry)
{
    return entry->index == CIA402_IDX_VELOCITY_ACCELERATION ? drive->profile->acceleration
                                                            : drive->profile->deceleration;
}

typedef struct ramp_rate {
    uint32_t delta_speed; /* rpm */
    uint32_t delta_time;  /* s */
} ramp_rate_t;

/* The distance of speed / time from the rate, times the rate's time (the same factor for every
 * fraction compared with it). */
static uint64_t rate_error(ramp_rate_t rate, uint64_t speed, uint64_t time)
{
    uint64_t a = speed * rate.delta_time, b = time * rate.delta_speed;
    return a > b ? a - b : b - a;
}

/* The fraction of positive terms of at most `max` nearest rate.delta_speed / rate.delta_time:
 * the fraction itself in lowest terms when they fit, else its best rational approximation. The
 * convergents h/k of its continued fraction, each in lowest terms and nearer than any fraction of
 * smaller terms, are followed while they fit; past the last one, the semiconvergent
 * (h0 + m h1) / (k0 + m k1) with the largest m that fits may be nearer. A zero time (too steep
 * for any delta time) gives max.delta_speed / 1, a rate below 1 / max.delta_time that rate. */
static ramp_rate_t nearest_rate(ramp_rate_t rate, ramp_rate_t max)
{
    uint64_t h0 = 0, k0 = 1, h1 = 1, k1 = 0; /* the convergents before the first: 0/1, 1/0 */
    uint64_t n = rate.delta_speed, d = rate.delta_time;
    while (d != 0) {
        uint64_t a = n / d;
        if (a * h1 + h0 > max.delta_speed || a * k1 + k0 > max.delta_time) {
            uint64_t m = h1 != 0 ? (max.delta_speed - h0) / h1 : UINT64_MAX;
            if (k1 != 0 && (max.delta_time - k0) / k1 < m)
                m = (max.delta_time - k0) / k1;
            uint64_t hm = m * h1 + h0, km = m * k1 + k0;
            if (k1 == 0 ||
                (m != 0 && rate_error(rate, hm, km) * k1 < rate_error(rate, h1, k1) * km))
                h1 = hm, k1 = km;
            break;
        }
        uint64_t h2 = a * h1 + h0, k2 = a * k1 + k0;
        h0 = h1, k0 = k1, h1 = h2, k1 = k2;
        uint64_t r = n % d;
        n = d, d = r;
    }
    if (k1 == 0)
        return (ramp_rate_t){max.delta_speed, 1};
    if (h1 == 0)
        return (ramp_rate_t){1, max.delta_time};
    return (ramp_rate_t){(uint32_t)h1, (uint32_t)k1};
}

/* The view's two entries: delta speed (sub-index 1) and delta time (sub-index 2). */
typedef struct rate_view {
    const co_od_entry_t *speed, *time;
} rate_view_t;

static rate_view_t rate_view(const drive_t *drive, uint16_t index)
{
    return (rate_view_t){co_od_find(drive->profile->od, index, 1),
                         co_od_find(drive->profile->od, index, 2)};
}

/* The highest value of a term (its HighLimit, else its type's). */
static uint32_t term_max(const co_od_entry_t *term)
{
    return term != NULL ? (uint32_t)co_od_saturate(term, UINT32_MAX) : UINT32_MAX;
}

static bool term_within(const co_od_entry_t *term, uint32_t value)
{
    return value != 0 && (term == NULL || co_od_saturate(term, value) == value);
}

/* The pair the view's entries hold: the last one read or written. */
static ramp_rate_t kept_rate(const drive_t *drive, rate_view_t view)
{
    return (ramp_rate_t){(uint32_t)drive_entry_value(drive, view.speed),
                         (uint32_t)drive_entry_value(drive, view.time)};
}

static void keep_rate(drive_t *drive, rate_view_t view, ramp_rate_t rate)
{
    drive_entry_set(drive, view.speed, rate.delta_speed);
    drive_entry_set(drive, view.time, rate.delta_time);
}

/* The ramp time (0.1 s) a rate stands for: delta time x 10 x nominal speed / delta speed,
 * rounded. */
static uint64_t ramp_time_of(const drive_t *drive, ramp_rate_t rate)
{
    uint64_t nominal = drive_param_value(drive, drive->profile->nominal_speed);
    return ((uint64_t)rate.delta_time * 10u * nominal + rate.delta_speed / 2) / rate.delta_speed;
}

/* What the view reads: the pair it holds while that pair still stands for the ramp (written
 * back, it gives the ramp time the drive has), else the nearest fraction to the ramp's rate. So a
 * pair written term by term composes, whatever ramp the first term gave on the way (a master's
 * 700, then 3, from a ramp of 500 / 1: 700 / 3; an image restored record by record), and a
 * master reads back the pair it wrote. */
static ramp_rate_t ramp_rate_of(const drive_t *drive, const co_od_entry_t *entry)
{
    uint32_t ramp = drive_param_value(drive, ramp_of(drive, entry));
    rate_view_t view = rate_view(drive, entry->index);
    ramp_rate_t kept = kept_rate(drive, view);
    if (term_within(view.speed, kept.delta_speed) && term_within(view.time, kept.delta_time) &&
        ramp_time_of(drive, kept) == ramp)
        return kept;
    ramp_rate_t rate = {10u * drive_param_value(drive, drive->profile->nominal_speed), ramp};
    return nearest_rate(rate, (ramp_rate_t){term_max(view.speed), term_max(view.time)});
}

static uint32_t ramp_rate_read(co_node_t *node, const co_od_entry_t *entry)
{
    drive_t *drive = drive_of(node);
    keep_rate(drive, rate_view(drive, entry->index), ramp_rate_of(drive, entry));
    return CO_SDO_OK;
}

/* A term the view reads, written back, leaves the ramp as it is (a rate too steep for the
 * view's terms reads as their limits, which stand for any steeper one). */
static uint32_t ramp_rate_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                size_t len, co_od_origin_t origin)
{
    (void)origin;
    drive_t *drive = drive_of(node);
    rate_view_t view = rate_view(drive, entry->index);
    ramp_rate_t rate = ramp_rate_of(drive, entry);
    uint32_t *term = entry->subindex == 1 ? &rate.delta_speed : &rate.delta_time;
    uint32_t value = written_value(data, len);
    uint32_t abort = CO_OD_HANDLED;
    /* A zero delta speed would be an endless ramp; the dictionary's low limit should refuse it. */
    if (entry->subindex == 1 && value == 0)
        return CO_SDO_ABORT_VALUE_LOW;
    if (value != *term) {
        *term = value;
        abort = write_param(node, ramp_of(drive, entry), ramp_time_of(drive, rate));
    }
    if (abort == CO_OD_HANDLED)
        keep_rate(drive, view, rate);
    return abort;
}

const co_od_hook_t drive_ramp_rate = {.write = ramp_rate_write, .read = ramp_rate_read};

/* Auto-tuning injects current into the standing motor, so it needs Operation enabled (DeviceNet
 * manual, "Operation enabled": "[Auto tuning] (tUn) requires an injection of current"); DONE is
 * the drive's answer, not a command. */
static uint32_t auto_tune_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                size_t len, co_od_origin_t origin)
{
    (void)entry, (void)origin;
    drive_t *drive = drive_of(node);
    uint32_t value = written_value(data, len);
    if (value == DRIVE_AUTO_TUNE_DONE)
        return CO_SDO_ABORT_VALUE_RANGE;
    if (value == DRIVE_AUTO_TUNE_NO) {
        drive->auto_tune_end = CO_TIME_NEVER;
        return CO_SDO_OK;
    }
    drive_motor_advance(&drive->motor, node->now);
    if (drive->cia402.state != CIA402_OPERATION_ENABLED || drive_motor_running(&drive->motor))
        return CO_SDO_ABORT_DATA_STATE;
    drive->auto_tune_end = node->now + DRIVE_AUTO_TUNE_TIME_US;
    return CO_SDO_OK;
}

const co_od_hook_t drive_auto_tune = {auto_tune_write, NULL};

/* The highest fixed value of a switch: the channel pairs' select_second, none (0) for the ramp
 * switch; above it only switching sources. */
static uint32_t switch_fixed_max(const drive_t *drive, const co_od_entry_t *entry)
{
    const drive_profile_t *profile = drive->profile;
    if (drive_is_param(entry, profile->command_channels.select))
        return profile->command_channels.select_second;
    if (drive_is_param(entry, profile->reference_channels.select))
        return profile->reference_channels.select_second;
    return 0;
}

static bool is_switch(const drive_t *drive, const co_od_entry_t *entry)
{
    const drive_profile_t *profile = drive->profile;
    return drive_is_param(entry, profile->command_channels.select) ||
           drive_is_param(entry, profile->reference_channels.select) ||
           drive_is_param(entry, profile->ramp_switch);
}

static bool switch_on_bit(const drive_t *drive, drive_param_t param)
{
    return drive_source_is_bit(drive_param_value(drive, param));
}

/* Something only the full access level allows is set: a separate channel mode (separate, I/O),
 * or a control word bit as a switching source. */
static bool full_access_settings(const drive_t *drive)
{
    const drive_profile_t *profile = drive->profile;
    return drive_mode_separate(profile, drive_param_value(drive, profile->channel_mode)) ||
           switch_on_bit(drive, profile->command_channels.select) ||
           switch_on_bit(drive, profile->reference_channels.select) ||
           switch_on_bit(drive, profile->ramp_switch);
}

/* The access level decides what the command menu may hold (ATV312 DeviceNet manual: "separate
 * mode is only allowed when the [ACCESS LEVEL] (LAC) parameter ... is set to L3"; control word
 * bits 11-15 are reassigned "depending on LAC": "configure LAC = L3 ... and set ... (rPS) to
 * Cd15"). A value the level does not allow, or a lower level while such a value is set, is a
 * parameter incompatibility: the master changes the other parameter first. */
static uint32_t command_setting_check(const drive_t *drive, const co_od_entry_t *entry,
                                      uint32_t value)
{
    const drive_profile_t *profile = drive->profile;
    bool full = drive_access_full(drive);
    if (drive_is_param(entry, profile->access_level))
        return value < profile->access_level_full && full_access_settings(drive)
                   ? CO_SDO_ABORT_PARAM_INCOMPATIBLE
                   : CO_SDO_OK;
    if (drive_is_param(entry, profile->channel_mode))
        return drive_mode_separate(profile, value) && !full ? CO_SDO_ABORT_PARAM_INCOMPATIBLE
                                                            : CO_SDO_OK;
    if (!is_switch(drive, entry) || value <= switch_fixed_max(drive, entry))
        return CO_SDO_OK;
    if (!drive_source_valid(drive, value))
        return CO_SDO_ABORT_VALUE_RANGE;
    return drive_source_is_bit(value) && !full ? CO_SDO_ABORT_PARAM_INCOMPATIBLE : CO_SDO_OK;
}

static uint32_t command_setting_write(co_node_t *node, const co_od_entry_t *entry,
                                      const uint8_t *data, size_t len, co_od_origin_t origin)
{
    uint32_t abort = command_setting_check(drive_of(node), entry, written_value(data, len));
    return abort != CO_SDO_OK ? abort : configuration_write(node, entry, data, len, origin);
}

const co_od_hook_t drive_command_setting = {command_setting_write, NULL};
