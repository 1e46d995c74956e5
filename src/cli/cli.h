/* What the command-line tools (comaster, dnscan) share in their output: the one-line error on
 * stderr with its --json twin on stdout, JSON strings, and the words for an interface that would
 * not open (docs/comaster.md, docs/dnscan.md: "Errors and exit codes"). */
#ifndef CO_CLI_H
#define CO_CLI_H

#include "co_linux/loop.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* Writes `text` to `out` as a JSON string: quoted, '"' and '\' escaped, control characters as
 * \u00XX. */
void cli_json_string(FILE *out, const char *text);

/* "<program>: <message>" on stderr and, when json, {"error": "<message>", "exit": <status>} on
 * stdout; returns `status`. */
int cli_vfail(const char *program, bool json, int status, const char *format, va_list ap)
    __attribute__((format(printf, 4, 0)));

/* Why co_linux_loop_open failed (result, with the loop's iface, open_call and open_errno) in one
 * line, with what to do: `iface_env` names the program's interface variable ("DNSCAN_IFACE").
 * Returns the exit status: EX_UNAVAILABLE for the kernel or the interface, EX_OSERR for a
 * system call. */
int cli_open_error_text(const co_linux_loop_t *loop, co_linux_open_result_t result,
                        const char *program, const char *iface_env, char *out, size_t cap);

#endif
