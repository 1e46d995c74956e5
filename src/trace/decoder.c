/* SPDX-License-Identifier: Apache-2.0 */
#include "trace/decoder.h"
#include "trace/text.h"

#include "co/co_cia402_master.h"
#include "co/co_emcy.h"
#include "co/co_lss.h"
#include "co/co_nmt.h"
#include "co/co_pdo.h"
#include "co/co_time_of_day.h"

#include <stdio.h>
#include <string.h>

static const eds_t *eds_of(const cotrace_decoder_t *dec, uint8_t node)
{
    return dec->eds && node == dec->eds_node ? dec->eds : NULL;
}

static void say_object(text_t *t, const cotrace_decoder_t *dec, uint8_t node, uint16_t index,
                       uint8_t sub)
{
    say(t, "%04X:%02X", index, sub);
    const eds_t *eds = eds_of(dec, node);
    const char *name = eds ? eds_name(eds, index, sub) : NULL;
    if (name)
        say(t, " %s", name);
}

/* ---- NMT, SYNC, TIME, EMCY, error control ------------------------------------------------- */

static const char *nmt_command_name(uint8_t cs)
{
    switch (cs) {
    case 0x01:
        return "Start remote node";
    case 0x02:
        return "Stop remote node";
    case 0x80:
        return "Enter pre-operational";
    case 0x81:
        return "Reset node";
    case 0x82:
        return "Reset communication";
    default:
        return NULL;
    }
}

static void decode_nmt(const struct can_frame *f, text_t *t)
{
    if (f->can_id & CAN_RTR_FLAG || f->len != 2) {
        say(t, "NMT malformed: %u bytes, a command has 2 (command, node-id)", f->len);
        return;
    }
    const char *name = nmt_command_name(f->data[0]);
    if (name)
        say(t, "NMT %s", name);
    else
        say(t, "NMT unknown command 0x%02X", f->data[0]);
    if (f->data[1] == 0)
        say(t, ", all nodes");
    else
        say(t, ", node %u%s", f->data[1], f->data[1] > COTRACE_NODE_MAX ? " (not a node-id)" : "");
}

static void decode_sync(const struct can_frame *f, text_t *t)
{
    if (f->len == 0)
        say(t, "SYNC");
    else if (f->len == 1)
        say(t, "SYNC counter %u", f->data[0]);
    else
        say(t, "SYNC malformed: %u bytes, a SYNC has none or 1 (counter)", f->len);
}

static void decode_time(const struct can_frame *f, text_t *t)
{
    co_time_of_day_t time;
    if (!co_time_of_day_decode(f->data, f->len, &time)) {
        say(t, "TIME malformed: %u bytes, a TIME_OF_DAY has %u", f->len, CO_TIME_OF_DAY_LEN);
        return;
    }
    char text[CO_TIME_OF_DAY_TEXT_SIZE];
    co_time_of_day_format(&time, text);
    say(t, "TIME %s", text);
}

static void say_error_register(text_t *t, uint8_t reg)
{
    static const struct {
        uint8_t bit;
        const char *name;
    } bits[] = {{CO_ERR_REG_GENERIC, "generic"},
                {CO_ERR_REG_CURRENT, "current"},
                {CO_ERR_REG_VOLTAGE, "voltage"},
                {CO_ERR_REG_TEMPERATURE, "temperature"},
                {CO_ERR_REG_COMMUNICATION, "communication"},
                {CO_ERR_REG_PROFILE, "device profile"},
                {0x40, "reserved"},
                {CO_ERR_REG_MANUFACTURER, "manufacturer"}};
    say(t, "error register 0x%02X", reg);
    const char *sep = " (";
    for (size_t i = 0; i < sizeof bits / sizeof bits[0]; i++) {
        if (reg & bits[i].bit) {
            say(t, "%s%s", sep, bits[i].name);
            sep = ", ";
        }
    }
    if (reg)
        say(t, ")");
}

static void decode_emcy(const cotrace_decoder_t *dec, const struct can_frame *f, text_t *t)
{
    co_frame_t frame;
    co_emcy_message_t msg;
    frame.id = f->can_id & CAN_SFF_MASK;
    frame.len = f->len;
    frame.flags = f->can_id & CAN_RTR_FLAG ? CO_FRAME_RTR : 0;
    memcpy(frame.data, f->data, sizeof frame.data);
    co_emcy_decode_t result = co_emcy_decode(&frame, &msg);
    if (result != CO_EMCY_DECODE_OK) {
        say(t, "EMCY node %u malformed: %s (%u bytes)", frame.id - CO_CAN_ID_SYNC,
            co_emcy_decode_text(result), f->len);
        return;
    }
    say(t, "EMCY node %u: 0x%04X %s, ", msg.node_id, msg.code,
        co_emcy_code_text_in(dec->vendor, msg.code));
    say_error_register(t, msg.reg);
    say(t, ", manufacturer bytes ");
    say_bytes(t, msg.msef, CO_EMCY_MSEF_LEN);
}

/* A heartbeat or guarding state byte: 00h is the boot-up there, not a state. */
static const char *nmt_state_name(uint8_t state)
{
    return state == CO_NMT_INITIALISING ? "Boot-up" : co_nmt_state_name(state);
}

static void say_state(text_t *t, uint8_t state)
{
    const char *name = nmt_state_name(state);
    if (name)
        say(t, "%s", name);
    else
        say(t, "unknown state 0x%02X", state);
}

static void decode_error_control(cotrace_decoder_t *dec, uint8_t node, const struct can_frame *f,
                                 text_t *t)
{
    if (f->can_id & CAN_RTR_FLAG) {
        dec->guard_pending[node] = true;
        say(t, "guarding request, node %u", node);
        return;
    }
    if (f->len != 1) {
        say(t, "heartbeat malformed: node %u, %u bytes, a heartbeat or guarding reply has 1", node,
            f->len);
        return;
    }
    uint8_t byte = f->data[0];
    if (dec->guard_pending[node]) {
        dec->guard_pending[node] = false;
        say(t, "guarding reply, node %u: ", node);
        say_state(t, byte & CO_NMT_STATE_MASK);
        say(t, ", toggle %u", byte & CO_GUARD_TOGGLE ? 1 : 0);
    } else if (byte == 0) {
        say(t, "boot-up, node %u", node);
    } else {
        say(t, "heartbeat, node %u: ", node);
        say_state(t, byte);
    }
}

/* ---- SDO ---------------------------------------------------------------------------------- */

static void sdo_reset(cotrace_sdo_t *s)
{
    memset(s, 0, sizeof *s);
}

static void sdo_start(cotrace_sdo_t *s, cotrace_sdo_kind_t kind, const uint8_t *data)
{
    sdo_reset(s);
    s->kind = kind;
    s->index = co_get_u16(&data[1]);
    s->sub = data[3];
}

static void sdo_keep(cotrace_sdo_t *s, const uint8_t *data, size_t len)
{
    for (size_t i = 0; i < len; i++, s->count++) {
        if (s->count < COTRACE_SDO_KEEP)
            s->data[s->count] = data[i];
    }
}

/* "1008:00 Name = value (n bytes)" for a completed transfer. */
static void say_result(text_t *t, const cotrace_decoder_t *dec, uint8_t node,
                       const cotrace_sdo_t *s)
{
    say_object(t, dec, node, s->index, s->sub);
    size_t kept = s->count < COTRACE_SDO_KEEP ? s->count : COTRACE_SDO_KEEP;
    say(t, " = ");
    say_value(t, s->data, kept, s->count);
    say(t, " (%lu bytes)", (unsigned long)s->count);
}

static void say_abort(text_t *t, const cotrace_decoder_t *dec, uint8_t node,
                      const struct can_frame *f)
{
    if (f->len < 8) {
        say(t, "abort, malformed: %u bytes, an abort has 8", f->len);
        return;
    }
    uint32_t code = co_get_u32(&f->data[4]);
    say(t, "abort ");
    say_object(t, dec, node, co_get_u16(&f->data[1]), f->data[3]);
    say(t, ": 0x%08X %s", code, co_sdo_abort_text(code));
}

/* A segment of a segmented transfer (either direction): toggle, data, last. */
static void sdo_segment(text_t *t, cotrace_sdo_t *s, const uint8_t *data, const char *what)
{
    uint8_t cmd = data[0];
    size_t n = CO_SDO_SEGMENT_BYTES - (cmd >> 1 & 7u);
    sdo_keep(s, &data[1], n);
    say(t, "%s segment, toggle %u, %zu bytes: ", what, cmd & CO_SDO_TOGGLE ? 1 : 0, n);
    say_value(t, &data[1], n, n);
    if (cmd & CO_SDO_LAST_SEGMENT)
        say(t, ", last");
}

/* A segment of a block (either direction): sequence number, data, last. */
static void sdo_block_segment(text_t *t, cotrace_sdo_t *s, const uint8_t *data, const char *what)
{
    uint8_t seq = data[0] & 0x7Fu;
    if (seq == 1)
        s->block_start = s->count;
    s->count = s->block_start + (uint32_t)(seq - 1) * CO_SDO_SEGMENT_BYTES;
    sdo_keep(s, &data[1], CO_SDO_SEGMENT_BYTES);
    say(t, "%s segment %u: ", what, seq);
    say_bytes(t, &data[1], CO_SDO_SEGMENT_BYTES);
    if (data[0] & CO_SDO_BLOCK_LAST) {
        s->last_sent = true;
        say(t, ", last");
    }
    if (data[0] & CO_SDO_BLOCK_LAST || seq >= s->block_size)
        s->in_subblock = false;
}

/* In a sub-block the data direction sends segments, sequence numbers 1..127; 0x80 there is an
 * abort (sequence number 0 does not exist), and a segment is always 8 bytes. */
static bool is_block_segment(const cotrace_sdo_t *s, const struct can_frame *f)
{
    return s->in_subblock && f->len == 8 && (f->data[0] & 0x7Fu) != 0;
}

/* A block acknowledgement: the segments up to ackseq arrived; what follows them is resent. */
static void sdo_block_ack(text_t *t, cotrace_sdo_t *s, const uint8_t *data, const char *what)
{
    s->count = s->block_start + (uint32_t)data[1] * CO_SDO_SEGMENT_BYTES;
    s->block_start = s->count;
    s->block_size = data[2];
    s->in_subblock = !s->last_sent || data[1] == 0;
    say(t, "%s ack: received up to segment %u, next block size %u", what, data[1], data[2]);
}

/* The end of a block transfer: unused bytes of the last segment, CRC. */
static void sdo_block_end(text_t *t, cotrace_sdo_t *s, const uint8_t *data, const char *what)
{
    unsigned unused = data[0] >> 2 & 7u;
    s->count = s->count > unused ? s->count - unused : 0;
    say(t, "%s end: %u bytes unused in the last segment, CRC 0x%04X", what, unused,
        co_get_u16(&data[1]));
}

/* The size of an initiate: its flag is bit 0 in segmented transfers, bit 1 in block ones. */
static void sdo_initiate_size(text_t *t, cotrace_sdo_t *s, const uint8_t *data, uint8_t flag)
{
    if (data[0] & flag) {
        s->size = co_get_u32(&data[4]);
        say(t, ", %lu bytes", (unsigned long)s->size);
    } else {
        say(t, ", size not indicated");
    }
}

/* What requests and replies share: the line's start, the segments of a block transfer in the
 * frame's direction (`block`, named `block_name`), an abort, a frame too short. Returns true when
 * that said all there is to say of the frame. */
static bool sdo_common(cotrace_decoder_t *dec, uint8_t node, const struct can_frame *f, text_t *t,
                       const char *what, cotrace_sdo_kind_t block, const char *block_name)
{
    cotrace_sdo_t *s = &dec->sdo[node];
    say(t, "SDO %u %s: ", node, what);
    if (s->kind == block && is_block_segment(s, f)) {
        sdo_block_segment(t, s, f->data, block_name);
        return true;
    }
    if (CO_SDO_CS(f->data[0]) == CO_SDO_CS_ABORT) {
        say_abort(t, dec, node, f);
        sdo_reset(s);
        return true;
    }
    if (f->len < 8) {
        say(t, "malformed: %u bytes, an SDO %s has 8", f->len, what);
        return true;
    }
    return false;
}

static void sdo_request(cotrace_decoder_t *dec, uint8_t node, const struct can_frame *f, text_t *t)
{
    if (sdo_common(dec, node, f, t, "request", COTRACE_SDO_BLOCK_DOWNLOAD, "block download"))
        return;
    cotrace_sdo_t *s = &dec->sdo[node];
    const uint8_t *d = f->data;
    uint8_t cs = CO_SDO_CS(d[0]);
    switch (cs) {
    case CO_SDO_CCS_DOWNLOAD_INITIATE:
        sdo_start(s, COTRACE_SDO_DOWNLOAD, d);
        say(t, "download ");
        say_object(t, dec, node, s->index, s->sub);
        if (d[0] & CO_SDO_EXPEDITED) {
            size_t n = d[0] & CO_SDO_SIZE_INDICATED ? 4u - (d[0] >> 2 & 3u) : 4u;
            s->expedited = true;
            sdo_keep(s, &d[4], n);
            say(t, " = ");
            say_value(t, &d[4], n, n);
        } else {
            sdo_initiate_size(t, s, d, CO_SDO_SIZE_INDICATED);
            say(t, ", segmented");
        }
        return;
    case CO_SDO_CCS_DOWNLOAD_SEGMENT:
        sdo_segment(t, s, d, "download");
        s->last_sent = d[0] & CO_SDO_LAST_SEGMENT;
        return;
    case CO_SDO_CCS_UPLOAD_INITIATE:
        sdo_start(s, COTRACE_SDO_UPLOAD, d);
        say(t, "upload ");
        say_object(t, dec, node, s->index, s->sub);
        return;
    case CO_SDO_CCS_UPLOAD_SEGMENT:
        say(t, "upload segment, toggle %u", d[0] & CO_SDO_TOGGLE ? 1 : 0);
        return;
    case CO_SDO_CCS_BLOCK_DOWNLOAD:
        if ((d[0] & 1u) == 0) {
            sdo_start(s, COTRACE_SDO_BLOCK_DOWNLOAD, d);
            say(t, "block download ");
            say_object(t, dec, node, s->index, s->sub);
            sdo_initiate_size(t, s, d, CO_SDO_BLOCK_SIZE_INDICATED);
            say(t, "%s", d[0] & CO_SDO_BLOCK_CRC ? ", CRC" : ", no CRC");
        } else {
            sdo_block_end(t, s, d, "block download");
        }
        return;
    case CO_SDO_CCS_BLOCK_UPLOAD:
        switch (d[0] & CO_SDO_SUB_MASK) {
        case 0:
            sdo_start(s, COTRACE_SDO_BLOCK_UPLOAD, d);
            s->block_size = d[4];
            say(t, "block upload ");
            say_object(t, dec, node, s->index, s->sub);
            say(t, ", blocks of %u segments%s", d[4],
                d[0] & CO_SDO_BLOCK_CRC ? ", CRC" : ", no CRC");
            return;
        case 1:
            say(t, "block upload end confirmed: ");
            say_result(t, dec, node, s);
            sdo_reset(s);
            return;
        case 2:
            sdo_block_ack(t, s, d, "block upload");
            return;
        default:
            s->in_subblock = true;
            say(t, "block upload start");
            return;
        }
    default:
        say(t, "unknown command 0x%02X", d[0]);
        return;
    }
}

static void sdo_reply(cotrace_decoder_t *dec, uint8_t node, const struct can_frame *f, text_t *t)
{
    if (sdo_common(dec, node, f, t, "reply", COTRACE_SDO_BLOCK_UPLOAD, "block upload"))
        return;
    cotrace_sdo_t *s = &dec->sdo[node];
    const uint8_t *d = f->data;
    uint8_t cs = CO_SDO_CS(d[0]);
    switch (cs) {
    case CO_SDO_SCS_UPLOAD_INITIATE:
        s->index = co_get_u16(&d[1]);
        s->sub = d[3];
        say(t, "upload ");
        say_object(t, dec, node, s->index, s->sub);
        if (d[0] & CO_SDO_EXPEDITED) {
            size_t n = d[0] & CO_SDO_SIZE_INDICATED ? 4u - (d[0] >> 2 & 3u) : 4u;
            say(t, " = ");
            say_value(t, &d[4], n, n);
            sdo_reset(s);
        } else {
            sdo_initiate_size(t, s, d, CO_SDO_SIZE_INDICATED);
            say(t, ", segmented");
        }
        return;
    case CO_SDO_SCS_UPLOAD_SEGMENT:
        sdo_segment(t, s, d, "upload");
        if (d[0] & CO_SDO_LAST_SEGMENT) {
            say(t, ": ");
            say_result(t, dec, node, s);
            sdo_reset(s);
        }
        return;
    case CO_SDO_SCS_DOWNLOAD_INITIATE:
        say(t, "download ");
        say_object(t, dec, node, co_get_u16(&d[1]), d[3]);
        if (s->expedited) {
            say(t, " done");
            sdo_reset(s);
        } else {
            say(t, " accepted, send the segments");
        }
        return;
    case CO_SDO_SCS_DOWNLOAD_SEGMENT:
        say(t, "download segment, toggle %u, received", d[0] & CO_SDO_TOGGLE ? 1 : 0);
        if (s->kind == COTRACE_SDO_DOWNLOAD && s->last_sent) {
            say(t, ": done, ");
            say_result(t, dec, node, s);
            sdo_reset(s);
        }
        return;
    case CO_SDO_SCS_BLOCK_DOWNLOAD:
        switch (d[0] & CO_SDO_SUB_MASK) {
        case 0:
            s->block_size = d[4];
            s->in_subblock = true;
            say(t, "block download ");
            say_object(t, dec, node, co_get_u16(&d[1]), d[3]);
            say(t, " accepted, blocks of %u segments", d[4]);
            return;
        case 1:
            say(t, "block download done: ");
            say_result(t, dec, node, s);
            sdo_reset(s);
            return;
        case 2:
            sdo_block_ack(t, s, d, "block download");
            return;
        default:
            break;
        }
        break;
    case CO_SDO_SCS_BLOCK_UPLOAD:
        if ((d[0] & 1u) == 0) {
            say(t, "block upload ");
            say_object(t, dec, node, co_get_u16(&d[1]), d[3]);
            sdo_initiate_size(t, s, d, CO_SDO_BLOCK_SIZE_INDICATED);
            say(t, "%s", d[0] & CO_SDO_BLOCK_CRC ? ", CRC" : ", no CRC");
        } else {
            sdo_block_end(t, s, d, "block upload");
        }
        return;
    default:
        break;
    }
    say(t, "unknown command 0x%02X", d[0]);
}

/* ---- PDO ---------------------------------------------------------------------------------- */

/* The sub-index of a PDO's COB-ID in its communication parameter (1400h + n, 1800h + n). */
#define PDO_COB_ID_SUB 1u
/* Mapping entries below 0x0020 are data type indices: "dummy" entries that fill a gap. */
#define PDO_DUMMY_LIMIT 0x0020u

/* The PDO of the EDS whose COB-ID is `cob_id`. */
static bool pdo_from_eds(const cotrace_decoder_t *dec, uint16_t cob_id, cotrace_pdo_t *ref)
{
    for (size_t i = 0; i < dec->pdo_count; i++) {
        if (dec->pdos[i].cob_id == cob_id) {
            *ref = dec->pdos[i];
            return true;
        }
    }
    return false;
}

/* The PDOs of the EDS by the value of their COB-ID (1400h+n:01 / 1800h+n:01). The valid bit is
 * ignored: a PDO the EDS leaves invalid (ATV312 PDO6) is enabled by a master at run time. */
static void pdos_of_eds(cotrace_decoder_t *dec)
{
    for (unsigned i = 0; i < CO_PDO_INDEX_SPAN && dec->pdo_count < COTRACE_PDO_MAX; i++) {
        for (int transmit = 0; transmit <= 1; transmit++) {
            uint16_t comm = (uint16_t)((transmit ? CO_PDO_TPDO_COMM : CO_PDO_RPDO_COMM) + i);
            const eds_entry_t *e = eds_find(dec->eds, comm, PDO_COB_ID_SUB);
            if (e && e->has_value && !(e->value & CO_PDO_COBID_FRAME) &&
                dec->pdo_count < COTRACE_PDO_MAX) {
                cotrace_pdo_t *pdo = &dec->pdos[dec->pdo_count++];
                pdo->cob_id = (uint16_t)(e->value & CAN_SFF_MASK);
                pdo->transmit = transmit;
                pdo->number = (uint16_t)(i + 1);
                pdo->mapping = (uint16_t)(comm + CO_PDO_INDEX_SPAN);
            }
        }
    }
}

/* The predefined connection set: TPDO1 180h+id, RPDO1 200h+id, ... RPDO4 500h+id. */
static bool pdo_predefined(uint16_t cob_id, cotrace_pdo_t *ref)
{
    unsigned function = cob_id >> 7;
    if ((cob_id & CO_NODE_ID_MASK) == 0 || function < 3 || function > 10)
        return false;
    ref->cob_id = cob_id;
    ref->transmit = function % 2 == 1;
    ref->number = (uint16_t)((function - 1) / 2);
    ref->mapping = 0;
    return true;
}

static uint64_t extract_bits(const uint8_t *data, unsigned offset, unsigned bits)
{
    uint64_t v = 0;
    for (unsigned i = 0; i < bits; i++) {
        unsigned bit = offset + i;
        if (data[bit / 8] >> (bit % 8) & 1u)
            v |= (uint64_t)1 << i;
    }
    return v;
}

const char *cotrace_control_word_command(uint16_t word)
{
    static const struct {
        uint16_t mask, value;
        const char *name;
    } commands[] = {{0x0080, 0x0080, "Fault reset"}, {0x0082, 0x0000, "Disable voltage"},
                    {0x0086, 0x0002, "Quick stop"},  {0x0087, 0x0006, "Shutdown"},
                    {0x008F, 0x0007, "Switch on"},   {0x008F, 0x000F, "Enable operation"}};
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        if ((word & commands[i].mask) == commands[i].value)
            return commands[i].name;
    }
    return NULL;
}

static void say_mapped_value(text_t *t, uint16_t index, uint16_t type, uint64_t v, unsigned bits)
{
    if (index == CO_CIA402_CONTROL_WORD || index == CO_CIA402_STATUS_WORD) {
        const char *meaning = index == CO_CIA402_CONTROL_WORD
                                  ? cotrace_control_word_command((uint16_t)v)
                                  : co_cia402_state_name(co_cia402_state((uint16_t)v));
        say(t, "0x%04llX%s%s", (unsigned long long)v, meaning ? " " : "", meaning ? meaning : "");
        return;
    }
    switch (type) {
    case CO_DT_INTEGER8:
    case CO_DT_INTEGER16:
    case CO_DT_INTEGER32:
    case CO_DT_INTEGER64:
        if (bits < 64 && v >> (bits - 1) & 1u)
            v |= ~(uint64_t)0 << bits;
        say(t, "%lld", (long long)v);
        return;
    case CO_DT_REAL32:
        if (bits == 32) {
            uint32_t raw = (uint32_t)v;
            float f;
            memcpy(&f, &raw, sizeof f);
            say(t, "%g", (double)f);
            return;
        }
        break;
    default:
        break;
    }
    say(t, "%llu", (unsigned long long)v);
}

/* Each mapped object with its value; false when the mapping does not fit the frame. */
static bool say_mapping(text_t *t, const eds_t *eds, uint16_t mapping, const struct can_frame *f)
{
    const eds_entry_t *count = eds_find(eds, mapping, 0);
    if (!count || !count->has_value)
        return false;
    unsigned offset = 0;
    for (unsigned k = 1; k <= count->value && k <= 64; k++) {
        const eds_entry_t *m = eds_find(eds, mapping, (uint8_t)k);
        if (!m || !m->has_value)
            return false;
        uint16_t index = (uint16_t)(m->value >> 16);
        uint8_t sub = (uint8_t)(m->value >> 8);
        unsigned bits = (unsigned)(m->value & 0xFFu);
        if (bits == 0 || offset + bits > 8u * f->len)
            return false;
        if (index >= PDO_DUMMY_LIMIT) {
            const eds_entry_t *obj = eds_find(eds, index, sub);
            const char *name = eds_name(eds, index, sub);
            say(t, "%s%04X:%02X%s%s = ", offset ? ", " : "", index, sub, name ? " " : "",
                name ? name : "");
            say_mapped_value(t, index, obj ? obj->data_type : 0,
                             extract_bits(f->data, offset, bits), bits);
        }
        offset += bits;
    }
    if (offset != 8u * f->len)
        return false;
    return true;
}

static void decode_pdo(const cotrace_decoder_t *dec, const struct can_frame *f,
                       const cotrace_pdo_t *ref, uint8_t node, text_t *t)
{
    say(t, "%s%u", ref->transmit ? "TPDO" : "RPDO", ref->number);
    if (node)
        say(t, " node %u", node);
    if (f->can_id & CAN_RTR_FLAG) {
        say(t, ": remote request");
        return;
    }
    say(t, ": ");
    if (ref->mapping && dec->eds) {
        size_t mark = t->len;
        if (say_mapping(t, dec->eds, ref->mapping, f))
            return;
        t->len = mark;
        t->buf[mark] = '\0';
        say(t, "%u bytes do not fit the mapping %04X of the EDS: ", f->len, ref->mapping);
    }
    if (f->len == 0)
        say(t, "no data");
    else
        say_bytes(t, f->data, f->len);
}

/* ---- everything else ---------------------------------------------------------------------- */

/* ---- LSS (CiA 305) ------------------------------------------------------------------------- */

static const char *const lss_part_name[CO_LSS_FASTSCAN_PARTS] = {"vendor-ID", "product code",
                                                                 "revision", "serial"};

static void say_lss_node_id(text_t *t, uint8_t id)
{
    if (id == CO_LSS_NODE_ID_UNCONFIGURED)
        say(t, "255 (none)");
    else
        say(t, "%u%s", id, id == 0 || id > COTRACE_NODE_MAX ? " (not a node-id)" : "");
}

static void say_lss_bit_timing(text_t *t, uint8_t table, uint8_t index)
{
    say(t, "table %u index %u", table, index);
    if (table != CO_LSS_BIT_TIMING_TABLE)
        return;
    uint16_t kbit = co_lss_bit_rate_kbit(index);
    if (kbit != 0)
        say(t, " (%u kbit/s)", kbit);
    else if (index == CO_LSS_BIT_TIMING_AUTO)
        say(t, " (automatic bit rate detection)");
    else
        say(t, " (not in the table)");
}

/* The error code of a confirmation (configure node-ID, configure bit timing, store). */
static void say_lss_error(text_t *t, uint8_t cs, const uint8_t *d)
{
    if (d[1] == CO_LSS_OK) {
        say(t, "done");
        return;
    }
    say(t, "error %u", d[1]);
    if (d[1] == CO_LSS_SPECIFIC_ERROR)
        say(t, " (device-specific error 0x%02X)", d[2]);
    else if (d[1] == 1 && cs == CO_LSS_CS_CONFIGURE_NODE_ID)
        say(t, " (node-ID out of range)");
    else if (d[1] == 1 && cs == CO_LSS_CS_CONFIGURE_BIT_TIMING)
        say(t, " (bit timing not supported)");
    else if (d[1] == 1 && cs == CO_LSS_CS_STORE)
        say(t, " (store configuration not supported)");
    else if (d[1] == CO_LSS_STORE_MEDIA_ERROR && cs == CO_LSS_CS_STORE)
        say(t, " (storage media access error)");
    else
        say(t, " (reserved)");
}

/* Which specifiers go which way (CiA 305): 44h, 4Fh and 50h come only from a slave; the answers
 * of the confirmed services repeat their request's specifier. */
static bool lss_slave_only(uint8_t cs)
{
    return cs == CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE || cs == CO_LSS_CS_IDENTIFY_SLAVE ||
           cs == CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE;
}

static bool lss_confirmed(uint8_t cs)
{
    return cs == CO_LSS_CS_CONFIGURE_NODE_ID || cs == CO_LSS_CS_CONFIGURE_BIT_TIMING ||
           cs == CO_LSS_CS_STORE ||
           (cs >= CO_LSS_CS_INQUIRE_VENDOR && cs <= CO_LSS_CS_INQUIRE_NODE_ID);
}

static void lss_request(const uint8_t *d, text_t *t)
{
    uint8_t cs = d[0];
    uint32_t value = co_get_u32(&d[1]);
    if (cs == CO_LSS_CS_SWITCH_GLOBAL) {
        if (d[1] == CO_LSS_WAITING)
            say(t, ": waiting");
        else if (d[1] == CO_LSS_CONFIGURATION)
            say(t, ": configuration");
        else
            say(t, ": unknown state %u", d[1]);
    } else if (cs == CO_LSS_CS_CONFIGURE_NODE_ID) {
        say(t, " ");
        say_lss_node_id(t, d[1]);
    } else if (cs == CO_LSS_CS_CONFIGURE_BIT_TIMING) {
        say(t, " ");
        say_lss_bit_timing(t, d[1], d[2]);
    } else if (cs == CO_LSS_CS_ACTIVATE_BIT_TIMING) {
        say(t, ", switch delay %u ms", (unsigned)(d[1] | d[2] << 8));
    } else if ((cs >= CO_LSS_CS_SWITCH_SELECTIVE_VENDOR &&
                cs <= CO_LSS_CS_SWITCH_SELECTIVE_SERIAL) ||
               (cs >= CO_LSS_CS_IDENTIFY_VENDOR && cs <= CO_LSS_CS_IDENTIFY_SERIAL_HIGH)) {
        say(t, " 0x%08X", (unsigned)value);
    } else if (cs == CO_LSS_CS_FASTSCAN) {
        if (d[5] == CO_LSS_FASTSCAN_RESET) {
            say(t, " reset: every non-configured slave answers");
            return;
        }
        if (d[5] > CO_LSS_FASTSCAN_BIT_MAX || d[6] >= CO_LSS_FASTSCAN_PARTS ||
            d[7] >= CO_LSS_FASTSCAN_PARTS) {
            say(t, " out of range: bit %u, LSS sub %u, next %u", d[5], d[6], d[7]);
            return;
        }
        say(t, " %s 0x%08X, bits 31..%u, next %s", lss_part_name[d[6]], (unsigned)value, d[5],
            lss_part_name[d[7]]);
    }
}

static void lss_answer(const uint8_t *d, text_t *t)
{
    uint8_t cs = d[0];
    if (lss_confirmed(cs))
        say(t, " answer");
    if (cs == CO_LSS_CS_CONFIGURE_NODE_ID || cs == CO_LSS_CS_CONFIGURE_BIT_TIMING ||
        cs == CO_LSS_CS_STORE) {
        say(t, ": ");
        say_lss_error(t, cs, d);
    } else if (cs >= CO_LSS_CS_INQUIRE_VENDOR && cs <= CO_LSS_CS_INQUIRE_SERIAL) {
        say(t, ": 0x%08X", (unsigned)co_get_u32(&d[1]));
    } else if (cs == CO_LSS_CS_INQUIRE_NODE_ID) {
        say(t, ": ");
        say_lss_node_id(t, d[1]);
    }
}

static void decode_lss(const struct can_frame *f, text_t *t)
{
    bool from_slave = (f->can_id & CAN_SFF_MASK) == CO_LSS_ID_SLAVE;
    const char *who = from_slave ? "slave" : "master";
    if (f->can_id & CAN_RTR_FLAG || f->len != CO_LSS_FRAME_LEN) {
        say(t, "LSS %s malformed: %u bytes, an LSS frame has 8", who, f->len);
        return;
    }
    uint8_t cs = f->data[0];
    const char *name = co_lss_cs_name(cs);
    bool known = name != NULL &&
                 (from_slave ? lss_slave_only(cs) || lss_confirmed(cs) : !lss_slave_only(cs));
    if (!known) {
        say(t, "LSS %s unknown command 0x%02X", who, cs);
        return;
    }
    say(t, "LSS %s", name);
    if (from_slave)
        lss_answer(f->data, t);
    else
        lss_request(f->data, t);
}

void cotrace_decode(cotrace_decoder_t *dec, const struct can_frame *f, char *out, size_t cap)
{
    text_t t;
    if (!say_start(&t, out, cap, f, "CANopen"))
        return;
    uint16_t id = f->can_id & CAN_SFF_MASK;
    uint8_t node = id & CO_NODE_ID_MASK;
    bool rtr = f->can_id & CAN_RTR_FLAG;
    cotrace_pdo_t pdo;
    if (pdo_from_eds(dec, id, &pdo)) {
        decode_pdo(dec, f, &pdo, dec->eds_node, &t);
    } else if (id == CO_CAN_ID_NMT) {
        decode_nmt(f, &t);
    } else if (id == CO_CAN_ID_SYNC) {
        decode_sync(f, &t);
    } else if (id > CO_CAN_ID_SYNC && id < CO_CAN_ID_TIME) {
        decode_emcy(dec, f, &t);
    } else if (id == CO_CAN_ID_TIME) {
        decode_time(f, &t);
    } else if (id > CO_CAN_ID_SDO_TX && id < CO_CAN_ID_SDO_TX + CO_CAN_ID_NODE_SPAN && !rtr) {
        sdo_reply(dec, node, f, &t);
    } else if (id > CO_CAN_ID_SDO_RX && id < CO_CAN_ID_SDO_RX + CO_CAN_ID_NODE_SPAN && !rtr) {
        sdo_request(dec, node, f, &t);
    } else if (id > CO_CAN_ID_ERROR_CONTROL && id < CO_CAN_ID_ERROR_CONTROL + CO_CAN_ID_NODE_SPAN) {
        decode_error_control(dec, node, f, &t);
    } else if (id == CO_LSS_ID_MASTER || id == CO_LSS_ID_SLAVE) {
        decode_lss(f, &t);
    } else if (pdo_predefined(id, &pdo)) {
        decode_pdo(dec, f, &pdo, node, &t);
    } else {
        say(&t, "COB-ID 0x%03X: no predefined meaning", id);
    }
}

void cotrace_decoder_init(cotrace_decoder_t *dec, const eds_t *eds, uint8_t eds_node,
                          const co_emcy_code_table_t *vendor)
{
    memset(dec, 0, sizeof *dec);
    dec->eds = eds;
    dec->eds_node = eds_node;
    dec->vendor = vendor;
    if (eds)
        pdos_of_eds(dec);
}
