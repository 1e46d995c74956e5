/* SPDX-License-Identifier: Apache-2.0 */
#include "memory_storage.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The core's side of the storage contract (co_store.h). Checked with abort rather than ck_assert:
 * the fuzz harnesses (fuzz/) run these callbacks outside any Check test, where ck_assert exits. */
#define REQUIRE(cond) require(cond, #cond, __LINE__)
static void require(bool ok, const char *what, int line)
{
    if (!ok) {
        fprintf(stderr, "memory_storage.c:%d: storage contract broken: %s\n", line, what);
        abort();
    }
}

static int save_begin(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    REQUIRE(area < MEMORY_STORAGE_AREAS);
    m->saving = area;
    m->staged = 0;
    return 0;
}

static int save_write(void *ctx, const uint8_t *data, size_t len)
{
    memory_storage_t *m = ctx;
    if (m->fail_write || m->staged + len > MEMORY_STORAGE_IMAGE_MAX)
        return -1;
    memcpy(m->staging + m->staged, data, len);
    m->staged += len;
    return 0;
}

static int save_end(void *ctx, bool commit)
{
    memory_storage_t *m = ctx;
    if (commit) {
        memcpy(m->image[m->saving], m->staging, m->staged);
        m->size[m->saving] = (long)m->staged;
        m->saves++;
    }
    return 0;
}

static long load_size(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    REQUIRE(area < MEMORY_STORAGE_AREAS);
    return m->damaged && m->size[area] != 0 ? -1 : m->size[area];
}

static int load_read(void *ctx, uint8_t area, uint32_t offset, uint8_t *buf, size_t len)
{
    memory_storage_t *m = ctx;
    REQUIRE(offset + len <= (size_t)m->size[area]);
    if (m->fail_offset > 0 && offset == (uint32_t)m->fail_offset)
        return -1;
    memcpy(buf, m->image[area] + offset, len);
    return 0;
}

static int erase(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    if (m->fail_erase)
        return -1;
    m->size[area] = 0;
    m->erases++;
    return 0;
}

static void refused(void *ctx, const co_node_t *node, uint16_t index, uint8_t subindex,
                    const uint8_t *value, size_t len, uint32_t abort)
{
    memory_storage_t *m = ctx;
    REQUIRE(node != NULL);
    REQUIRE(len == 0 || value != NULL);
    if (m->refusals < MEMORY_STORAGE_REFUSALS)
        m->refused[m->refusals] = (memory_refusal_t){index, subindex, len, abort};
    m->refusals++;
}

static void image_refused(void *ctx, const co_node_t *node, const co_store_image_fault_t *fault)
{
    memory_storage_t *m = ctx;
    REQUIRE(node != NULL);
    REQUIRE(fault->reason != CO_STORE_FAULT_NONE);
    m->image_fault = *fault;
    m->images_refused++;
}

void memory_storage_init(memory_storage_t *m, co_storage_t *storage)
{
    memset(m, 0, sizeof(*m));
    *storage = (co_storage_t){.ctx = m,
                              .save_begin = save_begin,
                              .save_write = save_write,
                              .save_end = save_end,
                              .load_size = load_size,
                              .load_read = load_read,
                              .erase = erase,
                              .refused = refused,
                              .image_refused = image_refused};
}

long memory_storage_record(const memory_storage_t *m, uint8_t area, uint16_t index,
                           uint8_t subindex)
{
    const uint8_t *img = m->image[area];
    for (long i = CO_STORE_IMAGE_HEADER_SIZE; i < m->size[area];
         i += CO_STORE_RECORD_HEADER_SIZE + co_get_u16(img + i + 3))
        if (co_get_u16(img + i) == index && img[i + 2] == subindex)
            return i + CO_STORE_RECORD_HEADER_SIZE;
    return 0;
}

uint32_t memory_storage_refusal(const memory_storage_t *m, uint16_t index, uint8_t subindex)
{
    for (unsigned i = 0; i < m->refusals && i < MEMORY_STORAGE_REFUSALS; i++)
        if (m->refused[i].index == index && m->refused[i].subindex == subindex)
            return m->refused[i].abort;
    ck_abort_msg("no refusal reported for %04X:%02X", index, subindex);
    return 0;
}
