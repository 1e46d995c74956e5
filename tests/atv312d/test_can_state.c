/* SPDX-License-Identifier: Apache-2.0 */
/* What atv312d says of CAN errors: the controller's state (error-active, error-warning,
 * error-passive, bus-off) and the bus-off count in the status line and the `state` JSON, and
 * which error control protocol lost the master in a drive's `state` line and JSON. */
#include "atv312/atv312.h"
#include "atv312d/control_commands.h"
#include "atv312d/status.h"
#include "check_main.h"

#include <check.h>
#include <string.h>

#define NODE 4

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

static uint8_t od_data[ATV312_OD_DATA_SIZE];
static drive_t drive;
static co_linux_loop_t loop;
static co_linux_device_t device;
static atv312d_counters_t counters;
static atv312d_control_node_t node;

static void setup(void)
{
    drive_config_t config = {
        .profile = &atv312_profile, .od_data = od_data, .node_id = NODE, .send = no_send};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    drive_start(&drive, 0);
    memset(&loop, 0, sizeof loop);
    snprintf(loop.iface, sizeof loop.iface, "vcan0");
    loop.bus.link_up = true;
    co_linux_conditions_init(&loop.bus.conditions);
    device = (co_linux_device_t){.loop = &loop};
    counters = (atv312d_counters_t){0};
    node = (atv312d_control_node_t){
        .id = NODE, .drive = &drive, .device = &device, .counters = &counters};
}

static const char *status_line(void)
{
    static char text[4096];
    atv312d_status_t status = {.loop = &loop, .nodes = &node, .count = 1};
    atv312d_status_format(&status, text, sizeof text);
    *strchr(text, '\n') = '\0';
    return text;
}

static void set(co_linux_condition_kind_t which, bool active)
{
    co_linux_conditions_set(&loop.bus.conditions, loop.iface, which, active);
}

static void expect_status(const char *state, unsigned bus_offs)
{
    char line[256];
    snprintf(line, sizeof line,
             "vcan0: CAN %s; frames received 0, sent 0, dropped 0, lost while down 0, "
             "error frames 0, bus-offs %u; wake-ups 0, sendmmsg calls 0",
             state, bus_offs);
    ck_assert_str_eq(status_line(), line);
}

START_TEST(status_line_tells_warning_from_passive_and_counts_bus_offs)
{
    expect_status("error-active", 0);
    set(CO_LINUX_COND_WARNING, true);
    expect_status("error-warning", 0);
    set(CO_LINUX_COND_PASSIVE, true);
    expect_status("error-passive", 0);
    set(CO_LINUX_COND_BUS_OFF, true);
    expect_status("bus-off", 1);
    /* The controller restarts error active; the same bus off told twice counts once, a second
     * one again. */
    co_linux_conditions_restart(&loop.bus.conditions);
    expect_status("error-active", 1);
    set(CO_LINUX_COND_BUS_OFF, true);
    set(CO_LINUX_COND_BUS_OFF, true);
    expect_status("bus-off", 2);
}
END_TEST

START_TEST(state_json_has_the_controller_state_and_bus_offs)
{
    atv312d_control_t control = {.nodes = &node, .count = 1};
    char reply[2048];
    set(CO_LINUX_COND_BUS_OFF, true);
    set(CO_LINUX_COND_BUS_OFF, false);
    set(CO_LINUX_COND_WARNING, true);
    ck_assert(atv312d_control_execute(&control, "json state", reply, sizeof reply));
    const char *start = "{\"ok\":true,\"can\":{\"state\":\"error-warning\",\"bus_offs\":1},"
                        "\"nodes\":[{\"node\":4,";
    ck_assert_msg(strncmp(reply, start, strlen(start)) == 0, "%s", reply);
}
END_TEST

static void receive(const char *candump, co_time_t now)
{
    co_frame_t frame = {0};
    unsigned id;
    char data[17] = "";
    ck_assert_int_ge(sscanf(candump, "%x#%16s", &id, data), 1);
    frame.id = id;
    if (strcmp(data, "R") == 0)
        frame.flags = CO_FRAME_RTR;
    else
        for (frame.len = 0; data[2 * frame.len]; frame.len++)
            sscanf(&data[2 * frame.len], "%2hhx", &frame.data[frame.len]);
    drive_receive(&drive, &frame, now);
    drive_process(&drive, now);
}

static void expect_state(const char *text, const char *json)
{
    char line[1024];
    atv312d_format_state(&node, false, line, sizeof line);
    ck_assert_msg(strstr(line, text) != NULL, "no '%s' in '%s'", text, line);
    atv312d_format_state(&node, true, line, sizeof line);
    ck_assert_msg(strstr(line, json) != NULL, "no '%s' in '%s'", json, line);
}

/* 1016h:01 = node 1 every 100 ms; its first heartbeat starts the monitoring. */
START_TEST(state_says_a_heartbeat_loss_and_its_producer)
{
    receive("604#2316100164000100", 0);
    receive("701#05", 1000);
    drive_process(&drive, 101000);
    expect_state(", ERR double flash, fault COF, comm-loss heartbeat node 1, frames received ",
                 ",\"fault\":\"COF\",\"comm_loss\":{\"by\":\"heartbeat\",\"node\":1},\"frames\"");
    receive("604#2B40600080000000", 200000); /* fault reset: the cause is gone with it */
    expect_state(", ERR off, fault none, frames received ", ",\"comm_loss\":null,");
}
END_TEST

/* Guard time 100 ms, life time factor 3: 300 ms after the last request. */
START_TEST(state_says_a_life_guarding_loss)
{
    receive("604#2B0C100064000000", 0);
    receive("604#2F0D100003000000", 0);
    receive("704#R", 1000);
    drive_process(&drive, 301000);
    expect_state(", ERR double flash, fault COF, comm-loss guarding, frames received ",
                 ",\"fault\":\"COF\",\"comm_loss\":{\"by\":\"guarding\"},\"frames\"");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("can_state");
    TCase *tc = tcase_create("can_state");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, status_line_tells_warning_from_passive_and_counts_bus_offs);
    tcase_add_test(tc, state_json_has_the_controller_state_and_bus_offs);
    tcase_add_test(tc, state_says_a_heartbeat_loss_and_its_producer);
    tcase_add_test(tc, state_says_a_life_guarding_loss);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
