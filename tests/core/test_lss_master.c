/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS master, frame by frame with injected time: every request's exact frames against a
 * scripted slave, its answers, errors and timeouts, frames that are not answers ignored; then the
 * master against the core's own LSS slaves on one in-process bus: every service end to end, and
 * twenty unconfigured slaves with distinct serial numbers found by fastscan one by one, numbered,
 * and booted. */
#include "check_main.h"
#include "co/co_lss_master.h"
#include "test_bus.h"
#include "test_od.h"

#include <stdio.h>
#include <string.h>

#define TIMEOUT 10000u /* 10 ms */
#define SLAVES 20u
#define LOG_MAX 64u /* the last frames of the bus */
#define QUEUE 256u

/* The scripted part: what the master sent, and what it reported. */
static co_frame_t sent[512];
static size_t sent_count, sent_next;
static co_lss_master_result_t done_result;
static unsigned done_calls;
static co_lss_master_t m;

static void record(void *user, const co_frame_t *frame)
{
    (void)user;
    ck_assert_uint_lt(sent_count, sizeof(sent) / sizeof(sent[0]));
    sent[sent_count++] = *frame;
}

static void on_done(void *user, const co_lss_master_result_t *result)
{
    (void)user;
    done_calls++;
    done_result = *result;
}

static void scripted_setup(void)
{
    sent_count = sent_next = 0;
    done_calls = 0;
    memset(&done_result, 0, sizeof(done_result));
    co_lss_master_config_t config = {.send = record, .done = on_done};
    ck_assert_int_eq(co_lss_master_init(&m, &config), 0);
}

#define expect_sent(text) expect_sent_at(text, __LINE__)
static void expect_sent_at(const char *text, int line)
{
    char want[32], got[32];
    co_frame_t f = test_frame(text);
    test_format(&f, want);
    ck_assert_msg(sent_next < sent_count, "line %d: expected %s, nothing sent", line, want);
    test_format(&sent[sent_next], got);
    ck_assert_msg(strcmp(want, got) == 0, "line %d: expected %s, got %s", line, want, got);
    sent_next++;
}

static void expect_nothing_sent(void)
{
    char got[32];
    if (sent_next < sent_count)
        ck_abort_msg("expected nothing sent, got %s", test_format(&sent[sent_next], got));
}

static bool answer(const char *text, co_time_t now)
{
    co_frame_t f = test_frame(text);
    return co_lss_master_receive(&m, &f, now);
}

START_TEST(init_needs_callbacks)
{
    co_lss_master_config_t config = {.send = record};
    ck_assert_int_eq(co_lss_master_init(&m, &config), CO_LSS_MASTER_ERR_CONFIG);
    config.send = NULL;
    config.done = on_done;
    ck_assert_int_eq(co_lss_master_init(&m, &config), CO_LSS_MASTER_ERR_CONFIG);
}
END_TEST

START_TEST(unconfirmed_services)
{
    scripted_setup();
    ck_assert_int_eq(co_lss_master_switch_global(&m, CO_LSS_CONFIGURATION), 0);
    ck_assert_int_eq(co_lss_master_switch_global(&m, CO_LSS_WAITING), 0);
    ck_assert_int_eq(co_lss_master_switch_global(&m, (co_lss_state_t)2), CO_LSS_MASTER_ERR_ARG);
    ck_assert_int_eq(co_lss_master_activate_bit_timing(&m, 1000), 0);
    expect_sent("7E5#0401000000000000");
    expect_sent("7E5#0400000000000000");
    expect_sent("7E5#15E8030000000000");
    expect_nothing_sent();
    ck_assert(!co_lss_master_busy(&m));
    ck_assert_uint_eq(co_lss_master_process(&m, 0), CO_TIME_NEVER);
    ck_assert_uint_eq(done_calls, 0);
}
END_TEST

START_TEST(switch_selective_and_its_timeout)
{
    static const co_lss_address_t address = {{0x5F, 0x312, 0x00010002, 0x12345678}};
    scripted_setup();
    ck_assert_int_eq(co_lss_master_switch_selective(&m, &address, TIMEOUT, 100), 0);
    expect_sent("7E5#405F000000000000");
    expect_sent("7E5#4112030000000000");
    expect_sent("7E5#4202000100000000");
    expect_sent("7E5#4378563412000000");
    ck_assert(co_lss_master_busy(&m));
    ck_assert_int_eq(co_lss_master_switch_selective(&m, &address, TIMEOUT, 100),
                     CO_LSS_MASTER_ERR_BUSY);
    expect_nothing_sent();
    ck_assert_uint_eq(co_lss_master_process(&m, 100), 100 + TIMEOUT);
    ck_assert(answer("7E4#4400000000000000", 200));
    ck_assert_uint_eq(done_calls, 1);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    ck_assert_uint_eq(done_result.service, CO_LSS_CS_SWITCH_SELECTIVE_SERIAL);
    ck_assert(!co_lss_master_busy(&m));
    /* No answer: the timeout, to the microsecond. */
    ck_assert_int_eq(co_lss_master_switch_selective(&m, &address, TIMEOUT, 1000), 0);
    ck_assert_uint_eq(co_lss_master_process(&m, 1000 + TIMEOUT - 1), 1000 + TIMEOUT);
    ck_assert_uint_eq(done_calls, 1);
    ck_assert_uint_eq(co_lss_master_process(&m, 1000 + TIMEOUT), CO_TIME_NEVER);
    ck_assert_uint_eq(done_calls, 2);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
}
END_TEST

START_TEST(configure_and_store_with_error_codes)
{
    scripted_setup();
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 0, TIMEOUT, 0), CO_LSS_MASTER_ERR_ARG);
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 128, TIMEOUT, 0), CO_LSS_MASTER_ERR_ARG);
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 5, 0, 0), CO_LSS_MASTER_ERR_ARG);
    expect_nothing_sent();
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 5, TIMEOUT, 0), 0);
    expect_sent("7E5#1105000000000000");
    ck_assert(answer("7E4#1101000000000000", 1));
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    ck_assert_uint_eq(done_result.error, CO_LSS_NODE_ID_OUT_OF_RANGE);
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 0xFF, TIMEOUT, 0), 0);
    expect_sent("7E5#11FF000000000000");
    ck_assert(answer("7E4#1100000000000000", 1));
    ck_assert_uint_eq(done_result.error, CO_LSS_OK);
    ck_assert_int_eq(co_lss_master_configure_bit_timing(&m, 0, 4, TIMEOUT, 0), 0);
    expect_sent("7E5#1300040000000000");
    ck_assert(answer("7E4#1301000000000000", 1));
    ck_assert_uint_eq(done_result.service, CO_LSS_CS_CONFIGURE_BIT_TIMING);
    ck_assert_uint_eq(done_result.error, CO_LSS_BIT_TIMING_NOT_SUPPORTED);
    ck_assert_int_eq(co_lss_master_store(&m, TIMEOUT, 0), 0);
    expect_sent("7E5#1700000000000000");
    ck_assert(answer("7E4#17FF420000000000", 1));
    ck_assert_uint_eq(done_result.service, CO_LSS_CS_STORE);
    ck_assert_uint_eq(done_result.error, CO_LSS_SPECIFIC_ERROR);
    ck_assert_uint_eq(done_result.specific, 0x42);
    ck_assert_uint_eq(done_calls, 4);
}
END_TEST

START_TEST(inquire_each_value)
{
    static const struct {
        uint8_t cs;
        const char *request, *reply;
        uint32_t value;
    } cases[] = {
        {0x5A, "7E5#5A00000000000000", "7E4#5A5F000000000000", 0x5F},
        {0x5B, "7E5#5B00000000000000", "7E4#5B12030000000000", 0x312},
        {0x5C, "7E5#5C00000000000000", "7E4#5C02000100000000", 0x00010002},
        {0x5D, "7E5#5D00000000000000", "7E4#5D78563412000000", 0x12345678},
        {0x5E, "7E5#5E00000000000000", "7E4#5EFFAABBCC000000", 0xFF},
    };
    scripted_setup();
    ck_assert_int_eq(co_lss_master_inquire(&m, 0x59, TIMEOUT, 0), CO_LSS_MASTER_ERR_ARG);
    ck_assert_int_eq(co_lss_master_inquire(&m, 0x5F, TIMEOUT, 0), CO_LSS_MASTER_ERR_ARG);
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        ck_assert_int_eq(co_lss_master_inquire(&m, cases[i].cs, TIMEOUT, 0), 0);
        expect_sent(cases[i].request);
        /* Another service's answer is not this one's. */
        ck_assert(answer(i == 0 ? "7E4#5B12030000000000" : "7E4#5A5F000000000000", 1));
        ck_assert_uint_eq(done_calls, i);
        ck_assert(answer(cases[i].reply, 1));
        ck_assert_uint_eq(done_calls, i + 1);
        ck_assert_uint_eq(done_result.service, cases[i].cs);
        ck_assert_uint_eq(done_result.value, cases[i].value);
    }
}
END_TEST

START_TEST(identify_counts_answers_until_the_timeout)
{
    static const co_lss_address_t low = {{0x5F, 0x312, 0x00010000, 0x1000}};
    static const co_lss_address_t high = {{0, 0, 0x0001FFFF, 0x1FFF}};
    scripted_setup();
    ck_assert_int_eq(co_lss_master_identify_remote(&m, &low, &high, TIMEOUT, 0), 0);
    expect_sent("7E5#465F000000000000");
    expect_sent("7E5#4712030000000000");
    expect_sent("7E5#4800000100000000");
    expect_sent("7E5#49FFFF0100000000");
    expect_sent("7E5#4A00100000000000");
    expect_sent("7E5#4BFF1F0000000000");
    ck_assert(answer("7E4#4F00000000000000", 10));
    ck_assert(answer("7E4#4F00000000000000", 20));
    ck_assert(answer("7E4#5000000000000000", 20)); /* not this service's answer */
    ck_assert_uint_eq(done_calls, 0);
    co_lss_master_process(&m, TIMEOUT);
    ck_assert_uint_eq(done_calls, 1);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    ck_assert_uint_eq(done_result.answers, 2);
    ck_assert_int_eq(co_lss_master_identify_non_configured(&m, TIMEOUT, 0), 0);
    expect_sent("7E5#4C00000000000000");
    co_lss_master_process(&m, TIMEOUT);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
    ck_assert_uint_eq(done_result.answers, 0);
    ck_assert_int_eq(co_lss_master_identify_non_configured(&m, TIMEOUT, 0), 0);
    expect_sent("7E5#4C00000000000000");
    ck_assert(answer("7E4#5000000000000000", 1));
    co_lss_master_process(&m, TIMEOUT);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    ck_assert_uint_eq(done_result.answers, 1);
}
END_TEST

START_TEST(frames_that_are_not_answers)
{
    scripted_setup();
    ck_assert(!answer("7E5#1100000000000000", 0)); /* the master's own COB-ID */
    ck_assert(!answer("705#00", 0));
    ck_assert(answer("7E4#1100000000000000", 0)); /* idle: nothing awaited */
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 5, TIMEOUT, 0), 0);
    expect_sent("7E5#1105000000000000");
    ck_assert(answer("7E4#11000000000000", 1)); /* DLC 7 */
    ck_assert(answer("7E4#R8", 1));
    co_frame_t eff = test_frame("7E4#1100000000000000");
    eff.flags = CO_FRAME_EFF;
    ck_assert(!co_lss_master_receive(&m, &eff, 1));
    ck_assert(answer("7E4#1300000000000000", 1));
    ck_assert_uint_eq(done_calls, 0);
    ck_assert(co_lss_master_busy(&m));
    ck_assert(answer("7E4#1100000000000000", 1));
    ck_assert_uint_eq(done_calls, 1);
    ck_assert_uint_eq(done_result.error, 0);
}
END_TEST

/* Answers the master's inquiry `f` (5Ah..5Dh) with that part of `address`. */
static void answer_inquiry(const co_frame_t *f, const co_lss_address_t *address, co_time_t now)
{
    ck_assert_uint_eq(f->id, 0x7E5);
    ck_assert_uint_eq(f->len, 8);
    ck_assert_uint_ge(f->data[0], CO_LSS_CS_INQUIRE_VENDOR);
    ck_assert_uint_le(f->data[0], CO_LSS_CS_INQUIRE_SERIAL);
    uint8_t data[4];
    co_put_u32(data, address->part[f->data[0] - CO_LSS_CS_INQUIRE_VENDOR]);
    co_frame_t a;
    co_lss_frame(&a, CO_LSS_ID_SLAVE, f->data[0], data, sizeof(data));
    ck_assert(co_lss_master_receive(&m, &a, now));
}

/* A scripted fastscan: the master's frames against one slave's rules, answered by the test. */
START_TEST(fastscan_frames_exact)
{
    static const co_lss_address_t address = {{0x5F, 0x312, 0x00010002, 0x12345679}};
    scripted_setup();
    ck_assert_int_eq(co_lss_master_fastscan(&m, NULL, TIMEOUT, TIMEOUT, 0), 0);
    expect_sent("7E5#5100000000800000");
    co_time_t now = 0;
    /* Nobody there: one frame and its timeout. */
    co_lss_master_process(&m, now + TIMEOUT);
    ck_assert_uint_eq(done_calls, 1);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
    ck_assert_uint_eq(done_result.answers, 0);
    expect_nothing_sent();

    ck_assert_int_eq(co_lss_master_fastscan(&m, NULL, TIMEOUT, TIMEOUT, now), 0);
    expect_sent("7E5#5100000000800000");
    ck_assert(answer("7E4#4F00000000000000", now));
    size_t frames = 1;
    while (done_calls == 1) {
        now += TIMEOUT;
        co_lss_master_process(&m, now);
        if (sent_next == sent_count)
            break;
        const co_frame_t *f = &sent[sent_next++];
        frames++;
        while (f->data[0] != CO_LSS_CS_FASTSCAN && done_calls == 1) {
            answer_inquiry(f, &address, now);
            if (sent_next < sent_count) {
                f = &sent[sent_next++];
                frames++;
            }
        }
        if (done_calls != 1)
            break;
        ck_assert_uint_eq(f->id, 0x7E5);
        ck_assert_uint_eq(f->len, 8);
        uint32_t id = co_get_u32(&f->data[1]);
        uint8_t bit = f->data[5], sub = f->data[6], next = f->data[7];
        ck_assert_uint_le(bit, 31);
        ck_assert_uint_eq(next, bit == 0 ? (sub + 1) % 4 : sub);
        uint32_t mask = UINT32_MAX << bit;
        if (((id ^ address.part[sub]) & mask) == 0)
            ck_assert(answer("7E4#4F00000000000000", now));
    }
    ck_assert_uint_eq(done_calls, 2);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    for (int i = 0; i < 4; i++)
        ck_assert_uint_eq(done_result.address.part[i], address.part[i]);
    /* The reset, 32 bit checks a part, a confirmation for each part whose bit 0 is 1 (the
     * revision's and the serial's), and the four inquiries of the address found. */
    ck_assert_uint_eq(frames, 1 + 4 * 32 + 2 + 4);

    /* Known vendor-ID, product code and revision: one frame each. */
    static const co_lss_fastscan_known_t known = {0x07, 0, {{0x5F, 0x312, 0x00010002, 0}}};
    ck_assert_int_eq(co_lss_master_fastscan(&m, &known, TIMEOUT, TIMEOUT, now), 0);
    expect_sent("7E5#5100000000800000");
    ck_assert(answer("7E4#4F00000000000000", now));
    co_lss_master_process(&m, now += TIMEOUT);
    expect_sent("7E5#515F000000000001");
    ck_assert(answer("7E4#4F00000000000000", now));
    co_lss_master_process(&m, now += TIMEOUT);
    expect_sent("7E5#5112030000000102");
    /* The product code unanswered: the slave that answered the reset was lost (answers 1). */
    co_lss_master_process(&m, now += TIMEOUT);
    ck_assert_uint_eq(done_calls, 3);
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
    ck_assert_uint_eq(done_result.answers, 1);
    expect_nothing_sent();
}
END_TEST

/* The address found is the one the slave in configuration state gives, part by part; another
 * one, or no answer, and the scan lost its slave. */
START_TEST(fastscan_checks_the_address_found)
{
    static const co_lss_fastscan_known_t known = {0x0F, 0, {{0x5F, 0x312, 0x00010002, 0x12345679}}};
    for (int run = 0; run < 3; run++) {
        scripted_setup();
        co_time_t now = 0;
        ck_assert_int_eq(co_lss_master_fastscan(&m, &known, TIMEOUT, TIMEOUT, now), 0);
        expect_sent("7E5#5100000000800000");
        static const char *const confirmations[] = {"7E5#515F000000000001", "7E5#5112030000000102",
                                                    "7E5#5102000100000203", "7E5#5179563412000300"};
        for (int i = 0; i < 5; i++) {
            ck_assert(answer("7E4#4F00000000000000", now));
            co_lss_master_process(&m, now += TIMEOUT);
            if (i < 4)
                expect_sent(confirmations[i]);
        }
        expect_sent("7E5#5A00000000000000");
        /* A late answer of fastscan is not the inquiry's. */
        ck_assert(answer("7E4#4F00000000000000", now));
        if (run == 0) {
            co_lss_master_process(&m, now + TIMEOUT - 1);
            ck_assert_uint_eq(done_calls, 0);
            co_lss_master_process(&m, now + TIMEOUT);
            ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
            ck_assert_uint_eq(done_result.answers, 1);
            expect_nothing_sent();
            continue;
        }
        ck_assert(answer("7E4#5A5F000000000000", now));
        expect_sent("7E5#5B00000000000000");
        ck_assert(answer("7E4#5B12030000000000", now));
        expect_sent("7E5#5C00000000000000");
        ck_assert(answer("7E4#5C02000100000000", now));
        expect_sent("7E5#5D00000000000000");
        ck_assert_uint_eq(done_calls, 0);
        ck_assert(answer(run == 1 ? "7E4#5D78563412000000" : "7E4#5D79563412000000", now));
        ck_assert_uint_eq(done_calls, 1);
        ck_assert_uint_eq(done_result.status, run == 1 ? CO_LSS_MASTER_TIMEOUT : CO_LSS_MASTER_OK);
        ck_assert_uint_eq(done_result.answers, 1);
        ck_assert_uint_eq(done_result.address.part[CO_LSS_SERIAL], 0x12345679);
        ck_assert(!co_lss_master_busy(&m));
        expect_nothing_sent();
    }
}
END_TEST

#define MIN_WAIT 1000u /* 1 ms: the shortest wait of a frame after the reset */

/* The reset waits the whole timeout; every later frame twice the slowest answer so far, at least
 * MIN_WAIT and at most the timeout, an answer later than half the wait stretching its own frame. */
START_TEST(fastscan_waits_twice_the_slowest_answer)
{
    static const co_lss_fastscan_known_t known = {0x07, 0, {{0x5F, 0x312, 0x00010002, 0}}};
    scripted_setup();
    ck_assert_int_eq(co_lss_master_fastscan(&m, &known, TIMEOUT, 0, 0), CO_LSS_MASTER_ERR_ARG);
    ck_assert_int_eq(co_lss_master_fastscan(&m, &known, TIMEOUT, TIMEOUT + 1, 0),
                     CO_LSS_MASTER_ERR_ARG);
    expect_nothing_sent();
    co_time_t now = 100000;
    ck_assert_int_eq(co_lss_master_fastscan(&m, &known, TIMEOUT, MIN_WAIT, now), 0);
    expect_sent("7E5#5100000000800000");
    ck_assert(answer("7E4#4F00000000000000", now + 200));
    ck_assert(answer("7E4#4F00000000000000", now + 300));
    ck_assert_uint_eq(co_lss_master_process(&m, now + TIMEOUT - 1), now + TIMEOUT);
    expect_nothing_sent();
    /* 2 x 300 us is below the floor: the vendor-ID's confirmation waits MIN_WAIT. */
    now += TIMEOUT;
    ck_assert_uint_eq(co_lss_master_process(&m, now), now + MIN_WAIT);
    expect_sent("7E5#515F000000000001");
    ck_assert(answer("7E4#4F00000000000000", now + 100));
    ck_assert_uint_eq(co_lss_master_process(&m, now + MIN_WAIT - 1), now + MIN_WAIT);
    expect_nothing_sent();
    now += MIN_WAIT;
    ck_assert_uint_eq(co_lss_master_process(&m, now), now + MIN_WAIT);
    expect_sent("7E5#5112030000000102");
    /* An answer after 700 us stretches this frame's wait to 1.4 ms, and the next frame's. */
    ck_assert(answer("7E4#4F00000000000000", now + 700));
    ck_assert_uint_eq(co_lss_master_process(&m, now + MIN_WAIT), now + 1400);
    expect_nothing_sent();
    now += 1400;
    ck_assert_uint_eq(co_lss_master_process(&m, now), now + 1400);
    expect_sent("7E5#5102000100000203");
    /* 2 x 6 ms is beyond the timeout: it caps the wait. */
    ck_assert(answer("7E4#4F00000000000000", now + 6000));
    ck_assert_uint_eq(co_lss_master_process(&m, now + 6000), now + TIMEOUT);
    now += TIMEOUT;
    ck_assert_uint_eq(co_lss_master_process(&m, now), now + TIMEOUT);
    expect_sent("7E5#51000000001F0303");
    /* No answer: bit 31 is 1, after the whole (capped) wait. */
    now += TIMEOUT;
    ck_assert_uint_eq(co_lss_master_process(&m, now), now + TIMEOUT);
    expect_sent("7E5#51000000801E0303");
    expect_nothing_sent();
    ck_assert_uint_eq(done_calls, 0);
}
END_TEST

/* A guessed part answered is confirmed in one frame; unanswered, it is scanned bit by bit. */
START_TEST(fastscan_tries_a_guessed_part_then_scans_it)
{
    static const co_lss_fastscan_known_t guess = {0, 0x07, {{0x5F, 0x999, 0x00010002, 0}}};
    static const co_lss_address_t address = {{0x5F, 0x312, 0x00010002, 0x12345678}};
    scripted_setup();
    co_time_t now = 0;
    ck_assert_int_eq(co_lss_master_fastscan(&m, &guess, TIMEOUT, TIMEOUT, now), 0);
    expect_sent("7E5#5100000000800000");
    ck_assert(answer("7E4#4F00000000000000", now));
    co_lss_master_process(&m, now += TIMEOUT);
    expect_sent("7E5#515F000000000001");
    ck_assert(answer("7E4#4F00000000000000", now));
    co_lss_master_process(&m, now += TIMEOUT);
    /* Nobody has product 999h: the slaves stay on the product code, scanned from bit 31. */
    expect_sent("7E5#5199090000000102");
    co_lss_master_process(&m, now += TIMEOUT);
    expect_sent("7E5#51000000001F0101");
    size_t frames = 4;
    while (done_calls == 0) {
        const co_frame_t *f = &sent[sent_next - 1];
        if (f->data[0] != CO_LSS_CS_FASTSCAN) {
            answer_inquiry(f, &address, now);
            if (sent_next < sent_count) {
                sent_next++;
                frames++;
            }
            continue;
        }
        uint32_t mask = UINT32_MAX << f->data[5];
        if (((co_get_u32(&f->data[1]) ^ address.part[f->data[6]]) & mask) == 0)
            ck_assert(answer("7E4#4F00000000000000", now));
        co_lss_master_process(&m, now += TIMEOUT);
        if (sent_next < sent_count) {
            sent_next++;
            frames++;
        }
    }
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    for (int i = 0; i < 4; i++)
        ck_assert_uint_eq(done_result.address.part[i], address.part[i]);
    /* The reset, the vendor-ID, the guess of the product, its 32 bit checks, the revision, the
     * serial's 32 bit checks, and the four inquiries. */
    ck_assert_uint_eq(frames, 1 + 1 + 1 + 32 + 1 + 32 + 4);
}
END_TEST

/* The in-process bus: the master and the core's LSS slaves, each frame delivered in order to
 * every party but its sender. */
typedef struct slave {
    co_node_t node;
    co_lss_slave_t lss;
    co_od_t od;
    uint8_t data[2048];
    uint8_t defaults[2048];
    uint8_t stored_id;
    co_time_t deadline;
} slave_t;

static slave_t slaves[SLAVES];
static size_t slave_count;
static struct {
    co_frame_t frame;
    int from; /* -1: the master */
} queue[QUEUE];
static size_t queue_head, queue_tail;
static co_frame_t bus_log[LOG_MAX];
static size_t log_count, master_frames;
static co_time_t bus_now;

static void enqueue(int from, const co_frame_t *frame)
{
    ck_assert_uint_lt(queue_tail - queue_head, QUEUE);
    queue[queue_tail % QUEUE].frame = *frame;
    queue[queue_tail % QUEUE].from = from;
    queue_tail++;
    bus_log[log_count++ % LOG_MAX] = *frame;
    master_frames += from < 0;
}

static void master_send(void *user, const co_frame_t *frame)
{
    (void)user;
    enqueue(-1, frame);
}

static void slave_send(void *user, const co_frame_t *frame)
{
    enqueue((int)((slave_t *)user - slaves), frame);
}

static uint8_t slave_store(co_node_t *node, uint8_t node_id, uint8_t bit_timing, uint8_t *specific)
{
    (void)bit_timing;
    (void)specific;
    ((slave_t *)node->user)->stored_id = node_id;
    return CO_LSS_OK;
}

static const co_lss_slave_hooks_t slave_hooks = {.store = slave_store};

static void pump(void)
{
    while (queue_head != queue_tail) {
        co_frame_t frame = queue[queue_head % QUEUE].frame;
        int from = queue[queue_head % QUEUE].from;
        queue_head++;
        if (from >= 0)
            co_lss_master_receive(&m, &frame, bus_now);
        for (size_t i = 0; i < slave_count; i++) {
            if ((int)i == from)
                continue;
            co_node_receive(&slaves[i].node, &frame, bus_now);
            slaves[i].deadline = co_node_process(&slaves[i].node, bus_now);
        }
    }
}

/* Runs the bus until the master is idle; returns the time it took. */
static co_time_t run_until_idle(void)
{
    co_time_t start = bus_now;
    pump();
    while (co_lss_master_busy(&m)) {
        co_time_t next = co_lss_master_process(&m, bus_now);
        for (size_t i = 0; i < slave_count; i++)
            next = co_time_min(next, slaves[i].deadline);
        ck_assert_uint_ne(next, CO_TIME_NEVER);
        if (next > bus_now)
            bus_now = next;
        co_lss_master_process(&m, bus_now);
        for (size_t i = 0; i < slave_count; i++)
            slaves[i].deadline = co_node_process(&slaves[i].node, bus_now);
        pump();
    }
    return bus_now - start;
}

/* Slaves on the test dictionary, each its own copy of the defaults with serial `serial + i`. */
static void bus_setup(size_t count, uint8_t node_id, uint32_t serial)
{
    memset(slaves, 0, sizeof(slaves));
    slave_count = count;
    queue_head = queue_tail = log_count = master_frames = 0;
    bus_now = 0;
    scripted_setup();
    co_lss_master_config_t config = {.send = master_send, .done = on_done};
    ck_assert_int_eq(co_lss_master_init(&m, &config), 0);
    const co_od_entry_t *serial_entry = co_od_find(&test_od, CO_IDX_IDENTITY, CO_IDENTITY_SERIAL);
    ck_assert_ptr_nonnull(serial_entry);
    ck_assert_uint_le(test_od.data_size, sizeof(slaves[0].defaults));
    for (size_t i = 0; i < count; i++) {
        slave_t *s = &slaves[i];
        memcpy(s->defaults, test_od.defaults, test_od.data_size);
        co_put_u32(&s->defaults[serial_entry->offset], serial + (uint32_t)i * 0x01010101u);
        s->od = test_od;
        s->od.defaults = s->defaults;
        co_lss_slave_init(&s->lss, &slave_hooks, 3);
        co_node_config_t nc = {.node_id = node_id,
                               .od = &s->od,
                               .od_data = s->data,
                               .send = slave_send,
                               .user = s,
                               .lss = &s->lss};
        ck_assert_int_eq(co_node_init(&s->node, &nc), 0);
        co_node_start(&s->node, 0);
        s->deadline = co_node_process(&s->node, 0);
    }
    pump();
}

START_TEST(every_service_against_the_core_slave)
{
    bus_setup(1, CO_LSS_NODE_ID_UNCONFIGURED, 0x12345678);
    ck_assert_uint_eq(log_count, 0); /* no boot-up */
    ck_assert_int_eq(co_lss_master_identify_non_configured(&m, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.answers, 1);
    static const co_lss_address_t address = {{0x5F, 0x312, 0x00010002, 0x12345678}};
    ck_assert_int_eq(co_lss_master_switch_selective(&m, &address, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
    for (uint8_t cs = CO_LSS_CS_INQUIRE_VENDOR; cs <= CO_LSS_CS_INQUIRE_NODE_ID; cs++) {
        ck_assert_int_eq(co_lss_master_inquire(&m, cs, TIMEOUT, bus_now), 0);
        run_until_idle();
        ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
        ck_assert_uint_eq(done_result.value, cs == CO_LSS_CS_INQUIRE_NODE_ID
                                                 ? 0xFF
                                                 : address.part[cs - CO_LSS_CS_INQUIRE_VENDOR]);
    }
    ck_assert_int_eq(co_lss_master_configure_bit_timing(&m, 0, 2, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.error, CO_LSS_BIT_TIMING_NOT_SUPPORTED);
    ck_assert_int_eq(co_lss_master_configure_node_id(&m, 42, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.error, CO_LSS_OK);
    ck_assert_int_eq(co_lss_master_store(&m, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.error, CO_LSS_OK);
    ck_assert_uint_eq(slaves[0].stored_id, 42);
    size_t before = log_count;
    ck_assert_int_eq(co_lss_master_switch_global(&m, CO_LSS_WAITING), 0);
    pump();
    ck_assert_uint_eq(log_count, before + 2);
    ck_assert_uint_eq(bus_log[(before + 1) % LOG_MAX].id, 0x700 + 42); /* its boot-up */
    ck_assert_uint_eq(slaves[0].node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    static const co_lss_address_t high = {{0, 0, 0x00010002, 0x12345678}};
    ck_assert_int_eq(co_lss_master_identify_remote(&m, &address, &high, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.answers, 1);
    ck_assert_int_eq(co_lss_master_identify_non_configured(&m, TIMEOUT, bus_now), 0);
    run_until_idle();
    ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT);
}
END_TEST

static co_time_t scan_time; /* fastscan_all's scans, on the bus's clock */

/* Finds, numbers 1..20 and boots the twenty slaves, each frame after a reset waiting at least
 * min_wait, the parts of the slave found guessed for the next scan when `guess`; returns the
 * master's frames. */
static size_t fastscan_all(const co_lss_fastscan_known_t *known, co_time_t min_wait, bool guess)
{
    bus_setup(SLAVES, CO_LSS_NODE_ID_UNCONFIGURED, 0x10203040);
    bool found[SLAVES] = {false};
    co_lss_fastscan_known_t parts = {0};
    if (known != NULL)
        parts = *known;
    size_t scan_frames = 0;
    scan_time = 0;
    for (uint8_t n = 1; n <= SLAVES + 1; n++) {
        size_t before = master_frames;
        ck_assert_int_eq(co_lss_master_fastscan(&m, &parts, TIMEOUT, min_wait, bus_now), 0);
        scan_time += run_until_idle();
        scan_frames += master_frames - before;
        if (n == SLAVES + 1) {
            ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_TIMEOUT); /* none left */
            break;
        }
        ck_assert_uint_eq(done_result.status, CO_LSS_MASTER_OK);
        uint32_t serial = done_result.address.part[CO_LSS_SERIAL];
        size_t which = (serial - 0x10203040u) / 0x01010101u;
        ck_assert_uint_lt(which, SLAVES);
        ck_assert(!found[which]);
        found[which] = true;
        ck_assert_uint_eq(done_result.address.part[CO_LSS_VENDOR], 0x5F);
        ck_assert_uint_eq(done_result.address.part[CO_LSS_PRODUCT], 0x312);
        ck_assert_uint_eq(done_result.address.part[CO_LSS_REVISION], 0x00010002);
        ck_assert_uint_eq(slaves[which].lss.state, CO_LSS_CONFIGURATION);
        if (guess) {
            parts.guessed = (uint8_t)(0x07 & ~parts.known);
            parts.address = done_result.address;
        }
        ck_assert_int_eq(co_lss_master_configure_node_id(&m, n, TIMEOUT, bus_now), 0);
        run_until_idle();
        ck_assert_uint_eq(done_result.error, CO_LSS_OK);
        ck_assert_int_eq(co_lss_master_switch_global(&m, CO_LSS_WAITING), 0);
        pump();
        ck_assert_uint_eq(slaves[which].node.node_id, n);
        ck_assert_uint_eq(bus_log[(log_count - 1) % LOG_MAX].id, 0x700u + n);
    }
    for (size_t i = 0; i < SLAVES; i++) {
        ck_assert(found[i]);
        ck_assert_uint_eq(slaves[i].node.nmt_state, CO_NMT_PRE_OPERATIONAL);
    }
    printf("fastscan of %u slaves%s%s: %zu master frames, %.2f s of bus time, %u ms a reset, "
           "%u us a frame at least\n",
           SLAVES, known != NULL ? " (vendor, product, revision known)" : "",
           guess ? " (the last one's parts guessed)" : "", scan_frames, (double)scan_time / 1e6,
           TIMEOUT / 1000, (unsigned)min_wait);
    return scan_frames;
}

/* Each scan: the reset, 32 bit checks for each part, a confirmation for each part whose bit 0
 * is 1 (the vendor-ID 5Fh's, the odd serials': 10 of 20), the four inquiries of the address
 * found; and the last scan's reset that nobody answers. */
START_TEST(fastscan_twenty_slaves)
{
    size_t frames = fastscan_all(NULL, TIMEOUT, false);
    ck_assert_uint_eq(frames, 20 * (1 + 4 * 32 + 1 + 4) + 10 + 1);
    /* The inquiries are answered at once, every other frame waits the whole timeout. */
    ck_assert_uint_eq(scan_time, (frames - 20 * 4) * TIMEOUT);
}
END_TEST

/* Vendor, product and revision known: one frame each instead of 32. */
START_TEST(fastscan_twenty_slaves_of_a_known_product)
{
    static const co_lss_fastscan_known_t known = {0x07, 0, {{0x5F, 0x312, 0x00010002, 0}}};
    ck_assert_uint_eq(fastscan_all(&known, TIMEOUT, false), 20 * (1 + 3 + 32 + 4) + 10 + 1);
}
END_TEST

/* Nothing known: the first slave's vendor-ID, product code and revision, guessed for the next
 * ones, take one frame each from the second scan on; the slaves answer at once, so every frame
 * after a reset waits MIN_WAIT (the inquiries none): 21 resets of 10 ms and 804 frames of 1 ms,
 * 1.01 s of bus time instead of the 26.11 s of the fixed wait. */
START_TEST(fastscan_twenty_slaves_guessing_and_waiting_the_least)
{
    size_t frames = fastscan_all(NULL, MIN_WAIT, true);
    /* The first scan as without guesses (the vendor-ID's bit 0 is 1, its serial's 0), then 19 of
     * a reset, three confirmations, 32 bit checks and four inquiries, 10 odd serials confirmed,
     * the last reset. */
    ck_assert_uint_eq(frames, (1 + 4 * 32 + 1 + 4) + 19 * (1 + 3 + 32 + 4) + 10 + 1);
    ck_assert_uint_eq(scan_time, 21 * TIMEOUT + (frames - 21 - 20 * 4) * MIN_WAIT);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("lss_master");
    TCase *tc = tcase_create("lss_master");
    tcase_add_test(tc, init_needs_callbacks);
    tcase_add_test(tc, unconfirmed_services);
    tcase_add_test(tc, switch_selective_and_its_timeout);
    tcase_add_test(tc, configure_and_store_with_error_codes);
    tcase_add_test(tc, inquire_each_value);
    tcase_add_test(tc, identify_counts_answers_until_the_timeout);
    tcase_add_test(tc, frames_that_are_not_answers);
    tcase_add_test(tc, fastscan_frames_exact);
    tcase_add_test(tc, fastscan_checks_the_address_found);
    tcase_add_test(tc, fastscan_waits_twice_the_slowest_answer);
    tcase_add_test(tc, fastscan_tries_a_guessed_part_then_scans_it);
    tcase_add_test(tc, every_service_against_the_core_slave);
    tcase_add_test(tc, fastscan_twenty_slaves);
    tcase_add_test(tc, fastscan_twenty_slaves_of_a_known_product);
    tcase_add_test(tc, fastscan_twenty_slaves_guessing_and_waiting_the_least);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
