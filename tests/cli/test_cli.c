/* src/cli: what comaster and dnscan print when the interface does not open, word for word with
 * its exit status, and JSON strings escaped. */
#include "check_main.h"
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

static co_linux_loop_t loop;
static char text[512];

static void failed(const char *call, int err)
{
    memset(&loop, 0, sizeof loop);
    strcpy(loop.iface, "vcan9");
    loop.open_call = call;
    loop.open_errno = err;
}

START_TEST(interface_errors)
{
    failed("socket(PF_CAN, SOCK_RAW, CAN_RAW)", EAFNOSUPPORT);
    ck_assert_int_eq(cli_open_error_text(&loop, CO_LINUX_OPEN_NO_CAN, "dnscan", "DNSCAN_IFACE",
                                         text, sizeof text),
                     EX_UNAVAILABLE);
    ck_assert_str_eq(text, "this kernel has no SocketCAN support (socket(PF_CAN, SOCK_RAW, "
                           "CAN_RAW): Address family not supported by protocol): load it with "
                           "modprobe can-raw vcan, or run inside the sandbox: tools/vcan-run "
                           "dnscan ...");

    failed("if_nametoindex", ENODEV);
    ck_assert_int_eq(cli_open_error_text(&loop, CO_LINUX_OPEN_NO_IFACE, "comaster",
                                         "COMASTER_IFACE", text, sizeof text),
                     EX_UNAVAILABLE);
    ck_assert_str_eq(text, "no network interface 'vcan9': give one with -i IFACE or "
                           "$COMASTER_IFACE (list them: ip link show type can, or type vcan)");

    failed("bind", ENODEV);
    ck_assert_int_eq(cli_open_error_text(&loop, CO_LINUX_OPEN_NOT_CAN, "dnscan", "DNSCAN_IFACE",
                                         text, sizeof text),
                     EX_UNAVAILABLE);
    ck_assert_str_eq(text, "'vcan9' is not a CAN interface (bind: No such device): give a "
                           "SocketCAN interface such as can0 or vcan0 with -i");

    failed("epoll_create1", EMFILE);
    ck_assert_int_eq(cli_open_error_text(&loop, CO_LINUX_OPEN_OS_ERROR, "dnscan", "DNSCAN_IFACE",
                                         text, sizeof text),
                     EX_OSERR);
    ck_assert_str_eq(text, "epoll_create1 on vcan9 failed: Too many open files");
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
    tcase_add_test(tc, interface_errors);
    tcase_add_test(tc, json_strings);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(cli_suite());
}
