/* SPDX-License-Identifier: Apache-2.0 */
/* The serial-line CAN protocol: frames to lines and lines to frames (include/slcan/slcan.h). */
#include "slcan/slcan.h"

#define SFF_DIGITS 3u
#define EFF_DIGITS 8u
#define EFF_MASK 0x1FFFFFFFu
#define SFF_MASK 0x7FFu

static const char hex_digits[16] = "0123456789ABCDEF";

static size_t put_hex(char *out, uint32_t value, unsigned digits)
{
    for (unsigned i = 0; i < digits; i++)
        out[i] = hex_digits[(value >> (4u * (digits - 1u - i))) & 0xFu];
    return digits;
}

size_t slcan_encode(const co_frame_t *frame, char *line)
{
    bool extended = (frame->flags & CO_FRAME_EFF) != 0;
    bool remote = (frame->flags & CO_FRAME_RTR) != 0;
    if (frame->len > CO_FRAME_DLC_MAX || frame->id > (extended ? EFF_MASK : SFF_MASK))
        return 0;
    size_t n = 0;
    line[n++] = remote ? (extended ? 'R' : 'r') : (extended ? 'T' : 't');
    n += put_hex(&line[n], frame->id, extended ? EFF_DIGITS : SFF_DIGITS);
    line[n++] = hex_digits[frame->len];
    if (!remote)
        for (unsigned i = 0; i < frame->len; i++)
            n += put_hex(&line[n], frame->data[i], 2u);
    line[n++] = SLCAN_CR;
    return n;
}

/* The value of one hexadecimal digit, either case, or -1. */
static int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

/* Reads digits hexadecimal digits of text into *value; false if any is not one. */
static bool get_hex(const char *text, unsigned digits, uint32_t *value)
{
    uint32_t v = 0;
    for (unsigned i = 0; i < digits; i++) {
        int d = hex_value(text[i]);
        if (d < 0)
            return false;
        v = v << 4 | (uint32_t)d;
    }
    *value = v;
    return true;
}

static slcan_message_t invalid(void)
{
    return (slcan_message_t){.kind = SLCAN_INVALID};
}

static slcan_message_t decode_frame(const char *line, size_t len)
{
    bool extended = line[0] == 'T' || line[0] == 'R';
    bool remote = line[0] == 'r' || line[0] == 'R';
    unsigned id_digits = extended ? EFF_DIGITS : SFF_DIGITS;
    uint32_t id, dlc;
    if (len < 1u + id_digits + 1u || !get_hex(&line[1], id_digits, &id) ||
        id > (extended ? EFF_MASK : SFF_MASK) || !get_hex(&line[1 + id_digits], 1u, &dlc) ||
        dlc > CO_FRAME_DLC_MAX)
        return invalid();
    size_t data_digits = remote ? 0u : 2u * dlc;
    if (len != 1u + id_digits + 1u + data_digits)
        return invalid();
    slcan_message_t m = {.kind = SLCAN_FRAME};
    m.frame.id = id;
    m.frame.len = (uint8_t)dlc;
    m.frame.flags = (uint8_t)((extended ? CO_FRAME_EFF : 0u) | (remote ? CO_FRAME_RTR : 0u));
    for (unsigned i = 0; i < data_digits / 2u; i++) {
        uint32_t byte;
        if (!get_hex(&line[2u + id_digits + 2u * i], 2u, &byte))
            return invalid();
        m.frame.data[i] = (uint8_t)byte;
    }
    return m;
}

slcan_message_t slcan_decode(const char *line, size_t len)
{
    if (len == 0)
        return (slcan_message_t){.kind = SLCAN_NOTHING};
    switch (line[0]) {
    case 't':
    case 'T':
    case 'r':
    case 'R':
        return decode_frame(line, len);
    case 'O':
        return len == 1u ? (slcan_message_t){.kind = SLCAN_OPEN} : invalid();
    case 'C':
        return len == 1u ? (slcan_message_t){.kind = SLCAN_CLOSE} : invalid();
    case 'S':
        if (len == 2u && line[1] >= '0' && line[1] <= '0' + (int)SLCAN_BITRATE_MAX)
            return (slcan_message_t){.kind = SLCAN_BITRATE, .bitrate = (uint8_t)(line[1] - '0')};
        return invalid();
    default:
        return invalid();
    }
}

void slcan_reader_init(slcan_reader_t *reader)
{
    *reader = (slcan_reader_t){.len = 0};
}

slcan_message_t slcan_read(slcan_reader_t *reader, uint8_t byte)
{
    if (byte != (uint8_t)SLCAN_CR) {
        if (reader->len < sizeof(reader->line))
            reader->line[reader->len++] = (char)byte;
        else
            reader->overlong = true;
        return (slcan_message_t){.kind = SLCAN_NOTHING};
    }
    slcan_message_t m = reader->overlong ? invalid() : slcan_decode(reader->line, reader->len);
    slcan_reader_init(reader);
    return m;
}

char slcan_answer(slcan_kind_t kind)
{
    switch (kind) {
    case SLCAN_OPEN:
    case SLCAN_CLOSE:
    case SLCAN_BITRATE:
        return SLCAN_CR;
    case SLCAN_INVALID:
        return SLCAN_BEL;
    default:
        return 0;
    }
}
