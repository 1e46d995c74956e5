/* Hooks named in atv312.hooks: the ATV312 rules on its own parameters, and the CiA 402 objects
 * that are views of drive parameters (6046h of LSP/HSP, 6048h/6049h of ACC/DEC). */
#include "cia402.h"
#include "drive.h"

/* SPEC section 2: RPDO6 accepts 1-240 (synchronous), 254 and 255 (asynchronous). */
static uint32_t rpdo6_type_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len, co_od_origin_t origin)
{
    (void)node, (void)entry, (void)len, (void)origin;
    uint8_t type = data[0];
    return (type >= 1 && type <= 240) || type >= 254 ? CO_SDO_OK : SDO_ABORT_VALUE_RANGE;
}

/* SPEC section 2: TPDO6 accepts 0 (synchronous acyclic), 1-240, 254 and 255. */
static uint32_t tpdo6_type_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                 size_t len, co_od_origin_t origin)
{
    (void)node, (void)entry, (void)len, (void)origin;
    uint8_t type = data[0];
    return type <= 240 || type >= 254 ? CO_SDO_OK : SDO_ABORT_VALUE_RANGE;
}

const co_od_hook_t atv312_rpdo6_type = {rpdo6_type_write, NULL};
const co_od_hook_t atv312_tpdo6_type = {tpdo6_type_write, NULL};

/* Motor data are configuration parameters (ATV312 DeviceNet manual, drive state machine): they
 * change only with the motor stopped, and a change returns the drive to Switch on disabled. */
static uint32_t motor_config_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                   size_t len, co_od_origin_t origin)
{
    (void)entry, (void)data, (void)len, (void)origin;
    atv312_t *drive = atv312_of(node);
    atv312_advance(drive, node->now);
    if (atv312_motor_running(drive))
        return SDO_ABORT_DATA_STATE;
    atv312_cia402_configuration_changed(&drive->cia402);
    return CO_SDO_OK;
}

const co_od_hook_t atv312_motor_config = {motor_config_write, NULL};

/* LSP may not exceed HSP (CiA 301 abort "maximum value is less than minimum value"). */
static uint32_t check_speed_limits(uint32_t low, uint32_t high)
{
    return low > high ? SDO_ABORT_MAX_LESS_MIN : CO_SDO_OK;
}

static uint32_t speed_limit_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                  size_t len, co_od_origin_t origin)
{
    (void)len, (void)origin;
    atv312_t *drive = atv312_of(node);
    uint16_t value = co_get_u16(data);
    bool is_high = entry->subindex == ATV312_SUB_HSP;
    uint16_t other =
        atv312_param(drive, ATV312_IDX_LIMITS, is_high ? ATV312_SUB_LSP : ATV312_SUB_HSP);
    return is_high ? check_speed_limits(other, value) : check_speed_limits(value, other);
}

const co_od_hook_t atv312_speed_limit = {speed_limit_write, NULL};

/* 6046h sub 1 (min) is LSP and sub 2 (max) is HSP, converted to rpm. */
static uint8_t limit_sub_of(const co_od_entry_t *entry)
{
    return entry->subindex == 1 ? ATV312_SUB_LSP : ATV312_SUB_HSP;
}

static uint32_t velocity_limits_read(co_node_t *node, const co_od_entry_t *entry)
{
    atv312_t *drive = atv312_of(node);
    uint16_t decihertz = atv312_param(drive, ATV312_IDX_LIMITS, limit_sub_of(entry));
    co_od_set(node, entry, atv312_frequency_to_rpm(drive, decihertz));
    return CO_SDO_OK;
}

static uint32_t velocity_limits_write(co_node_t *node, const co_od_entry_t *entry,
                                      const uint8_t *data, size_t len, co_od_origin_t origin)
{
    (void)len, (void)origin;
    atv312_t *drive = atv312_of(node);
    uint32_t decihertz = atv312_rpm_to_frequency(drive, co_get_u32(data));
    if (decihertz > ATV312_FREQUENCY_MAX)
        return SDO_ABORT_VALUE_HIGH;
    uint8_t sub = limit_sub_of(entry);
    uint32_t low =
        sub == ATV312_SUB_LSP ? decihertz : atv312_param(drive, ATV312_IDX_LIMITS, ATV312_SUB_LSP);
    uint32_t high =
        sub == ATV312_SUB_HSP ? decihertz : atv312_param(drive, ATV312_IDX_LIMITS, ATV312_SUB_HSP);
    uint32_t abort = check_speed_limits(low, high);
    if (abort == CO_SDO_OK)
        co_od_set_value(node, ATV312_IDX_LIMITS, sub, decihertz);
    return abort;
}

const co_od_hook_t atv312_velocity_limits = {.write = velocity_limits_write,
                                             .read = velocity_limits_read};

/* 6048h is ACC and 6049h DEC: delta speed / delta time = nominal speed / ramp time, kept as
 * the reduced fraction (NSP x 10) / ramp so that any ramp time is represented exactly. */
static uint8_t ramp_sub_of(const co_od_entry_t *entry)
{
    return entry->index == ATV312_IDX_VELOCITY_ACCELERATION ? ATV312_SUB_ACC : ATV312_SUB_DEC;
}

static uint32_t greatest_common_divisor(uint32_t a, uint32_t b)
{
    while (b != 0) {
        uint32_t r = a % b;
        a = b;
        b = r;
    }
    return a;
}

typedef struct ramp_rate {
    uint32_t delta_speed; /* rpm */
    uint32_t delta_time;  /* s */
} ramp_rate_t;

static ramp_rate_t ramp_rate_of(const atv312_t *drive, uint8_t ramp_sub)
{
    uint32_t speed = 10u * atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NSP);
    uint32_t time = atv312_param(drive, ATV312_IDX_RAMPS, ramp_sub);
    uint32_t divisor = greatest_common_divisor(speed, time);
    if (divisor == 0)
        divisor = 1;
    return (ramp_rate_t){speed / divisor, time / divisor};
}

static uint32_t ramp_rate_read(co_node_t *node, const co_od_entry_t *entry)
{
    ramp_rate_t rate = ramp_rate_of(atv312_of(node), ramp_sub_of(entry));
    co_od_set(node, entry, entry->subindex == 1 ? rate.delta_speed : rate.delta_time);
    return CO_SDO_OK;
}

static uint32_t ramp_rate_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                                size_t len, co_od_origin_t origin)
{
    (void)origin;
    atv312_t *drive = atv312_of(node);
    uint8_t ramp_sub = ramp_sub_of(entry);
    ramp_rate_t rate = ramp_rate_of(drive, ramp_sub);
    uint32_t value = len == 4 ? co_get_u32(data) : co_get_u16(data);
    if (entry->subindex == 1)
        rate.delta_speed = value;
    else
        rate.delta_time = value;
    uint64_t nominal = atv312_param(drive, ATV312_IDX_MOTOR, ATV312_SUB_NSP);
    /* ramp (0.1 s) = delta time x 10 x NSP / delta speed, rounded. */
    uint64_t ramp =
        ((uint64_t)rate.delta_time * 10u * nominal + rate.delta_speed / 2) / rate.delta_speed;
    if (ramp > ATV312_RAMP_MAX)
        return SDO_ABORT_VALUE_HIGH;
    if (ramp < 1)
        return SDO_ABORT_VALUE_LOW;
    co_od_set_value(node, ATV312_IDX_RAMPS, ramp_sub, (int64_t)ramp);
    return CO_SDO_OK;
}

const co_od_hook_t atv312_ramp_rate = {.write = ramp_rate_write, .read = ramp_rate_read};
