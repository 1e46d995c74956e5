/* SPDX-License-Identifier: Apache-2.0 */
/* The rule of docs/error-control.md, "Errors and resets", for every service whose error has an
 * EMCY, after every scope: reset node, reset communication, enter Pre-operational, stop (and
 * start again). After each, the service's error state and the EMCY producer's active errors
 * agree, shown by exact frames: an error the scope ended is gone from 1001h and the same fault
 * raises its EMCY again; an error the scope kept is still in 1001h and the end of its condition
 * sends the error reset. Node 5, as in issue 7. */
#include "check_main.h"
#include "test_bus.h"

#include <stdio.h>

#define MS 1000u
#define COMMUNICATION_ERROR (CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION)
#define HB_PRODUCER 0x20u /* the heartbeat producer the node monitors */
#define ERROR_RESET "085#0000000000000000"

static test_node_t t;

/* The service and scope under test, for the failure messages. */
static char label[96];
#define expect(text) test_expect_at(&t, text, label, __LINE__)
#define expect_none() test_expect_none_at(&t, label, __LINE__)

/* ---- The application ------------------------------------------------------------------- */

/* As on the ATV312 (docs/decisions.md, D-COMM-LOSS-CNF): the loss of a heartbeat producer or of
 * life guarding is a latched fault, EMCY 8130h until the application's fault reset; a CAN
 * condition of the runtime is an EMCY while it lasts (atv312_bus_event). */
static void application_fault(co_node_t *node)
{
    co_emcy_raise(node, CO_EMCY_HEARTBEAT, COMMUNICATION_ERROR, NULL);
}

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    (void)producer;
    if (lost)
        application_fault(node);
}

static void on_guarding(co_node_t *node, bool lost)
{
    if (lost)
        application_fault(node);
}

static const co_app_hooks_t hooks = {.heartbeat = on_heartbeat, .guarding = on_guarding};

static void application_clears(uint16_t code)
{
    t.node.now = t.bus.now;
    co_emcy_clear(&t.node, code);
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

/* ---- The services ---------------------------------------------------------------------- */

typedef struct service {
    const char *name;
    bool core;                /* the core raises and clears the EMCY, not the application */
    uint16_t code;            /* the EMCY error code */
    const char *emcy;         /* the EMCY frame of the fault */
    void (*configure)(void);  /* what the fault needs beyond the defaults, which a reset restores */
    void (*fault)(void);      /* makes the fault happen */
    void (*fault_ends)(void); /* the fault's condition ends */
} service_t;

static void nothing(void) {}

static void rpdo1_short_frame(void)
{
    test_rx(&t, "205#06");
}

static void rpdo1_long_frame(void)
{
    test_rx(&t, "205#060000");
}

static void rpdo1_right_frame(void)
{
    test_rx(&t, "205#0600");
}

/* RPDO6 on 305h with deadline monitoring of 100 ms. */
static void rpdo6_monitored(void)
{
    ck_assert_uint_eq(test_write(&t, 0x1405, 5, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x1405, 1, 0x305, 4), 0);
}

static void rpdo6_frame(void)
{
    test_rx(&t, "305#0F00B004");
}

static void rpdo6_silent(void)
{
    rpdo6_frame();
    test_advance(&t, 100 * MS);
}

static void sync_with_counter(void)
{
    test_rx(&t, "080#01");
}

static void sync_without_counter(void)
{
    test_rx(&t, "080#");
}

static void heartbeat_consumer(void)
{
    ck_assert_uint_eq(test_write(&t, 0x1016, 1, HB_PRODUCER << 16 | 100, 4), 0);
}

static void heartbeat_lost(void)
{
    test_rx(&t, "720#05");
    test_advance(&t, 100 * MS);
}

static void guard_time(void)
{
    ck_assert_uint_eq(test_write(&t, 0x100C, 0, 100, 2), 0);
    ck_assert_uint_eq(test_write(&t, 0x100D, 0, 1, 1), 0);
}

static void guarding_lost(void)
{
    char reply[16];
    snprintf(reply, sizeof(reply), "705#%02X", t.node.guarding.toggle | CO_NMT_OPERATIONAL);
    test_rx(&t, "705#R");
    expect(reply);
    test_advance(&t, 100 * MS);
}

static void fault_reset(void)
{
    application_clears(CO_EMCY_HEARTBEAT);
}

static void error_passive(void)
{
    t.node.now = t.bus.now;
    ck_assert(co_emcy_raise(&t.node, CO_EMCY_CAN_PASSIVE, COMMUNICATION_ERROR, NULL));
    t.bus.deadline = co_node_process(&t.node, t.bus.now);
}

static void error_active(void)
{
    application_clears(CO_EMCY_CAN_PASSIVE);
}

static const service_t services[] = {
    {"RPDO length 8210h", true, CO_EMCY_PDO_LENGTH, "085#1082110100010200", nothing,
     rpdo1_short_frame, rpdo1_right_frame},
    {"RPDO length 8220h", true, CO_EMCY_PDO_LENGTH_EXCEEDED, "085#2082110100030200", nothing,
     rpdo1_long_frame, rpdo1_right_frame},
    {"RPDO timeout 8250h", true, CO_EMCY_RPDO_TIMEOUT, "085#5082110600000400", rpdo6_monitored,
     rpdo6_silent, rpdo6_frame},
    {"SYNC length 8240h", true, CO_EMCY_SYNC_LENGTH, "085#4082110100000000", nothing,
     sync_with_counter, sync_without_counter},
    {"heartbeat consumer, application 8130h", false, CO_EMCY_HEARTBEAT, "085#3081110000000000",
     heartbeat_consumer, heartbeat_lost, fault_reset},
    {"life guarding, application 8130h", false, CO_EMCY_HEARTBEAT, "085#3081110000000000",
     guard_time, guarding_lost, fault_reset},
    {"CAN error passive, application 8120h", false, CO_EMCY_CAN_PASSIVE, "085#2081110000000000",
     nothing, error_passive, error_active},
};

#define SERVICES (sizeof(services) / sizeof(services[0]))

/* ---- The scopes ------------------------------------------------------------------------ */

typedef struct scope {
    const char *name;
    const char *command;
    const char *boot_up; /* NULL: no boot-up */
    bool core_keeps;     /* the errors the core raised stay */
    bool application_keeps;
} scope_t;

static const scope_t scopes[] = {
    {"reset node", "000#8105", "705#00", false, false},
    {"reset communication", "000#8205", "705#00", false, true},
    {"enter Pre-operational", "000#8005", NULL, true, true},
    {"stop", "000#0205", NULL, true, true},
};

#define SCOPES (sizeof(scopes) / sizeof(scopes[0]))

/* The service configured and the node Operational (PDOs), TPDO1 off so the bus carries only
 * what is checked. */
static void operational(const service_t *s)
{
    ck_assert_uint_eq(test_write(&t, 0x1800, 1, 0x80000185, 4), 0);
    s->configure();
    test_rx(&t, "000#0105");
}

static void expect_register(uint8_t reg, const char *when)
{
    ck_assert_msg(co_od_value(&t.node, 0x1001, 0) == reg, "%s: 1001h is %02X %s, not %02X", label,
                  (unsigned)co_od_value(&t.node, 0x1001, 0), when, reg);
}

START_TEST(error_state_and_emcy_agree_after_every_scope)
{
    const service_t *s = &services[(size_t)_i / SCOPES];
    const scope_t *scope = &scopes[(size_t)_i % SCOPES];
    snprintf(label, sizeof(label), "%s, %s", s->name, scope->name);
    bool kept = s->core ? scope->core_keeps : scope->application_keeps;

    test_node_start(&t, 5, &hooks, NULL);
    operational(s);
    s->fault();
    expect(s->emcy);
    expect_register(COMMUNICATION_ERROR, "after the fault");

    test_rx(&t, scope->command);
    if (scope->boot_up != NULL)
        expect(scope->boot_up);
    expect_none();
    ck_assert_msg(co_emcy_is_active(&t.node, s->code) == kept, "%s: the error is %s", label,
                  kept ? "gone" : "still active");
    expect_register(kept ? COMMUNICATION_ERROR : 0, "after the scope");

    operational(s);
    if (kept) {
        s->fault_ends();
        expect(ERROR_RESET);
        expect_register(0, "once the condition ended");
    }
    s->fault();
    expect(s->emcy);
    s->fault_ends();
    expect(ERROR_RESET);
    expect_none();
}
END_TEST

int main(void)
{
    Suite *s = suite_create("reset");
    TCase *tc = tcase_create("reset");
    tcase_add_loop_test(tc, error_state_and_emcy_agree_after_every_scope, 0,
                        (int)(SERVICES * SCOPES));
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
