/* Motor model: the speed follows its target on linear ramps (ACC away from zero, DEC or the fast
 * ramp towards zero; times in 0.1 s from 0 to nominal speed), plausible torque and current. */
#ifndef ATV312_MOTOR_H
#define ATV312_MOTOR_H

#include "atv312/atv312.h"

/* Ramps are sampled this often while they run: the status word and speed objects change at
 * this rate, and the exact end of a ramp segment is a deadline of its own. */
#define ATV312_MOTOR_TICK_US 10000u

void atv312_motor_reset(atv312_motor_t *motor, co_time_t now);
/* Moves the speed along the ramps up to `now`, with the target and parameters set so far. */
void atv312_motor_advance(atv312_motor_t *motor, co_time_t now);
/* New target, stop ramp or ramp parameters, effective from the time of the last advance. */
void atv312_motor_steer(atv312_motor_t *motor, int32_t target_rpm, bool fast,
                        const atv312_ramp_t *ramp);
/* Freewheel: the drive's output is off, the speed it reports drops to 0 at once. */
void atv312_motor_coast(atv312_motor_t *motor);
int32_t atv312_motor_rpm(const atv312_motor_t *motor);
bool atv312_motor_at_target(const atv312_motor_t *motor);
/* Next sample of a running ramp, CO_TIME_NEVER when steady. */
co_time_t atv312_motor_deadline(const atv312_motor_t *motor);
/* Torque in % of nominal while the output is on: load plus the torque the ramp demands. */
int16_t atv312_motor_torque(const atv312_motor_t *motor);

#endif
