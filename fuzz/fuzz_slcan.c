/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the serial-line CAN protocol (src/slcan/slcan.c, include/slcan/slcan.h),
 * the firmware's side of slcand. The input is used twice (docs/fuzzing.md):
 *
 * - as the bytes of the serial link, fed to slcan_read one by one (the way the board's UART
 *   interrupt feeds it; a chunk boundary is invisible to the reader, so what the chunking could
 *   change is where lines start and end: every position is tried as a line's end below). The
 *   harness cuts the stream at each CR itself and checks every message against the line: a frame
 *   is valid and its line is exactly slcan_encode's for it (but for the case of hexadecimal
 *   digits); a command is exactly its letter; a refused line leaves nothing behind; a line of up
 *   to SLCAN_LINE_MAX - 1 bytes gives what slcan_decode gives for it whole, a longer one
 *   SLCAN_INVALID; nothing but SLCAN_NOTHING before a CR, and a fresh reader after it. At every
 *   byte, a copy of the reader given a CR and then a well-formed line decodes that line: no junk
 *   keeps the reader from recovering.
 * - as frame records of RECORD_SIZE bytes (CAN-ID, length, flags, data, a case pattern): each is
 *   encoded, into a buffer of exactly SLCAN_LINE_MAX bytes, refused exactly when the protocol
 *   cannot carry it (writing nothing), else a line of the exact length ending in CR that,
 *   decoded whole and through the reader after junk, gives the frame back (without its unused
 *   bytes), with its hexadecimal digits in capitals or, as the case pattern says, in small
 *   letters. */
#include "rig.h"
#include "slcan/slcan.h"

#include <stdlib.h>
#include <string.h>

#define SFF_MAX 0x7FFu
#define EFF_MAX 0x1FFFFFFFu
#define READER_LINE_MAX (SLCAN_LINE_MAX - 1u) /* what slcan_reader_t holds: a line without CR */

/* A frame record: CAN-ID (4 bytes, little-endian), length, flags, 8 data bytes, case pattern. */
#define RECORD_SIZE 15u

/* The line the reader must always be able to decode after junk, and its frame. */
static const char good_line[] = "t12380011223344556677\r";
static const co_frame_t good_frame = {
    .id = 0x123, .len = 8, .data = {0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77}};

static bool same_frame(const co_frame_t *a, const co_frame_t *b)
{
    return a->id == b->id && a->len == b->len && a->flags == b->flags &&
           memcmp(a->data, b->data, sizeof a->data) == 0;
}

static bool same_message(const slcan_message_t *a, const slcan_message_t *b)
{
    return a->kind == b->kind && a->bitrate == b->bitrate && same_frame(&a->frame, &b->frame);
}

static bool is_empty_frame(const co_frame_t *f)
{
    static const co_frame_t empty = {.id = 0};
    return same_frame(f, &empty);
}

/* A frame the protocol carries, as the decoder must give it: only the RTR and EFF flags, the
 * identifier within its 11 or 29 bits, the DLC at most 8, no data bytes past the DLC, and none at
 * all in a remote frame (its line has none). */
static void check_valid_frame(const co_frame_t *f)
{
    bool extended = (f->flags & CO_FRAME_EFF) != 0;
    rig_check((f->flags & ~(CO_FRAME_RTR | CO_FRAME_EFF)) == 0, "a decoded frame with other flags");
    rig_check(f->id <= (extended ? EFF_MAX : SFF_MAX), "a decoded identifier too large");
    rig_check(f->len <= CO_FRAME_DLC_MAX, "a decoded DLC over 8");
    size_t data_len = (f->flags & CO_FRAME_RTR) ? 0u : f->len;
    for (size_t i = data_len; i < sizeof f->data; i++)
        rig_check(f->data[i] == 0, "a decoded frame with a data byte past its data");
}

/* The length of frame's line, CR included: letter, identifier, DLC, data digits, CR. */
static size_t line_length(const co_frame_t *f)
{
    size_t id_digits = (f->flags & CO_FRAME_EFF) ? 8u : 3u;
    size_t data_digits = (f->flags & CO_FRAME_RTR) ? 0u : 2u * f->len;
    return 1u + id_digits + 1u + data_digits + 1u;
}

/* Encodes f into a heap buffer of exactly SLCAN_LINE_MAX bytes (AddressSanitizer sees a byte past
 * it) and checks the line's form; returns its length (0: refused), the line in out. */
static size_t encode_checked(const co_frame_t *f, char out[SLCAN_LINE_MAX])
{
    char *line = malloc(SLCAN_LINE_MAX);
    rig_check(line != NULL, "out of memory");
    memset(line, '#', SLCAN_LINE_MAX);
    size_t n = slcan_encode(f, line);
    bool extended = (f->flags & CO_FRAME_EFF) != 0;
    bool carried = f->len <= CO_FRAME_DLC_MAX && f->id <= (extended ? EFF_MAX : SFF_MAX);
    if (!carried) {
        rig_check(n == 0, "a frame the protocol cannot carry encoded");
        for (size_t i = 0; i < SLCAN_LINE_MAX; i++)
            rig_check(line[i] == '#', "a refused frame wrote to the line");
    } else {
        rig_check(n == line_length(f), "an encoded line of the wrong length");
        rig_check(line[n - 1] == SLCAN_CR, "an encoded line without its CR");
        memcpy(out, line, n);
    }
    free(line);
    return n;
}

/* The line with its hexadecimal letters in capitals (after the first byte, the frame's kind). */
static void capitalise_digits(const uint8_t *line, size_t len, char *out)
{
    for (size_t i = 0; i < len; i++) {
        char c = (char)line[i];
        out[i] = i > 0 && c >= 'a' && c <= 'f' ? (char)(c - 'a' + 'A') : c;
    }
}

/* A complete line (without its CR) against what the reader made of it. */
static void check_line(const uint8_t *line, size_t len, const slcan_message_t *m)
{
    switch (m->kind) {
    case SLCAN_FRAME: {
        check_valid_frame(&m->frame);
        char encoded[SLCAN_LINE_MAX], expected[SLCAN_LINE_MAX];
        size_t n = encode_checked(&m->frame, encoded);
        rig_check(n == len + 1u, "a frame's line is not the length of its encoding");
        capitalise_digits(line, len, expected);
        rig_check(memcmp(encoded, expected, len) == 0, "a frame's line is not its encoding");
        slcan_message_t again = slcan_decode(encoded, n - 1u);
        rig_check(same_message(&again, m), "a decoded frame encoded and decoded again differs");
        break;
    }
    case SLCAN_OPEN:
    case SLCAN_CLOSE:
        rig_check(len == 1 && line[0] == (m->kind == SLCAN_OPEN ? 'O' : 'C'),
                  "an open or close command that is not its letter alone");
        rig_check(is_empty_frame(&m->frame) && m->bitrate == 0, "a command with a frame or rate");
        break;
    case SLCAN_BITRATE:
        rig_check(len == 2 && line[0] == 'S' && m->bitrate <= SLCAN_BITRATE_MAX &&
                      line[1] == '0' + m->bitrate,
                  "a bit rate command that is not S and its index");
        rig_check(is_empty_frame(&m->frame), "a bit rate command with a frame");
        break;
    case SLCAN_NOTHING:
        rig_check(len == 0, "a line with bytes that gives nothing");
        rig_check(is_empty_frame(&m->frame) && m->bitrate == 0, "nothing with a frame or rate");
        break;
    case SLCAN_INVALID:
        rig_check(len > 0, "an empty line refused");
        rig_check(is_empty_frame(&m->frame) && m->bitrate == 0, "a refused line left a frame");
        break;
    default:
        rig_check(false, "a message of no kind");
    }
    char want = m->kind == SLCAN_INVALID                             ? SLCAN_BEL
                : m->kind == SLCAN_FRAME || m->kind == SLCAN_NOTHING ? 0
                                                                     : SLCAN_CR;
    rig_check(slcan_answer(m->kind) == want, "the wrong answer to a line");
    if (len <= READER_LINE_MAX) {
        slcan_message_t whole = slcan_decode((const char *)line, len);
        rig_check(same_message(&whole, m), "the reader and slcan_decode disagree on a line");
    } else {
        rig_check(m->kind == SLCAN_INVALID, "an overlong line not refused");
    }
}

/* Feeds text to the reader; every byte but the last must give nothing. Returns the last's. */
static slcan_message_t feed(slcan_reader_t *r, const char *text, size_t len)
{
    slcan_message_t m = {.kind = SLCAN_NOTHING};
    for (size_t i = 0; i < len; i++) {
        rig_check(m.kind == SLCAN_NOTHING, "a message before the line's CR");
        m = slcan_read(r, (uint8_t)text[i]);
    }
    return m;
}

/* A copy of the reader, whatever it holds, ends its line with a CR and then reads a good line. */
static void check_recovers(const slcan_reader_t *reader)
{
    slcan_reader_t copy = *reader;
    slcan_read(&copy, (uint8_t)SLCAN_CR);
    slcan_message_t m = feed(&copy, good_line, sizeof good_line - 1u);
    rig_check(m.kind == SLCAN_FRAME && same_frame(&m.frame, &good_frame),
              "the reader does not recover after junk and a CR");
}

static void check_stream(const uint8_t *data, size_t size)
{
    slcan_reader_t reader;
    slcan_reader_init(&reader);
    size_t start = 0; /* the current line's first byte */
    for (size_t i = 0; i < size; i++) {
        check_recovers(&reader);
        slcan_message_t m = slcan_read(&reader, data[i]);
        rig_check(reader.len <= sizeof reader.line, "the reader's line past its buffer");
        if (data[i] != (uint8_t)SLCAN_CR) {
            rig_check(m.kind == SLCAN_NOTHING, "a message before the line's CR");
            continue;
        }
        check_line(&data[start], i - start, &m);
        rig_check(reader.len == 0 && !reader.overlong, "the reader not fresh after a CR");
        start = i + 1;
    }
    check_recovers(&reader);
}

/* The frame a record gives, and the case of each digit of its line (bit i % 8: small letters). */
static co_frame_t record_frame(const uint8_t *rec, uint8_t *case_pattern)
{
    co_frame_t f = {.id = (uint32_t)rec[0] | (uint32_t)rec[1] << 8 | (uint32_t)rec[2] << 16 |
                          (uint32_t)rec[3] << 24,
                    .len = rec[4],
                    .flags = rec[5]};
    memcpy(f.data, &rec[6], sizeof f.data);
    *case_pattern = rec[14];
    return f;
}

/* What decoding f's line must give: f with only its RTR and EFF flags and its data bytes. */
static co_frame_t carried_part(const co_frame_t *f)
{
    co_frame_t want = {
        .id = f->id, .len = f->len, .flags = f->flags & (CO_FRAME_RTR | CO_FRAME_EFF)};
    if (!(f->flags & CO_FRAME_RTR))
        memcpy(want.data, f->data, f->len);
    return want;
}

static void check_record(const uint8_t *rec, const uint8_t *junk, size_t junk_len)
{
    uint8_t case_pattern;
    co_frame_t f = record_frame(rec, &case_pattern);
    char line[SLCAN_LINE_MAX];
    size_t n = encode_checked(&f, line);
    if (n == 0)
        return;
    co_frame_t want = carried_part(&f);
    slcan_message_t m = slcan_decode(line, n - 1u);
    rig_check(m.kind == SLCAN_FRAME && same_frame(&m.frame, &want),
              "an encoded frame decoded is not the frame");
    for (size_t i = 1; i + 1u < n; i++) {
        if (line[i] >= 'A' && line[i] <= 'F' && (case_pattern >> (i % 8u) & 1u))
            line[i] = (char)(line[i] - 'A' + 'a');
    }
    m = slcan_decode(line, n - 1u);
    rig_check(m.kind == SLCAN_FRAME && same_frame(&m.frame, &want),
              "an encoded frame in small letters decoded is not the frame");
    slcan_reader_t reader;
    slcan_reader_init(&reader);
    for (size_t i = 0; i < junk_len; i++)
        slcan_read(&reader, junk[i]);
    slcan_read(&reader, (uint8_t)SLCAN_CR);
    m = feed(&reader, line, n);
    rig_check(m.kind == SLCAN_FRAME && same_frame(&m.frame, &want),
              "an encoded frame read after junk is not the frame");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_stream(data, size);
    /* Each record is read after the bytes before it as junk on the link. */
    for (size_t at = 0; at + RECORD_SIZE <= size; at += RECORD_SIZE)
        check_record(&data[at], data, at);
    return 0;
}
