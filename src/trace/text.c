/* SPDX-License-Identifier: Apache-2.0 */
/* The decoders' shared line helpers (text.h). */
#include "trace/text.h"

#include <linux/can/error.h>
#include <stdarg.h>
#include <stdio.h>

void say(text_t *t, const char *format, ...)
{
    if (t->len + 1 >= t->cap)
        return;
    va_list args;
    va_start(args, format);
    int n = vsnprintf(t->buf + t->len, t->cap - t->len, format, args);
    va_end(args);
    if (n > 0)
        t->len = t->len + (size_t)n < t->cap ? t->len + (size_t)n : t->cap - 1;
}

void say_bytes(text_t *t, const uint8_t *data, size_t len)
{
    for (size_t i = 0; i < len; i++)
        say(t, i ? " %02X" : "%02X", data[i]);
}

static bool printable(const uint8_t *data, size_t len)
{
    if (len == 0)
        return false;
    for (size_t i = 0; i < len; i++) {
        if (data[i] < 0x20 || data[i] > 0x7E)
            return false;
    }
    return true;
}

/* A value as bytes, and as the string or little-endian number they are most likely to be. */
void say_value(text_t *t, const uint8_t *data, size_t len, size_t total)
{
    if (printable(data, len)) {
        say(t, "\"%.*s\"", (int)len, (const char *)data);
    } else {
        say_bytes(t, data, len);
        if (len >= 1 && len <= 4 && len == total) {
            uint32_t v = 0;
            for (size_t i = len; i-- > 0;)
                v = v << 8 | data[i];
            say(t, " (%lu)", (unsigned long)v);
        }
    }
    if (total > len)
        say(t, " ...");
}

void say_error_frame(text_t *t, const struct can_frame *f)
{
    static const struct {
        canid_t flag;
        const char *name;
    } classes[] = {{CAN_ERR_TX_TIMEOUT, "TX timeout"},
                   {CAN_ERR_LOSTARB, "arbitration lost"},
                   {CAN_ERR_CRTL, "controller problem"},
                   {CAN_ERR_PROT, "protocol violation"},
                   {CAN_ERR_TRX, "transceiver status"},
                   {CAN_ERR_ACK, "no ACK on transmission"},
                   {CAN_ERR_BUSOFF, "bus off"},
                   {CAN_ERR_BUSERROR, "bus error"},
                   {CAN_ERR_RESTARTED, "controller restarted"}};
    static const struct {
        uint8_t flag;
        const char *name;
    } controller[] = {{CAN_ERR_CRTL_RX_OVERFLOW, "RX overflow"},
                      {CAN_ERR_CRTL_TX_OVERFLOW, "TX overflow"},
                      {CAN_ERR_CRTL_RX_WARNING, "RX warning"},
                      {CAN_ERR_CRTL_TX_WARNING, "TX warning"},
                      {CAN_ERR_CRTL_RX_PASSIVE, "RX error passive"},
                      {CAN_ERR_CRTL_TX_PASSIVE, "TX error passive"},
                      {CAN_ERR_CRTL_ACTIVE, "back to error active"}};
    say(t, "CAN error frame");
    const char *sep = ": ";
    for (size_t i = 0; i < sizeof classes / sizeof classes[0]; i++) {
        if (!(f->can_id & classes[i].flag))
            continue;
        say(t, "%s%s", sep, classes[i].name);
        sep = ", ";
        if (classes[i].flag == CAN_ERR_CRTL && f->len > 1) {
            const char *inner = " (";
            for (size_t j = 0; j < sizeof controller / sizeof controller[0]; j++) {
                if (f->data[1] & controller[j].flag) {
                    say(t, "%s%s", inner, controller[j].name);
                    inner = ", ";
                }
            }
            if (inner[0] == ',')
                say(t, ")");
        }
    }
}

bool say_start(text_t *t, char *out, size_t cap, const struct can_frame *f, const char *protocol)
{
    *t = (text_t){out, cap, 0};
    if (cap == 0)
        return false;
    out[0] = '\0';
    if (f->can_id & CAN_ERR_FLAG) {
        say_error_frame(t, f);
        return false;
    }
    if (f->can_id & CAN_EFF_FLAG) {
        say(t, "29-bit identifier: not %s", protocol);
        return false;
    }
    return true;
}
