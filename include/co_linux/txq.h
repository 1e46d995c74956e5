/* SPDX-License-Identifier: Apache-2.0 */
/* A bounded FIFO of CAN frames. The runtime keeps frames the socket could not take yet (and frames
 * waiting for delivery to the other local devices) in it; a full queue refuses the frame and counts
 * it instead of growing or blocking. */
#ifndef CO_LINUX_TXQ_H
#define CO_LINUX_TXQ_H

#include "co/co_types.h"

#include <stdbool.h>
#include <stddef.h>

#ifndef CO_TXQ_MAX
#define CO_TXQ_MAX 256 /* largest capacity, frames */
#endif

typedef struct co_txq_entry {
    co_frame_t frame;
    const void *origin; /* who queued it (the sending device), or NULL */
} co_txq_entry_t;

typedef struct co_txq {
    co_txq_entry_t slots[CO_TXQ_MAX];
    size_t capacity;
    size_t head; /* oldest entry */
    size_t count;
    unsigned long long dropped; /* frames refused because the queue was full */
} co_txq_t;

/* Empties the queue and sets its capacity (1..CO_TXQ_MAX; larger values are clamped). The drop
 * count is kept. */
void co_txq_init(co_txq_t *q, size_t capacity);

/* Removes every entry and returns how many there were. */
size_t co_txq_clear(co_txq_t *q);

static inline size_t co_txq_count(const co_txq_t *q)
{
    return q->count;
}

static inline bool co_txq_full(const co_txq_t *q)
{
    return q->count == q->capacity;
}

/* The slot `position` entries after the head: both are below the capacity, so one subtraction
 * wraps it, without a division per frame. */
static inline size_t co_txq_slot(const co_txq_t *q, size_t position)
{
    size_t slot = q->head + position;
    return slot < q->capacity ? slot : slot - q->capacity;
}

/* The entry `position` places after the oldest (0: the oldest); NULL beyond the last. Inline, as
 * the functions below: the loop pushes, reads and pops every frame it sends. */
static inline const co_txq_entry_t *co_txq_at(const co_txq_t *q, size_t position)
{
    return position < q->count ? &q->slots[co_txq_slot(q, position)] : NULL;
}

/* The oldest entry, or NULL when the queue is empty. */
static inline const co_txq_entry_t *co_txq_peek(const co_txq_t *q)
{
    return co_txq_at(q, 0);
}

/* Appends a frame. Returns false, and counts the drop, when the queue is full. */
static inline bool co_txq_push(co_txq_t *q, const co_frame_t *frame, const void *origin)
{
    if (co_txq_full(q)) {
        q->dropped++;
        return false;
    }
    co_txq_entry_t *slot = &q->slots[co_txq_slot(q, q->count)];
    slot->frame = *frame;
    slot->origin = origin;
    q->count++;
    return true;
}

/* Removes the oldest entry (no effect when empty). */
static inline void co_txq_pop(co_txq_t *q)
{
    if (q->count == 0)
        return;
    q->head = co_txq_slot(q, 1);
    q->count--;
}

#endif
