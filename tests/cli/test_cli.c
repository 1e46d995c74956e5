/* SPDX-License-Identifier: Apache-2.0 */
/* src/cli: the programs' error line, the hint after a usage error and the --json twin, byte for
 * byte with the status returned; the exit statuses' one meaning each; what comaster, cotrace and
 * dnscan print when the interface does not open, word for word with its exit status; the value
 * names of options; JSON strings escaped. */
#include "check_main.h"
#include "cli/co_cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

static co_linux_loop_t loop;
static char text[512];

static void failed(const char *call, int err)
{
    memset(&loop, 0, sizeof loop);
    strcpy(loop.iface, "vcan9");
    loop.open_call = call;
    loop.open_errno = err;
}

/* What a call to cli_vfail (through fail_captured below) wrote to stderr and stdout. */
static char err_text[2048], out_text[2048];

static void read_back(FILE *f, char *buf, size_t cap)
{
    rewind(f);
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
}

static int fail_captured(const char *command, bool json, int status, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

static int fail_captured(const char *command, bool json, int status, const char *format, ...)
{
    FILE *err = tmpfile(), *out = tmpfile();
    ck_assert(err && out);
    fflush(stdout);
    int saved_err = dup(STDERR_FILENO), saved_out = dup(STDOUT_FILENO);
    dup2(fileno(err), STDERR_FILENO);
    dup2(fileno(out), STDOUT_FILENO);
    va_list ap;
    va_start(ap, format);
    int rc = cli_vfail(command, json, status, format, ap);
    va_end(ap);
    fflush(stdout);
    fflush(stderr);
    dup2(saved_err, STDERR_FILENO);
    dup2(saved_out, STDOUT_FILENO);
    close(saved_err);
    close(saved_out);
    read_back(err, err_text, sizeof err_text);
    read_back(out, out_text, sizeof out_text);
    return rc;
}

static void setup(void)
{
    unsetenv("JOURNAL_STREAM"); /* the journal's priority prefix is the log's tests' */
}

/* An error is "PROGRAM: error: WHAT" and its status; nothing on stdout without --json. */
START_TEST(error_line_and_status)
{
    co_log_setup("dnscan", CO_LOG_WARN);
    ck_assert_int_eq(fail_captured(NULL, false, CLI_EXIT_TIMEOUT, "MAC ID %u: no answer", 63u),
                     CLI_EXIT_TIMEOUT);
    ck_assert_str_eq(err_text, "dnscan: error: MAC ID 63: no answer\n");
    ck_assert_str_eq(out_text, "");
}
END_TEST

/* After a usage error, the help to read: the program's, or its command's. */
START_TEST(usage_error_names_the_help)
{
    co_log_setup("atv312d", CO_LOG_INFO);
    ck_assert_int_eq(fail_captured(NULL, false, EX_USAGE, "unknown option '%s'", "--bitrate"),
                     EX_USAGE);
    ck_assert_str_eq(err_text, "atv312d: error: unknown option '--bitrate'\n"
                               "Try 'atv312d --help'.\n");
    co_log_setup("comaster", CO_LOG_WARN);
    ck_assert_int_eq(fail_captured("read", false, EX_USAGE, "read: unknown option '--x'"),
                     EX_USAGE);
    ck_assert_str_eq(err_text, "comaster: error: read: unknown option '--x'\n"
                               "Try 'comaster read --help'.\n");
    /* Other statuses have no hint, whatever the command. */
    ck_assert_int_eq(fail_captured("read", false, EX_DATAERR, "bad"), EX_DATAERR);
    ck_assert_str_eq(err_text, "comaster: error: bad\n");
}
END_TEST

/* With --json the same message and status as one JSON object on stdout. */
START_TEST(json_twin)
{
    co_log_setup("comaster", CO_LOG_WARN);
    ck_assert_int_eq(fail_captured("write", true, EX_USAGE, "'%s' is not a node-id", "0\"x"),
                     EX_USAGE);
    ck_assert_str_eq(err_text, "comaster: error: '0\"x' is not a node-id\n"
                               "Try 'comaster write --help'.\n");
    ck_assert_str_eq(out_text, "{\"error\": \"'0\\\"x' is not a node-id\", \"exit\": 64}\n");
}
END_TEST

/* The statuses below 64 each mean one thing in every program, none of sysexits.h's. */
START_TEST(exit_statuses_are_distinct)
{
    const int statuses[] = {CLI_EXIT_OK,          CLI_EXIT_REFUSED,     CLI_EXIT_TIMEOUT,
                            CLI_EXIT_INTERRUPTED, CLI_EXIT_DRIVE_FAULT, CLI_EXIT_MAC_ID_IN_USE};
    size_t count = sizeof statuses / sizeof statuses[0];
    for (size_t i = 0; i < count; i++) {
        ck_assert_int_eq(statuses[i], (int)i);
        ck_assert_int_lt(statuses[i], EX__BASE);
    }
}
END_TEST

START_TEST(interface_errors)
{
    co_log_setup("dnscan", CO_LOG_WARN);
    failed("socket(PF_CAN, SOCK_RAW, CAN_RAW)", EAFNOSUPPORT);
    ck_assert_int_eq(
        cli_open_error_text(&loop, CO_LINUX_OPEN_NO_CAN, "DNSCAN_IFACE", text, sizeof text),
        EX_UNAVAILABLE);
    ck_assert_str_eq(text, "this kernel has no SocketCAN support (socket(PF_CAN, SOCK_RAW, "
                           "CAN_RAW): Address family not supported by protocol): load it with "
                           "modprobe can-raw vcan, or run inside the sandbox: tools/vcan-run "
                           "dnscan ...");

    co_log_setup("comaster", CO_LOG_WARN);
    failed("if_nametoindex", ENODEV);
    ck_assert_int_eq(
        cli_open_error_text(&loop, CO_LINUX_OPEN_NO_IFACE, "COMASTER_IFACE", text, sizeof text),
        EX_UNAVAILABLE);
    ck_assert_str_eq(text, "no network interface 'vcan9': give one with -i IFACE or "
                           "$COMASTER_IFACE (list them: ip link show type can, or type vcan)");

    /* cotrace has no variable for its interface. */
    co_log_setup("cotrace", CO_LOG_WARN);
    ck_assert_int_eq(cli_open_error_text(&loop, CO_LINUX_OPEN_NO_IFACE, NULL, text, sizeof text),
                     EX_UNAVAILABLE);
    ck_assert_str_eq(text, "no network interface 'vcan9': give one with -i IFACE (list them: ip "
                           "link show type can, or type vcan)");

    co_log_setup("dnscan", CO_LOG_WARN);
    failed("bind", ENODEV);
    ck_assert_int_eq(
        cli_open_error_text(&loop, CO_LINUX_OPEN_NOT_CAN, "DNSCAN_IFACE", text, sizeof text),
        EX_UNAVAILABLE);
    ck_assert_str_eq(text, "'vcan9' is not a CAN interface (bind: No such device): give a "
                           "SocketCAN interface such as can0 or vcan0 with -i");

    failed("epoll_create1", EMFILE);
    ck_assert_int_eq(
        cli_open_error_text(&loop, CO_LINUX_OPEN_OS_ERROR, "DNSCAN_IFACE", text, sizeof text),
        EX_OSERR);
    ck_assert_str_eq(text, "epoll_create1 on vcan9 failed: Too many open files");
}
END_TEST

START_TEST(value_names)
{
    static const cli_valued_option_t table[] = {{"--timeout", "MS"}, {"-i", "IFACE"}};
    ck_assert_str_eq(cli_value_name(table, 2, "-i"), "IFACE");
    ck_assert_str_eq(cli_value_name(table, 2, "--timeout"), "MS");
    ck_assert_ptr_null(cli_value_name(table, 2, "--time"));
}
END_TEST

START_TEST(json_strings)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&buf, &len);
    ck_assert_ptr_nonnull(out);
    cli_json_string(out, "a \"b\" c\\d\te\x01");
    fclose(out);
    ck_assert_str_eq(buf, "\"a \\\"b\\\" c\\\\d\\u0009e\\u0001\"");
    free(buf);
}
END_TEST

static Suite *cli_suite(void)
{
    Suite *s = suite_create("cli");
    TCase *tc = tcase_create("cli");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, error_line_and_status);
    tcase_add_test(tc, usage_error_names_the_help);
    tcase_add_test(tc, json_twin);
    tcase_add_test(tc, exit_statuses_are_distinct);
    tcase_add_test(tc, interface_errors);
    tcase_add_test(tc, value_names);
    tcase_add_test(tc, json_strings);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(cli_suite());
}
