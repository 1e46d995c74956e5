/* SPDX-License-Identifier: Apache-2.0 */
/* The programs' messages and exit statuses (co_cli.h). */
#include "cli/co_cli.h"

#include "cli/json.h"

#include <string.h>

const char *cli_value_name(const cli_valued_option_t *table, size_t count, const char *option)
{
    for (size_t i = 0; i < count; i++) {
        if (strcmp(table[i].option, option) == 0)
            return table[i].value;
    }
    return NULL;
}

void cli_json_string(FILE *out, const char *text)
{
    fputc('"', out);
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) {
        char escaped[CLI_JSON_ESCAPE_MAX];
        fwrite(escaped, 1, cli_json_escape(*p, escaped), out);
    }
    fputc('"', out);
}

int cli_vfail(const char *command, bool json, int status, const char *format, va_list ap)
{
    char message[1024];
    vsnprintf(message, sizeof message, format, ap);
    co_log(CO_LOG_ERROR, "%s", message);
    if (status == EX_USAGE)
        fprintf(stderr, "Try '%s%s%s --help'.\n", co_log_ident(), command ? " " : "",
                command ? command : "");
    if (json) {
        printf("{\"error\": ");
        cli_json_string(stdout, message);
        printf(", \"exit\": %d}\n", status);
    }
    return status;
}

int cli_fail(const char *command, int status, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    status = cli_vfail(command, false, status, format, ap);
    va_end(ap);
    return status;
}

int cli_open_error_text(const co_linux_loop_t *loop, co_linux_open_result_t result,
                        const char *iface_env, char *out, size_t cap)
{
    const char *why = strerror(loop->open_errno);
    switch (result) {
    case CO_LINUX_OPEN_NO_CAN:
        snprintf(out, cap,
                 "this kernel has no SocketCAN support (%s: %s): load it with modprobe can-raw "
                 "vcan, or run inside the sandbox: tools/vcan-run %s ...",
                 loop->open_call, why, co_log_ident());
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NO_IFACE:
        snprintf(out, cap,
                 "no network interface '%s': give one with -i IFACE%s%s (list them: ip link "
                 "show type can, or type vcan)",
                 loop->iface, iface_env ? " or $" : "", iface_env ? iface_env : "");
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_NOT_CAN:
        snprintf(out, cap,
                 "'%s' is not a CAN interface (%s: %s): give a SocketCAN interface such as can0 "
                 "or vcan0 with -i",
                 loop->iface, loop->open_call, why);
        return EX_UNAVAILABLE;
    case CO_LINUX_OPEN_OS_ERROR:
    case CO_LINUX_OPEN_OK:
        break;
    }
    snprintf(out, cap, "%s on %s failed: %s", loop->open_call, loop->iface, why);
    return EX_OSERR;
}
