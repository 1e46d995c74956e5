/* Internal interface between the drive's glue (atv312.c) and its object dictionary hooks
 * (od_hooks.c). */
#ifndef ATV312_DRIVE_H
#define ATV312_DRIVE_H

#include "atv312/atv312.h"

/* Objects of eds/ATV312.eds the drive reads or writes. Manufacturer parameters sit at
 * 0x2000 + (ADL - 3000) / 100, sub-index ADL mod 100 + 1 (SPEC section 2). */
#define ATV312_IDX_ERROR_CODE 0x603Fu
#define ATV312_IDX_CONTROLWORD 0x6040u
#define ATV312_IDX_STATUSWORD 0x6041u
#define ATV312_IDX_TARGET_VELOCITY 0x6042u
#define ATV312_IDX_VELOCITY_DEMAND 0x6043u
#define ATV312_IDX_VELOCITY_ACTUAL 0x6044u
#define ATV312_IDX_VELOCITY_ACCELERATION 0x6048u
#define ATV312_IDX_LIMITS 0x2001u /* HSP ADL 3104, LSP ADL 3105 */
#define ATV312_SUB_HSP 5u
#define ATV312_SUB_LSP 6u
#define ATV312_IDX_MONITORING 0x2002u /* ETA 3201, LCR 3203, OTR 3208 */
#define ATV312_SUB_ETA 2u
#define ATV312_SUB_LCR 4u
#define ATV312_SUB_OTR 9u
#define ATV312_IDX_COMMAND 0x2037u /* CMD 8501 */
#define ATV312_SUB_CMD 2u
#define ATV312_IDX_RAMPS 0x203Cu /* ACC 9001, DEC 9002 */
#define ATV312_SUB_ACC 2u
#define ATV312_SUB_DEC 3u
#define ATV312_IDX_MOTOR 0x2042u /* FRS 9602, NCR 9603, NSP 9604 */
#define ATV312_SUB_FRS 3u
#define ATV312_SUB_NCR 4u
#define ATV312_SUB_NSP 5u

/* Largest ramp time and frequency the dictionary accepts (0.1 s, 0.1 Hz). */
#define ATV312_RAMP_MAX 9999u
#define ATV312_FREQUENCY_MAX 5000u

atv312_t *atv312_of(co_node_t *node);
/* Brings the motor model up to `now` before anything it depends on changes. */
void atv312_advance(atv312_t *drive, co_time_t now);
/* Recomputes the motor's target from the state and the dictionary, and publishes the status
 * word, speeds, current and torque. */
void atv312_settle(atv312_t *drive);
/* The motor turns or has a run command with a non-zero target. */
bool atv312_motor_running(const atv312_t *drive);
/* Unsigned 16-bit parameter of the dictionary. */
uint16_t atv312_param(const atv312_t *drive, uint16_t index, uint8_t subindex);
/* Conversions between 0.1 Hz and rpm through the motor's nominal frequency and speed. */
uint32_t atv312_frequency_to_rpm(const atv312_t *drive, uint32_t decihertz);
uint32_t atv312_rpm_to_frequency(const atv312_t *drive, uint32_t rpm);

#endif
