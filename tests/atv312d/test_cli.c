/* SPDX-License-Identifier: Apache-2.0 */
/* The atv312d command line: node-id forms, duplicates and ranges, the model of each --node-id,
 * every usage error with its exit code and a message naming what would be right. */
#include "atv31/atv31.h"
#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "atv312d/options.h"
#include "atv58/atv58.h"
#include "check_main.h"
#include "nodes/io/io401.h"
#include "nodes/plc300/plc300.h"

#include <check.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

static atv312d_options_t opts;
static char err[256];

/* Parses a NULL-terminated list of arguments after the program name. */
static int parse(const char *first, ...)
{
    char *argv[32] = {"atv312d"};
    int argc = 1;
    va_list args;
    va_start(args, first);
    for (const char *a = first; a; a = va_arg(args, const char *))
        argv[argc++] = (char *)a;
    va_end(args);
    err[0] = '\0';
    return atv312d_parse_args(argc, argv, &opts, err, sizeof err);
}

static void assert_ids(size_t count, const uint8_t *ids)
{
    ck_assert_uint_eq(opts.node_count, count);
    ck_assert_mem_eq(opts.node_ids, ids, count);
}

START_TEST(single_node_with_defaults)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", NULL), 0);
    ck_assert_str_eq(opts.iface, "vcan0");
    assert_ids(1, (const uint8_t[]){4});
    ck_assert_ptr_null(opts.store_path);
    ck_assert_ptr_null(opts.trace_path);
    ck_assert_ptr_null(opts.control_path);
    ck_assert_ptr_null(opts.status_path);
    ck_assert_int_eq(opts.log_level, CO_LOG_INFO);
    ck_assert(!opts.help && !opts.version);
    ck_assert_str_eq(opts.models[0].name, "atv312");
    ck_assert_ptr_eq(opts.models[0].drive->profile, &atv312_profile);
}
END_TEST

/* --model names the model of the node-ids of the --node-id just before it; the others are the
 * default's. */
START_TEST(model_of_each_node_id_group)
{
    const drive_model_t *atv312 = drive_model_find("atv312");
    ck_assert_ptr_nonnull(atv312);
    ck_assert_ptr_eq(atv312, &drive_models[0]);
    ck_assert_int_eq(parse("vcan0", "--node-id", "6", "--node-id", "4-5", "--model=atv312", NULL),
                     0);
    assert_ids(3, (const uint8_t[]){4, 5, 6});
    for (size_t i = 0; i < 3; i++)
        ck_assert_ptr_eq(opts.models[i].drive, atv312);
    ck_assert_int_eq(parse("--node-id", "4", "--model", "atv312", "vcan0", NULL), 0);
    ck_assert_ptr_eq(opts.models[0].drive, atv312);
    ck_assert_ptr_null(drive_model_find("ATV312"));
    /* A mixed bench: the ATV31 of firmware V1.2 and the one before, beside the default. */
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--node-id", "5", "--model", "atv31",
                           "--node-id", "6", "--model", "atv31-v1.1", NULL),
                     0);
    assert_ids(3, (const uint8_t[]){4, 5, 6});
    ck_assert_ptr_eq(opts.models[0].drive->profile, &atv312_profile);
    ck_assert_ptr_eq(opts.models[1].drive->profile, &atv31_profile);
    ck_assert_ptr_eq(opts.models[2].drive->profile, &atv31_v11_profile);
}
END_TEST

START_TEST(model_errors)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--model", "atv99", NULL), EX_USAGE);
    ck_assert_str_eq(
        err, "--model: unknown model 'atv99': the models are atv312, atv31, atv31-v1.1, atv58, "
             "plc300, io");
    ck_assert_int_eq(parse("vcan0", "--model", "atv312", "--node-id", "4", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--model atv312: no --node-id before it: a model follows the node-ids "
                          "of its drives, e.g. --node-id 4 --model atv312 (--mac-id 25 --model "
                          "atv312 on DeviceNet), or comes just before --unconfigured: --model io "
                          "--unconfigured 20");
    ck_assert_int_eq(
        parse("vcan0", "--node-id", "4", "--model", "atv312", "--model", "atv312", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--model atv312: the nodes of the --node-id before it are already "
                          "atv312: give one --model after each --node-id");
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--model", NULL), EX_USAGE);
    ck_assert_str_eq(err, "option --model needs a value: give --model M");
}
END_TEST

/* --canopen-off (docs/decisions.md, D-ADCO-BDCO): the drives of the --node-id before it have AdCO
 * = 0, the others not; refused before any --node-id, for a model without AdCO (the atv58, the
 * plain nodes) and on DeviceNet. */
START_TEST(canopen_off_of_a_group)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "5-6", "--canopen-off", "--node-id", "4", NULL),
                     0);
    assert_ids(3, (const uint8_t[]){4, 5, 6});
    ck_assert(!opts.can_off[0]);
    ck_assert(opts.can_off[1]);
    ck_assert(opts.can_off[2]);
    ck_assert_int_eq(parse("vcan0", "--canopen-off", "--node-id", "4", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--canopen-off: no --node-id before it: it follows the node-ids of its "
                          "drives, e.g. --node-id 4 --canopen-off");
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--model", "atv58", "--canopen-off", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--canopen-off: the atv58 has no AdCO (its node-id is set on its card): "
                          "CANopen off is the atv312's and the atv31's AdCO = 0");
    ck_assert_int_eq(parse("vcan0", "--devicenet", "--mac-id", "4", "--canopen-off", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--canopen-off: AdCO is the CANopen port's address; a DeviceNet drive "
                          "is on the bus by its card's MAC ID: leave --canopen-off out");
    ck_assert_int_eq(parse("vcan0", "--node-id", "10", "--model", "io", "--canopen-off", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--canopen-off: the io is a plain node, not a drive: it has no AdCO, "
                          "CANopen off is the atv312's and the atv31's AdCO = 0; leave "
                          "--canopen-off out");
    ck_assert_int_eq(parse("vcan0", "--node-id", "1", "--model", "plc300", "--canopen-off", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--canopen-off: the plc300 is a plain node, not a drive: it has no AdCO, "
                          "CANopen off is the atv312's and the atv31's AdCO = 0; leave "
                          "--canopen-off out");
}
END_TEST

/* The ATV58's card takes node-ids 1..63 (its address switches): one above is refused, naming the
 * range, and the same id is fine for the other models. */
START_TEST(atv58_node_ids_up_to_63)
{
    ck_assert_int_eq(
        parse("vcan0", "--node-id", "4", "--node-id", "60-64", "--model", "atv58", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--node-id 64: the atv58 takes node-ids 1..63, give it one of those");
    ck_assert_int_eq(parse("vcan0", "--node-id", "64", "--model", "atv31", "--node-id", "1,63",
                           "--model", "atv58", NULL),
                     0);
    assert_ids(3, (const uint8_t[]){1, 63, 64});
    ck_assert_ptr_eq(opts.models[0].drive->profile, &atv58_profile);
    ck_assert_ptr_eq(opts.models[1].drive->profile, &atv58_profile);
    ck_assert_ptr_eq(opts.models[2].drive->profile, &atv31_profile);
}
END_TEST

/* --help lists every model with its description, the default first. */
START_TEST(help_lists_the_models)
{
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    ck_assert_ptr_nonnull(out);
    atv312d_print_usage(out);
    fclose(out);
    ck_assert_msg(strstr(text, "(default atv312)") != NULL, "%s", text);
    for (size_t i = 0; i < atv312d_model_count(); i++)
        ck_assert_msg(strstr(text, atv312d_model_at(i).description) != NULL, "%s", text);
    ck_assert_msg(strstr(text, "a drive or a node, one of:") != NULL, "%s", text);
    free(text);
}
END_TEST

/* Drives and plain nodes on one bus: each --node-id group its model and the model's kind. */
START_TEST(plain_nodes_beside_drives)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--node-id", "10-11", "--model", "io",
                           "--node-id", "1", "--model", "plc300", NULL),
                     0);
    ck_assert_uint_eq(opts.node_count, 4);
    ck_assert_uint_eq(opts.node_ids[0], 1);
    ck_assert_str_eq(opts.models[0].name, "plc300");
    ck_assert_int_eq(opts.models[0].kind, ATV312D_KIND_NODE);
    ck_assert_ptr_eq(opts.models[0].node, &plc300_model);
    ck_assert_ptr_null(opts.models[0].drive);
    ck_assert_int_eq(opts.models[1].kind, ATV312D_KIND_DRIVE);
    ck_assert_ptr_eq(opts.models[1].drive->profile, &atv312_profile);
    ck_assert_ptr_eq(opts.models[2].node, &io401_model);
    ck_assert_ptr_eq(opts.models[3].node, &io401_model);
    ck_assert_str_eq(atv312d_kind_name(opts.models[3].kind), "node");
}
END_TEST

START_TEST(plain_nodes_have_no_devicenet_card)
{
    ck_assert_int_eq(parse("vcan0", "--devicenet", "--mac-id", "5", "--model", "io", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--model io: the io has no DeviceNet card here: on DeviceNet give "
                          "--model atv312, or leave --model out");
}
END_TEST

/* --unconfigured N: N nodes with node-id FFh after those with node-ids, of the --model just
 * before or after it, which must have LSS. */
START_TEST(unconfigured_nodes_of_a_model_with_lss)
{
    ck_assert_int_eq(parse("vcan0", "--model", "io", "--unconfigured", "20", NULL), 0);
    ck_assert_uint_eq(opts.node_count, 20);
    for (size_t i = 0; i < 20; i++) {
        ck_assert_uint_eq(opts.node_ids[i], CO_LSS_NODE_ID_UNCONFIGURED);
        ck_assert_ptr_eq(opts.models[i].node, &io401_model);
    }
    ck_assert_int_eq(parse("vcan0", "--unconfigured", "2", "--model", "io", "--node-id", "4",
                           "--node-id", "10", "--model", "io", NULL),
                     0);
    assert_ids(4, (const uint8_t[]){4, 10, 0xFF, 0xFF});
    ck_assert_ptr_eq(opts.models[0].drive->profile, &atv312_profile);
    ck_assert_ptr_eq(opts.models[1].node, &io401_model);
    ck_assert_ptr_eq(opts.models[3].node, &io401_model);
}
END_TEST

START_TEST(unconfigured_refused_without_lss)
{
    ck_assert_int_eq(parse("vcan0", "--unconfigured", "3", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--unconfigured 3: the atv312 has no LSS (CiA 305), so it cannot start "
                          "without node-id: give --model io --unconfigured 3, or give the atv312 "
                          "--node-id");
    ck_assert_int_eq(parse("vcan0", "--model", "plc300", "--unconfigured", "3", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--unconfigured 3: the plc300 has no LSS (CiA 305), so it cannot start "
                          "without node-id: give --model io --unconfigured 3, or give the plc300 "
                          "--node-id");
    ck_assert_int_eq(parse("vcan0", "--devicenet", "--model", "io", "--unconfigured", "3", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--unconfigured 3: nodes without node-id wait for a CANopen LSS master "
                          "(CiA 305); --devicenet makes vcan0 a DeviceNet bus, which has no LSS: "
                          "leave --devicenet out, or give the drives --mac-id 0..63");
    ck_assert_int_eq(parse("vcan0", "--unconfigured", "0", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--unconfigured 0: give the number of nodes without node-id, 1..127, "
                          "e.g. --model io --unconfigured 20");
    ck_assert_int_eq(parse("vcan0", "--node-id", "1-10", "--model", "io", "--model", "io",
                           "--unconfigured", "118", NULL),
                     EX_USAGE);
    ck_assert_str_eq(err, "--unconfigured 118: with the other nodes that is 128 nodes, and a "
                          "CANopen bus numbers at most 127");
    ck_assert_int_eq(parse("vcan0", "--model", "io", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--model io: no --node-id before it: a model follows the node-ids of its "
                          "drives, e.g. --node-id 4 --model io (--mac-id 25 --model io on "
                          "DeviceNet), or comes just before --unconfigured: --model io "
                          "--unconfigured 20");
}
END_TEST

START_TEST(every_option_in_both_spellings)
{
    ck_assert_int_eq(parse("--node-id=0x7F", "--store", "/tmp/s", "--trace=-", "--log-level",
                           "debug", "--control=/tmp/c.sock", "--status", "/tmp/st", "can1", NULL),
                     0);
    ck_assert_str_eq(opts.control_path, "/tmp/c.sock");
    ck_assert_str_eq(opts.status_path, "/tmp/st");
    ck_assert_str_eq(opts.iface, "can1");
    assert_ids(1, (const uint8_t[]){127});
    ck_assert_str_eq(opts.store_path, "/tmp/s");
    ck_assert_str_eq(opts.trace_path, "-");
    ck_assert_int_eq(opts.log_level, CO_LOG_DEBUG);
}
END_TEST

START_TEST(ranges_lists_and_repeats_are_sorted)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "7-9", "--node-id", "2,4", "--node-id=1", NULL),
                     0);
    assert_ids(6, (const uint8_t[]){1, 2, 4, 7, 8, 9});
    ck_assert_int_eq(parse("vcan0", "--node-id", "1-127", NULL), 0);
    ck_assert_uint_eq(opts.node_count, 127);
    ck_assert_uint_eq(opts.node_ids[126], 127);
    ck_assert_int_eq(parse("vcan0", "--node-id", "5-5", NULL), 0);
    assert_ids(1, (const uint8_t[]){5});
}
END_TEST

START_TEST(out_of_range_names_the_range)
{
    static const char *const bad[] = {"0", "128", "0-4", "120-130", "300"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ck_assert_int_eq(parse("vcan0", "--node-id", bad[i], NULL), EX_USAGE);
        ck_assert_msg(strstr(err, "1..127") != NULL, "%s: %s", bad[i], err);
        ck_assert_msg(strstr(err, "out of range") != NULL, "%s: %s", bad[i], err);
    }
}
END_TEST

START_TEST(malformed_node_ids)
{
    static const char *const bad[] = {"abc", "4x", "-4", "4-", "-", "4,,5", "", "+4", "0x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ck_assert_msg(parse("vcan0", "--node-id", bad[i], NULL) == EX_USAGE, "accepted '%s'",
                      bad[i]);
        ck_assert_msg(strstr(err, "--node-id") != NULL, "%s: %s", bad[i], err);
    }
    ck_assert_int_eq(parse("vcan0", "--node-id", "9-4", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--node-id: range 9-4 is backwards: write it as 4-9");
}
END_TEST

START_TEST(duplicates_are_refused)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "4-9", "--node-id", "5", NULL), EX_USAGE);
    ck_assert_str_eq(err,
                     "--node-id: node-id 5 is given twice: each drive needs its own node-id in "
                     "1..127");
    ck_assert_int_eq(parse("vcan0", "--node-id", "4,0x4", NULL), EX_USAGE);
    ck_assert(strstr(err, "node-id 4 is given twice") != NULL);
}
END_TEST

START_TEST(missing_pieces)
{
    ck_assert_int_eq(parse("--node-id", "4", NULL), EX_USAGE);
    ck_assert(strstr(err, "missing interface") != NULL);
    ck_assert_int_eq(parse("vcan0", NULL), EX_USAGE);
    ck_assert(strstr(err, "missing --node-id") != NULL);
    ck_assert_int_eq(parse("vcan0", "--node-id", NULL), EX_USAGE);
    ck_assert_str_eq(err, "option --node-id needs a value: give --node-id N");
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--store=", NULL), EX_USAGE);
    ck_assert_str_eq(err, "option --store needs a value: give --store FILE");
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--http", "", NULL), EX_USAGE);
    ck_assert_str_eq(err, "option --http needs a value: give --http [ADDRESS:]PORT");
}
END_TEST

START_TEST(unknown_options_and_extra_arguments)
{
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--bitrate", "250000", NULL), EX_USAGE);
    ck_assert_str_eq(err, "unknown option '--bitrate'");
    ck_assert_int_eq(parse("vcan0", "vcan1", "--node-id", "4", NULL), EX_USAGE);
    ck_assert(strstr(err, "'vcan1'") != NULL);
    ck_assert_int_eq(parse("vcan0", "--help=yes", NULL), EX_USAGE);
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", "--log-level", "verbose", NULL), EX_USAGE);
    ck_assert_str_eq(err, "--log-level: unknown level 'verbose': use error, warn, info or debug");
    ck_assert_int_eq(parse("averyverylongname0", "--node-id", "4", NULL), EX_USAGE);
    ck_assert(strstr(err, "at most 15 characters") != NULL);
}
END_TEST

START_TEST(help_and_version_win)
{
    ck_assert_int_eq(parse("--help", NULL), 0);
    ck_assert(opts.help);
    ck_assert_int_eq(parse("-V", "--node-id", "0", NULL), 0);
    ck_assert(opts.version);
    ck_assert_int_eq(parse("vcan0", "--node-id", "0", "--help", NULL), EX_USAGE);
}
END_TEST

/* --devicenet: the drives on a DeviceNet bus, at MAC ID 63 when none is given, 125 kbit/s. */
START_TEST(devicenet_defaults)
{
    ck_assert_int_eq(parse("vcan1", "--devicenet", NULL), 0);
    ck_assert(opts.devicenet);
    assert_ids(1, (const uint8_t[]){63});
    ck_assert_str_eq(opts.models[0].name, "atv312");
    ck_assert_ptr_eq(opts.models[0].drive->devicenet, &atv312_devicenet_profile);
    ck_assert_int_eq(opts.baud, ATV312D_BAUD_125K);
    ck_assert_int_eq(parse("vcan0", "--node-id", "4", NULL), 0);
    ck_assert(!opts.devicenet);
}
END_TEST

/* MAC IDs are written like node-ids (ranges, lists, repeats, --model after them), 0..63. */
START_TEST(devicenet_mac_ids_and_baud)
{
    ck_assert_int_eq(parse("--mac-id", "25", "vcan1", "--devicenet", "--mac-id=0,62-63", "--model",
                           "atv312", "--baud", "500k", NULL),
                     0);
    assert_ids(4, (const uint8_t[]){0, 25, 62, 63});
    for (size_t i = 0; i < 4; i++)
        ck_assert_str_eq(opts.models[i].name, "atv312");
    ck_assert_int_eq(opts.baud, ATV312D_BAUD_500K);
    ck_assert_int_eq(parse("vcan1", "--devicenet", "--baud=250k", NULL), 0);
    ck_assert_int_eq(opts.baud, ATV312D_BAUD_250K);
    ck_assert_int_eq(parse("vcan1", "--devicenet", "--mac-id", "0-63", NULL), 0);
    ck_assert_uint_eq(opts.node_count, 64);
}
END_TEST

START_TEST(devicenet_errors)
{
    static const struct {
        const char *args[8];
        const char *message;
    } cases[] = {
        {{"vcan1", "--devicenet", "--mac-id", "64"},
         "--mac-id: 64 is out of range: MAC IDs are 0..63"},
        {{"vcan1", "--devicenet", "--mac-id", "x"},
         "--mac-id: 'x' is not a MAC ID: use a number 0..63, a range like 4-9 or a list like 4,6"},
        {{"vcan1", "--devicenet", "--mac-id", "9-4"},
         "--mac-id: range 9-4 is backwards: write it as 4-9"},
        {{"vcan1", "--devicenet", "--mac-id", "25", "--mac-id", "20-30"},
         "--mac-id: MAC ID 25 is given twice: each drive needs its own MAC ID in 0..63"},
        {{"vcan1", "--mac-id", "25"},
         "--mac-id 25: MAC IDs are DeviceNet's and this interface is CANopen: add --devicenet to "
         "put the drives on DeviceNet"},
        {{"vcan1", "--node-id", "4", "--baud", "125k"},
         "--baud: the data rate is DeviceNet's (its DeviceNet object reports it): add "
         "--devicenet; a CANopen interface's bitrate is set with ip link"},
        {{"vcan1", "--devicenet", "--node-id", "4"},
         "--node-id 4: --devicenet makes vcan1 a DeviceNet bus, whose drives have MAC IDs: give "
         "--mac-id 0..63 instead (one interface is either CANopen or DeviceNet: run one atv312d "
         "per bus)"},
        {{"vcan1", "--mac-id", "25", "--node-id", "4-5", "--devicenet"},
         "--node-id 4-5: --devicenet makes vcan1 a DeviceNet bus, whose drives have MAC IDs: give "
         "--mac-id 0..63 instead (one interface is either CANopen or DeviceNet: run one atv312d "
         "per bus)"},
        {{"vcan1", "--node-id", "4", "--mac-id", "25"},
         "--mac-id 25: MAC IDs are DeviceNet's and this interface is CANopen: add --devicenet to "
         "put the drives on DeviceNet"},
        {{"vcan1", "--devicenet", "--mac-id", "25", "--model", "atv31"},
         "--model atv31: the atv31 has no DeviceNet card here: on DeviceNet give --model atv312, "
         "or leave --model out"},
        {{"vcan1", "--mac-id", "1", "--model", "atv58", "--mac-id", "2", "--devicenet"},
         "--model atv58: the atv58 has no DeviceNet card here: on DeviceNet give --model atv312, "
         "or leave --model out"},
        {{"vcan1", "--devicenet", "--baud", "1M"},
         "--baud: unknown data rate '1M': DeviceNet runs at 125k, 250k or 500k"},
        {{"vcan1", "--devicenet=yes"}, "unknown option '--devicenet=yes'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *argv[10] = {"atv312d"};
        int argc = 1;
        for (size_t k = 0; k < 8 && cases[i].args[k]; k++)
            argv[argc++] = (char *)cases[i].args[k];
        ck_assert_int_eq(atv312d_parse_args(argc, argv, &opts, err, sizeof err), EX_USAGE);
        ck_assert_str_eq(err, cases[i].message);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cli");
    TCase *tc = tcase_create("cli");
    tcase_add_test(tc, single_node_with_defaults);
    tcase_add_test(tc, model_of_each_node_id_group);
    tcase_add_test(tc, model_errors);
    tcase_add_test(tc, canopen_off_of_a_group);
    tcase_add_test(tc, atv58_node_ids_up_to_63);
    tcase_add_test(tc, help_lists_the_models);
    tcase_add_test(tc, plain_nodes_beside_drives);
    tcase_add_test(tc, plain_nodes_have_no_devicenet_card);
    tcase_add_test(tc, every_option_in_both_spellings);
    tcase_add_test(tc, ranges_lists_and_repeats_are_sorted);
    tcase_add_test(tc, out_of_range_names_the_range);
    tcase_add_test(tc, malformed_node_ids);
    tcase_add_test(tc, duplicates_are_refused);
    tcase_add_test(tc, missing_pieces);
    tcase_add_test(tc, unknown_options_and_extra_arguments);
    tcase_add_test(tc, help_and_version_win);
    tcase_add_test(tc, devicenet_defaults);
    tcase_add_test(tc, devicenet_mac_ids_and_baud);
    tcase_add_test(tc, devicenet_errors);
    tcase_add_test(tc, unconfigured_nodes_of_a_model_with_lss);
    tcase_add_test(tc, unconfigured_refused_without_lss);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
