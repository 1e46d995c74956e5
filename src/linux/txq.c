#include "co_linux/txq.h"

void co_txq_init(co_txq_t *q, size_t capacity)
{
    if (capacity < 1)
        capacity = 1;
    if (capacity > CO_TXQ_MAX)
        capacity = CO_TXQ_MAX;
    q->capacity = capacity;
    q->head = 0;
    q->count = 0;
}

bool co_txq_push(co_txq_t *q, const co_frame_t *frame, const void *origin)
{
    if (co_txq_full(q)) {
        q->dropped++;
        return false;
    }
    co_txq_entry_t *slot = &q->slots[(q->head + q->count) % q->capacity];
    slot->frame = *frame;
    slot->origin = origin;
    q->count++;
    return true;
}

const co_txq_entry_t *co_txq_peek(const co_txq_t *q)
{
    return co_txq_at(q, 0);
}

const co_txq_entry_t *co_txq_at(const co_txq_t *q, size_t position)
{
    return position < q->count ? &q->slots[(q->head + position) % q->capacity] : NULL;
}

void co_txq_pop(co_txq_t *q)
{
    if (q->count == 0)
        return;
    q->head = (q->head + 1) % q->capacity;
    q->count--;
}

size_t co_txq_clear(co_txq_t *q)
{
    size_t n = q->count;
    q->head = 0;
    q->count = 0;
    return n;
}
