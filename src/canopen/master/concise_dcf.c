/* SPDX-License-Identifier: Apache-2.0 */
/* The concise DCF of CiA 302-3, read in place and written into the caller's buffer. */
#include "co/co_concise_dcf.h"

#include <string.h>

/* The entry at *pos, when its header and its bytes lie within len; *pos past it. */
static bool entry_at(const uint8_t *dcf, size_t len, size_t *pos, co_concise_dcf_entry_t *entry)
{
    if (len - *pos < CO_CONCISE_DCF_ENTRY_HEADER)
        return false;
    const uint8_t *p = dcf + *pos;
    uint32_t size = co_get_u32(p + 3);
    if (size == 0 || size > len - *pos - CO_CONCISE_DCF_ENTRY_HEADER)
        return false;
    *entry = (co_concise_dcf_entry_t){
        .index = co_get_u16(p),
        .subindex = p[2],
        .data = p + CO_CONCISE_DCF_ENTRY_HEADER,
        .len = size,
    };
    *pos += CO_CONCISE_DCF_ENTRY_HEADER + size;
    return true;
}

bool co_concise_dcf_valid(const uint8_t *dcf, size_t len, uint32_t *count)
{
    if (dcf == NULL || len < CO_CONCISE_DCF_HEADER)
        return false;
    uint32_t entries = co_get_u32(dcf);
    size_t pos = CO_CONCISE_DCF_HEADER;
    co_concise_dcf_entry_t entry;
    for (uint32_t k = 0; k < entries; k++) {
        if (!entry_at(dcf, len, &pos, &entry))
            return false;
    }
    if (pos != len)
        return false;
    if (count != NULL)
        *count = entries;
    return true;
}

bool co_concise_dcf_next(const uint8_t *dcf, size_t len, size_t *pos, co_concise_dcf_entry_t *entry)
{
    return *pos < len && entry_at(dcf, len, pos, entry);
}

size_t co_concise_dcf_begin(uint8_t *buf, size_t cap)
{
    if (cap < CO_CONCISE_DCF_HEADER)
        return 0;
    co_put_u32(buf, 0);
    return CO_CONCISE_DCF_HEADER;
}

size_t co_concise_dcf_add(uint8_t *buf, size_t cap, size_t used,
                          const co_concise_dcf_entry_t *entry)
{
    if (used < CO_CONCISE_DCF_HEADER || used > cap || entry->len == 0 || entry->len > cap - used ||
        cap - used - entry->len < CO_CONCISE_DCF_ENTRY_HEADER)
        return 0;
    uint8_t *p = buf + used;
    co_put_u16(p, entry->index);
    p[2] = entry->subindex;
    co_put_u32(p + 3, entry->len);
    memcpy(p + CO_CONCISE_DCF_ENTRY_HEADER, entry->data, entry->len);
    co_put_u32(buf, co_get_u32(buf) + 1);
    return used + CO_CONCISE_DCF_ENTRY_HEADER + entry->len;
}
