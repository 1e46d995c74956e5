/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace's DeviceNet decoder on lists of frames, each with the exact line it must give: the
 * groups and message IDs, the duplicate MAC ID check, explicit requests and responses with their
 * errors, fragments reassembled both ways, allocation and release, polled and COS I/O by the
 * assembly selected, the selection applied at the node's restart, malformed frames. */
#include "check_main.h"
#include "co_linux/candump.h"
#include "trace/devicenet_decoder.h"

#include <stdio.h>
#include <string.h>

typedef struct step {
    const char *frame; /* candump -L ID#DATA */
    const char *meaning;
} step_t;

static void play(cotrace_dn_decoder_t *dec, const step_t *steps, size_t n)
{
    char out[1024];
    for (size_t i = 0; i < n; i++) {
        struct can_frame f;
        struct timespec wall;
        char iface[IFNAMSIZ];
        char line[128];
        snprintf(line, sizeof line, "(1700000000.000000) vcan0 %s", steps[i].frame);
        ck_assert_msg(co_candump_parse(line, &wall, iface, &f), "bad test frame %s",
                      steps[i].frame);
        cotrace_dn_decode(dec, &f, out, sizeof out);
        ck_assert_msg(strcmp(out, steps[i].meaning) == 0, "%s:\n  got      '%s'\n  expected '%s'",
                      steps[i].frame, out, steps[i].meaning);
    }
}

#define PLAY(dec, steps) play(dec, steps, sizeof(steps) / sizeof((steps)[0]))

static cotrace_dn_decoder_t dec;

static void defaults(void)
{
    cotrace_dn_decoder_init(&dec, 0, 0);
}

START_TEST(groups_and_identifiers)
{
    static const step_t steps[] = {
        {"3FF#", "G1 msg 15 from 63: poll response: no data (idle)"},
        {"37F#01020304", "G1 msg 13 from 63: COS/cyclic data: assembly 71: Faulted, Drive "
                         "state 2 Not_Ready, Speed actual 1027 rpm"},
        {"3BF#01", "G1 msg 14 from 63: bit-strobe response: 01"},
        {"33F#", "G1 msg 12 from 63: multicast poll response"},
        {"07F#AA", "G1 msg 1 from 63: not in the predefined master/slave connection set: AA"},
        {"5F8#0102", "G2 msg 0 from 63: bit-strobe command: 01 02"},
        {"5F9#", "G2 msg 1 from 63: multicast poll command"},
        {"5FA#", "G2 msg 2 to 63: COS/cyclic acknowledge"},
        {"605#01", "G3 msg 0 from 5: UCMM connection message: 01"},
        {"7C1#", "G4 msg 1: reserved"},
        {"7ED#00CC", "G4 msg 45: communication faulted request: 00 CC"},
        {"7F0#", "identifier 0x7F0: invalid in DeviceNet"},
        {"5FC#R", "remote frame 0x5FC: DeviceNet has none"},
        {"12345678#00", "29-bit identifier: not DeviceNet"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(duplicate_mac_id_check)
{
    static const step_t steps[] = {
        {"4CF#00F30078563412", "G2 msg 7 from 25: duplicate MAC ID check request, port 0, vendor "
                               "0x00F3, serial number 0x12345678"},
        {"4CF#81F30078563412", "G2 msg 7 from 25: duplicate MAC ID check response, port 1, "
                               "vendor 0x00F3, serial number 0x12345678"},
        {"4CF#00F300", "G2 msg 7 from 25: duplicate MAC ID check malformed: 3 bytes, it has 7"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(explicit_requests_responses_and_errors)
{
    static const step_t steps[] = {
        {"5FE#014B03010301", "G2 msg 6 to 63: unconnected request from 1: "
                             "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, "
                             "choice 0x03 (explicit, polled), allocator 1"},
        {"5FB#01CB00", "G2 msg 3 from 63: explicit response to 1: "
                       "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: "
                       "message body format 8/8"},
        {"5FC#010E010101", "G2 msg 4 to 63: explicit request from 1: Get_Attribute_Single "
                           "Identity (0x01) instance 1 attribute 1"},
        {"5FB#018EF300", "G2 msg 3 from 63: explicit response to 1: Get_Attribute_Single "
                         "Identity (0x01) instance 1 attribute 1 = F3 00 (243)"},
        {"5FC#4110050209E803", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single "
                               "Connection (0x05) instance 2 attribute 9 = E8 03 (1000)"},
        {"5FB#4190E803", "G2 msg 3 from 63: explicit response to 1: Set_Attribute_Single "
                         "Connection (0x05) instance 2 attribute 9: done, answered E8 03 (1000)"},
        {"5FC#010E7001C8", "G2 msg 4 to 63: explicit request from 1: Get_Attribute_Single class "
                           "0x70 instance 1 attribute 200"},
        {"5FB#019414FF", "G2 msg 3 from 63: explicit response to 1: Get_Attribute_Single class "
                         "0x70 instance 1 attribute 200: error 0x14 attribute not supported, "
                         "additional code 0xFF"},
        {"5FE#014C03", "G2 msg 6 to 63: unconnected request from 1: "
                       "Release_Group_2_Identifier_Set, path cut short: 03"},
        {"5FB#019408", "G2 msg 3 from 63: explicit response to 1: error 0x08 service not "
                       "supported"},
        {"5FB#0194", "G2 msg 3 from 63: explicit response to 1: error response without a status"},
        {"5FB#01942A03", "G2 msg 3 from 63: explicit response to 1: error 0x2A reserved, "
                         "additional code 0x03"},
        {"5FB#0185", "G2 msg 3 from 63: explicit response to 1: Reset: done"},
        {"5FC#01", "G2 msg 4 to 63: explicit request from ?: malformed: 1 bytes, an explicit "
                   "message has a header and a service"},
        {"5FC#0132990203", "G2 msg 4 to 63: explicit request from 1: service 0x32 class 0x99 "
                           "instance 2 = 03 (3)"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(fragments_reassembled)
{
    static const step_t steps[] = {
        {"5FC#010E010107", "G2 msg 4 to 63: explicit request from 1: Get_Attribute_Single "
                           "Identity (0x01) instance 1 attribute 7"},
        {"5FB#81008E0641545633", "G2 msg 3 from 63: explicit response to 1: fragment 0 (first), "
                                 "6 bytes"},
        {"5FC#81C000", "G2 msg 4 to 63: explicit request from 1: fragment 0 acknowledged: success"},
        {"5FB#81008E0641545633", "G2 msg 3 from 63: explicit response to 1: fragment 0 (first), "
                                 "6 bytes"},
        {"5FB#81413132", "G2 msg 3 from 63: explicit response to 1: fragment 1 (middle), 2 bytes"},
        {"5FB#81413132", "G2 msg 3 from 63: explicit response to 1: fragment 1 (middle) repeated"},
        {"5FB#8182", "G2 msg 3 from 63: explicit response to 1: fragment 2 (last), 0 bytes, "
                     "message of 8 bytes: Get_Attribute_Single Identity (0x01) instance 1 "
                     "attribute 7 = \"ATV312\""},
        {"5FB#81C101", "G2 msg 3 from 63: explicit response to 1: fragment 1 acknowledged: too "
                       "much data"},
        {"5FB#81C107", "G2 msg 3 from 63: explicit response to 1: fragment 1 acknowledged: status "
                       "0x07"},
        {"5FC#8181B004", "G2 msg 4 to 63: explicit request from 1: fragment 1 (last) without a "
                         "first fragment: B0 04"},
        {"5FC#8100100415036100", "G2 msg 4 to 63: explicit request from 1: fragment 0 (first), 6 "
                                 "bytes"},
        {"5FC#8182B004", "G2 msg 4 to 63: explicit request from 1: fragment 2 (last) out of "
                         "sequence after 0: message dropped"},
        {"5FC#8100100415036100", "G2 msg 4 to 63: explicit request from 1: fragment 0 (first), 6 "
                                 "bytes"},
        {"5FC#8181B004", "G2 msg 4 to 63: explicit request from 1: fragment 1 (last), 2 bytes, "
                         "message of 8 bytes: Set_Attribute_Single Assembly (0x04) instance 21 "
                         "attribute 3 = assembly 21: Run fwd, NetCtrl, NetRef, Speed reference "
                         "1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(fragments_over_the_message_size_dropped)
{
    char frame[32];
    char meaning[160];
    step_t first = {"5FC#8100000000000000",
                    "G2 msg 4 to 63: explicit request from 1: fragment 0 (first), 6 bytes"};
    play(&dec, &first, 1);
    for (unsigned count = 1; count <= 10; count++) {
        snprintf(frame, sizeof frame, "5FC#81%02X000000000000", 0x40u | count);
        if (count < 10)
            snprintf(meaning, sizeof meaning,
                     "G2 msg 4 to 63: explicit request from 1: fragment %u (middle), 6 bytes",
                     count);
        else
            snprintf(meaning, sizeof meaning,
                     "G2 msg 4 to 63: explicit request from 1: fragment 10 (middle): more than 64 "
                     "bytes, message dropped");
        step_t step = {frame, meaning};
        play(&dec, &step, 1);
    }
}
END_TEST

START_TEST(io_by_allocation_and_assembly)
{
    static const step_t steps[] = {
        {"5FD#6100B004", "G2 msg 5 to 63: poll command: assembly 21: Run fwd, NetCtrl, NetRef, "
                         "Speed reference 1200 rpm"},
        {"5FD#", "G2 msg 5 to 63: poll command: no data (idle)"},
        {"5FD#0102", "G2 msg 5 to 63: poll command: assembly 21 (4 bytes) does not fit 2 bytes: "
                     "01 02"},
        {"3FF#FF074FFB", "G1 msg 15 from 63: poll response: assembly 71: Faulted, Warning, "
                         "Running1, Running2, Ready, Ctrl from net, Ref from net, At reference, "
                         "Drive state 7 Faulted, Speed actual -1201 rpm"},
        /* Change of state only: message 5 is the master's data, 0xF the slave's ack. */
        {"5FE#014B03011001", "G2 msg 6 to 63: unconnected request from 1: "
                             "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, "
                             "choice 0x10 (change of state), allocator 1"},
        {"5FB#01CB00", "G2 msg 3 from 63: explicit response to 1: "
                       "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: "
                       "message body format 8/8"},
        {"5FD#0100B004",
         "G2 msg 5 to 63: COS data: assembly 21: Run fwd, Speed reference 1200 rpm"},
        {"3FF#", "G1 msg 15 from 63: COS/cyclic acknowledge"},
        {"37F#70030000", "G1 msg 13 from 63: COS data: assembly 71: Ready, Ctrl from net, "
                         "Ref from net, Drive state 3 Ready, Speed actual 0 rpm"},
        {"5FA#", "G2 msg 2 to 63: COS/cyclic acknowledge"},
        {"5FE#014C030110", "G2 msg 6 to 63: unconnected request from 1: "
                           "Release_Group_2_Identifier_Set DeviceNet (0x03) instance 1, choice "
                           "0x10 (change of state)"},
        {"5FB#01CC", "G2 msg 3 from 63: explicit response to 1: Release_Group_2_Identifier_Set "
                     "DeviceNet (0x03) instance 1: done"},
        {"5FE#014B03012001", "G2 msg 6 to 63: unconnected request from 1: "
                             "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, "
                             "choice 0x20 (cyclic), allocator 1"},
        {"5FB#01CB00", "G2 msg 3 from 63: explicit response to 1: "
                       "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: "
                       "message body format 8/8"},
        {"37F#70030000", "G1 msg 13 from 63: cyclic data: assembly 71: Ready, Ctrl from net, "
                         "Ref from net, Drive state 3 Ready, Speed actual 0 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* A Set of Connection class attributes 100/101 is stored; the node uses it from its restart on
 * (its duplicate MAC ID check request). A refused Set changes nothing. */
START_TEST(assembly_selection_applies_at_restart)
{
    static const step_t steps[] = {
        {"5FC#01100500646400", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single "
                               "Connection (0x05) instance 0 attribute 100 = 64 00 (100)"},
        {"5FB#0190", "G2 msg 3 from 63: explicit response to 1: Set_Attribute_Single Connection "
                     "(0x05) instance 0 attribute 100: done"},
        {"5FC#01100500651400", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single "
                               "Connection (0x05) instance 0 attribute 101 = 14 00 (20)"},
        {"5FB#019409FF", "G2 msg 3 from 63: explicit response to 1: Set_Attribute_Single "
                         "Connection (0x05) instance 0 attribute 101: error 0x09 invalid "
                         "attribute value, additional code 0xFF"},
        {"5FD#0F00B004", "G2 msg 5 to 63: poll command: assembly 21: Run fwd, Run rev, Fault "
                         "reset, Speed reference 1200 rpm"},
        {"5FF#00F30078563412", "G2 msg 7 from 63: duplicate MAC ID check request, port 0, vendor "
                               "0x00F3, serial number 0x12345678"},
        {"5FD#0F00B004", "G2 msg 5 to 63: poll command: assembly 100: Control word 0x000F "
                         "Enable operation, Reference speed 1200 rpm"},
        {"3FF#2706B004", "G1 msg 15 from 63: poll response: assembly 71: Faulted, Warning, "
                         "Running1, Ctrl from net, Drive state 6 Fault_Stop, Speed actual 1200 "
                         "rpm"},
        {"5FC#010E046503", "G2 msg 4 to 63: explicit request from 1: Get_Attribute_Single "
                           "Assembly (0x04) instance 101 attribute 3"},
        {"5FB#018E2706B004", "G2 msg 3 from 63: explicit response to 1: Get_Attribute_Single "
                             "Assembly (0x04) instance 101 attribute 3 = assembly 101: Status "
                             "word 0x0627 Operation enabled, Output speed 1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* Only a request of the service's form changes what the trace knows at its success: Allocate
 * with one byte, or a selection Set with three, is shown as bytes and allocates or selects
 * nothing (the slave library refuses both). */
START_TEST(an_allocate_of_one_byte_allocates_nothing)
{
    static const step_t steps[] = {
        {"5FE#014B030110", "G2 msg 6 to 63: unconnected request from 1: "
                           "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1 = "
                           "10 (16)"},
        {"5FB#01CB00", "G2 msg 3 from 63: explicit response to 1: "
                       "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: "
                       "message body format 8/8"},
        {"5FD#0100B004", "G2 msg 5 to 63: poll command: assembly 21: Run fwd, Speed reference "
                         "1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(a_selection_of_three_bytes_selects_nothing)
{
    static const step_t steps[] = {
        {"5FC#0110050064140001", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single "
                                 "Connection (0x05) instance 0 attribute 100 = 14 00 01 (65556)"},
        {"5FB#0190", "G2 msg 3 from 63: explicit response to 1: Set_Attribute_Single Connection "
                     "(0x05) instance 0 attribute 100: done"},
        {"5FF#00F30078563412", "G2 msg 7 from 63: duplicate MAC ID check request, port 0, vendor "
                               "0x00F3, serial number 0x12345678"},
        {"5FD#0F00B004", "G2 msg 5 to 63: poll command: assembly 21: Run fwd, Run rev, Fault "
                         "reset, Speed reference 1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

/* The master's identifiers carry requests, the slave's responses: a body of the other kind is
 * shown as such and neither answers nor replaces the request awaiting its response. */
START_TEST(a_response_on_a_request_identifier_answers_nothing)
{
    static const step_t steps[] = {
        {"5FC#01100500646400", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single "
                               "Connection (0x05) instance 0 attribute 100 = 64 00 (100)"},
        {"5FC#0190", "G2 msg 4 to 63: explicit request from 1: Set_Attribute_Single response on "
                     "a request identifier"},
        {"5FF#00F30078563412", "G2 msg 7 from 63: duplicate MAC ID check request, port 0, vendor "
                               "0x00F3, serial number 0x12345678"},
        {"5FD#0F00B004", "G2 msg 5 to 63: poll command: assembly 21: Run fwd, Run rev, Fault "
                         "reset, Speed reference 1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(a_request_on_a_response_identifier_replaces_nothing)
{
    static const step_t steps[] = {
        {"5FE#014B03011001", "G2 msg 6 to 63: unconnected request from 1: "
                             "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, "
                             "choice 0x10 (change of state), allocator 1"},
        {"5FB#014C030110", "G2 msg 3 from 63: explicit response to 1: "
                           "Release_Group_2_Identifier_Set request on a response identifier: 03 "
                           "01 10"},
        {"5FB#01CB00", "G2 msg 3 from 63: explicit response to 1: "
                       "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: "
                       "message body format 8/8"},
        {"5FD#0100B004",
         "G2 msg 5 to 63: COS data: assembly 21: Run fwd, Speed reference 1200 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(assemblies_given)
{
    cotrace_dn_decoder_init(&dec, 20, 70);
    static const step_t steps[] = {
        {"5FD#0500F6FF", "G2 msg 5 to 63: poll command: assembly 20: Run fwd, Fault reset, "
                         "Speed reference -10 rpm"},
        {"3FF#FF00F6FF", "G1 msg 15 from 63: poll response: assembly 70: Faulted, Running1, "
                         "Speed actual -10 rpm"},
        /* No bit set: the speed right after the assembly's colon. */
        {"3FF#00000000", "G1 msg 15 from 63: poll response: assembly 70: Speed actual 0 rpm"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(ucmm)
{
    static const step_t steps[] = {
        {"781#194B0031", "G3 msg 6 from 1: UCMM request to 25: Open Explicit Messaging "
                         "Connection request: body format 0, group 3, source message ID 1"},
        {"759#01CB00100A00", "G3 msg 5 from 25: UCMM response to 1: Open Explicit Messaging "
                             "Connection response: body format 0, destination message ID 1, "
                             "source message ID 0, instance 10"},
        {"641#190E010101", "G3 msg 1 from 1: UCMM connection request to 25: "
                           "Get_Attribute_Single Identity (0x01) instance 1 attribute 1"},
        {"619#018EF300", "G3 msg 0 from 25: UCMM connection response to 1: "
                         "Get_Attribute_Single Identity (0x01) instance 1 attribute 1 = F3 00 "
                         "(243)"},
        {"781#194C0A00", "G3 msg 6 from 1: UCMM request to 25: Close Connection request: "
                         "instance 10"},
        {"759#01CC", "G3 msg 5 from 25: UCMM response to 1: Close Connection response"},
        {"759#019402FF", "G3 msg 5 from 25: UCMM response to 1: Error_Response response: 0x02 "
                         "resource unavailable"},
        {"759#01CB00", "G3 msg 5 from 25: UCMM response to 1: Open Explicit Messaging "
                       "Connection response: 00"},
        {"781#19", "G3 msg 6 from 1: UCMM request, malformed: 19"},
    };
    PLAY(&dec, steps);
}
END_TEST

START_TEST(output_truncated_safely)
{
    char out[16];
    struct can_frame f = {.can_id = 0x5FB, .len = 4, .data = {0x01, 0x94, 0x16, 0xFF}};
    cotrace_dn_decode(&dec, &f, out, sizeof out);
    ck_assert_str_eq(out, "G2 msg 3 from 6");
    cotrace_dn_decode(&dec, &f, out, 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cotrace_devicenet_decoder");
    TCase *tc = tcase_create("devicenet");
    tcase_add_checked_fixture(tc, defaults, NULL);
    tcase_add_test(tc, groups_and_identifiers);
    tcase_add_test(tc, duplicate_mac_id_check);
    tcase_add_test(tc, explicit_requests_responses_and_errors);
    tcase_add_test(tc, fragments_reassembled);
    tcase_add_test(tc, fragments_over_the_message_size_dropped);
    tcase_add_test(tc, io_by_allocation_and_assembly);
    tcase_add_test(tc, assembly_selection_applies_at_restart);
    tcase_add_test(tc, an_allocate_of_one_byte_allocates_nothing);
    tcase_add_test(tc, a_selection_of_three_bytes_selects_nothing);
    tcase_add_test(tc, a_response_on_a_request_identifier_answers_nothing);
    tcase_add_test(tc, a_request_on_a_response_identifier_replaces_nothing);
    tcase_add_test(tc, assemblies_given);
    tcase_add_test(tc, ucmm);
    tcase_add_test(tc, output_truncated_safely);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
