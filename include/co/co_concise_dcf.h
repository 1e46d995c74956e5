/* SPDX-License-Identifier: Apache-2.0 */
/* Concise DCF (CiA 302-3; the value of an NMT master's 1F22h, sub-index the slave's node-id): a
 * slave's configuration as bytes, UNSIGNED32 the number of entries, then per entry UNSIGNED16
 * index, UNSIGNED8 sub-index, UNSIGNED32 size and that many bytes of value, all little-endian.
 * Read in place (no copy, no malloc) and written into the caller's buffer; the network master
 * downloads a slave's configuration from it (docs/net-master.md, "Concise DCF 1F22h"). */
#ifndef CO_CONCISE_DCF_H
#define CO_CONCISE_DCF_H

#include "co_types.h"

#define CO_CONCISE_DCF_HEADER 4u       /* the number of entries */
#define CO_CONCISE_DCF_ENTRY_HEADER 7u /* index, sub-index, size */

/* One entry: `len` bytes at `data`, inside the concise DCF read. */
typedef struct co_concise_dcf_entry {
    uint16_t index;
    uint8_t subindex;
    const uint8_t *data;
    uint32_t len;
} co_concise_dcf_entry_t;

/* Whether dcf[0 .. len) is one whole concise DCF: as many entries as it says, each of 1 byte or
 * more and inside the bytes, nothing after the last; *count (may be NULL) its entries. */
bool co_concise_dcf_valid(const uint8_t *dcf, size_t len, uint32_t *count);

/* The entry at byte offset *pos (CO_CONCISE_DCF_HEADER for the first) of a valid concise DCF, and
 * *pos past it; false at its end. */
bool co_concise_dcf_next(const uint8_t *dcf, size_t len, size_t *pos,
                         co_concise_dcf_entry_t *entry);

/* Writing one: co_concise_dcf_begin starts an empty one in buf (0 entries; returns its length,
 * CO_CONCISE_DCF_HEADER, or 0 when cap is smaller), co_concise_dcf_add appends an entry of `len`
 * bytes (1 or more) to the `used` bytes and counts it; returns the new length, or 0, and buf
 * unchanged, when it does not fit. */
size_t co_concise_dcf_begin(uint8_t *buf, size_t cap);
size_t co_concise_dcf_add(uint8_t *buf, size_t cap, size_t used,
                          const co_concise_dcf_entry_t *entry);

#endif
