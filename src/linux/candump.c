/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/candump.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char hex_digits[] = "0123456789ABCDEF";

#define NSEC_PER_SEC 1000000000L

size_t co_candump_format(char *buf, size_t cap, const struct timespec *wall, const char *iface,
                         const struct can_frame *frame)
{
    int n = snprintf(buf, cap, "(%010lld.%06ld) %s ", (long long)wall->tv_sec, wall->tv_nsec / 1000,
                     iface);
    if (n < 0 || (size_t)n + 8 + 1 + 2 * CAN_MAX_DLEN + 2 > cap)
        return 0;
    char *p = buf + n;
    canid_t id = frame->can_id;
    if (id & CAN_ERR_FLAG)
        p += sprintf(p, "%08X", (unsigned)(id & (CAN_ERR_MASK | CAN_ERR_FLAG)));
    else if (id & CAN_EFF_FLAG)
        p += sprintf(p, "%08X", (unsigned)(id & CAN_EFF_MASK));
    else
        p += sprintf(p, "%03X", (unsigned)(id & CAN_SFF_MASK));
    *p++ = '#';
    uint8_t len = frame->len > CAN_MAX_DLEN ? CAN_MAX_DLEN : frame->len;
    if (id & CAN_RTR_FLAG) {
        *p++ = 'R';
        if (len)
            *p++ = hex_digits[len];
    } else {
        for (uint8_t i = 0; i < len; i++) {
            *p++ = hex_digits[frame->data[i] >> 4];
            *p++ = hex_digits[frame->data[i] & 0xF];
        }
    }
    *p++ = '\n';
    *p = '\0';
    return (size_t)(p - buf);
}

static int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = (char)toupper((unsigned char)c);
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* Reads exactly `digits` hex digits. */
static bool parse_hex(const char **p, int digits, unsigned long *value)
{
    *value = 0;
    for (int i = 0; i < digits; i++) {
        int v = hex_value((*p)[i]);
        if (v < 0)
            return false;
        *value = *value << 4 | (unsigned long)v;
    }
    *p += digits;
    return true;
}

/* Reads "(SECONDS.FRACTION) ". candump writes 6 fraction digits, but canplayer and log2asc read
 * any number of digits on either side of the point (at least one each), so hand-written and
 * other tools' logs such as "(1.0)" are accepted too. The fraction is read as a decimal fraction
 * of a second, kept to the nanosecond (D-CANDUMP-FRACTION). */
static bool parse_timestamp(const char **p, struct timespec *wall)
{
    const char *s = *p;
    if (*s++ != '(' || !isdigit((unsigned char)*s))
        return false;
    char *end;
    errno = 0;
    long long sec = strtoll(s, &end, 10);
    if (errno == ERANGE || *end != '.' || !isdigit((unsigned char)end[1]))
        return false;
    s = end + 1;
    long nsec = 0;
    long scale = NSEC_PER_SEC;
    for (; isdigit((unsigned char)*s); s++) {
        scale /= 10;
        nsec += (*s - '0') * scale;
    }
    if (*s++ != ')' || *s++ != ' ')
        return false;
    wall->tv_sec = (time_t)sec;
    wall->tv_nsec = nsec;
    *p = s;
    return true;
}

static bool parse_iface(const char **p, char iface[IFNAMSIZ])
{
    const char *space = strchr(*p, ' ');
    if (!space || space == *p || space - *p >= IFNAMSIZ)
        return false;
    memcpy(iface, *p, (size_t)(space - *p));
    iface[space - *p] = '\0';
    *p = space + 1;
    return true;
}

static bool parse_id(const char **p, canid_t *id)
{
    const char *hash = strchr(*p, '#');
    unsigned long value;
    if (!hash)
        return false;
    if (hash - *p == 3) {
        if (!parse_hex(p, 3, &value) || value > CAN_SFF_MASK)
            return false;
        *id = (canid_t)value;
    } else if (hash - *p == 8) {
        if (!parse_hex(p, 8, &value))
            return false;
        if (value > (CAN_ERR_FLAG | CAN_ERR_MASK))
            return false;
        if (value & CAN_ERR_FLAG)
            *id = (canid_t)value;
        else
            *id = (canid_t)value | CAN_EFF_FLAG;
    } else {
        return false;
    }
    (*p)++; /* the '#' */
    return true;
}

static bool at_line_end(const char *p)
{
    return *p == '\0' || (*p == '\n' && p[1] == '\0');
}

static bool parse_payload(const char *p, struct can_frame *frame)
{
    if (*p == 'R') {
        frame->can_id |= CAN_RTR_FLAG;
        p++;
        int dlc = hex_value(*p);
        if (dlc >= 0 && dlc <= CAN_MAX_DLEN) {
            frame->len = (uint8_t)dlc;
            p++;
        }
        return at_line_end(p);
    }
    while (!at_line_end(p)) {
        unsigned long byte;
        if (frame->len == CAN_MAX_DLEN || !parse_hex(&p, 2, &byte))
            return false;
        frame->data[frame->len++] = (uint8_t)byte;
    }
    return true;
}

bool co_candump_parse(const char *line, struct timespec *wall, char iface[IFNAMSIZ],
                      struct can_frame *frame)
{
    memset(frame, 0, sizeof *frame);
    const char *p = line;
    return parse_timestamp(&p, wall) && parse_iface(&p, iface) && parse_id(&p, &frame->can_id) &&
           parse_payload(p, frame);
}
