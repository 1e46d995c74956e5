/* SPDX-License-Identifier: Apache-2.0 */
/* Motor model of a velocity drive: the speed follows its target on linear ramps (the acceleration
 * ramp away from zero, the deceleration or the fast ramp towards zero; times in 0.1 s from 0 to
 * nominal speed), with plausible torque. Time is passed in; no dictionary, no state machine. */
#ifndef DRIVE_MOTOR_H
#define DRIVE_MOTOR_H

#include "co/co_types.h"

/* Ramps are sampled this often while they run: the status word and speed objects change at
 * this rate, and the exact end of a ramp segment is a deadline of its own. */
#define DRIVE_MOTOR_TICK_US 10000u

/* Ramp parameters as the motor model uses them, refreshed from the dictionary. */
typedef struct drive_ramp {
    uint16_t acc;         /* 0.1 s from 0 to nominal speed */
    uint16_t dec;         /* 0.1 s from nominal speed to 0 */
    uint16_t fast_dec;    /* fast stop / quick stop ramp, 0.1 s */
    uint16_t nominal_rpm; /* nominal motor speed */
} drive_ramp_t;

/* The motor: speed in milli-rpm so that ramps of any slope add up exactly over time. */
typedef struct drive_motor {
    int64_t speed;      /* milli-rpm, signed (negative = reverse) */
    int32_t target;     /* rpm the ramp is heading to */
    bool fast;          /* decelerate on the fast ramp */
    int8_t phase;       /* +1 accelerating, -1 decelerating, 0 steady, over the last interval */
    uint64_t remainder; /* of the last ramp division, carried to the next interval */
    co_time_t updated;  /* time the speed refers to */
    drive_ramp_t ramp;  /* parameters used since `updated` */
    uint8_t load;       /* extra load torque while turning, % of nominal torque */
} drive_motor_t;

void drive_motor_reset(drive_motor_t *motor, co_time_t now);
/* Moves the speed along the ramps up to `now`, with the target and parameters set so far. */
void drive_motor_advance(drive_motor_t *motor, co_time_t now);
/* New target, stop ramp or ramp parameters, effective from the time of the last advance. */
void drive_motor_steer(drive_motor_t *motor, int32_t target_rpm, bool fast,
                       const drive_ramp_t *ramp);
/* Freewheel: the drive's output is off, the speed it reports drops to 0 at once. */
void drive_motor_coast(drive_motor_t *motor);
int32_t drive_motor_rpm(const drive_motor_t *motor);
/* The motor stands (exactly, not rounded to rpm). */
bool drive_motor_stands(const drive_motor_t *motor);
/* The motor turns or has a non-zero target. */
bool drive_motor_running(const drive_motor_t *motor);
/* It turns in reverse, or stands with a reverse target. */
bool drive_motor_reverse(const drive_motor_t *motor);
bool drive_motor_at_target(const drive_motor_t *motor);
/* Next sample of a running ramp, CO_TIME_NEVER when steady. */
co_time_t drive_motor_deadline(const drive_motor_t *motor);
/* An extra load, % of nominal torque, added to the torque while the motor turns (0 after a
 * reset). */
void drive_motor_load(drive_motor_t *motor, uint8_t percent);
/* Torque in % of nominal while the output is on: the fan-like load, the extra load while
 * turning, and the torque the ramp demands, limited to 150 %. */
int16_t drive_motor_torque(const drive_motor_t *motor);

#endif
