/* SPDX-License-Identifier: Apache-2.0 */
/* The TIME_OF_DAY data type (co_time_of_day.h): codec, host clock, calendar and text. */
#include "co/co_time_of_day.h"

void co_time_of_day_encode(const co_time_of_day_t *time, uint8_t data[CO_TIME_OF_DAY_LEN])
{
    co_put_u32(data, time->ms & CO_TIME_OF_DAY_MS_MASK);
    co_put_u16(&data[4], time->days);
}

bool co_time_of_day_decode(const uint8_t *data, size_t len, co_time_of_day_t *time)
{
    if (len != CO_TIME_OF_DAY_LEN)
        return false;
    time->ms = co_get_u32(data) & CO_TIME_OF_DAY_MS_MASK;
    time->days = co_get_u16(&data[4]);
    return true;
}

bool co_time_of_day_from_unix_ms(uint64_t unix_ms, co_time_of_day_t *time)
{
    uint64_t days = unix_ms / CO_TIME_MS_PER_DAY;
    if (days < CO_TIME_EPOCH_DAYS_FROM_1970 || days - CO_TIME_EPOCH_DAYS_FROM_1970 > UINT16_MAX)
        return false;
    time->days = (uint16_t)(days - CO_TIME_EPOCH_DAYS_FROM_1970);
    time->ms = (uint32_t)(unix_ms % CO_TIME_MS_PER_DAY);
    return true;
}

/* Days since 1970-01-01 to a date of the proleptic Gregorian calendar, by 400-year eras of
 * 146 097 days whose years start on 1 March (so that the leap day ends the year); days are never
 * before 1970 here. */
void co_time_of_day_civil(const co_time_of_day_t *time, co_civil_time_t *civil)
{
    uint32_t z = time->days + CO_TIME_EPOCH_DAYS_FROM_1970 + 719468u; /* from 0000-03-01 */
    uint32_t era = z / 146097u;
    uint32_t doe = z - era * 146097u;
    uint32_t yoe = (doe - doe / 1460u + doe / 36524u - doe / 146096u) / 365u;
    uint32_t doy = doe - (365u * yoe + yoe / 4u - yoe / 100u);
    uint32_t mp = (5u * doy + 2u) / 153u;
    civil->day = (uint8_t)(doy - (153u * mp + 2u) / 5u + 1u);
    civil->month = (uint8_t)(mp < 10u ? mp + 3u : mp - 9u);
    civil->year = (int)(yoe + era * 400u + (civil->month <= 2u ? 1u : 0u));
    uint32_t ms = time->ms;
    civil->hour = (uint8_t)(ms / 3600000u);
    civil->minute = (uint8_t)(ms / 60000u % 60u);
    civil->second = (uint8_t)(ms / 1000u % 60u);
    civil->ms = (uint16_t)(ms % 1000u);
}

/* Writes `value` as `digits` decimal digits, zeros in front, and returns the end. */
static char *put_digits(char *p, uint32_t value, unsigned digits)
{
    for (unsigned i = digits; i > 0; i--) {
        p[i - 1] = (char)('0' + value % 10u);
        value /= 10u;
    }
    return p + digits;
}

void co_time_of_day_format(const co_time_of_day_t *time, char text[CO_TIME_OF_DAY_TEXT_SIZE])
{
    co_civil_time_t c;
    co_time_of_day_civil(time, &c);
    /* 1984..2163: always four digits of year. */
    char *p = put_digits(text, (uint32_t)c.year, 4);
    *p++ = '-';
    p = put_digits(p, c.month, 2);
    *p++ = '-';
    p = put_digits(p, c.day, 2);
    *p++ = ' ';
    p = put_digits(p, c.hour, 2);
    *p++ = ':';
    p = put_digits(p, c.minute, 2);
    *p++ = ':';
    p = put_digits(p, c.second, 2);
    *p++ = '.';
    p = put_digits(p, c.ms, 3);
    *p = '\0';
}
