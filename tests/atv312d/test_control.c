/* SPDX-License-Identifier: Apache-2.0 */
/* The control surface's replies where a CANopen and a DeviceNet drive differ: a fault happening
 * (its EMCY on CANopen; on DeviceNet, where EMCYs stay on the card's internal link, the Control
 * supervisor's state and the Identity's fault), the RUN key refused under network control, and the
 * state line's counters (the CANopen services', or the DeviceNet card's); the STOP key's reset of
 * a fault where the model's manual gives it (the ATV31). A drive of each kind is
 * a device of an unopened loop: nothing here reaches a socket. */
#include "atv31/atv31.h"
#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "atv312d/control_commands.h"
#include "atv58/atv58.h"
#include "check_main.h"

#include <check.h>
#include <string.h>

#define NODE 4
#define MAC_ID 25

static co_linux_loop_t loop;
#define LARGER(a, b) ((a) > (b) ? (a) : (b))
static uint8_t od_data[LARGER(LARGER(ATV312_OD_DATA_SIZE, ATV58_OD_DATA_SIZE), ATV31_OD_DATA_SIZE)];
static drive_t drive;
static drive_dn_t dn;
static co_linux_device_t device;
static atv312d_counters_t counters;
static atv312d_control_node_t node;
static atv312d_control_t control;
static char reply[4096];

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

static co_time_t canopen_process(void *ctx, co_time_t now)
{
    return drive_process(ctx, now);
}

static co_time_t devicenet_process(void *ctx, co_time_t now)
{
    return drive_dn_process(ctx, now);
}

static const co_linux_device_ops_t canopen_ops = {.process = canopen_process};
static const co_linux_device_ops_t devicenet_ops = {.process = devicenet_process};

static void start_model(const drive_profile_t *profile)
{
    memset(&loop, 0, sizeof loop);
    drive_config_t config = {
        .profile = profile, .od_data = od_data, .node_id = NODE, .send = no_send};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    drive_start(&drive, loop.now);
    co_linux_loop_add(&loop, &device, &canopen_ops, &drive);
    node = (atv312d_control_node_t){
        .id = NODE, .drive = &drive, .device = &device, .counters = &counters};
    control = (atv312d_control_t){.nodes = &node, .count = 1};
}

static void start_canopen(void)
{
    start_model(&atv312_profile);
}

static void start_devicenet(void)
{
    memset(&loop, 0, sizeof loop);
    drive_config_t config = {.profile = atv312_devicenet_profile.drive,
                             .od_data = od_data,
                             .node_id = 1,
                             .send = drive_dn_drop_frame};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    drive_dn_config_t dn_config = {.drive = &drive,
                                   .profile = &atv312_devicenet_profile,
                                   .mac_id = MAC_ID,
                                   .serial_number = 0x31200019,
                                   .send = no_send};
    ck_assert_int_eq(drive_dn_init(&dn, &dn_config), 0);
    drive_dn_start(&dn, loop.now);
    co_linux_loop_add(&loop, &device, &devicenet_ops, &dn);
    node = (atv312d_control_node_t){
        .id = MAC_ID, .drive = &drive, .devicenet = &dn, .device = &device, .counters = &counters};
    control = (atv312d_control_t){.nodes = &node, .count = 1};
}

static const char *execute(const char *line)
{
    atv312d_control_execute(&control, line, reply, sizeof reply);
    return reply;
}

START_TEST(canopen_fault_is_its_emcy)
{
    start_canopen();
    ck_assert_str_eq(execute("fault 4 OHF"), "ok node 4: OHF (drive overheating), EMCY 4210");
    ck_assert_str_eq(execute("json fault 4 OCF"),
                     "{\"ok\":true,\"message\":\"node 4: OCF (overcurrent), EMCY 2310\"}");
}
END_TEST

/* A fault (the ATV312's all freewheel but CnF): Faulted at once, which the card shows as the
 * Identity's major recoverable fault. */
START_TEST(devicenet_fault_is_the_supervisor_and_identity)
{
    start_devicenet();
    ck_assert_str_eq(execute("fault 25 OHF"), "ok node 25: OHF (drive overheating), supervisor "
                                              "faulted, Identity major recoverable fault");
    ck_assert_uint_eq(dn_node_identity_status(&dn.node) & DN_STATUS_MAJOR_RECOVERABLE,
                      DN_STATUS_MAJOR_RECOVERABLE);
    ck_assert_str_eq(execute("json mains 25 undervoltage"),
                     "{\"ok\":true,\"message\":\"node 25: USF (line supply undervoltage), "
                     "supervisor faulted, Identity major recoverable fault\"}");
}
END_TEST

START_TEST(run_key_refused_under_network_control)
{
    start_canopen();
    ck_assert_str_eq(execute("run-key 4"),
                     "error: node 4 is under network control: the RUN key works under local "
                     "control (local 4 on, or a command channel other than CANopen)");
    start_devicenet();
    ck_assert_str_eq(execute("run-key 25"),
                     "error: node 25 is under network control (CtrlFromNet 1): the RUN key works "
                     "under local control (local 25 on, or a command channel other than "
                     "DeviceNet: NetCtrl 0 with CCS = C212)");
    ck_assert_str_eq(execute("local 25 on"), "ok node 25: local control (status word bit 9 = 0)");
    ck_assert_str_eq(execute("run-key 25"), "ok node 25: RUN key");
}
END_TEST

/* The ATV31's STOP/RESET key resets a fault whose cause is gone; the ATV312's STOP key does not. */
START_TEST(stop_key_resets_a_fault_where_the_manual_says)
{
    start_model(&atv31_profile);
    ck_assert_str_eq(execute("fault 4 OHF"), "ok node 4: OHF (drive overheating), EMCY 4210");
    ck_assert_str_eq(execute("stop-key 4"),
                     "ok node 4: STOP key: still in fault OHF (status word bit 14)");
    ck_assert_str_eq(execute("clear 4 OHF"), "ok node 4: cause of OHF removed");
    ck_assert_str_eq(execute("stop-key 4"),
                     "ok node 4: STOP/RESET key: fault OHF reset (status word bit 14)");
    ck_assert_str_eq(drive_state_name(&drive), "Switch on disabled");
    start_canopen();
    execute("fault 4 OHF");
    execute("clear 4 OHF");
    ck_assert_str_eq(execute("stop-key 4"),
                     "ok node 4: STOP key: still in fault OHF (status word bit 14)");
}
END_TEST

/* Analogue inputs in the units their manuals give them: volts for AI1/AI2, mA for AI3, % for the
 * ATV31's potentiometer; each model's own inputs and ranges, refusals naming them. With Fr1 =
 * AI2 and the network commanding, the motor runs to the input's speed. */
START_TEST(analog_inputs_in_their_units)
{
    start_canopen();
    ck_assert_str_eq(execute("analog 4 AI2 -2.5"), "ok node 4: AI2 -2.500 V");
    ck_assert_int_eq(drive_analog(&drive, (uint8_t)drive_analog_find(&drive, "AI2")), -2500);
    ck_assert_str_eq(execute("analog 4 ai3 12"), "ok node 4: AI3 12.000 mA");
    char line[1024];
    atv312d_format_state(&node, false, line, sizeof line);
    const char *text = ", EMCY 0, analog AI2 -2.500 V AI3 12.000 mA";
    ck_assert_str_eq(line + strlen(line) - strlen(text), text);
    atv312d_format_state(&node, true, line, sizeof line);
    const char *json =
        ",\"inputs\":[],\"analog\":{\"AI2\":-2.500,\"AI3\":12.000},\"kind\":\"drive\"}";
    ck_assert_str_eq(line + strlen(line) - strlen(json), json);
    ck_assert_str_eq(execute("json analog 4 AI2 5"),
                     "{\"ok\":true,\"message\":\"node 4: AI2 5.000 V\"}");
    ck_assert_str_eq(execute("analog 4 AI2 10.5"), "error: analog AI2 10.5: give a voltage of "
                                                   "-10..10 V");
    ck_assert_str_eq(execute("analog 4 AI3 -1"),
                     "error: analog AI3 -1: give a current of 0..20 mA");
    ck_assert_str_eq(execute("analog 4 AI2 1.2345"),
                     "error: analog AI2 1.2345: give a voltage of -10..10 V");
    ck_assert_str_eq(execute("analog 4 AI1 5"),
                     "error: node 4 has no analogue input AI1: its analogue inputs are AI2, AI3");
    ck_assert_str_eq(execute("analog 4 AI2"), "error: usage: analog NODE AIn VALUE (volts or mA "
                                              "as the input takes them, e.g. analog 4 AI2 -2.5)");
    ck_assert_str_eq(execute("pot 4 50"), "error: node 4 has no reference potentiometer");
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x2036, 2, (const uint8_t *)"\x02\x00", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x2036, 14, (const uint8_t *)"\x02\x00", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x6040, 0, (const uint8_t *)"\x06\x00", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x6040, 0, (const uint8_t *)"\x0F\x00", 2, CO_OD_ORIGIN_SDO), 0);
    loop.now = 3000000;
    drive_process(&drive, loop.now);
    ck_assert_int_eq((int16_t)co_od_value(&drive.node, 0x6044, 0), 750);

    start_model(&atv31_profile);
    ck_assert_str_eq(execute("pot 4 50.5"), "ok node 4: AIP 50.5 %");
    atv312d_format_state(&node, true, line, sizeof line);
    ck_assert_ptr_nonnull(
        strstr(line, "\"analog\":{\"AI1\":0.000,\"AI2\":0.000,\"AI3\":0.000,\"AIP\":50.5}"));
    ck_assert_str_eq(execute("analog 4 AIP 20"), "ok node 4: AIP 20.0 %");
    ck_assert_str_eq(execute("pot 4 101"), "error: pot AIP 101: give a percentage of 0..100");
    ck_assert_str_eq(execute("analog 4 AI1 -1"), "error: analog AI1 -1: give a voltage of 0..10 V");
    start_model(&atv58_profile);
    ck_assert_str_eq(execute("analog 4 AI1 5"), "error: node 4 has no analogue inputs");
}
END_TEST

/* Under terminal control (CHCF = SEP, Cd1 = terminals) LI1 is the forward run input. */
START_TEST(input_runs_the_drive_from_the_terminals)
{
    start_canopen();
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x2036, 2, (const uint8_t *)"\x02\x00", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_uint_eq(
        co_od_write(&drive.node, 0x2036, 24, (const uint8_t *)"\x01\x00", 2, CO_OD_ORIGIN_SDO), 0);
    ck_assert_str_eq(execute("input 4 LI1 on"), "ok node 4: LI1 on");
    ck_assert_str_eq(drive_state_name(&drive), "Operation enabled");
    ck_assert_str_eq(execute("input 4 LI1 off"), "ok node 4: LI1 off");
    ck_assert_str_eq(drive_state_name(&drive), "Switch on disabled");
}
END_TEST

/* The state line ends with the device's frame counts and the card's counters (then the logic
 * inputs that are on and the analogue inputs not at 0: none here; in JSON every analogue input). */
START_TEST(devicenet_state_shows_the_card_counters)
{
    start_devicenet();
    device.stats = (co_linux_device_stats_t){.rx = 52, .tx = 50, .tx_dropped = 1};
    dn.stats = (dn_stats_t){.explicit_requests = 7,
                            .error_responses = 2,
                            .io_messages = 40,
                            .fragments = 3,
                            .timeouts = 1};
    char line[1024];
    atv312d_format_state(&node, false, line, sizeof line);
    const char *text = ", fault none, frames received 52, sent 50, dropped 1, explicit requests 7, "
                       "error responses 2, I/O messages 40, fragments 3, timeouts 1";
    ck_assert_str_eq(line + strlen(line) - strlen(text), text);
    atv312d_format_state(&node, true, line, sizeof line);
    const char *json =
        ",\"fault\":null,\"comm_loss\":null,\"frames\":{\"received\":52,\"sent\":50,\"dropped\":1,"
        "\"explicit_requests\":7,\"error_responses\":2,\"io_messages\":40,"
        "\"fragments\":3,\"timeouts\":1},\"inputs\":[],"
        "\"analog\":{\"AI2\":0.000,\"AI3\":0.000},\"kind\":\"drive\"}";
    ck_assert_str_eq(line + strlen(line) - strlen(json), json);
}
END_TEST

/* Each model's LEDs as its manual names them: the ATV312's RUN and ERR (CiA 303-3), the ATV58
 * card's green OK and yellow COM (COM flashing for 1 s after an SDO request). */
START_TEST(canopen_state_shows_the_models_leds)
{
    char line[1024];
    start_canopen();
    atv312d_format_state(&node, false, line, sizeof line);
    ck_assert_ptr_nonnull(strstr(line, ", display nSt, RUN blinking, ERR off, fault none, "));
    atv312d_format_state(&node, true, line, sizeof line);
    ck_assert_ptr_nonnull(strstr(line, ",\"run_led\":\"blinking\",\"err_led\":\"off\","));

    start_model(&atv58_profile);
    atv312d_format_state(&node, false, line, sizeof line);
    ck_assert_ptr_nonnull(strstr(line, ", display nSt, OK on, COM off, fault none, "));
    co_frame_t request = {.id = 0x604, .len = 8, .data = {0x40, 0x0C, 0x10}};
    drive_receive(&drive, &request, loop.now);
    atv312d_format_state(&node, true, line, sizeof line);
    ck_assert_ptr_nonnull(strstr(line, ",\"ok_led\":\"on\",\"com_led\":\"flashing\","));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("control");
    TCase *tc = tcase_create("control");
    tcase_add_test(tc, canopen_fault_is_its_emcy);
    tcase_add_test(tc, devicenet_fault_is_the_supervisor_and_identity);
    tcase_add_test(tc, run_key_refused_under_network_control);
    tcase_add_test(tc, stop_key_resets_a_fault_where_the_manual_says);
    tcase_add_test(tc, analog_inputs_in_their_units);
    tcase_add_test(tc, input_runs_the_drive_from_the_terminals);
    tcase_add_test(tc, devicenet_state_shows_the_card_counters);
    tcase_add_test(tc, canopen_state_shows_the_models_leds);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
