/* SPDX-License-Identifier: Apache-2.0 */
/* A model's communication profile area (1000h-1FFFh) against the table its manual prints: every
 * row is an entry of the generated dictionary with the type and access the table gives, the
 * number of entries of each record or array (its sub-index 0) reads as printed, a row the model
 * leaves out on purpose (a "reserved" sub-index) is absent, and the dictionary has no entry in the
 * area that is neither a row nor one of the model's documented additions. */
#ifndef MANUAL_TABLE_H
#define MANUAL_TABLE_H

#include "check_main.h"
#include "drive_bench.h"

#include <stdbool.h>

/* The access a row prints: RO (readable, never writable by SDO), RW, or none (the ATV58 card's
 * tables have no access column); ABSENT for a row the model leaves out, with the reason in the
 * model's page. */
typedef enum manual_access { MANUAL_ANY, MANUAL_RO, MANUAL_RW, MANUAL_ABSENT } manual_access_t;

/* No type printed (the ATV58 card's PDO and SDO tables give values only). */
#define MANUAL_TYPE_NOT_PRINTED 0

/* No number of entries printed: the row is not the sub-index 0 of a record or array. */
#define MANUAL_NOT_COUNT (-1)

typedef struct manual_row {
    uint16_t index;
    uint8_t subindex;
    uint8_t type; /* co_dtype_t, as the table names it, or MANUAL_TYPE_NOT_PRINTED */
    manual_access_t access;
    int entries; /* sub-index 0 of a record or array: its value as printed; else MANUAL_NOT_COUNT */
} manual_row_t;

static inline bool manual_row_lists(const manual_row_t *rows, size_t count, uint16_t index,
                                    uint8_t subindex)
{
    for (size_t i = 0; i < count; i++)
        if (rows[i].index == index && rows[i].subindex == subindex &&
            rows[i].access != MANUAL_ABSENT)
            return true;
    return false;
}

static inline bool manual_index_added(const uint16_t *added, size_t count, uint16_t index)
{
    for (size_t i = 0; i < count; i++)
        if (added[i] == index)
            return true;
    return false;
}

/* Checks the bench's drive (started on the model) against the manual's rows; `added` are the
 * indexes of the area the model adds to its manual's table (docs/<model>.md). */
static inline void manual_table_check(bench_t *b, const manual_row_t *rows, size_t count,
                                      const uint16_t *added, size_t added_count)
{
    const co_od_t *od = b->drive.node.od;
    for (size_t i = 0; i < count; i++) {
        const manual_row_t *row = &rows[i];
        const co_od_entry_t *entry = co_od_find(od, row->index, row->subindex);
        if (row->access == MANUAL_ABSENT) {
            ck_assert_msg(entry == NULL, "%04Xh:%02X is in the dictionary", row->index,
                          row->subindex);
            continue;
        }
        ck_assert_msg(entry != NULL, "%04Xh:%02X is missing", row->index, row->subindex);
        ck_assert_msg(row->type == MANUAL_TYPE_NOT_PRINTED || entry->type == row->type,
                      "%04Xh:%02X has type %u, the table %u", row->index, row->subindex,
                      entry->type, row->type);
        bool writable = (entry->flags & CO_OD_WRITE) != 0;
        ck_assert_msg(row->access == MANUAL_ANY || writable == (row->access == MANUAL_RW),
                      "%04Xh:%02X is %s", row->index, row->subindex, writable ? "rw" : "ro");
        if (row->entries != MANUAL_NOT_COUNT)
            ck_assert_msg(bench_read(b, row->index, 0) == (uint32_t)row->entries,
                          "%04Xh:00 reads %u, the table prints %d", row->index,
                          bench_read(b, row->index, 0), row->entries);
    }
    for (uint16_t i = 0; i < od->count; i++) {
        const co_od_entry_t *entry = &od->entries[i];
        if (entry->index < 0x1000 || entry->index > 0x1FFF ||
            manual_index_added(added, added_count, entry->index))
            continue;
        ck_assert_msg(manual_row_lists(rows, count, entry->index, entry->subindex),
                      "%04Xh:%02X is not in the manual's table", entry->index, entry->subindex);
    }
}

#endif
