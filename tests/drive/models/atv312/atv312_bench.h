/* SPDX-License-Identifier: Apache-2.0 */
/* The drive bench on the ATV312 model. */
#ifndef ATV312_BENCH_H
#define ATV312_BENCH_H

#include "atv312/atv312.h"
#include "drive_bench.h"

/* Boots node 4, an ATV312, at time 0 and consumes its boot-up frame. */
static inline void bench_start(bench_t *b)
{
    bench_start_model(b, &atv312_profile, NULL);
}

/* NMT start, and the event timers of TPDO1 and TPDO6 off so that they follow changes only. */
static inline void bench_operational(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x1800, 5, 0, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(b, 0x1805, 5, 0, 2), 0);
    bench_rx(b, "000#0104");
}

#endif
