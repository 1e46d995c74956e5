/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace's decoder on lists of frames, each with the exact line it must give: every service,
 * SDO transfers followed across frames, PDOs decoded through an EDS, malformed frames. */
#include "atv58/atv58_emcy.h"
#include "check_main.h"
#include "co_linux/candump.h"
#include "trace/decoder.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct step {
    const char *frame; /* candump -L ID#DATA */
    const char *meaning;
} step_t;

static struct can_frame parse_frame(const char *text)
{
    struct can_frame f;
    struct timespec wall;
    char iface[IFNAMSIZ];
    char line[128];
    snprintf(line, sizeof line, "(1700000000.000000) vcan0 %s", text);
    ck_assert_msg(co_candump_parse(line, &wall, iface, &f), "bad test frame %s", text);
    return f;
}

static void play(cotrace_decoder_t *dec, const step_t *steps, size_t n)
{
    char out[1024];
    for (size_t i = 0; i < n; i++) {
        struct can_frame f = parse_frame(steps[i].frame);
        cotrace_decode(dec, &f, out, sizeof out);
        ck_assert_msg(strcmp(out, steps[i].meaning) == 0, "%s:\n  got      '%s'\n  expected '%s'",
                      steps[i].frame, out, steps[i].meaning);
    }
}

#define PLAY(dec, steps) play(dec, steps, sizeof(steps) / sizeof((steps)[0]))

static cotrace_decoder_t dec;

static void plain(void)
{
    cotrace_decoder_init(&dec, NULL, 0, NULL);
}

START_TEST(nmt_commands)
{
    static const step_t steps[] = {
        {"000#0104", "NMT Start remote node, node 4"},
        {"000#0200", "NMT Stop remote node, all nodes"},
        {"000#8004", "NMT Enter pre-operational, node 4"},
        {"000#817F", "NMT Reset node, node 127"},
        {"000#8200", "NMT Reset communication, all nodes"},
        {"000#0504", "NMT unknown command 0x05, node 4"},
        {"000#0180", "NMT Start remote node, node 128 (not a node-id)"},
        {"000#01", "NMT malformed: 1 bytes, a command has 2 (command, node-id)"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(sync_and_time)
{
    static const step_t steps[] = {
        {"080#", "SYNC"},
        {"080#05", "SYNC counter 5"},
        {"080#0102", "SYNC malformed: 2 bytes, a SYNC has none or 1 (counter)"},
        {"100#80EE3603A515", "TIME 1999-03-04 14:58:51.648"},
        {"100#000000000000", "TIME 1984-01-01 00:00:00.000"},
        {"100#0000", "TIME malformed: 2 bytes, a TIME_OF_DAY has 6"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(emcy)
{
    static const step_t steps[] = {
        {"084#3081110102030405",
         "EMCY node 4: 0x8130 life guard error or heartbeat error, error register 0x11 (generic, "
         "communication), manufacturer bytes 01 02 03 04 05"},
        {"0FF#0000000000000000",
         "EMCY node 127: 0x0000 error reset or no error, error register 0x00, manufacturer bytes "
         "00 00 00 00 00"},
        {"084#1023A1", "EMCY node 4 malformed: EMCY frame shorter than 8 bytes (3 bytes)"},
    };
    PLAY(&dec, steps);
    cotrace_decoder_init(&dec, NULL, 0, &atv58_emcy_table);
    static const step_t atv58[] = {
        {"085#1023010000000000", "EMCY node 5: 0x2310 OCF: overcurrent fault (ATV58), error "
                                 "register 0x01 (generic), manufacturer bytes 00 00 00 00 00"},
    };
    PLAY(&dec, atv58);
}
END_TEST

START_TEST(heartbeat_and_guarding)
{
    static const step_t steps[] = {
        {"704#00", "boot-up, node 4"},
        {"704#7F", "heartbeat, node 4: Pre-operational"},
        {"704#05", "heartbeat, node 4: Operational"},
        {"704#R", "guarding request, node 4"},
        {"704#85", "guarding reply, node 4: Operational, toggle 1"},
        {"704#R", "guarding request, node 4"},
        {"705#04", "heartbeat, node 5: Stopped"},
        {"704#04", "guarding reply, node 4: Stopped, toggle 0"},
        {"704#7F", "heartbeat, node 4: Pre-operational"},
        {"704#42", "heartbeat, node 4: unknown state 0x42"},
        {"704#0505", "heartbeat malformed: node 4, 2 bytes, a heartbeat or guarding reply has 1"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(sdo_expedited_and_aborts)
{
    static const step_t steps[] = {
        {"604#4018100100000000", "SDO 4 request: upload 1018:01"},
        {"584#431810015F000000", "SDO 4 reply: upload 1018:01 = 5F 00 00 00 (95)"},
        {"604#2B3C20020A000000", "SDO 4 request: download 203C:02 = 0A 00 (10)"},
        {"584#603C200200000000", "SDO 4 reply: download 203C:02 done"},
        {"604#2300100000000000", "SDO 4 request: download 1000:00 = 00 00 00 00 (0)"},
        {"584#8000100002000106",
         "SDO 4 reply: abort 1000:00: 0x06010002 attempt to write a read only object"},
        {"604#8008100000000405", "SDO 4 request: abort 1008:00: 0x05040000 SDO protocol timed out"},
        {"584#8000100000000000", "SDO 4 reply: abort 1000:00: 0x00000000 unknown abort code"},
        {"584#80001000", "SDO 4 reply: abort, malformed: 4 bytes, an abort has 8"},
        {"604#40001000", "SDO 4 request: malformed: 4 bytes, an SDO request has 8"},
        {"604#E000000000000000", "SDO 4 request: unknown command 0xE0"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* The value of a segmented upload is shown with its last segment: it came in pieces. */
START_TEST(sdo_segmented_upload_followed)
{
    static const step_t steps[] = {
        {"604#4008100000000000", "SDO 4 request: upload 1008:00"},
        {"584#410810000A000000", "SDO 4 reply: upload 1008:00, 10 bytes, segmented"},
        {"604#6000000000000000", "SDO 4 request: upload segment, toggle 0"},
        {"584#0041545633313220", "SDO 4 reply: upload segment, toggle 0, 7 bytes: \"ATV312 \""},
        {"604#7000000000000000", "SDO 4 request: upload segment, toggle 1"},
        {"584#1976322E31000000", "SDO 4 reply: upload segment, toggle 1, 3 bytes: \"v2.\", last: "
                                 "1008:00 = \"ATV312 v2.\" (10 bytes)"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(sdo_segmented_download_followed)
{
    static const step_t steps[] = {
        {"605#2146600204000000", "SDO 5 request: download 6046:02, 4 bytes, segmented"},
        {"585#6046600200000000", "SDO 5 reply: download 6046:02 accepted, send the segments"},
        {"605#07DC050000000000",
         "SDO 5 request: download segment, toggle 0, 4 bytes: DC 05 00 00 (1500), last"},
        {"585#2000000000000000", "SDO 5 reply: download segment, toggle 0, received: done, "
                                 "6046:02 = DC 05 00 00 (1500) (4 bytes)"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* Two blocks of two segments; the server acknowledges only one segment of the second block, so
 * the client sends it again: the bytes counted are those acknowledged. */
START_TEST(sdo_block_download_followed)
{
    static const step_t steps[] = {
        {"604#C2501F0110000000", "SDO 4 request: block download 1F50:01, 16 bytes, no CRC"},
        {"584#A4501F0102000000",
         "SDO 4 reply: block download 1F50:01 accepted, blocks of 2 segments"},
        {"604#0101020304050607", "SDO 4 request: block download segment 1: 01 02 03 04 05 06 07"},
        {"604#0208090A0B0C0D0E", "SDO 4 request: block download segment 2: 08 09 0A 0B 0C 0D 0E"},
        {"584#A202020000000000",
         "SDO 4 reply: block download ack: received up to segment 2, next block size 2"},
        {"604#810F100000000000",
         "SDO 4 request: block download segment 1: 0F 10 00 00 00 00 00, last"},
        {"584#A200020000000000",
         "SDO 4 reply: block download ack: received up to segment 0, next block size 2"},
        {"604#810F100000000000",
         "SDO 4 request: block download segment 1: 0F 10 00 00 00 00 00, last"},
        {"584#A201020000000000",
         "SDO 4 reply: block download ack: received up to segment 1, next block size 2"},
        {"604#D534120000000000",
         "SDO 4 request: block download end: 5 bytes unused in the last segment, CRC 0x1234"},
        {"584#A100000000000000", "SDO 4 reply: block download done: 1F50:01 = 01 02 03 04 05 06 "
                                 "07 08 09 0A 0B 0C 0D 0E 0F 10 (16 bytes)"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(sdo_block_upload_followed)
{
    static const step_t steps[] = {
        {"604#A40810007F000000",
         "SDO 4 request: block upload 1008:00, blocks of 127 segments, CRC"},
        {"584#C608100006000000", "SDO 4 reply: block upload 1008:00, 6 bytes, CRC"},
        {"604#A300000000000000", "SDO 4 request: block upload start"},
        {"584#8141545633313200", "SDO 4 reply: block upload segment 1: 41 54 56 33 31 32 00, last"},
        {"604#A2017F0000000000",
         "SDO 4 request: block upload ack: received up to segment 1, next block size 127"},
        {"584#C5665D0000000000",
         "SDO 4 reply: block upload end: 1 bytes unused in the last segment, CRC 0x5D66"},
        {"604#A100000000000000",
         "SDO 4 request: block upload end confirmed: 1008:00 = \"ATV312\" (6 bytes)"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* An abort in the middle of a sub-block is an abort (sequence number 0 does not exist), a short
 * frame there is not a segment, and the transfer ends. */
START_TEST(sdo_block_abort_in_subblock)
{
    static const step_t steps[] = {
        {"604#C6501F0110000000", "SDO 4 request: block download 1F50:01, 16 bytes, CRC"},
        {"584#A4501F0102000000",
         "SDO 4 reply: block download 1F50:01 accepted, blocks of 2 segments"},
        {"604#0101", "SDO 4 request: malformed: 2 bytes, an SDO request has 8"},
        {"604#80501F0100000405", "SDO 4 request: abort 1F50:01: 0x05040000 SDO protocol timed out"},
        {"604#0101020304050607", "SDO 4 request: download segment, toggle 0, 7 bytes: 01 02 03 "
                                 "04 05 06 07, last"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* Transfers of different nodes interleave without mixing. */
START_TEST(sdo_transfers_per_node)
{
    static const step_t steps[] = {
        {"604#4008100000000000", "SDO 4 request: upload 1008:00"},
        {"605#4009100000000000", "SDO 5 request: upload 1009:00"},
        {"584#4108100002000000", "SDO 4 reply: upload 1008:00, 2 bytes, segmented"},
        {"585#4109100001000000", "SDO 5 reply: upload 1009:00, 1 bytes, segmented"},
        {"604#6000000000000000", "SDO 4 request: upload segment, toggle 0"},
        {"605#6000000000000000", "SDO 5 request: upload segment, toggle 0"},
        {"585#0D41000000000000",
         "SDO 5 reply: upload segment, toggle 0, 1 bytes: \"A\", last: 1009:00 = \"A\" (1 bytes)"},
        {"584#0B4F4B0000000000", "SDO 4 reply: upload segment, toggle 0, 2 bytes: \"OK\", last: "
                                 "1008:00 = \"OK\" (2 bytes)"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(pdos_without_eds)
{
    static const step_t steps[] = {
        {"184#2106", "TPDO1 node 4: 21 06"},
        {"204#0F00", "RPDO1 node 4: 0F 00"},
        {"284#", "TPDO2 node 4: no data"},
        {"504#01", "RPDO4 node 4: 01"},
        {"484#R", "TPDO4 node 4: remote request"},
        {"180#01", "COB-ID 0x180: no predefined meaning"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(pdos_with_eds)
{
    eds_t eds;
    char err[256];
    ck_assert_int_eq(eds_load(&eds, COTRACE_TEST_EDS, 4, err, sizeof err), EDS_OK);
    cotrace_decoder_init(&dec, &eds, 4, NULL);
    static const step_t steps[] = {
        {"284#27062C01", "TPDO6 node 4: 6041:00 Statusword (ETAD) = 0x0627 Operation enabled, "
                         "6044:00 vl velocity actual value (RFRD) = 300"},
        {"304#0F00D4FE", "RPDO6 node 4: 6040:00 Controlword (CMDD) = 0x000F Enable operation, "
                         "6042:00 vl target velocity (LFRD) = -300"},
        {"184#4006", "TPDO1 node 4: 6041:00 Statusword (ETAD) = 0x0640 Switch on disabled"},
        {"284#2706", "TPDO6 node 4: 2 bytes do not fit the mapping 1A05 of the EDS: 27 06"},
        {"185#4006", "TPDO1 node 5: 40 06"},
        {"604#4008100000000000", "SDO 4 request: upload 1008:00 Manufacturer device name"},
        {"605#4008100000000000", "SDO 5 request: upload 1008:00"},
    };
    PLAY(&dec, steps);
    eds_free(&eds);
}
END_TEST

/* Every LSS frame of CiA 305 by name, both ways, and what is not one. */
START_TEST(lss_frames)
{
    static const step_t steps[] = {
        {"7E5#0401000000000000", "LSS switch state global: configuration"},
        {"7E5#0400000000000000", "LSS switch state global: waiting"},
        {"7E5#0402000000000000", "LSS switch state global: unknown state 2"},
        {"7E5#405F000000000000", "LSS switch state selective vendor-ID 0x0000005F"},
        {"7E5#4112030000000000", "LSS switch state selective product code 0x00000312"},
        {"7E5#4202000100000000", "LSS switch state selective revision 0x00010002"},
        {"7E5#4378563412000000", "LSS switch state selective serial 0x12345678"},
        {"7E4#4400000000000000", "LSS switch state selective response"},
        {"7E5#1105000000000000", "LSS configure node-ID 5"},
        {"7E5#11FF000000000000", "LSS configure node-ID 255 (none)"},
        {"7E5#1180000000000000", "LSS configure node-ID 128 (not a node-id)"},
        {"7E4#1100000000000000", "LSS configure node-ID answer: done"},
        {"7E4#1101000000000000", "LSS configure node-ID answer: error 1 (node-ID out of range)"},
        {"7E5#1300040000000000", "LSS configure bit timing table 0 index 4 (125 kbit/s)"},
        {"7E5#1300090000000000",
         "LSS configure bit timing table 0 index 9 (automatic bit rate detection)"},
        {"7E5#1300050000000000", "LSS configure bit timing table 0 index 5 (not in the table)"},
        {"7E5#1381020000000000", "LSS configure bit timing table 129 index 2"},
        {"7E4#1301000000000000",
         "LSS configure bit timing answer: error 1 (bit timing not supported)"},
        {"7E5#1564000000000000", "LSS activate bit timing, switch delay 100 ms"},
        {"7E5#1700000000000000", "LSS store configuration"},
        {"7E4#1700000000000000", "LSS store configuration answer: done"},
        {"7E4#1701000000000000",
         "LSS store configuration answer: error 1 (store configuration not supported)"},
        {"7E4#1702000000000000",
         "LSS store configuration answer: error 2 (storage media access error)"},
        {"7E4#17FF420000000000",
         "LSS store configuration answer: error 255 (device-specific error 0x42)"},
        {"7E4#1703000000000000", "LSS store configuration answer: error 3 (reserved)"},
        {"7E5#5A00000000000000", "LSS inquire vendor-ID"},
        {"7E4#5A5F000000000000", "LSS inquire vendor-ID answer: 0x0000005F"},
        {"7E5#5B00000000000000", "LSS inquire product code"},
        {"7E4#5B12030000000000", "LSS inquire product code answer: 0x00000312"},
        {"7E5#5C00000000000000", "LSS inquire revision"},
        {"7E4#5C02000100000000", "LSS inquire revision answer: 0x00010002"},
        {"7E5#5D00000000000000", "LSS inquire serial"},
        {"7E4#5D78563412000000", "LSS inquire serial answer: 0x12345678"},
        {"7E5#5E00000000000000", "LSS inquire node-ID"},
        {"7E4#5E05000000000000", "LSS inquire node-ID answer: 5"},
        {"7E4#5EFF000000000000", "LSS inquire node-ID answer: 255 (none)"},
        {"7E5#465F000000000000", "LSS identify remote slave vendor-ID 0x0000005F"},
        {"7E5#4712030000000000", "LSS identify remote slave product code 0x00000312"},
        {"7E5#4800000000000000", "LSS identify remote slave revision low 0x00000000"},
        {"7E5#49FFFFFFFF000000", "LSS identify remote slave revision high 0xFFFFFFFF"},
        {"7E5#4A00000000000000", "LSS identify remote slave serial low 0x00000000"},
        {"7E5#4BFFFFFFFF000000", "LSS identify remote slave serial high 0xFFFFFFFF"},
        {"7E4#4F00000000000000", "LSS identify slave"},
        {"7E5#4C00000000000000", "LSS identify non-configured remote slave"},
        {"7E4#5000000000000000", "LSS identify non-configured slave"},
        {"7E5#5100000000800000", "LSS fastscan reset: every non-configured slave answers"},
        {"7E5#51000000001F0000", "LSS fastscan vendor-ID 0x00000000, bits 31..31, next vendor-ID"},
        {"7E5#5178563412000300", "LSS fastscan serial 0x12345678, bits 31..0, next vendor-ID"},
        {"7E5#5100000000200000", "LSS fastscan out of range: bit 32, LSS sub 0, next 0"},
        {"7E5#5100000000000400", "LSS fastscan out of range: bit 0, LSS sub 4, next 0"},
        {"7E5#4F00000000000000", "LSS master unknown command 0x4F"},
        {"7E4#0400000000000000", "LSS slave unknown command 0x04"},
        {"7E5#0500000000000000", "LSS master unknown command 0x05"},
        {"7E5#04010000", "LSS master malformed: 4 bytes, an LSS frame has 8"},
        {"7E4#R", "LSS slave malformed: 0 bytes, an LSS frame has 8"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(other_frames)
{
    static const step_t steps[] = {
        {"20000004#0020000000000000", "CAN error frame: controller problem (TX error passive)"},
        {"20000080#0000000000000000", "CAN error frame: bus error"},
        {"20000040#0000000000000000", "CAN error frame: bus off"},
        {"12345678#01", "29-bit identifier: not CANopen"},
        {"7FF#01", "COB-ID 0x7FF: no predefined meaning"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* A short buffer gets a truncated, terminated line. */
START_TEST(output_truncated_safely)
{
    char out[8];
    memset(out, 'x', sizeof out);
    struct can_frame f = parse_frame("000#0104");
    cotrace_decode(&dec, &f, out, sizeof out);
    ck_assert_str_eq(out, "NMT Sta");
}
END_TEST

START_TEST(eds_errors)
{
    eds_t eds;
    char err[256];
    ck_assert_int_eq(eds_load(&eds, "/nonexistent.eds", 4, err, sizeof err), EDS_CANNOT_READ);
    ck_assert_str_eq(err, "cannot read the EDS '/nonexistent.eds': No such file or directory");
    char path[] = "/tmp/cotrace-test-XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    FILE *f = fdopen(fd, "w");
    fputs("[1000]\nParameterName=Device type\nDataType=seven\n", f);
    fclose(f);
    ck_assert_int_eq(eds_load(&eds, path, 4, err, sizeof err), EDS_MALFORMED);
    char expected[256];
    snprintf(expected, sizeof expected, "%s:3: DataType 'seven' is not a number such as 0x0006",
             path);
    ck_assert_str_eq(err, expected);
    f = fopen(path, "w");
    fputs("[FileInfo]\nFileName=x.eds\n", f);
    fclose(f);
    ck_assert_int_eq(eds_load(&eds, path, 4, err, sizeof err), EDS_MALFORMED);
    snprintf(expected, sizeof expected, "%s: no object sections such as [1000]: not an EDS or DCF",
             path);
    ck_assert_str_eq(err, expected);
    unlink(path);
}
END_TEST

/* A DCF's ParameterValue wins over the EDS default, and $NODEID is the node's. */
START_TEST(dcf_values)
{
    char path[] = "/tmp/cotrace-test-XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    FILE *f = fdopen(fd, "w");
    fputs("[1800]\nParameterName=TPDO1\n[1800sub1]\nParameterName=COB-ID\nDataType=0x0007\n"
          "ParameterValue=0x190+$NODEID\nDefaultValue=$NODEID+0x180\n"
          "[1A00sub0]\nDefaultValue=1\n[1A00sub1]\nDefaultValue=0x20000008\n"
          "[2000]\nParameterName=Mode\nDataType=0x0002\n",
          f);
    fclose(f);
    eds_t eds;
    char err[256];
    ck_assert_int_eq(eds_load(&eds, path, 6, err, sizeof err), EDS_OK);
    unlink(path);
    const eds_entry_t *cob = eds_find(&eds, 0x1800, 1);
    ck_assert_ptr_nonnull(cob);
    ck_assert_uint_eq(cob->value, 0x196);
    ck_assert_str_eq(eds_name(&eds, 0x1800, 2), "TPDO1");
    ck_assert_ptr_null(eds_name(&eds, 0x1801, 0));
    cotrace_decoder_init(&dec, &eds, 6, NULL);
    static const step_t steps[] = {
        {"196#FE", "TPDO1 node 6: 2000:00 Mode = -2"},
        {"186#FE", "TPDO1 node 6: FE"},
    };
    PLAY(&dec, steps);
    eds_free(&eds);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cotrace_decoder");
    TCase *tc = tcase_create("decoder");
    tcase_add_checked_fixture(tc, plain, NULL);
    tcase_add_test(tc, nmt_commands);
    tcase_add_test(tc, lss_frames);
    tcase_add_test(tc, sync_and_time);
    tcase_add_test(tc, emcy);
    tcase_add_test(tc, heartbeat_and_guarding);
    tcase_add_test(tc, sdo_expedited_and_aborts);
    tcase_add_test(tc, sdo_segmented_upload_followed);
    tcase_add_test(tc, sdo_segmented_download_followed);
    tcase_add_test(tc, sdo_block_download_followed);
    tcase_add_test(tc, sdo_block_upload_followed);
    tcase_add_test(tc, sdo_block_abort_in_subblock);
    tcase_add_test(tc, sdo_transfers_per_node);
    tcase_add_test(tc, pdos_without_eds);
    tcase_add_test(tc, pdos_with_eds);
    tcase_add_test(tc, other_frames);
    tcase_add_test(tc, output_truncated_safely);
    tcase_add_test(tc, eds_errors);
    tcase_add_test(tc, dcf_values);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
