/* SPDX-License-Identifier: Apache-2.0 */
/* comaster gateway's CiA 309-3 lines: what each command line parses into, the defaults the set
 * commands keep, the exact error reply of every malformed or unsupported line, and the reply
 * lines of values as canopend prints them. */
#include "check_main.h"
#include "co/co_nmt.h"
#include "comaster/gateway_ascii.h"

#include <stdio.h>
#include <string.h>

static gw_session_t session;
static uint32_t last;
static gw_request_t req;

static void setup(void)
{
    gw_session_init(&session);
    last = 0;
}

static const gw_request_t *parse(const char *line)
{
    memset(&req, 0xA5, sizeof req);
    gw_parse(&session, &last, line, &req);
    return &req;
}

/* The line is answered at once with `reply`. */
static void replies(const char *line, const char *reply)
{
    parse(line);
    ck_assert_msg(req.action == GW_REPLY, "%s: action %d", line, (int)req.action);
    ck_assert_str_eq(req.reply, reply);
}

START_TEST(read_and_write_requests)
{
    parse("[7] 4 read 0x1017 0 u16");
    ck_assert_int_eq(req.action, GW_READ);
    ck_assert_uint_eq(req.sequence, 7);
    ck_assert_uint_eq(req.node, 4);
    ck_assert_uint_eq(req.index, 0x1017);
    ck_assert_uint_eq(req.sub, 0);
    ck_assert_str_eq(req.type->name, "u16");
    parse("[8] 1 5 r 0x1018 2");
    ck_assert_int_eq(req.action, GW_READ);
    ck_assert_uint_eq(req.node, 5);
    ck_assert_str_eq(req.type->name, "hex"); /* no data type: the bytes */
    parse("[9] 4 W 0x203C 2 U16 0x0032 # a comment");
    ck_assert_int_eq(req.action, GW_WRITE);
    ck_assert_uint_eq(req.len, 2);
    ck_assert_uint_eq(req.data[0], 0x32);
    ck_assert_uint_eq(req.data[1], 0x00);
    parse("[10] 4 w 0x2000 0 vs \"say \"\"hi\"\" now\"");
    ck_assert_int_eq(req.action, GW_WRITE);
    ck_assert_uint_eq(req.len, 12);
    ck_assert_mem_eq(req.data, "say \"hi\" now", 12);
    parse("[11] 4 w 0x2000 0 hex 01 02 0A");
    ck_assert_int_eq(req.action, GW_WRITE);
    ck_assert_uint_eq(req.len, 3);
    ck_assert_uint_eq(req.data[2], 0x0A);
    parse("[12] 4 w 0x2000 0 i8 -2");
    ck_assert_uint_eq(req.data[0], 0xFE);
}
END_TEST

START_TEST(nmt_requests)
{
    parse("[1] 4 start");
    ck_assert_int_eq(req.action, GW_NMT);
    ck_assert_uint_eq(req.nmt_command, CO_NMT_CS_START);
    ck_assert_uint_eq(req.node, 4);
    parse("[2] 0 preoperational");
    ck_assert_uint_eq(req.nmt_command, CO_NMT_CS_ENTER_PRE_OPERATIONAL);
    ck_assert_uint_eq(req.node, 0);
    parse("[3] 4 reset comm");
    ck_assert_uint_eq(req.nmt_command, CO_NMT_CS_RESET_COMMUNICATION);
    parse("[4] 4 reset node");
    ck_assert_uint_eq(req.nmt_command, CO_NMT_CS_RESET_NODE);
    parse("[5] 4 stop");
    ck_assert_uint_eq(req.nmt_command, CO_NMT_CS_STOP);
    replies("[6] 4 reset", "[6] ERROR:101\r\n");
    replies("[7] 4 start now", "[7] ERROR:101\r\n");
}
END_TEST

START_TEST(set_commands_keep_defaults)
{
    replies("[1] read 0x1000 0 u32", "[1] ERROR:105\r\n");
    replies("[2] start", "[2] ERROR:105\r\n");
    replies("[3] set node 5", "[3] OK\r\n");
    parse("[4] read 0x1000 0 u32");
    ck_assert_int_eq(req.action, GW_READ);
    ck_assert_uint_eq(req.node, 5);
    replies("[5] set node 0", "[5] ERROR:101\r\n");
    replies("[6] set node 128", "[6] ERROR:101\r\n");
    replies("[7] set sdo_timeout 20", "[7] OK\r\n");
    ck_assert_uint_eq(session.sdo_timeout_ms, 20);
    replies("[8] set sdo_block 1", "[8] OK\r\n");
    ck_assert(session.sdo_block);
    replies("[9] set sdo_block 2", "[9] ERROR:101\r\n");
    replies("[10] set network 1", "[10] OK\r\n");
    replies("[11] set network 2", "[11] ERROR:106\r\n");
    replies("[12] set baud 3", "[12] ERROR:100\r\n");
    replies("[13] 2 4 start", "[13] ERROR:106\r\n");
    parse("[14] 1 4 stop");
    ck_assert_int_eq(req.action, GW_NMT);
}
END_TEST

START_TEST(errors_of_lines)
{
    replies("", "\r\n");
    replies("   # only a comment", "\r\n");
    replies("[3] 200 start", "[3] ERROR:107\r\n");
    replies("[4] 0 read 0x1000 0", "[4] ERROR:107\r\n");
    /* A line without its sequence: the error repeats the sequence of the line before. */
    replies("4 start", "[4] ERROR:101\r\n");
    replies("[x] 4 start", "[4] ERROR:101\r\n");
    replies("[5] 4 read 0x10000 0 u8", "[5] ERROR:101\r\n");
    replies("[6] 4 read 0x1000 256 u8", "[6] ERROR:101\r\n");
    replies("[7] 4 read 0x1000 0 u12", "[7] ERROR:101\r\n");
    replies("[8] 4 read 0x1000 0 os", "[8] ERROR:100\r\n"); /* base64: not yet */
    replies("[9] 4 write 0x1000 0 u8 256", "[9] ERROR:101\r\n");
    replies("[10] 4 write 0x1000 0 u8", "[10] ERROR:101\r\n");
    replies("[11] 4 write 0x1000 0 vs \"open", "[10] ERROR:101\r\n");
    replies("[12] lss_allnodes", "[12] ERROR:100\r\n");
    replies("[13] 4 frobnicate", "[13] ERROR:100\r\n");
    replies("[14] 1 2 3 start", "[14] ERROR:101\r\n");
    parse("[15] help");
    ck_assert_str_eq(req.reply, "[15] ");
    ck_assert_ptr_nonnull(req.help);
    ck_assert(strstr(req.help, "r[ead] <index> <subindex>") != NULL);
}
END_TEST

START_TEST(lss_requests)
{
    parse("[1] lss_switch_sel 0 401 0x10000 0x40100081");
    ck_assert_int_eq(req.action, GW_LSS);
    ck_assert_int_eq(req.lss, GW_LSS_SWITCH_SELECTIVE);
    ck_assert_uint_eq(req.args[1], 401);
    ck_assert_uint_eq(req.args[3], 0x40100081);
    parse("[2] 1 lss_set_node 255");
    ck_assert_int_eq(req.lss, GW_LSS_SET_NODE);
    ck_assert_uint_eq(req.args[0], 255);
    parse("[3] lss_inquire_addr");
    ck_assert_int_eq(req.lss, GW_LSS_INQUIRE_ALL);
    parse("[4] lss_inquire_addr 3");
    ck_assert_int_eq(req.lss, GW_LSS_INQUIRE);
    ck_assert_uint_eq(req.args[0], 3);
    parse("[5] _lss_fastscan");
    ck_assert_int_eq(req.lss, GW_LSS_FASTSCAN);
    ck_assert_uint_eq(req.args[0], GW_DEFAULT_FASTSCAN_MS);
    parse("[6] lss_conf_bitrate 0 4");
    ck_assert_int_eq(req.lss, GW_LSS_CONF_BITRATE);
    ck_assert_uint_eq(req.args[1], 4);
    replies("[7] lss_set_node 0", "[7] ERROR:101\r\n");
    replies("[8] lss_set_node 128", "[8] ERROR:101\r\n");
    replies("[9] lss_conf_bitrate 0 5", "[9] ERROR:101\r\n");
    replies("[10] lss_conf_bitrate 1 4", "[10] ERROR:101\r\n");
    replies("[11] lss_inquire_addr 4", "[11] ERROR:101\r\n");
    replies("[12] lss_switch_glob", "[12] ERROR:101\r\n");
    replies("[13] lss_store now", "[13] ERROR:101\r\n");
    replies("[14] 2 lss_store", "[14] ERROR:106\r\n");
    replies("[15] 1 4 lss_store", "[15] ERROR:101\r\n");
    replies("[16] 200 set node 3", "[16] ERROR:106\r\n");
    parse("[17] 1 lss_store");
    ck_assert_int_eq(req.action, GW_LSS);
    char out[128];
    const uint32_t address[] = {0, 401, 0x10000, 0x40100081};
    gw_reply_words(out, sizeof out, 3, address, 4, 8);
    ck_assert_str_eq(out, "[3] 0x00000000 0x00000191 0x00010000 0x40100081\r\n");
    const uint32_t node = 0xFF;
    gw_reply_words(out, sizeof out, 4, &node, 1, 2);
    ck_assert_str_eq(out, "[4] 0xFF\r\n");
}
END_TEST

static void value(const char *type_name, const uint8_t *data, size_t len, const char *text)
{
    char out[256];
    char line[256];
    parse(type_name);
    ck_assert_int_eq(req.action, GW_READ);
    ck_assert(gw_reply_value(out, sizeof out, 3, req.type, data, len));
    snprintf(line, sizeof line, "[3] %s\r\n", text);
    ck_assert_str_eq(out, line);
}

START_TEST(values_as_canopend_prints_them)
{
    static const uint8_t u16[] = {0xE8, 0x03};
    static const uint8_t i32[] = {0xFE, 0xFF, 0xFF, 0xFF};
    static const uint8_t r32[] = {0x00, 0x00, 0xC0, 0x3F}; /* 1.5 */
    static const uint8_t vs[] = {'A', 'T', 'V', '"', '3'};
    value("[1] 4 r 0x1017 0 u16", u16, 2, "1000");
    value("[1] 4 r 0x1017 0 x16", u16, 2, "0x03E8");
    value("[1] 4 r 0x1017 0 i32", i32, 4, "-2");
    value("[1] 4 r 0x1017 0 x32", i32, 4, "0xFFFFFFFE");
    value("[1] 4 r 0x1017 0 r32", r32, 4, "1.5");
    value("[1] 4 r 0x1017 0 vs", vs, 5, "\"ATV\"\"3\"");
    value("[1] 4 r 0x1017 0", u16, 2, "E8 03");
    value("[1] 4 r 0x1017 0 b", u16, 1, "232");
    char out[64];
    parse("[1] 4 r 0x1017 0 u32");
    ck_assert(!gw_reply_value(out, sizeof out, 3, req.type, u16, 2));
    gw_reply_abort(out, sizeof out, 9, 0x06020000);
    ck_assert_str_eq(out, "[9] ERROR:0x06020000\r\n");
    gw_reply_ok(out, sizeof out, 4294967295u);
    ck_assert_str_eq(out, "[4294967295] OK\r\n");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("comaster_gateway_ascii");
    TCase *tc = tcase_create("lines");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, read_and_write_requests);
    tcase_add_test(tc, nmt_requests);
    tcase_add_test(tc, set_commands_keep_defaults);
    tcase_add_test(tc, errors_of_lines);
    tcase_add_test(tc, values_as_canopend_prints_them);
    tcase_add_test(tc, lss_requests);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
