/* SPDX-License-Identifier: Apache-2.0 */
/* What every model reports stays within its objects' limits (issue 22; docs/decisions.md,
 * D-VIEW-LIMITS). For each model of the table (models.c) and the minimal test model, each
 * combination of the ends of the ranges of the parameters the views and the published values
 * are computed from (nominal speed and frequency, nominal current, the ramps, the speed limits),
 * with the motor run towards the highest reference in either direction: every readable numeric
 * object reads within its limits (its LowLimit..HighLimit, else its type's range), and every view
 * takes back the value it reads, leaving the parameters as they were. */
#include "check_main.h"
#include "drive/models/models.h"
#include "minimal_model.h"

/* Time to reach 1638350 rpm (500.0 Hz at 32767 rpm per 10.0 Hz) at the shortest ramp, 0.1 s per
 * 32767 rpm: 5 s. */
#define RUN_US 5000000u

static bench_t b;

/* The parameters varied, one bit of a combination each (the two ramps together: 6048h and 6049h
 * are one computation), the direction of the reference the last bit. */
enum { NOMINAL_SPEED, NOMINAL_FREQUENCY, NOMINAL_CURRENT, RAMPS, HIGH_SPEED, LOW_SPEED, REVERSE };

typedef struct varied {
    drive_param_t param;
    unsigned bit;
} varied_t;

#define VARIED_COUNT 7

/* Parameter i of VARIED_COUNT, in an order the write rules accept: the high speed before the
 * low. */
static varied_t varied_parameter(const drive_profile_t *p, size_t i)
{
    const varied_t all[VARIED_COUNT] = {
        {p->nominal_speed, NOMINAL_SPEED},
        {p->nominal_frequency, NOMINAL_FREQUENCY},
        {p->nominal_current, NOMINAL_CURRENT},
        {p->acceleration, RAMPS},
        {p->deceleration, RAMPS},
        {p->high_speed, HIGH_SPEED},
        {p->low_speed, LOW_SPEED},
    };
    return all[i];
}

/* The model's entry of a parameter the network can write, or NULL. */
static const co_od_entry_t *writable_entry(const drive_profile_t *profile, drive_param_t param)
{
    const co_od_entry_t *e = co_od_find(profile->od, param.index, param.subindex);
    return param.index != 0 && e != NULL && (e->flags & CO_OD_WRITE) ? e : NULL;
}

/* The bits of the parameters the model lets the network write, and the direction's. */
static unsigned varied_bits(const drive_profile_t *profile)
{
    unsigned bits = 1u << REVERSE;
    for (size_t i = 0; i < VARIED_COUNT; i++) {
        varied_t varied = varied_parameter(profile, i);
        if (writable_entry(profile, varied.param) != NULL)
            bits |= 1u << varied.bit;
    }
    return bits;
}

/* The combination `bits`: a parameter at the high end of its range where its bit is set, else
 * at the low end (the low speed's high end is the high speed chosen); the reference the highest
 * forward or, with REVERSE, in reverse. */
static void configure(const drive_profile_t *profile, unsigned bits)
{
    int64_t high_speed = 0;
    for (size_t i = 0; i < VARIED_COUNT; i++) {
        varied_t varied = varied_parameter(profile, i);
        const co_od_entry_t *e = writable_entry(profile, varied.param);
        if (e == NULL)
            continue;
        bool high = (bits >> varied.bit) & 1u;
        int64_t value = co_od_saturate(e, high ? INT64_MAX : INT64_MIN);
        if (varied.bit == HIGH_SPEED)
            high_speed = value;
        if (varied.bit == LOW_SPEED && high)
            value = high_speed;
        ck_assert_msg(
            bench_sdo_write(&b, e->index, e->subindex, (uint32_t)value, (uint8_t)e->size) == 0,
            "%s: %04Xh:%02X = %lld refused", profile->od->name, e->index, e->subindex,
            (long long)value);
    }
    bool reverse = (bits >> REVERSE) & 1u;
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, reverse ? 0x8000u : 0x7FFFu, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x0007);
    bench_command(&b, 0x000F);
    /* One process call at the end (the motor model is exact over any interval), so that the
     * combinations cost no ramp sampling. */
    b.now += RUN_US;
    b.deadline = drive_process(&b.drive, b.now);
}

static bool numeric(const co_od_entry_t *e)
{
    return co_od_type_size(e->type) != 0 && e->type != CO_DT_REAL32 && e->type != CO_DT_REAL64;
}

/* A view: its value is computed when it is read (6046h, 6048h, 6049h), or it mirrors another
 * object (the profile's frequency reference). */
static bool is_view(const drive_profile_t *profile, const co_od_entry_t *e)
{
    return (e->hook != NULL && e->hook->read != NULL) ||
           (e->index == profile->frequency_reference.index &&
            e->subindex == profile->frequency_reference.subindex);
}

static void check_reports(const drive_profile_t *profile, unsigned bits)
{
    co_node_t *node = &b.drive.node;
    const co_od_t *od = profile->od;
    for (const co_od_entry_t *e = od->entries; e < od->entries + od->count; e++) {
        const co_od_entry_t *read;
        if (!(e->flags & CO_OD_READ) || !numeric(e) ||
            co_od_read_check(node, e->index, e->subindex, &read) != 0)
            continue;
        int64_t value = co_od_get(node, e);
        ck_assert_msg(co_od_saturate(e, value) == value,
                      "%s, combination %#x: %04Xh:%02X reads %lld, outside its limits", od->name,
                      bits, e->index, e->subindex, (long long)value);
        if (!is_view(profile, e) || !(e->flags & CO_OD_WRITE))
            continue;
        uint32_t abort =
            bench_sdo_write(&b, e->index, e->subindex, (uint32_t)value, (uint8_t)e->size);
        ck_assert_msg(abort == 0, "%s, combination %#x: %04Xh:%02X refuses %lld back: %08X",
                      od->name, bits, e->index, e->subindex, (long long)value, abort);
    }
}

/* The parameters as configured, after the views took back what they read. */
static void check_parameters_kept(const drive_profile_t *profile, unsigned bits,
                                  const int64_t configured[VARIED_COUNT])
{
    for (size_t i = 0; i < VARIED_COUNT; i++) {
        drive_param_t param = varied_parameter(profile, i).param;
        int64_t value = co_od_value(&b.drive.node, param.index, param.subindex);
        ck_assert_msg(value == configured[i],
                      "%s, combination %#x: %04Xh:%02X %lld, was %lld before the write-backs",
                      profile->od->name, bits, param.index, param.subindex, (long long)value,
                      (long long)configured[i]);
    }
}

static void check_model(const drive_profile_t *profile)
{
    unsigned varies = varied_bits(profile);
    for (unsigned bits = 0; bits <= varies; bits++) {
        if ((bits & ~varies) != 0)
            continue;
        bench_start_model(&b, profile, NULL);
        configure(profile, bits);
        int64_t configured[VARIED_COUNT];
        for (size_t i = 0; i < VARIED_COUNT; i++) {
            drive_param_t param = varied_parameter(profile, i).param;
            configured[i] = co_od_value(&b.drive.node, param.index, param.subindex);
        }
        check_reports(profile, bits);
        check_parameters_kept(profile, bits, configured);
    }
}

START_TEST(every_model_reports_within_its_limits)
{
    check_model(drive_models[_i].profile);
}
END_TEST

START_TEST(minimal_model_reports_within_its_limits)
{
    check_model(&minimal_profile);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("models_views");
    TCase *tc = tcase_create("views");
    tcase_set_timeout(tc, 60);
    tcase_add_loop_test(tc, every_model_reports_within_its_limits, 0, (int)drive_model_count);
    tcase_add_test(tc, minimal_model_reports_within_its_limits);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
