/* SPDX-License-Identifier: Apache-2.0 */
/* The network description of comaster run: the example bench (examples/netmaster: bench.ini, its
 * CiA 306-3 nodelist and three ATV312 DCFs) read into the master's configuration (slaves, options,
 * identity checks, the configuration writes byte by byte, the PDOs and the named variables of the
 * process image), and every kind of bad file refused with a message naming file, line and key. */
#include "check_main.h"
#include "comaster/network.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

#define DIR COMASTER_TEST_NETWORK_DIR

static comaster_network_t net;
static char err[512];
static char tmpdir[] = "/tmp/comaster-network-XXXXXX";
static char ini[PATH_MAX];
static char cpj[PATH_MAX];
static char dcf[PATH_MAX];

static void setup(void)
{
    ck_assert_ptr_nonnull(mkdtemp(tmpdir));
    snprintf(ini, sizeof ini, "%s/net.ini", tmpdir);
    snprintf(cpj, sizeof cpj, "%s/net.cpj", tmpdir);
    snprintf(dcf, sizeof dcf, "%s/slave.dcf", tmpdir);
    err[0] = '\0';
}

static void teardown(void)
{
    comaster_network_free(&net);
    unlink(ini);
    unlink(cpj);
    unlink(dcf);
    rmdir(tmpdir);
    memcpy(tmpdir + strlen(tmpdir) - 6, "XXXXXX", 6);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
}

/* Writes the nodelist and the option file, then loads the option file. */
static int load_files(const char *nodelist, const char *options)
{
    comaster_network_free(&net);
    write_file(cpj, nodelist);
    write_file(ini, options);
    return comaster_network_load(&net, ini, err, sizeof err);
}

/* A nodelist of node 4 (drive4.dcf of the examples). */
#define NODELIST "[Topology]\nNetName=t\nNodes=1\nNode4Present=1\nNode4DCFName=" DIR "/drive4.dcf\n"

/* The nodelist of node 4 and an option file with `options`. */
static int load_with(const char *options)
{
    char text[1024];
    snprintf(text, sizeof text, "[Master]\ncpj = net.cpj\n%s", options);
    return load_files(NODELIST, text);
}

static const co_net_slave_config_t *slave(size_t i)
{
    return &net.config.slaves[i];
}

/* A slave's configuration is its concise DCF (1F22h): its entries, and entry k as a write. */
static size_t write_count(const co_net_slave_config_t *c)
{
    uint32_t count = 0;
    ck_assert(co_concise_dcf_valid(c->concise_dcf, c->concise_dcf_len, &count));
    return count;
}

static co_net_write_t write_at(const co_net_slave_config_t *c, size_t k)
{
    size_t pos = CO_CONCISE_DCF_HEADER;
    co_concise_dcf_entry_t e = {0};
    for (size_t i = 0; i <= k; i++)
        ck_assert(co_concise_dcf_next(c->concise_dcf, c->concise_dcf_len, &pos, &e));
    return (co_net_write_t){e.index, e.subindex, e.data, e.len};
}

START_TEST(bench_slaves_and_options)
{
    ck_assert_int_eq(comaster_network_load(&net, DIR "/bench.ini", err, sizeof err), 0);
    ck_assert_str_eq(net.net_name, "bench");
    ck_assert_str_eq(net.iface, "vcan0");
    ck_assert_uint_eq(net.config.slave_count, 3);
    ck_assert_uint_eq(net.config.sdo_timeout_ms, 500);
    ck_assert_uint_eq(net.config.boot_time_ms, 1000);
    ck_assert_uint_eq(net.config.retry_delay_ms, 1000);
    ck_assert_uint_eq(net.config.start, CO_NET_START_EACH);
    ck_assert(net.config.reset_all);
    ck_assert_uint_eq(net.config.sync_period_us, 0);
    for (size_t i = 0; i < 3; i++) {
        ck_assert_uint_eq(slave(i)->node_id, 4 + i);
        ck_assert_uint_eq(slave(i)->heartbeat_ms, 300);
        ck_assert_uint_eq(slave(i)->check, CO_NET_CHECK_DEVICE_TYPE | CO_NET_CHECK_VENDOR);
        ck_assert_uint_eq(slave(i)->device_type, 0x00010192);
        ck_assert_uint_eq(slave(i)->identity[0], 0x5F);
        ck_assert_uint_eq(slave(i)->on_error, CO_NET_ON_ERROR_REBOOT);
    }
    ck_assert(slave(0)->mandatory);
    ck_assert(!slave(1)->mandatory);
    ck_assert_str_eq(net.slave[1].name, "drive5");
}
END_TEST

/* The ParameterValue entries of rw objects, in file order, with their type's size. */
START_TEST(configuration_writes_from_the_dcf)
{
    ck_assert_int_eq(comaster_network_load(&net, DIR "/bench.ini", err, sizeof err), 0);
    const co_net_slave_config_t *s = slave(1); /* node 5 */
    ck_assert_uint_eq(write_count(s), 5);
    /* The slave's configuration is comaster's concise DCF of it: the count, 5 entry headers and
     * 14 bytes of values. */
    ck_assert_ptr_nonnull(net.slave[1].concise);
    ck_assert_ptr_eq(s->concise_dcf, net.slave[1].concise);
    ck_assert_uint_eq(net.slave[1].concise_len,
                      CO_CONCISE_DCF_HEADER + 5 * CO_CONCISE_DCF_ENTRY_HEADER + 14);
    ck_assert_uint_eq(s->concise_dcf_len, net.slave[1].concise_len);
    static const struct {
        uint16_t index;
        uint8_t sub;
        uint32_t len;
        const char *bytes;
    } want[] = {{0x1017, 0, 2, "\x64\x00"},
                {0x1405, 1, 4, "\x05\x03\x00\x00"},
                {0x1805, 1, 4, "\x85\x02\x00\x00"},
                {0x203C, 2, 2, "\x14\x00"},
                {0x203C, 3, 2, "\x14\x00"}};
    for (size_t i = 0; i < 5; i++) {
        co_net_write_t w = write_at(s, i);
        ck_assert_uint_eq(w.index, want[i].index);
        ck_assert_uint_eq(w.subindex, want[i].sub);
        ck_assert_uint_eq(w.len, want[i].len);
        ck_assert_mem_eq(w.data, want[i].bytes, want[i].len);
    }
}
END_TEST

START_TEST(process_image_from_the_mappings)
{
    ck_assert_int_eq(comaster_network_load(&net, DIR "/bench.ini", err, sizeof err), 0);
    /* Per node: TPDO1 (status) then TPDO6 (status, actual speed); RPDO1 then RPDO6. */
    ck_assert_uint_eq(net.config.input_count, 6);
    ck_assert_uint_eq(net.config.output_count, 6);
    ck_assert_uint_eq(net.config.input_size, 18);
    ck_assert_uint_eq(net.config.output_size, 18);
    const co_net_pdo_t *in = net.config.inputs, *out = net.config.outputs;
    ck_assert_uint_eq(in[0].can_id, 0x184);
    ck_assert_uint_eq(in[0].len, 2);
    ck_assert_uint_eq(in[0].offset, 0);
    ck_assert_uint_eq(in[1].can_id, 0x284);
    ck_assert_uint_eq(in[1].len, 4);
    ck_assert_uint_eq(in[1].offset, 2);
    ck_assert_uint_eq(in[2].can_id, 0x185);
    ck_assert_uint_eq(in[2].offset, 6);
    ck_assert_uint_eq(out[1].can_id, 0x304);
    ck_assert_uint_eq(out[1].node_id, 4);
    ck_assert_uint_eq(out[5].can_id, 0x306);
    ck_assert_uint_eq(out[5].offset, 14);

    const comaster_variable_t *v;
    ck_assert_uint_eq(comaster_network_find(&net, 5, "speed", &v, err, sizeof err), 1);
    ck_assert_str_eq(v->name, "speed");
    ck_assert(v->output);
    ck_assert_uint_eq(v->index, 0x6042);
    ck_assert_uint_eq(v->offset, 10);
    ck_assert_uint_eq(v->size, 2);
    ck_assert_uint_eq(v->data_type, CO_DT_INTEGER16);
    /* Mapped by PDO1 and PDO6: two variables. */
    ck_assert_uint_eq(comaster_network_find(&net, 4, "control", &v, err, sizeof err), 2);
    ck_assert_uint_eq(v->offset, 0);
    ck_assert_uint_eq(comaster_network_find(&net, 6, "status", &v, err, sizeof err), 2);
    ck_assert(!v->output);
    ck_assert_uint_eq(v->offset, 12);
    /* By its ParameterName, or index and sub-index, too. */
    ck_assert_uint_eq(
        comaster_network_find(&net, 4, "vl velocity actual value", &v, err, sizeof err), 1);
    ck_assert_str_eq(v->name, "actual_speed");
    ck_assert_uint_eq(comaster_network_find(&net, 4, "0x6044", &v, err, sizeof err), 1);
    ck_assert_uint_eq(v->offset, 4);
}
END_TEST

START_TEST(unknown_variables_are_told)
{
    ck_assert_int_eq(comaster_network_load(&net, DIR "/bench.ini", err, sizeof err), 0);
    const comaster_variable_t *v;
    ck_assert_uint_eq(comaster_network_find(&net, 4, "ACC", &v, err, sizeof err), 0);
    ck_assert_ptr_null(v);
    ck_assert_str_eq(err, "node 4: 203Ch:02 (ACC) is in none of its PDOs");
    ck_assert_uint_eq(comaster_network_find(&net, 9, "speed", &v, err, sizeof err), 0);
    ck_assert_str_eq(err, "node 9 is not a slave of the network");
    ck_assert_uint_eq(comaster_network_find(&net, 4, "no such thing", &v, err, sizeof err), 0);
}
END_TEST

START_TEST(one_slave_for_boot)
{
    ck_assert_int_eq(comaster_network_single(&net, 4, DIR "/drive4.dcf", err, sizeof err), 0);
    ck_assert_uint_eq(net.config.slave_count, 1);
    ck_assert(!net.config.reset_all);
    ck_assert_uint_eq(slave(0)->node_id, 4);
    ck_assert_uint_eq(write_count(slave(0)), 5);
    /* 1017h = 100 ms in the DCF: consumed with 150 ms. */
    ck_assert_uint_eq(slave(0)->heartbeat_ms, 150);
    comaster_network_free(&net);
    ck_assert_int_eq(comaster_network_single(&net, 4, DIR "/none.dcf", err, sizeof err),
                     EX_NOINPUT);
}
END_TEST

START_TEST(node_options)
{
    ck_assert_int_eq(load_with("start = all\nsync_period = 10\nreset_all = no\n"
                               "[Node4]\nvendor = 0x99\ncheck = vendor serial\nguard_time = 100\n"
                               "life_time_factor = 3\nheartbeat = 0\non_error = report\n"),
                     0);
    ck_assert_uint_eq(net.config.start, CO_NET_START_ALL);
    ck_assert_uint_eq(net.config.sync_period_us, 10000);
    ck_assert(!net.config.reset_all);
    ck_assert_uint_eq(slave(0)->check, CO_NET_CHECK_VENDOR | CO_NET_CHECK_SERIAL);
    ck_assert_uint_eq(slave(0)->identity[0], 0x99);
    ck_assert_uint_eq(slave(0)->guard_ms, 100);
    ck_assert_uint_eq(slave(0)->life_time_factor, 3);
    ck_assert_uint_eq(slave(0)->heartbeat_ms, 0);
    ck_assert_uint_eq(slave(0)->on_error, CO_NET_ON_ERROR_REPORT);
}
END_TEST

/* The master's own heartbeat: [Master] heartbeat and node_id, which no slave may have. */
START_TEST(master_heartbeat_and_node_id)
{
    ck_assert_int_eq(load_with("node_id = 1\nheartbeat = 50\n"), 0);
    ck_assert_uint_eq(net.config.node_id, 1);
    ck_assert_uint_eq(net.config.heartbeat_ms, 50);
    ck_assert_int_eq(load_with(""), 0);
    ck_assert_uint_eq(net.config.heartbeat_ms, 0);
    ck_assert_int_eq(load_with("heartbeat = 50\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini: [Master] heartbeat = 50 needs node_id = N, the "
                                      "master's own node-id"));
    ck_assert_int_eq(load_with("node_id = 4\nheartbeat = 50\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini: [Master] node_id = 4 is the node-id of a slave"));
    ck_assert_int_eq(load_with("node_id = 128\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "node_id"));
    ck_assert_int_eq(load_with("heartbeat = 65536\nnode_id = 1\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "heartbeat"));
    /* The node-id marker (%CB3052) alone is the master's own too. */
    ck_assert_int_eq(load_with("node_id = 4\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini: [Master] node_id = 4 is the node-id of a slave"));
}
END_TEST

/* The start options and CiA 302-2's 1F80h, the object they stand for, both ways. */
START_TEST(nmt_startup_options_and_1f80)
{
    ck_assert_int_eq(load_with(""), 0);
    ck_assert_uint_eq(co_net_master_1f80(&net.config), 0x01);
    ck_assert_int_eq(load_with("start = all\non_mandatory_error = stop_all\n"), 0);
    ck_assert_uint_eq(co_net_master_1f80(&net.config), 0x43);
    ck_assert_int_eq(load_with("start = none\non_mandatory_error = reset_all\n"), 0);
    ck_assert_uint_eq(co_net_master_1f80(&net.config), 0x19);
    ck_assert_int_eq(load_with("nmt_startup = 0x13\n"), 0);
    ck_assert_uint_eq(net.config.start, CO_NET_START_ALL);
    ck_assert_uint_eq(net.config.on_mandatory_error, CO_NET_MANDATORY_RESET_ALL);
    ck_assert_int_eq(load_with("nmt_startup = 0x41\nstart = none\n"), 0); /* the last one */
    ck_assert_uint_eq(co_net_master_1f80(&net.config), 0x49);
    ck_assert_int_eq(load_with("nmt_startup = 0x05\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "net.ini:3: nmt_startup = '0x05': give CiA 302's 1F80h with "
                                      "bit 0 (NMT master)"));
    ck_assert_int_eq(load_with("nmt_startup = 2\n"), EX_DATAERR);
    ck_assert_int_eq(load_with("on_mandatory_error = reboot\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "give alone, stop_all or reset_all"));
}
END_TEST

/* [NodeN] assignment, CiA 302-2's 1F81h, and the keys it stands for, both ways. */
START_TEST(slave_assignment_1f81)
{
    ck_assert_int_eq(load_with("[Node4]\nmandatory = yes\non_error = report\nguard_time = 100\n"
                               "life_time_factor = 3\n"),
                     0);
    ck_assert_uint_eq(co_net_slave_1f81(slave(0)), 0x00640309);
    ck_assert_int_eq(load_with("[Node4]\nassignment = 0x0032020D\n"), 0);
    ck_assert(slave(0)->mandatory);
    ck_assert_uint_eq(slave(0)->on_error, CO_NET_ON_ERROR_REBOOT);
    ck_assert_uint_eq(slave(0)->guard_ms, 50);
    ck_assert_uint_eq(slave(0)->life_time_factor, 2);
    ck_assert_int_eq(load_with("[Node4]\nassignment = 0x1D\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "net.ini:4: assignment = '0x1D': give CiA 302's 1F81h with "
                                      "bit 0 (NMT slave)"));
}
END_TEST

/* The identity keys of [NodeN] are CiA 302-2's 1F84h..1F88h (0: no check), network_boot_time
 * its 1F89h. */
START_TEST(expected_identity_and_boot_time_objects)
{
    ck_assert_int_eq(load_with(""), 0);
    ck_assert_uint_eq(net.config.boot_limit_ms, 0);
    ck_assert_uint_eq(co_net_slave_expected(slave(0), CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION),
                      0x00010192); /* the DCF's */
    ck_assert_uint_eq(co_net_slave_expected(slave(0), CO_NET_IDX_VENDOR_IDENTIFICATION), 0x5F);
    ck_assert_int_eq(load_with("network_boot_time = 2500\n[Node4]\nproduct = 0x312\n"
                               "device_type = 0\n"),
                     0);
    ck_assert_uint_eq(net.config.boot_limit_ms, 2500);
    ck_assert_uint_eq(co_net_slave_expected(slave(0), CO_NET_IDX_PRODUCT_CODE), 0x312);
    ck_assert_uint_eq(co_net_slave_expected(slave(0), CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION), 0);
    ck_assert_uint_eq(slave(0)->check, CO_NET_CHECK_VENDOR | CO_NET_CHECK_PRODUCT);
    ck_assert_int_eq(load_with("network_boot_time = 3600001\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "net.ini:3: network_boot_time = '3600001': give 0 (no limit) "
                                      "or 1..3600000 ms"));
}
END_TEST

/* The bit rate marker, the PLC300's %CB3055 codes: 0 = 1 Mbit/s, 1 reserved, 2..7 = 500..20
 * kbit/s. */
START_TEST(master_bit_rate_code)
{
    ck_assert_int_eq(load_with(""), 0);
    ck_assert_uint_eq(net.bit_rate, COMASTER_BIT_RATE_NONE);
    for (unsigned code = 0; code <= 7; code++) {
        char line[32];
        snprintf(line, sizeof line, "bit_rate = %u\n", code);
        ck_assert_int_eq(load_with(line), code == 1 ? EX_DATAERR : 0);
        if (code != 1)
            ck_assert_uint_eq(net.bit_rate, code);
    }
    ck_assert_ptr_nonnull(strstr(err, "net.ini:3: bit_rate = '1': give the PLC300's code: 0 = 1 "
                                      "Mbit/s, 2 = 500, 3 = 250, 4 = 125, 5 = 100, 6 = 50, 7 = 20 "
                                      "kbit/s (1 is reserved)"));
    ck_assert_int_eq(load_with("bit_rate = 8\n"), EX_DATAERR);
    ck_assert_int_eq(load_with("bit_rate = 500k\n"), EX_DATAERR);
}
END_TEST

START_TEST(bad_files_are_refused)
{
    ck_assert_int_eq(comaster_network_load(&net, "/nonexistent/net.ini", err, sizeof err),
                     EX_NOINPUT);
    ck_assert_ptr_nonnull(strstr(err, "cannot read '/nonexistent/net.ini'"));

    ck_assert_int_eq(load_with("sdo_timeout = 4\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "net.ini:3: sdo_timeout = '4': give 5..5000 ms"));
    ck_assert_int_eq(load_with("colour = blue\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "net.ini:3: unknown key 'colour' in [Master]"));
    ck_assert_int_eq(load_with("start = later\n"), EX_DATAERR);
    ck_assert_int_eq(load_with("[Node9]\nmandatory = yes\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "[Node9]: node 9 is not present in the nodelist"));
    ck_assert_int_eq(load_with("[Node4]\nheartbeat = 70000\n"), EX_DATAERR);
    ck_assert_int_eq(load_with("[Node4]\ncheck = colour\n"), EX_DATAERR);
    ck_assert_int_eq(load_with("[Slaves]\nx = 1\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "unknown section [Slaves]"));
    ck_assert_int_eq(load_with("no equals sign\n"), EX_DATAERR);

    write_file(ini, "[Master]\ninterface = vcan0\n");
    ck_assert_int_eq(comaster_network_load(&net, ini, err, sizeof err), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "[Master] has no cpj"));

    write_file(ini, "[Master]\ncpj = net.cpj\n");
    write_file(cpj, "[Topology]\nNodes=1\nNode4Present=1\n");
    ck_assert_int_eq(comaster_network_load(&net, ini, err, sizeof err), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "node 4 is present but has no Node4DCFName"));
    write_file(cpj, "[Topology]\nNodes=2\nNode4Present=1\nNode4DCFName=" DIR "/drive4.dcf\n");
    ck_assert_int_eq(comaster_network_load(&net, ini, err, sizeof err), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "Nodes = 2 but 1 nodes are present"));
    write_file(cpj, "[Topology]\nNodes=0\n");
    ck_assert_int_eq(comaster_network_load(&net, ini, err, sizeof err), EX_DATAERR);
    write_file(cpj, "[Topology]\nNodes=1\nNode4Present=1\nNode4DCFName=missing.dcf\n");
    ck_assert_int_eq(comaster_network_load(&net, ini, err, sizeof err), EX_NOINPUT);
    ck_assert_uint_eq(net.slave_count, 0);
}
END_TEST

/* The INI syntax of the option file and the nodelist: comments on lines of their own or after a
 * blank, blanks and carriage returns around everything, sections and keys of any case, a repeated
 * key's last value, a repeated section's keys all taken, a nodelist's other sections ignored. */
START_TEST(option_file_and_nodelist_syntax)
{
    ck_assert_int_eq(load_files("; nodelist\r\n"
                                "[Tool]\r\n"
                                "Nodes = not read\r\n"
                                "  [ topology ]  ; the network\r\n"
                                "  netname = syntax # name\r\n"
                                "NODES=1\r\n"
                                "node4present = 0x01\r\n"
                                "Node4Name = first#drive\r\n"
                                "node4dcfname = " DIR "/drive4.dcf\r\n",
                                "# options\n"
                                "[MASTER]\n"
                                "  CPJ  =  net.cpj  ; the nodelist\n"
                                "Interface = vcan1#2\n"
                                "sdo_timeout = 100\n"
                                "sdo_timeout = 200 ; the last one wins\n"
                                "\t; indented comment\n"
                                "[node4] # the drive\n"
                                "heartbeat = 50\n"
                                "[Master]\n"
                                "boot_time = 7\n"
                                "[Node4]\n"
                                "guard_time = 20\n"),
                     0);
    ck_assert_str_eq(net.net_name, "syntax");
    ck_assert_str_eq(net.slave[0].name, "first#drive");
    ck_assert_str_eq(net.iface, "vcan1#2");
    ck_assert_uint_eq(net.config.sdo_timeout_ms, 200);
    ck_assert_uint_eq(net.config.boot_time_ms, 7);
    ck_assert_uint_eq(slave(0)->heartbeat_ms, 50);
    ck_assert_uint_eq(slave(0)->guard_ms, 20);
}
END_TEST

/* Syntax errors of either file name the file and the line, comments and blank lines counted. */
START_TEST(option_file_and_nodelist_syntax_errors)
{
    ck_assert_int_eq(load_with("; comment\n\n[Node4\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini:5: section header '[Node4' has no ']'"));
    ck_assert_int_eq(load_with("[Node4 ; a comment]\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini:3: section header '[Node4' has no ']'"));
    ck_assert_int_eq(load_with("\n  no equals sign ; comment\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(
        strstr(err, "/net.ini:4: 'no equals sign' is neither a [section] nor a key = value line"));
    ck_assert_int_eq(load_with("; comment\nsdo_timeout = 4 ; ms\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini:4: sdo_timeout = '4': give 5..5000 ms"));
    ck_assert_int_eq(load_files(NODELIST, "cpj = net.cpj\n[Master]\ncpj = net.cpj\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.ini:1: unknown section [] (give [Master] and [NodeN]"));
    ck_assert_int_eq(
        load_files("; nodelist\n[Topology]\nNodes = many\n", "[Master]\ncpj = net.cpj\n"),
        EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.cpj:3: Nodes = 'many': not a number of nodes 0..127"));
    ck_assert_int_eq(load_files("[Topology\n", "[Master]\ncpj = net.cpj\n"), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/net.cpj:1: section header '[Topology' has no ']'"));
    ck_assert_uint_eq(net.slave_count, 0);
}
END_TEST

/* ---- a DCF's values and PDOs, as the master downloads them ---------------------------------- */

/* The DCF `text` (after a [1000] section, so line 6 is its first line) as node 4's, for boot. */
static int load_dcf(const char *text)
{
    comaster_network_free(&net);
    char file[4096];
    snprintf(file, sizeof file,
             "[1000]\nParameterName=Device type\nDataType=0x0007\nAccessType=ro\n"
             "DefaultValue=0x00010192\n%s",
             text);
    write_file(dcf, file);
    return comaster_network_single(&net, 4, dcf, err, sizeof err);
}

/* An object section of the DCF: a plain variable, read-write, with its ParameterValue. */
#define VARIABLE(index, type, value)                                                               \
    "[" index "]\nParameterName=v\nObjectType=0x7\nDataType=" type                                 \
    "\nAccessType=rw\nParameterValue=" value "\n"

/* The writes of node 4 as the expedited SDO downloads that carry them, in candump text, one
 * after the other with a blank; a write of more than 4 bytes as "segmented". */
static const char *download_frames(void)
{
    static char text[4096];
    static const uint8_t command[] = {0, 0x2F, 0x2B, 0x27, 0x23};
    size_t used = 0;
    text[0] = '\0';
    for (size_t i = 0; i < write_count(slave(0)); i++) {
        co_net_write_t write = write_at(slave(0), i);
        const co_net_write_t *w = &write;
        const char *blank = i ? " " : "";
        if (w->len > 4) {
            used += (size_t)snprintf(text + used, sizeof text - used, "%ssegmented", blank);
            continue;
        }
        uint8_t data[4] = {0};
        memcpy(data, w->data, w->len);
        used += (size_t)snprintf(text + used, sizeof text - used,
                                 "%s604#%02X%02X%02X%02X%02X%02X%02X%02X", blank, command[w->len],
                                 w->index & 0xFF, w->index >> 8, w->subindex, data[0], data[1],
                                 data[2], data[3]);
    }
    return text;
}

/* CiA 306: a sign for the signed types, decimal, 0x hexadecimal, 0 octal, $NODEID+number; every
 * integer type to its limits, BOOLEAN, REAL32/REAL64 as decimal numbers. */
START_TEST(every_numeric_form_of_every_type)
{
    ck_assert_int_eq(
        load_dcf(VARIABLE("2005", "0x0003", "-1234") VARIABLE("2006", "0x0002", "-128")
                     VARIABLE("2007", "0x0004", "-0x10") VARIABLE("2008", "0x0006", "010")
                         VARIABLE("2009", "0x0007", "$NODEID+0x180") VARIABLE("200A", "0x0001", "1")
                             VARIABLE("200B", "0x0008", "-1.5") VARIABLE("200C", "0x0003", "32767")
                                 VARIABLE("200D", "0x0003", "-32768")
                                     VARIABLE("200E", "0x0002", "-010")),
        0);
    ck_assert_str_eq(download_frames(), "604#2B0520002EFB0000 604#2F06200080000000 "
                                        "604#23072000F0FFFFFF 604#2B08200008000000 "
                                        "604#2309200084010000 604#2F0A200001000000 "
                                        "604#230B20000000C0BF 604#2B0C2000FF7F0000 "
                                        "604#2B0D200000800000 604#2F0E2000F8000000");
    ck_assert_int_eq(load_dcf(VARIABLE("2005", "0x0015", "-2") VARIABLE(
                         "2006", "0x001B", "0xFFFFFFFFFFFFFFFF") VARIABLE("2007", "0x0011", "0.5")),
                     0);
    ck_assert_str_eq(download_frames(), "segmented segmented segmented");
    ck_assert_mem_eq(write_at(slave(0), 0).data, "\xFE\xFF\xFF\xFF\xFF\xFF\xFF\xFF", 8);
    ck_assert_mem_eq(write_at(slave(0), 1).data, "\xFF\xFF\xFF\xFF\xFF\xFF\xFF\xFF", 8);
    ck_assert_mem_eq(write_at(slave(0), 2).data, "\x00\x00\x00\x00\x00\x00\xE0\x3F", 8);
}
END_TEST

/* What cannot be written is refused with the file, the line, the section and the key. */
START_TEST(values_out_of_their_type_are_refused)
{
    static const struct {
        const char *dcf;
        const char *message;
    } cases[] = {
        {VARIABLE("2005", "0x0003", "-32769"),
         ":11: [2005] ParameterValue = '-32769': out of range for INTEGER16 (-32768..32767)"},
        {VARIABLE("2005", "0x0003", "0xFFFF"),
         ":11: [2005] ParameterValue = '0xFFFF': out of range for INTEGER16 (-32768..32767)"},
        {VARIABLE("2005", "0x0006", "-1"),
         ":11: [2005] ParameterValue = '-1': out of range for UNSIGNED16 (0..65535, no sign)"},
        {VARIABLE("2005", "0x0006", "70000"),
         ":11: [2005] ParameterValue = '70000': out of range for UNSIGNED16 (0..65535)"},
        {VARIABLE("2005", "0x0005", "256"),
         ":11: [2005] ParameterValue = '256': out of range for UNSIGNED8 (0..255)"},
        {VARIABLE("2005", "0x0001", "2"),
         ":11: [2005] ParameterValue = '2': out of range for BOOLEAN (0..1)"},
        {VARIABLE("2005sub3", "0x0003", "$NODEID+-5"),
         ":11: [2005sub3] ParameterValue = '$NODEID+-5': not a number for INTEGER16: give 12, "
         "-12 (a signed type), 0x1F, 017 or $NODEID+number"},
        {VARIABLE("2005", "0x0003", "-$NODEID"), ":11: [2005] ParameterValue = '-$NODEID': not a "
                                                 "number for INTEGER16"},
        {VARIABLE("2005", "0x0008", "0x3F800000"),
         ":11: [2005] ParameterValue = '0x3F800000': not a number for REAL32: give a decimal "
         "number such as 1.5 or -2e3"},
        {VARIABLE("2005", "0x0008", "1e39"),
         ":11: [2005] ParameterValue = '1e39': 1e39 is out of range for REAL32"},
        {VARIABLE("2005", "0x0010", "-5"),
         ":11: [2005] ParameterValue = '-5': comaster cannot write a value of DataType 0x0010"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ck_assert_int_eq(load_dcf(cases[i].dcf), EX_DATAERR);
        ck_assert_msg(strstr(err, cases[i].message) != NULL, "%zu: %s", i, err);
        ck_assert_ptr_nonnull(strstr(err, "/slave.dcf:11: ["));
    }
}
END_TEST

#define SUB(index, sub, type, key, value)                                                          \
    "[" index "sub" sub "]\nParameterName=v\nDataType=" type "\nAccessType=rw\n" key "=" value "\n"

/* TPDO1's COB-ID with the slave's default and the DCF's value. */
#define TPDO1_COB_ID(default_value, value)                                                         \
    "[1800sub1]\nParameterName=v\nDataType=0x0007\nAccessType=rw\nDefaultValue=" default_value     \
    "\nParameterValue=" value "\n"

/* TPDO1 of a DCF that changes its transmission type, inhibit time, event timer and mapping, the
 * PDO being valid: CiA 301's procedure as CiA 302 masters follow it, at the place of the PDO's
 * first entry: invalidate, parameters, mapping count 0, entries, count, validate. */
START_TEST(pdo_configured_invalid_then_valid)
{
    ck_assert_int_eq(
        load_dcf(
            VARIABLE("2005", "0x0003", "-1234") SUB("1800", "2", "0x0005", "ParameterValue", "254")
                SUB("1800", "1", "0x0007", "DefaultValue", "$NODEID+0x180")
                    SUB("1800", "3", "0x0006", "ParameterValue", "100")
                        SUB("1800", "5", "0x0006", "ParameterValue", "500")
                            SUB("1A00", "0", "0x0005", "ParameterValue", "2")
                                SUB("1A00", "1", "0x0007", "ParameterValue", "0x60410010")
                                    SUB("1A00", "2", "0x0007", "ParameterValue", "0x20050010")
                                        VARIABLE("2006", "0x0005", "7")),
        0);
    ck_assert_str_eq(download_frames(), "604#2B0520002EFB0000 "
                                        "604#2300180184010080 "
                                        "604#2F001802FE000000 "
                                        "604#2B00180364000000 "
                                        "604#2B001805F4010000 "
                                        "604#2F001A0000000000 "
                                        "604#23001A0110004160 "
                                        "604#23001A0210000520 "
                                        "604#2F001A0002000000 "
                                        "604#2300180184010000 "
                                        "604#2F06200007000000");
    /* A PDO the DCF leaves invalid stays so: no validation at the end. */
    ck_assert_int_eq(load_dcf(SUB("1800", "1", "0x0007", "ParameterValue", "0x80000184")
                                  SUB("1800", "5", "0x0006", "ParameterValue", "500")),
                     0);
    ck_assert_str_eq(download_frames(), "604#2300180184010080 604#2B001805F4010000");
    /* Only a COB-ID, the PDO invalid by default: written alone. */
    ck_assert_int_eq(load_dcf(SUB("1800", "1", "0x0007", "ParameterValue", "$NODEID+0x190")), 0);
    ck_assert_str_eq(download_frames(), "604#2300180194010000");
    ck_assert_int_eq(load_dcf(TPDO1_COB_ID("0x80000184", "$NODEID+0x190")), 0);
    ck_assert_str_eq(download_frames(), "604#2300180194010000");
    /* Only a COB-ID, same CAN-ID as the default: written alone. */
    ck_assert_int_eq(load_dcf(TPDO1_COB_ID("$NODEID+0x180", "0x40000184")), 0);
    ck_assert_str_eq(download_frames(), "604#2300180184010040");
}
END_TEST

/* A DCF that changes only the CAN-ID of a PDO valid on the slave: the slave refuses a new CAN-ID
 * of a valid PDO (0x06090030), so the master first invalidates it on its old COB-ID (the DCF's
 * DefaultValue, which the slave holds after its reset) and then writes the new one. */
START_TEST(pdo_can_id_changed_on_a_valid_pdo)
{
    ck_assert_int_eq(load_dcf(TPDO1_COB_ID("$NODEID+0x180", "$NODEID+0x190")), 0);
    ck_assert_str_eq(download_frames(), "604#2300180184010080 604#2300180194010000");
    /* A new COB-ID that leaves the PDO invalid needs no invalidation first. */
    ck_assert_int_eq(load_dcf(TPDO1_COB_ID("$NODEID+0x180", "0x80000194")), 0);
    ck_assert_str_eq(download_frames(), "604#2300180194010080");
    /* A whole PDO whose CAN-ID changes is invalidated on its old COB-ID too. */
    ck_assert_int_eq(load_dcf(TPDO1_COB_ID("$NODEID+0x180", "$NODEID+0x190")
                                  SUB("1800", "5", "0x0006", "ParameterValue", "500")),
                     0);
    ck_assert_str_eq(download_frames(),
                     "604#2300180184010080 604#2B001805F4010000 604#2300180194010000");
    /* Without a COB-ID to invalidate and validate the PDO with, the DCF is refused. */
    ck_assert_int_eq(load_dcf(SUB("1A00", "0", "0x0005", "ParameterValue", "1")), EX_DATAERR);
    ck_assert_ptr_nonnull(strstr(err, "/slave.dcf: [1800sub1] has no value (ParameterValue or "
                                      "DefaultValue) to configure the PDO with"));
}
END_TEST

static Suite *network_suite(void)
{
    Suite *s = suite_create("network");
    TCase *tc = tcase_create("network");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, bench_slaves_and_options);
    tcase_add_test(tc, configuration_writes_from_the_dcf);
    tcase_add_test(tc, process_image_from_the_mappings);
    tcase_add_test(tc, unknown_variables_are_told);
    tcase_add_test(tc, one_slave_for_boot);
    tcase_add_test(tc, node_options);
    tcase_add_test(tc, master_heartbeat_and_node_id);
    tcase_add_test(tc, master_bit_rate_code);
    tcase_add_test(tc, nmt_startup_options_and_1f80);
    tcase_add_test(tc, slave_assignment_1f81);
    tcase_add_test(tc, expected_identity_and_boot_time_objects);
    tcase_add_test(tc, bad_files_are_refused);
    tcase_add_test(tc, option_file_and_nodelist_syntax);
    tcase_add_test(tc, option_file_and_nodelist_syntax_errors);
    tcase_add_test(tc, every_numeric_form_of_every_type);
    tcase_add_test(tc, values_out_of_their_type_are_refused);
    tcase_add_test(tc, pdo_configured_invalid_then_valid);
    tcase_add_test(tc, pdo_can_id_changed_on_a_valid_pdo);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(network_suite());
}
