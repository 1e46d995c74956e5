/* SPDX-License-Identifier: Apache-2.0 */
/* The control commands on plain nodes (docs/atv312d.md, "Plain nodes"): a PLC300's markers read
 * and written as its program would, an I/O node's terminals, their state lines, and a drive's
 * commands refused on them. Each node is a device of an unopened loop: nothing reaches a socket. */
#include "atv312d/control_commands.h"
#include "atv312d/view.h"
#include "check_main.h"
#include "nodes/io/io401.h"
#include "nodes/node_models.h"
#include "nodes/plc300/plc300.h"

#include <check.h>
#include <string.h>

static co_linux_loop_t loop;
static uint8_t plc_data[8192], io_data[1024];
static plain_node_t plc, io;
static co_linux_device_t plc_device, io_device;
static atv312d_counters_t counters;
static atv312d_control_node_t nodes[2];
static atv312d_control_t control;
static char reply[4096];

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

static co_time_t plain_process(void *ctx, co_time_t now)
{
    return plain_node_process(ctx, now);
}

static const co_linux_device_ops_t plain_ops = {.process = plain_process};

static void start_node(plain_node_t *plain, const plain_model_t *model, uint8_t id, uint8_t *data,
                       co_linux_device_t *device, atv312d_control_node_t *node)
{
    ck_assert_uint_le(model->od->data_size, id == 1 ? sizeof plc_data : sizeof io_data);
    plain_node_config_t config = {.model = model,
                                  .od_data = data,
                                  .node_id = id,
                                  .serial_number = model->serial_base + id,
                                  .send = no_send};
    ck_assert_int_eq(plain_node_init(plain, &config), 0);
    plain_node_start(plain, loop.now);
    co_linux_loop_add(&loop, device, &plain_ops, plain);
    *node = (atv312d_control_node_t){
        .id = id, .model = model->name, .plain = plain, .device = device, .counters = &counters};
}

static void setup(void)
{
    memset(&loop, 0, sizeof loop);
    start_node(&plc, &plc300_model, 1, plc_data, &plc_device, &nodes[0]);
    start_node(&io, &io401_model, 10, io_data, &io_device, &nodes[1]);
    control = (atv312d_control_t){.nodes = nodes, .count = 2};
}

static void expect(const char *line, bool ok, const char *want)
{
    ck_assert_int_eq(atv312d_control_execute(&control, line, reply, sizeof reply), ok);
    ck_assert_str_eq(reply, want);
}

START_TEST(markers_read_and_written_as_the_program_would)
{
    expect("marker 1 %IW2000", true, "ok node 1: %IW2000 = 999 (0x03E7, 3400h)");
    expect("marker 1 ib2001", true, "ok node 1: %IB2001 = 3 (0x03, 3001h)");
    expect("marker 1 %QD2508 0xDEADBEEF", true, "ok node 1: %QD2508 = 3735928559 (49FCh)");
    expect("marker 1 %QB2511", true, "ok node 1: %QB2511 = 222 (0xDE, 41FFh)");
    ck_assert_int_eq(co_od_value(&plc.node, 0x45FE, 0), 0xDEAD);
    expect("marker 1 %QB2000 256", false,
           "error: marker %QB2000 256: give 0..255 (or 0x in hexadecimal)");
    expect("marker 1 %QW2001", false,
           "error: '%QW2001' is no network marker: give %IB, %IW or %ID (inputs), %QB, %QW or "
           "%QD (outputs) and its number, 2000..2511 (a word's even, a double word's a multiple "
           "of 4)");
    expect("marker 10 %QB2000 1", false, "error: node 10 is an io node: markers are a PLC300's");
}
END_TEST

START_TEST(terminals_of_the_io_node)
{
    expect("input 10 DI3 on", true, "ok node 10: DI3 on (6000h:01 = 04)");
    expect("input 10 di8 on", true, "ok node 10: DI8 on (6000h:01 = 84)");
    expect("input 10 DI9 on", false, "error: node 10 has no input DI9: its inputs are DI1..DI8");
    expect("analog 10 AI2 -300", true, "ok node 10: AI2 -300 (6401h:02)");
    expect("analog 10 AI1 40000", false,
           "error: analog AI1 40000: give the raw value of 6401h:01, -32768..32767");
    expect("input 1 DI1 on", false,
           "error: node 1 is a plc300 node: it has no inputs to set; its commands are marker, "
           "state");
    ck_assert_int_eq(io401_analog(&io, 2), -300);
}
END_TEST

/* Every plain model of the catalogue has its row in the surfaces: its commands for a refusal and
 * its data in the state (a model without one would show and take only what every node has). */
START_TEST(every_plain_model_has_its_surface)
{
    for (size_t i = 0; i < plain_model_count; i++) {
        const atv312d_plain_surface_t *surface = atv312d_plain_surface(plain_models[i]);
        ck_assert_msg(surface != NULL, "model %s has no surface", plain_models[i]->name);
        ck_assert_ptr_eq(surface->model, plain_models[i]);
    }
    ck_assert_str_eq(atv312d_plain_surface(&plc300_model)->commands, "marker, state");
    ck_assert_str_eq(atv312d_plain_surface(&io401_model)->commands, "input, analog, state");
}
END_TEST

START_TEST(drive_commands_are_refused)
{
    expect("fault 1 OHF", false,
           "error: node 1 is a plc300 node, not a drive: fault is a drive's command; its commands "
           "are marker, state");
    expect("local 10 on", false,
           "error: node 10 is an io node, not a drive: local is a drive's command; its commands "
           "are input, analog, state");
}
END_TEST

START_TEST(state_lines)
{
    expect("state 1", true,
           "ok node 1: nmt Pre-operational, model plc300, RUN blinking, ERR off, frames received "
           "0, sent 0, dropped 0, SDO requests 0, SDO aborts 0, EMCY 0, inputs %IB2000 E7 "
           "%IB2001 03, outputs none");
    expect("input 10 DI1 on", true, "ok node 10: DI1 on (6000h:01 = 01)");
    expect("state 10", true,
           "ok node 10: nmt Pre-operational, model io, RUN blinking, ERR off, frames received 0, "
           "sent 0, dropped 0, SDO requests 0, SDO aborts 0, EMCY 0, inputs DI1, outputs none, "
           "analog AI1 0 AI2 0, time none");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312d_plain_control");
    TCase *tc = tcase_create("plain");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, markers_read_and_written_as_the_program_would);
    tcase_add_test(tc, terminals_of_the_io_node);
    tcase_add_test(tc, every_plain_model_has_its_surface);
    tcase_add_test(tc, drive_commands_are_refused);
    tcase_add_test(tc, state_lines);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
