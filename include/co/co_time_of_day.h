/* SPDX-License-Identifier: Apache-2.0 */
/* The TIME_OF_DAY data type (CiA 301 7.1.6.5): the 6 bytes of a TIME frame, the host clock's
 * milliseconds to it, its calendar date and its text. Shared by the TIME service
 * (co_time_stamp.h) and the tools that send or decode a TIME (cotrace, comaster, atv312d);
 * without stdio, so that a firmware may print a date too. docs/time.md. */
#ifndef CO_TIME_OF_DAY_H
#define CO_TIME_OF_DAY_H

#include "co_types.h"

/* TIME_OF_DAY (CiA 301 7.1.6.5): 28 bits of milliseconds after midnight, 4 bits reserved (0),
 * then 16 bits of days since 1984-01-01: 6 bytes, little-endian. */
#define CO_TIME_OF_DAY_LEN 6u
#define CO_TIME_OF_DAY_MS_MASK 0x0FFFFFFFu
#define CO_TIME_MS_PER_DAY 86400000u
/* 1984-01-01 is day 5113 of the Unix epoch (1970-01-01). */
#define CO_TIME_EPOCH_DAYS_FROM_1970 5113u

typedef struct co_time_of_day {
    uint32_t ms;   /* after midnight, 0..86 399 999 */
    uint16_t days; /* since 1984-01-01 */
} co_time_of_day_t;

/* A TIME_OF_DAY as a calendar date and time (proleptic Gregorian, no time zone). */
typedef struct co_civil_time {
    int year;
    uint8_t month; /* 1..12 */
    uint8_t day;   /* 1..31 */
    uint8_t hour;
    uint8_t minute;
    uint8_t second;
    uint16_t ms;
} co_civil_time_t;

/* The 6 bytes of a TIME frame. */
void co_time_of_day_encode(const co_time_of_day_t *time, uint8_t data[CO_TIME_OF_DAY_LEN]);
/* False for a frame of another length than 6; the reserved bits are ignored. */
bool co_time_of_day_decode(const uint8_t *data, size_t len, co_time_of_day_t *time);
/* Milliseconds since 1970-01-01 (a host's clock in UTC) to a TIME_OF_DAY; false before 1984 or
 * after the last day 16 bits count (2163-06-06). */
bool co_time_of_day_from_unix_ms(uint64_t unix_ms, co_time_of_day_t *time);
void co_time_of_day_civil(const co_time_of_day_t *time, co_civil_time_t *civil);

/* "2026-11-29 12:34:56.789" and its NUL: the date and time of day, as the tools print a TIME. */
#define CO_TIME_OF_DAY_TEXT_SIZE 24u
void co_time_of_day_format(const co_time_of_day_t *time, char text[CO_TIME_OF_DAY_TEXT_SIZE]);

#endif
