/* SPDX-License-Identifier: Apache-2.0 */
/* Motor model. The speed is kept in milli-rpm and every ramp division carries its remainder to
 * the next interval, so a ramp reaches the same speed at the same time however often it is
 * sampled (ACC = 3.0 s to 1500 rpm gives exactly 1200 rpm at 2.4 s). */
#include "drive/motor.h"

#define MILLI 1000
#define RAMP_UNIT_US 100000u   /* ramp times are in 0.1 s */
#define LOAD_TORQUE_PERCENT 20 /* at nominal speed, steady */
#define TORQUE_LIMIT_PERCENT 150

static int64_t magnitude(int64_t v)
{
    return v < 0 ? -v : v;
}

void drive_motor_reset(drive_motor_t *motor, co_time_t now)
{
    *motor = (drive_motor_t){.updated = now};
}

/* Where the current ramp segment ends: the target, or zero first when the direction reverses. */
static int64_t segment_goal(const drive_motor_t *motor)
{
    int64_t goal = (int64_t)motor->target * MILLI;
    if ((motor->speed > 0 && goal < 0) || (motor->speed < 0 && goal > 0))
        return 0;
    return goal;
}

static bool segment_accelerates(const drive_motor_t *motor, int64_t goal)
{
    return magnitude(goal) > magnitude(motor->speed);
}

/* Ramp time of the segment, in microseconds for a change of nominal speed. */
static uint64_t segment_period(const drive_motor_t *motor, bool accelerates)
{
    uint16_t ramp =
        accelerates ? motor->ramp.acc : (motor->fast ? motor->ramp.fast_dec : motor->ramp.dec);
    return (uint64_t)(ramp ? ramp : 1) * RAMP_UNIT_US;
}

static uint64_t segment_rate(const drive_motor_t *motor)
{
    return (uint64_t)(motor->ramp.nominal_rpm ? motor->ramp.nominal_rpm : 1) * MILLI;
}

/* Microseconds until the segment reaches its goal. */
static uint64_t segment_time_left(const drive_motor_t *motor, int64_t goal)
{
    uint64_t period = segment_period(motor, segment_accelerates(motor, goal));
    uint64_t rate = segment_rate(motor);
    uint64_t distance = (uint64_t)magnitude(goal - motor->speed) * period - motor->remainder;
    return (distance + rate - 1) / rate;
}

void drive_motor_advance(drive_motor_t *motor, co_time_t now)
{
    if (now <= motor->updated)
        return;
    uint64_t elapsed = now - motor->updated;
    motor->updated = now;
    motor->phase = 0;
    while (elapsed > 0 && motor->speed != (int64_t)motor->target * MILLI) {
        int64_t goal = segment_goal(motor);
        bool accelerates = segment_accelerates(motor, goal);
        motor->phase = accelerates ? 1 : -1;
        uint64_t needed = segment_time_left(motor, goal);
        if (elapsed >= needed) {
            motor->speed = goal;
            motor->remainder = 0;
            elapsed -= needed;
            continue;
        }
        uint64_t period = segment_period(motor, accelerates);
        uint64_t travel = segment_rate(motor) * elapsed + motor->remainder;
        int64_t step = (int64_t)(travel / period);
        motor->remainder = travel % period;
        motor->speed += goal > motor->speed ? step : -step;
        elapsed = 0;
    }
    if (drive_motor_at_target(motor))
        motor->phase = 0;
}

void drive_motor_steer(drive_motor_t *motor, int32_t target_rpm, bool fast,
                       const drive_ramp_t *ramp)
{
    bool same_ramp = motor->ramp.acc == ramp->acc && motor->ramp.dec == ramp->dec &&
                     motor->ramp.fast_dec == ramp->fast_dec &&
                     motor->ramp.nominal_rpm == ramp->nominal_rpm;
    if (motor->target == target_rpm && motor->fast == fast && same_ramp)
        return;
    /* The remainder belongs to the slope it was computed for. */
    motor->remainder = 0;
    motor->target = target_rpm;
    motor->fast = fast;
    motor->ramp = *ramp;
}

void drive_motor_coast(drive_motor_t *motor)
{
    motor->speed = 0;
    motor->remainder = 0;
    motor->phase = 0;
}

int32_t drive_motor_rpm(const drive_motor_t *motor)
{
    return (int32_t)(motor->speed / MILLI);
}

bool drive_motor_stands(const drive_motor_t *motor)
{
    return motor->speed == 0;
}

bool drive_motor_running(const drive_motor_t *motor)
{
    return motor->speed != 0 || motor->target != 0;
}

bool drive_motor_reverse(const drive_motor_t *motor)
{
    return motor->speed < 0 || (motor->speed == 0 && motor->target < 0);
}

bool drive_motor_at_target(const drive_motor_t *motor)
{
    return motor->speed == (int64_t)motor->target * MILLI;
}

co_time_t drive_motor_deadline(const drive_motor_t *motor)
{
    if (drive_motor_at_target(motor))
        return CO_TIME_NEVER;
    uint64_t left = segment_time_left(motor, segment_goal(motor));
    return motor->updated + (left < DRIVE_MOTOR_TICK_US ? left : DRIVE_MOTOR_TICK_US);
}

void drive_motor_load(drive_motor_t *motor, uint8_t percent)
{
    motor->load = percent;
}

int16_t drive_motor_torque(const drive_motor_t *motor)
{
    int64_t nominal = motor->ramp.nominal_rpm ? motor->ramp.nominal_rpm : 1;
    int64_t torque = LOAD_TORQUE_PERCENT * magnitude(motor->speed) / (nominal * MILLI);
    if (motor->speed != 0)
        torque += motor->load;
    if (motor->phase != 0) {
        /* 100 % torque accelerates the load from 0 to nominal speed in 1 s. */
        uint64_t period = segment_period(motor, motor->phase > 0);
        torque += motor->phase * (int64_t)(100 * 10 * RAMP_UNIT_US / period);
    }
    if (torque > TORQUE_LIMIT_PERCENT)
        torque = TORQUE_LIMIT_PERCENT;
    if (torque < -TORQUE_LIMIT_PERCENT)
        torque = -TORQUE_LIMIT_PERCENT;
    return (int16_t)torque;
}
