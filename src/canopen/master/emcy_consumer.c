/* SPDX-License-Identifier: Apache-2.0 */
/* EMCY consumer: decoding the emergencies of other nodes and the meaning of their error codes. */
#include "co/co_emcy_consumer.h"

#include "co/co_emcy.h"

#define EXACT CO_EMCY_MASK_EXACT
#define SUBCLASS CO_EMCY_MASK_SUBCLASS
#define CLASS CO_EMCY_MASK_CLASS

#define TABLE(meanings)                                                                            \
    {                                                                                              \
        meanings, sizeof(meanings) / sizeof((meanings)[0])                                         \
    }

/* CiA 301 v4.2 table 21 (the generic classes, the communication and protocol errors). */
static const co_emcy_meaning_t cia301_meanings[] = {
    {CO_EMCY_NO_ERROR, SUBCLASS, "error reset or no error"},
    {CO_EMCY_GENERIC, SUBCLASS, "generic error"},
    {0x2000, CLASS, "current"},
    {0x2100, SUBCLASS, "current, device input side"},
    {0x2200, SUBCLASS, "current inside the device"},
    {0x2300, SUBCLASS, "current, device output side"},
    {0x3000, CLASS, "voltage"},
    {0x3100, SUBCLASS, "mains voltage"},
    {0x3200, SUBCLASS, "voltage inside the device"},
    {0x3300, SUBCLASS, "output voltage"},
    {0x4000, CLASS, "temperature"},
    {0x4100, SUBCLASS, "ambient temperature"},
    {0x4200, SUBCLASS, "device temperature"},
    {0x5000, CLASS, "device hardware"},
    {0x6000, CLASS, "device software"},
    {0x6100, SUBCLASS, "internal software"},
    {0x6200, SUBCLASS, "user software"},
    {0x6300, SUBCLASS, "data set"},
    {0x7000, CLASS, "additional modules"},
    {0x8000, CLASS, "monitoring"},
    {0x8100, SUBCLASS, "communication"},
    {CO_EMCY_CAN_OVERRUN, EXACT, "CAN overrun (objects lost)"},
    {CO_EMCY_CAN_PASSIVE, EXACT, "CAN in error passive mode"},
    {CO_EMCY_HEARTBEAT, EXACT, "life guard error or heartbeat error"},
    {CO_EMCY_BUS_OFF, EXACT, "recovered from bus off"},
    {0x8150, EXACT, "CAN-ID collision"},
    {0x8200, SUBCLASS, "protocol error"},
    {CO_EMCY_PDO_LENGTH, EXACT, "PDO not processed due to length error"},
    {CO_EMCY_PDO_LENGTH_EXCEEDED, EXACT, "PDO length exceeded"},
    {0x8230, EXACT, "DAM MPDO not processed, destination object not available"},
    {CO_EMCY_SYNC_LENGTH, EXACT, "unexpected SYNC data length"},
    {CO_EMCY_RPDO_TIMEOUT, EXACT, "RPDO timeout"},
    {0x9000, SUBCLASS, "external error"},
    {0xF000, SUBCLASS, "additional functions"},
    {0xFF00, SUBCLASS, "device specific"},
};

/* CiA 402-2 (IEC 61800-7-201) drive error codes, the refinements of the CiA 301 classes. */
static const co_emcy_meaning_t cia402_meanings[] = {
    {0x2110, EXACT, "short circuit/earth leakage (input)"},
    {0x2120, EXACT, "earth leakage (input)"},
    {0x2130, EXACT, "short circuit (input)"},
    {0x2213, EXACT, "over-current in ramp function"},
    {0x2214, EXACT, "over-current in the sequence"},
    {0x2220, EXACT, "continuous over current (device internal)"},
    {0x2230, EXACT, "short circuit/earth leakage (device internal)"},
    {0x2240, EXACT, "earth leakage (device internal)"},
    {0x2250, EXACT, "short circuit (device internal)"},
    {0x2310, EXACT, "continuous over current"},
    {0x2320, EXACT, "short circuit/earth leakage (motor side)"},
    {0x2330, EXACT, "earth leakage (motor side)"},
    {0x2340, EXACT, "short circuit (motor side)"},
    {0x3110, EXACT, "mains over-voltage"},
    {0x3120, EXACT, "mains under-voltage"},
    {0x3130, EXACT, "phase failure"},
    {0x3140, EXACT, "mains frequency"},
    {0x3210, EXACT, "DC link over-voltage"},
    {0x3220, EXACT, "DC link under-voltage"},
    {0x3230, EXACT, "load error"},
    {0x3310, EXACT, "output over-voltage"},
    {0x3320, EXACT, "armature circuit"},
    {0x3330, EXACT, "field circuit"},
    {0x4110, EXACT, "excess ambient temperature"},
    {0x4120, EXACT, "too low ambient temperature"},
    {0x4130, EXACT, "temperature of the supply air"},
    {0x4140, EXACT, "temperature of the air outlet"},
    {0x4210, EXACT, "excess temperature of the device"},
    {0x4220, EXACT, "too low temperature of the device"},
    {0x4300, SUBCLASS, "drive temperature"},
    {0x4310, EXACT, "excess temperature of the drive"},
    {0x4320, EXACT, "too low temperature of the drive"},
    {0x4400, SUBCLASS, "supply temperature"},
    {0x5100, SUBCLASS, "supply"},
    {0x5200, SUBCLASS, "control"},
    {0x5300, SUBCLASS, "operating unit"},
    {0x5400, SUBCLASS, "power section"},
    {0x5500, SUBCLASS, "data storage"},
    {0x5530, EXACT, "non-volatile data memory"},
    {0x6010, EXACT, "software reset (watchdog)"},
    {0x6320, EXACT, "parameter error"},
    {0x7100, SUBCLASS, "power"},
    {0x7110, EXACT, "brake chopper"},
    {0x7120, EXACT, "motor"},
    {0x7121, EXACT, "motor blocked"},
    {0x7200, SUBCLASS, "measurement circuit"},
    {0x7300, SUBCLASS, "sensor"},
    {0x7310, EXACT, "speed sensor"},
    {0x7320, EXACT, "position sensor"},
    {0x7400, SUBCLASS, "computation circuit"},
    {0x7500, SUBCLASS, "communication"},
    {0x7510, EXACT, "serial interface no. 1"},
    {0x7520, EXACT, "serial interface no. 2"},
    {0x7600, SUBCLASS, "data storage (external)"},
    {0x8300, SUBCLASS, "torque control"},
    {0x8311, EXACT, "excess torque"},
    {0x8312, EXACT, "difficult start up"},
    {0x8313, EXACT, "standstill torque"},
    {0x8321, EXACT, "insufficient torque"},
    {0x8331, EXACT, "torque fault"},
    {0x8400, SUBCLASS, "velocity speed controller"},
    {0x8500, SUBCLASS, "position controller"},
    {0x8600, SUBCLASS, "positioning controller"},
    {0x8611, EXACT, "following error"},
    {0x8612, EXACT, "reference limit"},
    {0x8700, SUBCLASS, "sync controller"},
    {0x8800, SUBCLASS, "winding controller"},
    {0x8900, SUBCLASS, "process data monitoring"},
    {0x8A00, SUBCLASS, "control"},
    {0xF001, EXACT, "deceleration"},
    {0xF002, EXACT, "sub-synchronous run"},
    {0xF003, EXACT, "stroke operation"},
    {0xF004, EXACT, "control"},
};

static const co_emcy_code_table_t cia301_table = TABLE(cia301_meanings);
static const co_emcy_code_table_t cia402_table = TABLE(cia402_meanings);

static unsigned mask_bits(uint16_t mask)
{
    unsigned bits = 0;
    for (; mask; mask &= (uint16_t)(mask - 1))
        bits++;
    return bits;
}

/* The most specific meaning of `code` in `table` if it is more specific than *best; tables
 * searched earlier win ties. */
static void find_best(const co_emcy_code_table_t *table, uint16_t code,
                      const co_emcy_meaning_t **best)
{
    for (size_t i = 0; i < table->count; i++) {
        const co_emcy_meaning_t *m = &table->meanings[i];
        if ((code & m->mask) != m->code)
            continue;
        if (!*best || mask_bits(m->mask) > mask_bits((*best)->mask))
            *best = m;
    }
}

const char *co_emcy_code_text_in(const co_emcy_code_table_t *vendor, uint16_t code)
{
    const co_emcy_meaning_t *best = NULL;
    if (vendor)
        find_best(vendor, code, &best);
    find_best(&cia402_table, code, &best);
    find_best(&cia301_table, code, &best);
    return best ? best->text : "unknown error code";
}

const char *co_emcy_code_text(uint16_t code)
{
    return co_emcy_code_text_in(NULL, code);
}

co_emcy_decode_t co_emcy_decode(const co_frame_t *frame, co_emcy_message_t *out)
{
    if (frame->flags & (CO_FRAME_RTR | CO_FRAME_EFF) || frame->id <= CO_CAN_ID_EMCY ||
        frame->id > CO_CAN_ID_EMCY + CO_NODE_ID_MAX)
        return CO_EMCY_DECODE_NOT_EMCY;
    out->node_id = (uint8_t)(frame->id - CO_CAN_ID_EMCY);
    if (frame->len < CO_EMCY_FRAME_LEN)
        return CO_EMCY_DECODE_SHORT;
    out->code = co_get_u16(&frame->data[0]);
    out->reg = frame->data[2];
    for (unsigned i = 0; i < CO_EMCY_MSEF_LEN; i++)
        out->msef[i] = frame->data[3 + i];
    return CO_EMCY_DECODE_OK;
}

const char *co_emcy_decode_text(co_emcy_decode_t result)
{
    switch (result) {
    case CO_EMCY_DECODE_OK:
        return "EMCY frame";
    case CO_EMCY_DECODE_SHORT:
        return "EMCY frame shorter than 8 bytes";
    case CO_EMCY_DECODE_NOT_EMCY:
        break;
    }
    return "not an EMCY frame";
}

void co_emcy_consumer_init(co_emcy_consumer_t *consumer, co_emcy_consumer_fn on_emcy, void *user)
{
    for (unsigned i = 0; i < sizeof consumer->watched; i++)
        consumer->watched[i] = 0;
    consumer->on_emcy = on_emcy;
    consumer->user = user;
}

bool co_emcy_consumer_watch(co_emcy_consumer_t *consumer, uint8_t node_id, bool watch)
{
    if (node_id < 1 || node_id > CO_NODE_ID_MAX)
        return false;
    uint8_t bit = (uint8_t)(1u << (node_id & 7u));
    if (watch)
        consumer->watched[node_id >> 3] |= bit;
    else
        consumer->watched[node_id >> 3] &= (uint8_t)~bit;
    return true;
}

bool co_emcy_consumer_receive(co_emcy_consumer_t *consumer, const co_frame_t *frame, co_time_t now)
{
    co_emcy_message_t msg = {0};
    co_emcy_decode_t result = co_emcy_decode(frame, &msg);
    if (result == CO_EMCY_DECODE_NOT_EMCY ||
        !(consumer->watched[msg.node_id >> 3] & (1u << (msg.node_id & 7u))))
        return false;
    consumer->on_emcy(consumer->user, result, &msg, now);
    return true;
}
