/* SPDX-License-Identifier: Apache-2.0 */
/* drive_init sets every field of the drive_t it is given (issue 22): a caller need not zero its
 * memory. A drive initialised over zeroes and again over a pattern is the same drive, byte for
 * byte, and its channels are those of the dictionary's defaults from the start (a drive booted
 * over a pattern on stored values: tests/drive/models/atv312/test_storage.c). */
#include "check_main.h"
#include "minimal_model.h"

#include <string.h>

/* A byte no field of a zeroed drive holds in every position: every bool, count and pointer
 * differs from it. */
#define PATTERN 0xA5u

static uint8_t od_data[BENCH_OD_DATA_MAX];

static void discard(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

/* Node 4 of the minimal model, on the one data block: the same configuration every time. */
static void init_over(drive_t *drive, uint8_t fill)
{
    memset(drive, fill, sizeof *drive);
    drive_config_t config = {
        .profile = &minimal_profile,
        .od_data = od_data,
        .node_id = BENCH_NODE_ID,
        .send = discard,
    };
    ck_assert_int_eq(drive_init(drive, &config), 0);
}

static size_t first_difference(const void *a, const void *b, size_t size)
{
    const uint8_t *x = a, *y = b;
    size_t i = 0;
    while (i < size && x[i] == y[i])
        i++;
    return i;
}

/* One drive_t, so that the pointers into itself (the node's SDO buffer) are the same both times. */
START_TEST(init_leaves_nothing_of_the_memory_it_is_given)
{
    static drive_t drive, over_zeroes;
    init_over(&drive, 0);
    memcpy(&over_zeroes, &drive, sizeof drive);
    init_over(&drive, PATTERN);
    size_t at = first_difference(&over_zeroes, &drive, sizeof drive);
    ck_assert_msg(at == sizeof drive, "byte %zu of %zu left as it was (drive_t.node is %zu bytes)",
                  at, sizeof drive, sizeof drive.node);
}
END_TEST

/* The minimal model's defaults: the network commands and gives the reference, no ramp switch, no
 * I/O mode, no control word bit assigned. */
START_TEST(init_computes_the_channels_of_the_defaults)
{
    static drive_t drive;
    init_over(&drive, PATTERN);
    ck_assert(drive.command_from_network);
    ck_assert(drive.reference_from_network);
    ck_assert(!drive.second_ramp);
    ck_assert(!drive.io_mode);
    ck_assert_uint_eq(drive.assigned_bits, 0);
    ck_assert_uint_eq(drive.bus_event_count, 0);
    ck_assert_uint_eq(drive.fault_causes, 0);
    ck_assert_uint_eq(drive.faults_active, 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("drive_init");
    TCase *tc = tcase_create("init");
    tcase_add_test(tc, init_leaves_nothing_of_the_memory_it_is_given);
    tcase_add_test(tc, init_computes_the_channels_of_the_defaults);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
