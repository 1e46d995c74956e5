/* SPDX-License-Identifier: Apache-2.0 */
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

size_t co_txq_clear(co_txq_t *q)
{
    size_t n = q->count;
    q->head = 0;
    q->count = 0;
    return n;
}
