/* The Altivar 312's profile: where eds/ATV312.eds puts the drive's parameters (manufacturer
 * parameters at 0x2000 + (ADL - 3000) / 100, sub-index ADL mod 100 + 1, SPEC section 2) and the
 * ATV312's default assignment of control word bits 11-14 (DeviceNet manual, "CMD control word":
 * "CMD = 16#080F: reverse operation" ...). */
#include "atv312/atv312.h"

const drive_profile_t atv312_profile = {
    .od = &atv312_od,
    .control_reverse = 0x0800,   /* bit 11 */
    .control_ramp_stop = 0x1000, /* bit 12: stop on the ramp (Stt = ramp) */
    /* Bit 13, DC injection stop, is modelled as the fast stop of bit 14. */
    .control_fast_stop = 0x2000 | 0x4000,
    .status_reverse = 0x8000,         /* ETA bit 15: direction of rotation */
    .fast_ramp_divider = 4,           /* dCF, the ramp divider's default */
    .acceleration = {0x203C, 2},      /* ACC, ADL 9001 */
    .deceleration = {0x203C, 3},      /* DEC, ADL 9002 */
    .high_speed = {0x2001, 5},        /* HSP, ADL 3104 */
    .low_speed = {0x2001, 6},         /* LSP, ADL 3105 */
    .nominal_frequency = {0x2042, 3}, /* FRS, ADL 9602 */
    .nominal_current = {0x2042, 4},   /* NCR, ADL 9603 */
    .nominal_speed = {0x2042, 5},     /* NSP, ADL 9604 */
    .motor_current = {0x2002, 4},     /* LCR, ADL 3203 */
    .motor_torque = {0x2002, 9},      /* OTR, ADL 3208 */
    .control_word_copy = {0x2037, 2}, /* CMD, ADL 8501 */
    .status_word_copy = {0x2002, 2},  /* ETA, ADL 3201 */
};
