/* SPDX-License-Identifier: Apache-2.0 */
/* dnscan: a DeviceNet scanner on a SocketCAN interface, for people and scripts: scan the bus,
 * allocate and release a slave's connections, get and set any attribute, poll I/O by the
 * assembly's names, monitor (docs/dnscan.md). The command line and output are here; the bus is
 * the Linux runtime's loop with the portable scanner (src/devicenet/scanner) as its device. */
#include "dnscan/dnscan.h"

#include "cli/co_cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: dnscan [-i IFACE] [--mac-id N] [--timeout MS] [--no-check]\n"
    "              [--ucmm-connection] [--json] COMMAND [ARGS...]\n"
    "\n"
    "A DeviceNet scanner (master) on a SocketCAN interface, using the slaves'\n"
    "predefined master/slave connection set, or their UCMM for get and set.\n"
    "\n"
    "Commands:\n"
    "  scan                         the slaves present and their identity\n"
    "  get MAC CLASS INST ATTR [--type T]\n"
    "                               an attribute (Get_Attribute_Single)\n"
    "  set MAC CLASS INST ATTR VALUE...\n"
    "                               set an attribute: hexadecimal bytes (B0 04),\n"
    "                               or TYPE:NUMBER (u8 u16 u32 i8 i16 i32: u16:1200)\n"
    "  allocate MAC [CHOICE]        allocate connections (default 0x03: explicit\n"
    "                               and polled; 0x10 COS, 0x20 cyclic, 0x40 no ack)\n"
    "  release MAC [CHOICE]         release connections (default 0x33: all)\n"
    "  poll MAC [--assembly OUT/IN] [--output HEX] [--set NAME=VALUE]...\n"
    "       [--every MS] [--count N]\n"
    "                               poll I/O once, or every MS (N times, or until\n"
    "                               interrupted); values by the assembly's names\n"
    "  monitor                      the DeviceNet frames as they arrive\n"
    "\n"
    "MAC is a MAC ID 0..63 (poll: also a list and ranges, 1-63 or 5,7); CLASS,\n"
    "INST, ATTR decimal or 0x hexadecimal. poll --every keeps each connection:\n"
    "lost (4 polls in a row unanswered), it is allocated again (3 tries 1 s apart,\n"
    "then every 10 s); SIGINT or SIGTERM releases what was allocated.\n"
    "\n"
    "Options:\n"
    "  -i, --interface IFACE  the SocketCAN interface; default $DNSCAN_IFACE, else can0\n"
    "                         (a real bus: the examples give -i vcan0, a virtual one)\n"
    "  --mac-id N     the scanner's own MAC ID (default 0)\n"
    "  --timeout MS   how long to wait for each answer (default 1000)\n"
    "  --no-check     skip the duplicate MAC ID check (2 s) of the scanner's MAC ID\n"
    "  --ucmm-connection  get, set: open the explicit connection by the slave's\n"
    "                     UCMM (group 3), not by Allocate, and close it after\n"
    "  --json         one JSON object per result line, for scripts\n"
    "  --type T       get: print the value as u8 u16 u32 i8 i16 i32 or string\n"
    "  --assembly OUT/IN  poll: the assemblies in use (default: read from the slave)\n"
    "  --output HEX   poll: the output data (default all zeros)\n"
    "  --set NAME=VALUE   poll: an output field by name (Run_fwd=1, Speed_reference=1200)\n"
    "  --every MS     poll: poll every MS milliseconds\n"
    "  --count N      poll: N polls, monitor: N frames\n"
    "  -h, --help     show this help\n"
    "  -V, --version  show the version\n"
    "\n"
    "Example: dnscan -i vcan0 get 63 1 1 7 --type string\n"
    "\n"
    "An error is one line on stderr, 'dnscan: error: ' then what is wrong and what\n"
    "would be right; after wrong arguments a second line names the --help to read.\n"
    "\n"
    "Exit status:\n"
    "  0   done\n"
    "  1   refused: the slave answered with a CIP error, or a fragment was refused\n"
    "      or lost\n"
    "  2   no answer in time\n"
    "  3   interrupted by SIGINT or SIGTERM before the command finished\n"
    "  5   the scanner's MAC ID is in use on the bus (give another with --mac-id)\n"
    "  64  wrong arguments: an unknown command or option, a bad MAC ID, class,\n"
    "      instance, attribute, type or assembly\n"
    "  65  bad data: a value, --output or a --set value that does not fit\n"
    "  69  no such interface, or no SocketCAN\n"
    "  70  internal error\n"
    "  71  system error\n";

/* Options that take a value, and what --help calls it. */
static const cli_valued_option_t valued[] = {
    {"-i", "IFACE"},   {"--interface", "IFACE"}, {"--mac-id", "N"},   {"--timeout", "MS"},
    {"--type", "T"},   {"--assembly", "OUT/IN"}, {"--output", "HEX"}, {"--set", "NAME=VALUE"},
    {"--every", "MS"}, {"--count", "N"}};

static const char *value_name(const char *arg)
{
    return cli_value_name(valued, sizeof valued / sizeof valued[0], arg);
}

static int option_value(dnscan_options_t *opts, const char *arg, const char *value)
{
    unsigned long n;
    if (strcmp(arg, "-i") == 0 || strcmp(arg, "--interface") == 0) {
        opts->iface = value;
    } else if (strcmp(arg, "--mac-id") == 0) {
        if (!dnscan_parse_number(value, DN_MAC_ID_MAX, &n))
            return dnscan_fail(opts, EX_USAGE, "--mac-id: '%s' is not a MAC ID: give 0..63", value);
        opts->mac_id = (uint8_t)n;
    } else if (strcmp(arg, "--timeout") == 0) {
        if (!dnscan_parse_number(value, 600000, &n) || n == 0)
            return dnscan_fail(opts, EX_USAGE,
                               "--timeout: '%s' is not a time: give milliseconds 1..600000", value);
        opts->timeout_ms = (uint32_t)n;
    } else if (strcmp(arg, "--every") == 0) {
        if (!dnscan_parse_number(value, 60000, &n) || n == 0)
            return dnscan_fail(opts, EX_USAGE,
                               "--every: '%s' is not a period: give milliseconds 1..60000", value);
        opts->every_ms = (uint32_t)n;
    } else if (strcmp(arg, "--count") == 0) {
        if (!dnscan_parse_number(value, UINT32_MAX, &n) || n == 0)
            return dnscan_fail(opts, EX_USAGE, "--count: '%s' is not a count: give 1 or more",
                               value);
        opts->count = (uint32_t)n;
    } else if (strcmp(arg, "--type") == 0) {
        opts->type = value;
    } else if (strcmp(arg, "--assembly") == 0) {
        opts->assembly = value;
    } else if (strcmp(arg, "--output") == 0) {
        opts->output = value;
    } else if (opts->set_count == DNSCAN_MAX_SETS) {
        return dnscan_fail(opts, EX_USAGE, "--set: at most %d fields", DNSCAN_MAX_SETS);
    } else {
        opts->sets[opts->set_count++] = value;
    }
    return -1;
}

/* Options anywhere, the command and its arguments; returns -1 to go on, else the exit status. */
static int parse(dnscan_options_t *opts, int argc, char **argv)
{
    bool options_done = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        bool is_option = !options_done && arg[0] == '-' && arg[1] != '\0';
        if (!is_option) {
            if (opts->arg_count == DNSCAN_MAX_ARGS)
                return dnscan_fail(opts, EX_USAGE,
                                   "too many arguments from '%s': a command takes at most %d", arg,
                                   DNSCAN_MAX_ARGS - 1);
            opts->args[opts->arg_count++] = arg;
        } else if (strcmp(arg, "--") == 0) {
            options_done = true;
        } else if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            fputs(usage_text, stdout);
            return 0;
        } else if (strcmp(arg, "-V") == 0 || strcmp(arg, "--version") == 0) {
            printf("dnscan %s\n", DNSCAN_VERSION);
            return 0;
        } else if (strcmp(arg, "--json") == 0) {
            opts->json = true;
        } else if (strcmp(arg, "--no-check") == 0) {
            opts->no_check = true;
        } else if (strcmp(arg, "--ucmm-connection") == 0) {
            opts->ucmm = true;
        } else if (value_name(arg)) {
            if (i + 1 == argc || argv[i + 1][0] == '\0')
                return dnscan_fail(opts, EX_USAGE, "option %s needs a value: give %s %s", arg, arg,
                                   value_name(arg));
            int rc = option_value(opts, arg, argv[++i]);
            if (rc >= 0)
                return rc;
        } else {
            return dnscan_fail(opts, EX_USAGE, "unknown option '%s'", arg);
        }
    }
    return -1;
}

typedef struct command {
    const char *name;
    int min_args;
    int max_args; /* after the command's name */
    const char *usage;
    int (*run)(dnscan_options_t *opts);
} command_t;

static const command_t commands[] = {
    {"scan", 0, 0, "scan", dnscan_scan},
    {"get", 4, 4, "get MAC CLASS INST ATTR [--type T]", dnscan_get},
    {"set", 5, DNSCAN_MAX_ARGS - 1, "set MAC CLASS INST ATTR VALUE...", dnscan_set},
    {"allocate", 1, 2, "allocate MAC [CHOICE]", dnscan_allocate},
    {"release", 1, 2, "release MAC [CHOICE]", dnscan_release},
    {"poll", 1, 1, "poll MAC [--assembly OUT/IN] [--output HEX] [--set NAME=VALUE]...",
     dnscan_poll},
    {"monitor", 0, 0, "monitor [--count N]", dnscan_monitor},
};

#define COMMAND_NAMES "scan, get, set, allocate, release, poll, monitor"

int main(int argc, char **argv)
{
    co_log_setup("dnscan", CO_LOG_WARN);
    const char *iface = getenv("DNSCAN_IFACE");
    dnscan_options_t opts = {
        .iface = iface && iface[0] ? iface : DNSCAN_DEFAULT_IFACE,
        .mac_id = DN_SCANNER_MAC_DEFAULT,
        .timeout_ms = DNSCAN_DEFAULT_TIMEOUT_MS,
    };
    int rc = parse(&opts, argc, argv);
    if (rc >= 0)
        return rc;
    if (opts.arg_count == 0)
        return dnscan_fail(&opts, EX_USAGE, "no command: give one of %s", COMMAND_NAMES);
    const char *name = opts.args[0];
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        const command_t *c = &commands[i];
        if (strcmp(c->name, name) != 0)
            continue;
        int given = opts.arg_count - 1;
        if (given < c->min_args)
            return dnscan_fail(&opts, EX_USAGE, "%s: missing arguments: usage: dnscan %s", name,
                               c->usage);
        if (given > c->max_args)
            return dnscan_fail(&opts, EX_USAGE,
                               "%s: too many arguments from '%s': usage: dnscan %s", name,
                               opts.args[c->max_args + 1], c->usage);
        if (opts.ucmm && c->run != dnscan_get && c->run != dnscan_set)
            return dnscan_fail(&opts, EX_USAGE, "--ucmm-connection: for get and set only, not %s",
                               name);
        return c->run(&opts);
    }
    return dnscan_fail(&opts, EX_USAGE, "unknown command '%s': give one of %s", name,
                       COMMAND_NAMES);
}
