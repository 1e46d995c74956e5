/* SPDX-License-Identifier: Apache-2.0 */
/* dnscan: what its files share: the options, the errors and --json with the exit statuses
 * (co_cli.h) and a number of an argument, in dnscan.c; and the commands of commands.c, which the
 * table in main.c runs. */
#ifndef DNSCAN_H
#define DNSCAN_H

#include "cli/co_cli.h"
#include "dn/dn_scanner.h"

#include <stdbool.h>
#include <stdint.h>

#define DNSCAN_DEFAULT_IFACE "can0"
#define DNSCAN_DEFAULT_TIMEOUT_MS 1000u
#define DNSCAN_MAX_ARGS 12
#define DNSCAN_MAX_SETS 8

typedef struct dnscan_options {
    const char *iface;
    uint8_t mac_id;
    uint32_t timeout_ms;
    bool json;
    bool no_check;
    bool ucmm;            /* --ucmm-connection: get and set over a connection the UCMM opens */
    const char *type;     /* get --type */
    const char *assembly; /* poll --assembly OUT/IN */
    const char *output;   /* poll --output HEX */
    const char *sets[DNSCAN_MAX_SETS];
    int set_count;
    uint32_t every_ms;
    uint32_t count;
    const char *args[DNSCAN_MAX_ARGS]; /* the command, then its arguments */
    int arg_count;
} dnscan_options_t;

int dnscan_fail(const dnscan_options_t *opts, int status, const char *format, ...)
    __attribute__((format(printf, 3, 4)));
bool dnscan_parse_number(const char *text, unsigned long max, unsigned long *value);

int dnscan_scan(dnscan_options_t *opts);
int dnscan_get(dnscan_options_t *opts);
int dnscan_set(dnscan_options_t *opts);
int dnscan_allocate(dnscan_options_t *opts);
int dnscan_release(dnscan_options_t *opts);
int dnscan_poll(dnscan_options_t *opts);
int dnscan_monitor(dnscan_options_t *opts);

#endif
