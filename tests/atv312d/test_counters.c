/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's per-drive counters: which frames are SDO requests of the drive, SDO aborts and EMCYs
 * it sent (a node's own COB-IDs only, data frames only), and the counters in the `state` line and
 * its JSON object beside the runtime's frame counts of the drive's device. */
#include "atv312/atv312.h"
#include "atv312d/control_commands.h"
#include "atv312d/counters.h"
#include "check_main.h"

#include <check.h>
#include <string.h>

#define NODE 4

static co_frame_t frame(uint32_t id, uint8_t flags, uint8_t first_byte)
{
    return (co_frame_t){.id = id, .flags = flags, .len = 8, .data = {first_byte}};
}

START_TEST(sdo_requests_of_its_node_only)
{
    atv312d_counters_t c = {0};
    atv312d_count_received(&c, NODE, &(co_frame_t){.id = 0x604, .len = 8, .data = {0x40}});
    atv312d_count_received(&c, NODE, &(co_frame_t){.id = 0x604, .len = 2, .data = {0x80}});
    ck_assert_uint_eq(c.sdo_requests, 2);
    atv312d_count_received(&c, NODE, &(co_frame_t){.id = 0x605, .len = 8});
    co_frame_t remote = frame(0x604, CO_FRAME_RTR, 0);
    co_frame_t extended = frame(0x604, CO_FRAME_EFF, 0x40);
    atv312d_count_received(&c, NODE, &remote);
    atv312d_count_received(&c, NODE, &extended);
    atv312d_count_received(&c, NODE, &(co_frame_t){.id = 0x584, .len = 8, .data = {0x80}});
    ck_assert_uint_eq(c.sdo_requests, 2);
    ck_assert_uint_eq(c.sdo_aborts, 0);
    ck_assert_uint_eq(c.emcy, 0);
}
END_TEST

START_TEST(aborts_and_emcys_sent)
{
    atv312d_counters_t c = {0};
    co_frame_t abort = frame(0x584, 0, 0x80);
    co_frame_t upload = frame(0x584, 0, 0x43);
    co_frame_t emcy = frame(0x084, 0, 0x10);
    co_frame_t error_reset = frame(0x084, 0, 0x00);
    co_frame_t other_emcy = frame(0x085, 0, 0x10);
    co_frame_t bootup = {.id = 0x704, .len = 1};
    co_frame_t tpdo = frame(0x184, 0, 0x80);
    atv312d_count_sent(&c, NODE, &abort);
    atv312d_count_sent(&c, NODE, &upload);
    atv312d_count_sent(&c, NODE, &emcy);
    atv312d_count_sent(&c, NODE, &error_reset);
    atv312d_count_sent(&c, NODE, &other_emcy);
    atv312d_count_sent(&c, NODE, &bootup);
    atv312d_count_sent(&c, NODE, &tpdo);
    atv312d_count_sent(&c, NODE, &(co_frame_t){.id = 0x584, .len = 0});
    ck_assert_uint_eq(c.sdo_aborts, 1);
    ck_assert_uint_eq(c.emcy, 2);
    ck_assert_uint_eq(c.sdo_requests, 0);
    ck_assert(atv312d_is_emcy(NODE, &emcy));
    ck_assert(!atv312d_is_emcy(NODE, &other_emcy));
}
END_TEST

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

/* The state line and its JSON end with the device's frame counts and the drive's counters (then
 * the logic inputs that are on: none here). */
START_TEST(state_shows_the_counters)
{
    static uint8_t od_data[ATV312_OD_DATA_SIZE];
    static drive_t drive;
    drive_config_t config = {
        .profile = &atv312_profile, .od_data = od_data, .node_id = NODE, .send = no_send};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    static co_linux_loop_t loop; /* the time the LEDs are shown at: 0 */
    co_linux_device_t device = {.loop = &loop, .stats = {.rx = 12, .tx = 9, .tx_dropped = 1}};
    atv312d_counters_t counters = {.sdo_requests = 7, .sdo_aborts = 2, .emcy = 3};
    atv312d_control_node_t node = {.drive = &drive, .device = &device, .counters = &counters};
    char line[1024];
    atv312d_format_state(&node, false, line, sizeof line);
    const char *text = ", fault none, frames received 12, sent 9, dropped 1, SDO requests 7, "
                       "SDO aborts 2, EMCY 3";
    ck_assert_str_eq(line + strlen(line) - strlen(text), text);
    atv312d_format_state(&node, true, line, sizeof line);
    const char *json =
        ",\"fault\":null,\"comm_loss\":null,\"frames\":{\"received\":12,\"sent\":9,\"dropped\":1,"
        "\"sdo_requests\":7,\"sdo_aborts\":2,\"emcy\":3},\"inputs\":[],"
        "\"analog\":{\"AI2\":0.000,\"AI3\":0.000},\"kind\":\"drive\"}";
    ck_assert_str_eq(line + strlen(line) - strlen(json), json);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("counters");
    TCase *tc = tcase_create("counters");
    tcase_add_test(tc, sdo_requests_of_its_node_only);
    tcase_add_test(tc, aborts_and_emcys_sent);
    tcase_add_test(tc, state_shows_the_counters);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
