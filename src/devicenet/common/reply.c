/* SPDX-License-Identifier: Apache-2.0 */
/* The builders of a success response's data (dn_reply_t, include/dn/dn_node.h), which the
 * library's objects and the application's classes fill: little-endian values, byte strings and
 * SHORT_STRINGs, an overflow kept for the message router to answer. */
#include "dn/dn_node.h"

#include <string.h>

void dn_reply_bytes(dn_reply_t *reply, const void *data, size_t len)
{
    if (len > sizeof(reply->data) - reply->len) {
        reply->overflow = true;
        return;
    }
    memcpy(&reply->data[reply->len], data, len);
    reply->len = (uint8_t)(reply->len + len);
}

void dn_reply_u8(dn_reply_t *reply, uint8_t value)
{
    dn_reply_bytes(reply, &value, 1);
}

void dn_reply_u16(dn_reply_t *reply, uint16_t value)
{
    uint8_t le[2];
    co_put_u16(le, value);
    dn_reply_bytes(reply, le, sizeof(le));
}

void dn_reply_u32(dn_reply_t *reply, uint32_t value)
{
    uint8_t le[4];
    co_put_u32(le, value);
    dn_reply_bytes(reply, le, sizeof(le));
}

void dn_reply_short_string(dn_reply_t *reply, const char *text)
{
    size_t len = text ? strlen(text) : 0;
    dn_reply_u8(reply, (uint8_t)len);
    dn_reply_bytes(reply, text, len);
}
