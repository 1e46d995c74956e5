/* SPDX-License-Identifier: Apache-2.0 */
/* The TIME service (co_time_stamp.h): the TIME_OF_DAY codec, the consumer, the producer and the
 * rules of 1012h. */
#include "co/co_node.h"
#include "co/co_time_stamp.h"

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

static uint32_t time_cob_id(const co_node_t *node)
{
    return (uint32_t)co_od_value(node, CO_IDX_TIME_COB_ID, 0);
}

static void time_reset(co_node_t *node)
{
    node->time_cob_id = time_cob_id(node);
}

static bool time_receive(co_node_t *node, const co_frame_t *frame)
{
    uint32_t cob_id = node->time_cob_id;
    if (!(cob_id & CO_TIME_COBID_CONSUMER) || frame->id != (cob_id & CO_TIME_COBID_CAN_ID) ||
        (frame->flags & CO_FRAME_RTR))
        return false;
    co_time_of_day_t time;
    /* CiA 301 gives a wrong TIME length no EMCY: the frame is dropped. */
    if (co_time_of_day_decode(frame->data, frame->len, &time) && node->hooks != NULL &&
        node->hooks->time_stamp != NULL)
        node->hooks->time_stamp(node, &time);
    return true;
}

/* CiA 301 7.5.2.12: bits 31 (consume) and 30 (produce), an 11-bit CAN-ID that is not restricted
 * (7.3.5; bit 29 and bits 28..11 refused, co_cob_id_check), and no new CAN-ID while the object
 * exists (bit 31 or 30) before and after the write. */
static uint32_t time_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              size_t len)
{
    if (entry->index != CO_IDX_TIME_COB_ID)
        return CO_SDO_OK;
    uint32_t old = node->time_cob_id;
    uint32_t value = co_get_u32(data);
    const uint32_t exists = CO_TIME_COBID_CONSUMER | CO_TIME_COBID_PRODUCER;
    uint32_t abort = co_cob_id_check(old, value, 0, exists);
    if (abort == CO_SDO_OK && (old & exists) && (value & exists) &&
        ((old ^ value) & CO_TIME_COBID_CAN_ID) != 0)
        abort = CO_SDO_ABORT_VALUE_RANGE;
    if (abort != CO_SDO_OK)
        return abort;
    co_od_store(node, entry, data, len);
    node->time_cob_id = value;
    return CO_OD_HANDLED;
}

const co_time_stamp_code_t co_time_stamp = {
    .reset = time_reset,
    .receive = time_receive,
    .od_write = time_od_write,
};

bool co_time_stamp_send(co_node_t *node, const co_time_of_day_t *time)
{
    uint32_t cob_id = time_cob_id(node);
    if (!(cob_id & CO_TIME_COBID_PRODUCER) ||
        (node->nmt_state != CO_NMT_PRE_OPERATIONAL && node->nmt_state != CO_NMT_OPERATIONAL))
        return false;
    co_frame_t frame = {.id = cob_id & CO_TIME_COBID_CAN_ID, .len = CO_TIME_OF_DAY_LEN};
    co_time_of_day_encode(time, frame.data);
    co_node_send(node, &frame);
    return true;
}
