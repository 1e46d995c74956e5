/* SPDX-License-Identifier: Apache-2.0 */
/* What the commands share: the common options, node-ids, one-line errors (the conventions of
 * src/cli; the EDS of a node is node_eds.c). */
#include "comaster/comaster.h"

#include "cli/co_cli.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int comaster_fail(const comaster_options_t *opts, int status, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    status = cli_vfail(opts ? opts->command : NULL, opts && opts->json, status, format, ap);
    va_end(ap);
    return status;
}

bool comaster_parse_node(const comaster_options_t *opts, const char *text, bool allow_all,
                         uint8_t *node)
{
    if (allow_all && strcmp(text, "all") == 0) {
        *node = 0;
        return true;
    }
    char *end;
    errno = 0;
    unsigned long n = strtoul(text, &end, 0);
    if (errno || end == text || *end || n < 1 || n > 127 || text[0] == '-') {
        comaster_fail(opts, EX_USAGE, "'%s' is not a node-id: give a number 1..127%s", text,
                      allow_all ? " or all" : "");
        return false;
    }
    *node = (uint8_t)n;
    return true;
}

#define TIMEOUT_MAX_MS 600000u /* ten minutes */

/* Milliseconds 1..max in decimal. */
static bool parse_ms(const char *text, uint32_t max, uint32_t *ms)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(text, &end, 10);
    if (errno || end == text || *end || v < 1 || v > max || text[0] == '-')
        return false;
    *ms = (uint32_t)v;
    return true;
}

/* Whether `arg` is one of the space-separated words of `flags`. */
static bool is_flag(const char *flags, const char *arg)
{
    size_t len = strlen(arg);
    for (const char *p = strstr(flags, arg); p; p = strstr(p + 1, arg)) {
        if ((p == flags || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0'))
            return true;
    }
    return false;
}

/* The options that take a value, and what --help calls it. */
static const cli_valued_option_t valued[] = {{"-i", "IFACE"},
                                             {"--interface", "IFACE"},
                                             {"--timeout", "MS"},
                                             {"--eds", "FILE"},
                                             {"--eds-dir", "DIR"},
                                             {"--output", "FILE"},
                                             {"--heartbeat", "MS"},
                                             {"--control", "PATH"},
                                             {"--vendor", "N"},
                                             {"--product", "N"},
                                             {"--revision", "N"},
                                             {"--frame-ms", "MS"},
                                             {"--listen", "[ADDR:]PORT"},
                                             {"--socket", "PATH"}};

int comaster_missing_value(const comaster_options_t *opts, const char *option)
{
    return comaster_fail(opts, EX_USAGE, "%s%soption %s needs a value: give %s %s",
                         opts->command ? opts->command : "", opts->command ? ": " : "", option,
                         option, cli_value_name(valued, sizeof valued / sizeof valued[0], option));
}

int comaster_parse_args(comaster_options_t *opts, comaster_args_t *args, int argc, char **argv,
                        const char *help, const char *flags, int min_args, int max_args)
{
    memset(args, 0, sizeof *args);
    const char *command = argv[0];
    /* The usage line of the help, "comaster read NODE OBJECT ...", for the argument errors. */
    const char *usage = strstr(help, "comaster");
    int usage_len = usage ? (int)strcspn(usage, "\n") : 0;
    bool options_done = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool is_option =
            !options_done && arg[0] == '-' && arg[1] != '\0' && !(arg[1] >= '0' && arg[1] <= '9');
        if (!is_option) {
            if (args->count == max_args || args->count == COMASTER_MAX_ARGS)
                return comaster_fail(opts, EX_USAGE,
                                     "%s: too many arguments from '%s': usage: %.*s", command, arg,
                                     usage_len, usage ? usage : "");
            args->positional[args->count++] = arg;
            continue;
        }
        if (strcmp(arg, "--") == 0) {
            options_done = true;
        } else if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            fputs(help, stdout);
            return 0;
        } else if (strcmp(arg, "--json") == 0) {
            opts->json = true;
        } else if (strcmp(arg, "--block") == 0 && is_flag(flags, arg)) {
            args->block = true;
        } else if (strcmp(arg, "--rpdo") == 0 && is_flag(flags, arg)) {
            args->rpdo = true;
        } else if (strcmp(arg, "-i") == 0 || strcmp(arg, "--interface") == 0 ||
                   strcmp(arg, "--timeout") == 0 || strcmp(arg, "--eds") == 0 ||
                   strcmp(arg, "--eds-dir") == 0 ||
                   (strcmp(arg, "--output") == 0 && is_flag(flags, arg)) ||
                   (strcmp(arg, "--heartbeat") == 0 && is_flag(flags, arg)) ||
                   (strcmp(arg, "--listen") == 0 && is_flag(flags, arg)) ||
                   (strcmp(arg, "--socket") == 0 && is_flag(flags, arg))) {
            if (!value || value[0] == '\0')
                return comaster_missing_value(opts, arg);
            i++;
            if (strcmp(arg, "--timeout") == 0) {
                if (!parse_ms(value, TIMEOUT_MAX_MS, &opts->timeout_ms))
                    return comaster_fail(opts, EX_USAGE,
                                         "--timeout: '%s' is not a time: give milliseconds "
                                         "1..600000",
                                         value);
            } else if (strcmp(arg, "--eds") == 0) {
                opts->eds_path = value;
            } else if (strcmp(arg, "--eds-dir") == 0) {
                opts->eds_dir = value;
            } else if (strcmp(arg, "--output") == 0) {
                args->output = value;
            } else if (strcmp(arg, "--listen") == 0) {
                args->listen = value;
            } else if (strcmp(arg, "--socket") == 0) {
                args->socket = value;
            } else if (strcmp(arg, "--heartbeat") == 0) {
                uint32_t ms;
                if (!parse_ms(value, UINT16_MAX, &ms))
                    return comaster_fail(opts, EX_USAGE,
                                         "--heartbeat: '%s' is not a consumer time: give "
                                         "milliseconds 1..65535",
                                         value);
                args->heartbeat_ms = (uint16_t)ms;
            } else {
                opts->iface = value;
            }
        } else {
            return comaster_fail(opts, EX_USAGE, "%s: unknown option '%s'", command, arg);
        }
    }
    if (args->count < min_args)
        return comaster_fail(opts, EX_USAGE, "%s: missing arguments: usage: %.*s", command,
                             usage_len, usage ? usage : "");
    return -1;
}
