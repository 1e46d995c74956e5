/* SPDX-License-Identifier: Apache-2.0 */
/* What dnscan's files share (dnscan.h), below the command line (main.c), the commands
 * (commands.c) and the bus (run.c): an error as the programs print it, and a number of an
 * argument. */
#include "dnscan/dnscan.h"

#include "cli/co_cli.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>

int dnscan_fail(const dnscan_options_t *opts, int status, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    status = cli_vfail(NULL, opts->json, status, format, ap);
    va_end(ap);
    return status;
}

bool dnscan_parse_number(const char *text, unsigned long max, unsigned long *value)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(text, &end, 0);
    if (errno || end == text || *end || text[0] == '-' || v > max)
        return false;
    *value = v;
    return true;
}
