/* SPDX-License-Identifier: Apache-2.0 */
/* Object dictionary access: binary search over the const table and the generic SDO read and write
 * checks of CiA 301. The rules of the communication parameters are the services', which the node
 * hands in (co_node_t.parameter_write): the dictionary is the ground floor and calls no service. */
#include "co/co_node.h"

#include <string.h>

static uint32_t entry_key(uint16_t index, uint8_t subindex)
{
    return ((uint32_t)index << 8) | subindex;
}

size_t co_od_type_size(uint8_t type)
{
    switch (type) {
    case CO_DT_BOOLEAN:
    case CO_DT_INTEGER8:
    case CO_DT_UNSIGNED8:
        return 1;
    case CO_DT_INTEGER16:
    case CO_DT_UNSIGNED16:
        return 2;
    case CO_DT_INTEGER32:
    case CO_DT_UNSIGNED32:
    case CO_DT_REAL32:
        return 4;
    case CO_DT_INTEGER64:
    case CO_DT_UNSIGNED64:
    case CO_DT_REAL64:
        return 8;
    default:
        return 0;
    }
}

static bool type_is_signed(uint8_t type)
{
    return type == CO_DT_INTEGER8 || type == CO_DT_INTEGER16 || type == CO_DT_INTEGER32 ||
           type == CO_DT_INTEGER64;
}

static bool type_is_string(uint8_t type)
{
    return type == CO_DT_VISIBLE_STRING || type == CO_DT_UNICODE_STRING;
}

co_od_error_t co_od_validate(const co_od_t *od, uint16_t *position)
{
    *position = 0;
    if (od == NULL || od->entries == NULL || od->count == 0)
        return CO_OD_ERR_EMPTY;
    uint32_t prev = 0;
    const co_od_entry_t *e = od->entries;
    for (uint16_t i = 0; i < od->count; i++, e++) {
        uint32_t key = entry_key(e->index, e->subindex);
        *position = i;
        if (i > 0 && key == prev)
            return CO_OD_ERR_DUPLICATE;
        if (i > 0 && key < prev)
            return CO_OD_ERR_UNSORTED;
        prev = key;
        bool stream = (e->flags & CO_OD_STREAM) != 0;
        if (stream && (od->streaming == NULL || !od->streaming->entry_valid(e)))
            return CO_OD_ERR_STREAM;
        size_t fixed = co_od_type_size(e->type);
        if ((e->size == 0 && !stream) || (fixed != 0 && e->size != fixed))
            return CO_OD_ERR_SIZE;
        if ((uint64_t)e->offset + e->size > od->data_size)
            return CO_OD_ERR_BOUNDS;
    }
    return CO_OD_VALID;
}

/* First entry whose key is >= the wanted key, or the end of the table. */
static const co_od_entry_t *lower_bound(const co_od_t *od, uint32_t key)
{
    const co_od_entry_t *first = od->entries;
    size_t len = od->count;
    while (len > 0) {
        size_t half = len / 2;
        const co_od_entry_t *mid = first + half;
        if (entry_key(mid->index, mid->subindex) < key) {
            first = mid + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    return first;
}

const co_od_entry_t *co_od_find(const co_od_t *od, uint16_t index, uint8_t subindex)
{
    const co_od_entry_t *e;
    (void)co_od_lookup(od, index, subindex, &e);
    return e;
}

const char *co_od_name(const co_od_t *od, uint16_t index, uint8_t subindex)
{
    const co_od_entry_t *e = co_od_find(od, index, subindex);
    return e != NULL && od->names != NULL ? od->names[e - od->entries] : NULL;
}

/* One search: when the entry is absent, its neighbours in the sorted table tell whether the
 * object has other sub-indexes. */
uint32_t co_od_lookup(const co_od_t *od, uint16_t index, uint8_t subindex,
                      const co_od_entry_t **entry)
{
    const co_od_entry_t *e = lower_bound(od, entry_key(index, subindex));
    *entry = NULL;
    if (e < od->entries + od->count && e->index == index) {
        if (e->subindex != subindex)
            return CO_SDO_ABORT_NO_SUBINDEX;
        *entry = e;
        return CO_SDO_OK;
    }
    if (e > od->entries && e[-1].index == index)
        return CO_SDO_ABORT_NO_SUBINDEX;
    return CO_SDO_ABORT_NO_OBJECT;
}

uint8_t *co_od_bytes(const co_node_t *node, const co_od_entry_t *entry)
{
    return node->od_data + entry->offset;
}

size_t co_od_length(const co_node_t *node, const co_od_entry_t *entry)
{
    const uint8_t *p = co_od_bytes(node, entry);
    if (!type_is_string(entry->type))
        return entry->size;
    size_t n = 0;
    while (n < entry->size && p[n] != 0)
        n++;
    return n;
}

uint32_t co_od_read_check(co_node_t *node, uint16_t index, uint8_t subindex,
                          const co_od_entry_t **entry)
{
    uint32_t abort = co_od_lookup(node->od, index, subindex, entry);
    if (abort != CO_SDO_OK)
        return abort;
    if (!((*entry)->flags & CO_OD_READ))
        return CO_SDO_ABORT_WRITE_ONLY;
    if ((*entry)->hook != NULL && (*entry)->hook->read != NULL)
        return (*entry)->hook->read(node, *entry);
    return CO_SDO_OK;
}

static uint64_t raw_value(const uint8_t *p, size_t size)
{
    uint64_t v = 0;
    for (size_t i = size; i > 0; i--)
        v = (v << 8) | p[i - 1];
    return v;
}

/* Signed types are 1, 2, 4 or 8 bytes: below 8 the value and its sign bit fit in 32 bits, whose
 * arithmetic is cheaper than 64-bit shifts on a 32-bit processor. */
static int64_t sign_extend(uint64_t v, size_t size)
{
    if (size >= 8)
        return (int64_t)v;
    uint32_t sign = 1u << (size * 8 - 1);
    return (int32_t)(((uint32_t)v ^ sign) - sign);
}

/* The value of `size` bytes (1..8, little-endian) of the given type. */
static int64_t typed_value(const uint8_t *p, size_t size, uint8_t type)
{
    uint64_t v = raw_value(p, size);
    return type_is_signed(type) ? sign_extend(v, size) : (int64_t)v;
}

int64_t co_od_get(const co_node_t *node, const co_od_entry_t *entry)
{
    return typed_value(co_od_bytes(node, entry), entry->size < 8 ? entry->size : 8, entry->type);
}

void co_od_set(co_node_t *node, const co_od_entry_t *entry, int64_t value)
{
    uint8_t *p = co_od_bytes(node, entry);
    size_t size = entry->size < 8 ? entry->size : 8;
    uint64_t v = (uint64_t)value;
    for (size_t i = 0; i < size; i++) {
        p[i] = (uint8_t)v;
        v >>= 8;
    }
}

int64_t co_od_value(const co_node_t *node, uint16_t index, uint8_t subindex)
{
    const co_od_entry_t *e = co_od_find(node->od, index, subindex);
    return e != NULL ? co_od_get(node, e) : 0;
}

uint32_t co_od_param(const co_node_t *node, uint16_t index, uint8_t subindex, uint32_t absent)
{
    const co_od_entry_t *e = co_od_find(node->od, index, subindex);
    return e != NULL ? (uint32_t)co_od_get(node, e) : absent;
}

bool co_od_set_value(co_node_t *node, uint16_t index, uint8_t subindex, int64_t value)
{
    const co_od_entry_t *e = co_od_find(node->od, index, subindex);
    if (e == NULL)
        return false;
    co_od_set(node, e, value);
    return true;
}

void co_od_store(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data, size_t len)
{
    uint8_t *p = co_od_bytes(node, entry);
    if (len > entry->size)
        len = entry->size;
    memcpy(p, data, len);
    memset(p + len, 0, entry->size - len);
}

/* CiA 301 7.2.4.3.17: too long 0x06070012, too short 0x06070013; strings may be shorter. `size`
 * is the type's fixed size, 0 for strings and domains. */
static uint32_t check_length(const co_od_entry_t *e, size_t size, size_t len)
{
    if (len > e->size)
        return CO_SDO_ABORT_LENGTH_HIGH;
    if (size != 0 && len < e->size)
        return CO_SDO_ABORT_LENGTH_LOW;
    if (e->type == CO_DT_OCTET_STRING && len < e->size)
        return CO_SDO_ABORT_LENGTH_LOW;
    return CO_SDO_OK;
}

static uint32_t check_limits(const co_od_entry_t *e, size_t size, const uint8_t *data)
{
    if (size == 0)
        return CO_SDO_OK;
    if (e->type == CO_DT_BOOLEAN && data[0] > 1)
        return CO_SDO_ABORT_VALUE_RANGE;
    if (e->limits == NULL || e->type == CO_DT_REAL32 || e->type == CO_DT_REAL64)
        return CO_SDO_OK;
    uint64_t value = (uint64_t)typed_value(data, size, e->type);
    if (value == 0 && (e->flags & CO_OD_ZERO_OK))
        return CO_SDO_OK;
    /* Signed values compare as unsigned once the sign bit of all three is flipped: the order of
     * int64_t maps onto that of uint64_t. */
    uint64_t bias = type_is_signed(e->type) ? UINT64_C(1) << 63 : 0;
    uint64_t v = value ^ bias;
    if (v > (e->limits->high ^ bias))
        return CO_SDO_ABORT_VALUE_HIGH;
    if (v < (e->limits->low ^ bias))
        return CO_SDO_ABORT_VALUE_LOW;
    return CO_SDO_OK;
}

/* The values of the entry's type of `size` bytes (1..8), as co_od_limits_t holds them. */
static co_od_limits_t type_range(uint8_t type, size_t size)
{
    if (type == CO_DT_BOOLEAN)
        return (co_od_limits_t){0, 1};
    unsigned bits = (unsigned)size * 8u;
    if (type_is_signed(type)) {
        uint64_t high = (UINT64_C(1) << (bits - 1u)) - 1u;
        return (co_od_limits_t){~high, high};
    }
    return (co_od_limits_t){0, bits == 64u ? UINT64_MAX : (UINT64_C(1) << bits) - 1u};
}

int64_t co_od_saturate(const co_od_entry_t *entry, int64_t value)
{
    size_t size = co_od_type_size(entry->type);
    if (size == 0 || entry->type == CO_DT_REAL32 || entry->type == CO_DT_REAL64)
        return value;
    if (value == 0 && (entry->flags & CO_OD_ZERO_OK))
        return 0;
    co_od_limits_t range = entry->limits != NULL ? *entry->limits : type_range(entry->type, size);
    if (type_is_signed(entry->type)) {
        int64_t low = (int64_t)range.low, high = (int64_t)range.high;
        return value < low ? low : (value > high ? high : value);
    }
    if (value < 0 || (uint64_t)value < range.low)
        return (int64_t)range.low;
    return (uint64_t)value > range.high ? (int64_t)range.high : value;
}

uint32_t co_od_write(co_node_t *node, uint16_t index, uint8_t subindex, const uint8_t *data,
                     size_t len, co_od_origin_t origin)
{
    const co_od_entry_t *e;
    uint32_t abort = co_od_lookup(node->od, index, subindex, &e);
    if (abort != CO_SDO_OK)
        return abort;
    return co_od_write_entry(node, e, data, len, origin);
}

uint32_t co_od_write_entry(co_node_t *node, const co_od_entry_t *e, const uint8_t *data, size_t len,
                           co_od_origin_t origin)
{
    uint32_t abort;
    if (!(e->flags & CO_OD_WRITE) && origin != CO_OD_ORIGIN_APP)
        return CO_SDO_ABORT_READ_ONLY;
    if (e->flags & CO_OD_STREAM)
        return node->od->streaming->write(node, e, data, len);
    size_t size = co_od_type_size(e->type);
    abort = check_length(e, size, len);
    if (abort == CO_SDO_OK)
        abort = check_limits(e, size, data);
    if (abort == CO_SDO_OK && e->hook != NULL && e->hook->write != NULL)
        abort = e->hook->write(node, e, data, len, origin);
    if (abort == CO_SDO_OK)
        abort = node->parameter_write(node, e, data, len);
    if (abort == CO_SDO_OK)
        co_od_store(node, e, data, len);
    else if (abort != CO_OD_HANDLED)
        return abort;
    if (node->hooks != NULL && node->hooks->od_written != NULL)
        node->hooks->od_written(node, e, origin);
    return CO_SDO_OK;
}

void co_od_restore_defaults(co_node_t *node, uint16_t first, uint16_t last)
{
    const co_od_t *od = node->od;
    for (const co_od_entry_t *e = lower_bound(od, entry_key(first, 0));
         e < od->entries + od->count && e->index <= last; e++) {
        memcpy(co_od_bytes(node, e), od->defaults + e->offset, e->size);
        if (e->flags & CO_OD_NODEID)
            co_od_set(node, e, co_od_get(node, e) + node->node_id);
    }
}
