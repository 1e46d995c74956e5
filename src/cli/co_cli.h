/* SPDX-License-Identifier: Apache-2.0 */
/* What the four programs (atv312d, comaster, cotrace, dnscan) share in their messages and exit
 * statuses (docs/architecture.md, "Messages and exit statuses"): the error line on stderr, the
 * hint after a usage error, the --json twin on stdout, JSON strings, the words for an interface
 * that would not open, and the statuses below 64 (64 and above are sysexits.h's). */
#ifndef CO_CLI_H
#define CO_CLI_H

#include "co_linux/log.h"
#include "co_linux/loop.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <sysexits.h>

/* Each status means one thing in every program; the programs' --help and docs list theirs. */
#define CLI_EXIT_OK 0
/* The other side said no: an SDO abort, a CIP error response, a control socket's error reply. */
#define CLI_EXIT_REFUSED 1
#define CLI_EXIT_TIMEOUT 2       /* no answer, or not the state awaited, in time */
#define CLI_EXIT_INTERRUPTED 3   /* SIGINT or SIGTERM before the command finished */
#define CLI_EXIT_DRIVE_FAULT 4   /* comaster drive: the drive is in Fault */
#define CLI_EXIT_MAC_ID_IN_USE 5 /* dnscan: the scanner's MAC ID is in use on the bus */

/* An option that takes a value, and the value's name in --help: {"--timeout", "MS"}. */
typedef struct cli_valued_option {
    const char *option;
    const char *value;
} cli_valued_option_t;

/* The name of the value `option` takes in the table of `count` options, NULL when it is not
 * there: the "give --timeout MS" of an option given without its value. */
const char *cli_value_name(const cli_valued_option_t *table, size_t count, const char *option);

/* Writes `text` to `out` as a JSON string, escaped as the JSON writer does (cli/json.h). */
void cli_json_string(FILE *out, const char *text);

/* An error: "<program>: error: <message>" on stderr (co_log's line at CO_LOG_ERROR, <program>
 * the ident of co_log_setup); after a usage error (EX_USAGE) the line "Try '<program> [<command>]
 * --help'." (`command`: the subcommand whose arguments were wrong, or NULL); when json, also
 * {"error": "<message>", "exit": <status>} on stdout. Returns `status`. */
int cli_vfail(const char *command, bool json, int status, const char *format, va_list ap)
    __attribute__((format(printf, 4, 0)));
int cli_fail(const char *command, int status, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/* Why co_linux_loop_open failed (result, with the loop's iface, open_call and open_errno) in one
 * line, with what to do: `iface_env` names the program's interface variable ("DNSCAN_IFACE"),
 * NULL when it has none. Returns the exit status: EX_UNAVAILABLE for the kernel or the
 * interface, EX_OSERR for a system call. */
int cli_open_error_text(const co_linux_loop_t *loop, co_linux_open_result_t result,
                        const char *iface_env, char *out, size_t cap);

#endif
