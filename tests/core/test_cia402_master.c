/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 402 master helper: every state from exact status words (the significant bits each
 * change it, the others never do), every (state, target) pair's command, the exact control words
 * of each path fed with the ATV312's status words, the deadline, and a fault on the way. */
#include "check_main.h"
#include "co/co_cia402_master.h"

#define MS 1000u /* co_time_t is in microseconds */
#define TIMEOUT (100u * MS)

/* Each state's word as the ATV312 sends it (remote, bit 9, set; the CANopen manual's "ETA status
 * word") and the bits of the state coding that decide it. */
static const struct {
    uint16_t word;
    uint16_t significant;
    co_cia402_state_t state;
    const char *name;
} states[] = {
    {0x0200, 0x004F, CO_CIA402_NOT_READY_TO_SWITCH_ON, "Not ready to switch on"},
    {0x0640, 0x004F, CO_CIA402_SWITCH_ON_DISABLED, "Switch on disabled"},
    {0x0621, 0x006F, CO_CIA402_READY_TO_SWITCH_ON, "Ready to switch on"},
    {0x0623, 0x006F, CO_CIA402_SWITCHED_ON, "Switched on"},
    {0x0227, 0x006F, CO_CIA402_OPERATION_ENABLED, "Operation enabled"},
    {0x0607, 0x006F, CO_CIA402_QUICK_STOP_ACTIVE, "Quick stop active"},
    {0x060F, 0x004F, CO_CIA402_FAULT_REACTION_ACTIVE, "Fault reaction active"},
    {0x0608, 0x004F, CO_CIA402_FAULT, "Fault"},
};

START_TEST(every_state_from_its_bits)
{
    for (size_t i = 0; i < sizeof states / sizeof states[0]; i++) {
        ck_assert_int_eq(co_cia402_state(states[i].word), states[i].state);
        ck_assert_str_eq(co_cia402_state_name(states[i].state), states[i].name);
        /* Every don't-care bit at once, either way. */
        ck_assert_int_eq(co_cia402_state((uint16_t)(states[i].word | ~states[i].significant)),
                         states[i].state);
        ck_assert_int_eq(co_cia402_state((uint16_t)(states[i].word & states[i].significant)),
                         states[i].state);
        for (unsigned bit = 0; bit < 16; bit++) {
            uint16_t flipped = (uint16_t)(states[i].word ^ (1u << bit));
            bool counts = states[i].significant >> bit & 1u;
            ck_assert_msg((co_cia402_state(flipped) == states[i].state) == !counts,
                          "0x%04X (bit %u of %s) decodes as %d", flipped, bit, states[i].name,
                          co_cia402_state(flipped));
        }
    }
    /* The manual's second values where bit 5 is not significant. */
    ck_assert_int_eq(co_cia402_state(0x0020), CO_CIA402_NOT_READY_TO_SWITCH_ON);
    ck_assert_int_eq(co_cia402_state(0x0060), CO_CIA402_SWITCH_ON_DISABLED);
    ck_assert_int_eq(co_cia402_state(0x0028), CO_CIA402_FAULT);
    ck_assert_int_eq(co_cia402_state(0x002F), CO_CIA402_FAULT_REACTION_ACTIVE);
    /* No row: Ready or Switched on without bit 5, switch on disabled with another state bit. */
    static const uint16_t none[] = {0x0001, 0x0003, 0x0041, 0x0047, 0x0048, 0x004F, 0x0002,
                                    0x0004, 0x0005, 0x0009, 0x0025, 0x0066, 0xFFFF};
    for (size_t i = 0; i < sizeof none / sizeof none[0]; i++)
        ck_assert_msg(co_cia402_state(none[i]) == CO_CIA402_NO_STATE, "0x%04X", none[i]);
    ck_assert_ptr_null(co_cia402_state_name(CO_CIA402_NO_STATE));
    ck_assert(co_cia402_faulted(CO_CIA402_FAULT));
    ck_assert(co_cia402_faulted(CO_CIA402_FAULT_REACTION_ACTIVE));
    ck_assert(!co_cia402_faulted(CO_CIA402_QUICK_STOP_ACTIVE));
}
END_TEST

/* What co_cia402_next gives for each (state, target): -1 when nothing. */
#define NONE                                                                                       \
    {                                                                                              \
        -1, CO_CIA402_NO_STATE                                                                     \
    }
#define DO(word, state)                                                                            \
    {                                                                                              \
        word, CO_CIA402_##state                                                                    \
    }

START_TEST(every_state_and_target)
{
    static const co_cia402_target_t targets[] = {
        CO_CIA402_TO_OPERATION_ENABLED,  CO_CIA402_TO_SWITCHED_ON, CO_CIA402_TO_READY_TO_SWITCH_ON,
        CO_CIA402_TO_SWITCH_ON_DISABLED, CO_CIA402_TO_QUICK_STOP,  CO_CIA402_TO_FAULT_RESET};
    static const struct {
        int word;
        co_cia402_state_t next;
    } expected[][6] = {
        /* To: Operation enabled, Switched on, Ready to switch on, Switch on disabled, quick stop,
         * fault reset. */
        [CO_CIA402_NO_STATE] = {NONE, NONE, NONE, NONE, NONE, NONE},
        [CO_CIA402_NOT_READY_TO_SWITCH_ON] = {NONE, NONE, NONE, NONE, NONE, NONE},
        [CO_CIA402_SWITCH_ON_DISABLED] = {DO(0x0006, READY_TO_SWITCH_ON),
                                          DO(0x0006, READY_TO_SWITCH_ON),
                                          DO(0x0006, READY_TO_SWITCH_ON), NONE, NONE, NONE},
        [CO_CIA402_READY_TO_SWITCH_ON] = {DO(0x0007, SWITCHED_ON), DO(0x0007, SWITCHED_ON), NONE,
                                          DO(0x0000, SWITCH_ON_DISABLED),
                                          DO(0x0002, SWITCH_ON_DISABLED), NONE},
        [CO_CIA402_SWITCHED_ON] = {DO(0x000F, OPERATION_ENABLED), NONE,
                                   DO(0x0006, READY_TO_SWITCH_ON), DO(0x0000, SWITCH_ON_DISABLED),
                                   DO(0x0002, SWITCH_ON_DISABLED), NONE},
        [CO_CIA402_OPERATION_ENABLED] = {NONE, DO(0x0007, SWITCHED_ON),
                                         DO(0x0006, READY_TO_SWITCH_ON),
                                         DO(0x0000, SWITCH_ON_DISABLED),
                                         DO(0x0002, QUICK_STOP_ACTIVE), NONE},
        [CO_CIA402_QUICK_STOP_ACTIVE] = {DO(0x0000, SWITCH_ON_DISABLED),
                                         DO(0x0000, SWITCH_ON_DISABLED),
                                         DO(0x0000, SWITCH_ON_DISABLED),
                                         DO(0x0000, SWITCH_ON_DISABLED), NONE, NONE},
        [CO_CIA402_FAULT_REACTION_ACTIVE] = {NONE, NONE, NONE, NONE, NONE, NONE},
        [CO_CIA402_FAULT] = {NONE, NONE, NONE, NONE, NONE, DO(0x0080, SWITCH_ON_DISABLED)},
    };
    for (int s = CO_CIA402_NO_STATE; s <= CO_CIA402_FAULT; s++) {
        for (size_t t = 0; t < 6; t++) {
            uint16_t word = 0xAAAA;
            co_cia402_state_t next = CO_CIA402_NO_STATE;
            bool some = co_cia402_next((co_cia402_state_t)s, targets[t], &word, &next);
            ck_assert_msg(some == (expected[s][t].word >= 0), "state %d, target %zu", s, t);
            if (some) {
                ck_assert_msg(word == expected[s][t].word, "state %d, target %zu: 0x%04X", s, t,
                              word);
                ck_assert_msg(next == expected[s][t].next, "state %d, target %zu: %d", s, t, next);
            }
        }
    }
}
END_TEST

/* Feeds `words` to a run started at t = 0, one every millisecond, and checks each step and
 * control word: the path as a (status word in, control word out) list, 0 when none is asked. */
typedef struct feed {
    uint16_t status;
    co_cia402_step_t step;
    uint16_t control;
} feed_t;

static void run(co_cia402_target_t target, const feed_t *feed, size_t n)
{
    co_cia402_master_t m;
    co_cia402_master_start(&m, target, TIMEOUT);
    for (size_t i = 0; i < n; i++) {
        uint16_t control = 0xAAAA;
        co_cia402_step_t step = co_cia402_master_step(&m, feed[i].status, i * MS, &control);
        ck_assert_msg(step == feed[i].step, "step %zu (0x%04X): %d, not %d", i, feed[i].status,
                      step, feed[i].step);
        ck_assert_msg(control == (step == CO_CIA402_WRITE ? feed[i].control : 0xAAAA),
                      "step %zu (0x%04X): control word 0x%04X", i, feed[i].status, control);
    }
}

#define RUN(target, ...)                                                                           \
    do {                                                                                           \
        static const feed_t feed[] = {__VA_ARGS__};                                                \
        run(target, feed, sizeof feed / sizeof feed[0]);                                           \
    } while (0)

START_TEST(enable_from_switch_on_disabled)
{
    /* Shutdown, Switch on, Enable operation, each once, however often the old state is read. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0640, CO_CIA402_WRITE, 0x0006},
        {0x0640, CO_CIA402_WAIT, 0}, {0x0621, CO_CIA402_WRITE, 0x0007}, {0x0621, CO_CIA402_WAIT, 0},
        {0x0623, CO_CIA402_WRITE, 0x000F}, {0x0223, CO_CIA402_WAIT, 0},
        {0x0227, CO_CIA402_REACHED, 0});
    /* Already there: nothing written. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0627, CO_CIA402_REACHED, 0});
}
END_TEST

START_TEST(enable_from_quick_stop_active)
{
    /* Through Switch on disabled (12), not back by transition 16. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0607, CO_CIA402_WRITE, 0x0000},
        {0x0640, CO_CIA402_WRITE, 0x0006}, {0x0621, CO_CIA402_WRITE, 0x0007},
        {0x0623, CO_CIA402_WRITE, 0x000F}, {0x0627, CO_CIA402_REACHED, 0});
}
END_TEST

START_TEST(fault_reset_then_enable)
{
    /* Bit 7 to 0, then to 1 (the edge), held while the drive leaves Fault. */
    RUN(CO_CIA402_TO_FAULT_RESET, {0x0608, CO_CIA402_WRITE, 0x0000},
        {0x0608, CO_CIA402_WRITE, 0x0080}, {0x0608, CO_CIA402_WAIT, 0}, {0x0608, CO_CIA402_WAIT, 0},
        {0x0640, CO_CIA402_REACHED, 0});
    /* Fault reaction active first: the reset waits for Fault (14). */
    RUN(CO_CIA402_TO_FAULT_RESET, {0x060F, CO_CIA402_WAIT, 0}, {0x0608, CO_CIA402_WRITE, 0x0000},
        {0x0608, CO_CIA402_WRITE, 0x0080}, {0x0640, CO_CIA402_REACHED, 0});
    /* The next run's first command clears bit 7 again. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0640, CO_CIA402_WRITE, 0x0006},
        {0x0621, CO_CIA402_WRITE, 0x0007}, {0x0623, CO_CIA402_WRITE, 0x000F},
        {0x0627, CO_CIA402_REACHED, 0});
    /* Not in Fault: a reset has nothing to do, whatever the state. */
    RUN(CO_CIA402_TO_FAULT_RESET, {0x0627, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_FAULT_RESET, {0x0607, CO_CIA402_REACHED, 0});
}
END_TEST

START_TEST(disable_and_stop_from_operation_enabled)
{
    RUN(CO_CIA402_TO_SWITCH_ON_DISABLED, {0x0627, CO_CIA402_WRITE, 0x0000},
        {0x0627, CO_CIA402_WAIT, 0}, {0x0640, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_SWITCHED_ON, {0x0627, CO_CIA402_WRITE, 0x0007},
        {0x0623, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_READY_TO_SWITCH_ON, {0x0627, CO_CIA402_WRITE, 0x0006},
        {0x0621, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_QUICK_STOP, {0x0627, CO_CIA402_WRITE, 0x0002}, {0x0627, CO_CIA402_WAIT, 0},
        {0x0607, CO_CIA402_REACHED, 0});
    /* A drive whose quick stop ends in Switch on disabled (12) on its own. */
    RUN(CO_CIA402_TO_QUICK_STOP, {0x0627, CO_CIA402_WRITE, 0x0002}, {0x0640, CO_CIA402_REACHED, 0});
    /* Quick stop of a drive that drives no motor: to Switch on disabled (10), or nothing. */
    RUN(CO_CIA402_TO_QUICK_STOP, {0x0623, CO_CIA402_WRITE, 0x0002}, {0x0640, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_QUICK_STOP, {0x0640, CO_CIA402_REACHED, 0});
    RUN(CO_CIA402_TO_SWITCH_ON_DISABLED, {0x0607, CO_CIA402_WRITE, 0x0000},
        {0x0640, CO_CIA402_REACHED, 0});
}
END_TEST

START_TEST(each_state_has_its_deadline)
{
    co_cia402_master_t m;
    uint16_t control = 0;
    co_cia402_master_start(&m, CO_CIA402_TO_OPERATION_ENABLED, TIMEOUT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0640, 0, &control), CO_CIA402_WRITE);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0640, TIMEOUT - 1, &control), CO_CIA402_WAIT);
    /* Ready to switch on at 150 ms: Switch on, due by 250 ms. */
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0621, 150 * MS, &control), CO_CIA402_WRITE);
    ck_assert_uint_eq(control, 0x0007);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0621, 250 * MS - 1, &control), CO_CIA402_WAIT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0621, 250 * MS, &control), CO_CIA402_TIMED_OUT);
    /* What a message says: the word, the state it awaited, the state the drive is in. */
    ck_assert_uint_eq(m.control, 0x0007);
    ck_assert(m.sent);
    ck_assert_int_eq(m.awaited, CO_CIA402_SWITCHED_ON);
    ck_assert_int_eq(m.state, CO_CIA402_READY_TO_SWITCH_ON);

    /* Nothing to send: Not ready to switch on moves on by itself, within the timeout. */
    co_cia402_master_start(&m, CO_CIA402_TO_OPERATION_ENABLED, TIMEOUT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0000, 5 * MS, &control), CO_CIA402_WAIT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0000, 5 * MS + TIMEOUT, &control),
                     CO_CIA402_TIMED_OUT);
    ck_assert(!m.sent);
    ck_assert_int_eq(m.awaited, CO_CIA402_SWITCH_ON_DISABLED);
    /* A word of no state is awaited likewise, with no command. */
    co_cia402_master_start(&m, CO_CIA402_TO_SWITCH_ON_DISABLED, TIMEOUT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0041, 0, &control), CO_CIA402_WAIT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0640, 10 * MS, &control), CO_CIA402_REACHED);
    /* A fault reset that does not take: the reset word's deadline. */
    co_cia402_master_start(&m, CO_CIA402_TO_FAULT_RESET, TIMEOUT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0608, 0, &control), CO_CIA402_WRITE);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0608, 20 * MS, &control), CO_CIA402_WRITE);
    ck_assert_uint_eq(control, 0x0080);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0608, 20 * MS + TIMEOUT - 1, &control),
                     CO_CIA402_WAIT);
    ck_assert_int_eq(co_cia402_master_step(&m, 0x0608, 20 * MS + TIMEOUT, &control),
                     CO_CIA402_TIMED_OUT);
    ck_assert_int_eq(m.awaited, CO_CIA402_SWITCH_ON_DISABLED);
}
END_TEST

START_TEST(a_fault_ends_the_run)
{
    /* On the way: the drive trips after Shutdown. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0640, CO_CIA402_WRITE, 0x0006},
        {0x0621, CO_CIA402_WRITE, 0x0007}, {0x060F, CO_CIA402_FAULTED, 0});
    /* Or while it initialises. */
    RUN(CO_CIA402_TO_OPERATION_ENABLED, {0x0000, CO_CIA402_WAIT, 0},
        {0x0608, CO_CIA402_FAULTED, 0});
    /* Already in Fault: nothing is written, whatever the target but a reset. */
    RUN(CO_CIA402_TO_SWITCH_ON_DISABLED, {0x0608, CO_CIA402_FAULTED, 0});
    RUN(CO_CIA402_TO_QUICK_STOP, {0x0628, CO_CIA402_FAULTED, 0});
    RUN(CO_CIA402_TO_SWITCHED_ON, {0x060F, CO_CIA402_FAULTED, 0});
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cia402_master");
    TCase *tc = tcase_create("cia402_master");
    tcase_add_test(tc, every_state_from_its_bits);
    tcase_add_test(tc, every_state_and_target);
    tcase_add_test(tc, enable_from_switch_on_disabled);
    tcase_add_test(tc, enable_from_quick_stop_active);
    tcase_add_test(tc, fault_reset_then_enable);
    tcase_add_test(tc, disable_and_stop_from_operation_enabled);
    tcase_add_test(tc, each_state_has_its_deadline);
    tcase_add_test(tc, a_fault_ends_the_run);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
