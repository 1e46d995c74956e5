/* SPDX-License-Identifier: Apache-2.0 */
/* comaster: a CANopen master on a SocketCAN interface, for people and scripts: SDO read and
 * write, NMT, scan, monitor, a CiA 402 drive helper (docs/comaster.md). This file holds the
 * global options and the table of commands; each command lives in its own file. */
#include "comaster/comaster.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One line per command; the summary is "USAGE: WHAT" (--help lists WHAT after the name). */
static const comaster_command_t commands[] = {
    {"read", "read NODE OBJECT [TYPE]: an object's value (SDO upload)", comaster_read_main},
    {"write", "write NODE OBJECT TYPE VALUE: set an object (SDO download)", comaster_write_main},
    {"nmt", "nmt start|stop|preop|reset-node|reset-comm NODE|all: NMT command", comaster_nmt_main},
    {"scan", "scan: the nodes present, their identity and NMT state", comaster_scan_main},
    {"monitor", "monitor [NODE...]: heartbeats, EMCYs, SYNC and PDOs as they arrive",
     comaster_monitor_main},
    {"drive", "drive NODE enable|disable|quick-stop|fault-reset|speed RPM: CiA 402",
     comaster_drive_main},
    {"boot", "boot NODE DCF: boot one slave from its DCF (network master)", comaster_boot_main},
    {"run", "run NETWORK: run the network master in the foreground", comaster_run_main},
    {"concise", "concise encode|decode ...: a DCF to CiA 302's concise DCF and back",
     comaster_concise_main},
    {"set", "set NODE NAME VALUE, set %QW2000 VALUE: set an output of a run's process image",
     comaster_set_main},
    {"get", "get NODE NAME, get %IW2000: a variable of a run's process image", comaster_get_main},
    {"status", "status: the status bits of a run's master and slaves", comaster_status_main},
    {"disable", "disable: disable the communication of a run's master", comaster_disable_main},
    {"enable", "enable: enable it again (the network boots again)", comaster_enable_main},
    {"can", "can: the CAN controller's state and counters of a run", comaster_can_main},
    {"configure", "configure NODE|all: configure a run's slave again (CiA 302's 1F25h)",
     comaster_configure_main},
    {"lss", "lss SERVICE [ARGS...]: CiA 305 LSS: node-ids, bit rates, fastscan", comaster_lss_main},
    {"time", "time [PERIOD]: send TIME (100h) from the host's clock, once or every PERIOD ms",
     comaster_time_main},
    {"gateway", "gateway [--listen [ADDR:]PORT] [--socket PATH]: a CiA 309-3 ASCII gateway",
     comaster_gateway_main},
};

#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void print_usage(void)
{
    printf("usage: comaster [-i IFACE] [--timeout MS] [--json] [--eds FILE] [--eds-dir DIR]\n"
           "                COMMAND [ARGS...]\n"
           "\n"
           "A CANopen master on a SocketCAN interface: SDO read and write by index or by\n"
           "name, NMT commands, a scan of the nodes present, a monitor of heartbeats,\n"
           "emergencies, SYNC and PDOs, a CiA 402 drive helper, the CiA 305 layer\n"
           "setting services (node-ids and bit rates, fastscan) and a CiA 309-3 ASCII\n"
           "gateway.\n"
           "\n"
           "Commands (comaster COMMAND --help tells more):\n");
    /* The names in a column as wide as the longest: two spaces or more before each summary,
     * which is how tools/man-from-help.py tells a term from its description. */
    int width = 0;
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if ((int)strlen(commands[i].name) > width)
            width = (int)strlen(commands[i].name);
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        printf("  %-*s  %s\n", width, commands[i].name, strchr(commands[i].summary, ':') + 2);
    printf("\n"
           "Options (before the command or among its arguments):\n"
           "  -i, --interface IFACE\n"
           "                 the SocketCAN interface; default $COMASTER_IFACE, else can0\n"
           "                 (a real bus: the examples give -i vcan0, a virtual one)\n"
           "  --timeout MS   how long to wait for each answer (default 1000)\n"
           "  --json         one JSON object per result line, for scripts\n"
           "  --eds FILE     the EDS or DCF of the node: objects by name, their types\n"
           "  --eds-dir DIR  where to look for the EDS matching the node's identity\n"
           "                 (1018h:01/02, 1008h); default the installed EDS directory,\n"
           "                 then eds/\n"
           "  -h, --help     show this help\n"
           "  -V, --version  show the version\n"
           "\n"
           "Example: comaster -i vcan0 read 4 ACC\n"
           "\n"
           "An error is one line on stderr, 'comaster: error: ' then what is wrong and what\n"
           "would be right; after wrong arguments a second line names the --help to read.\n"
           "\n"
           "Exit status:\n"
           "  0   done\n"
           "  1   refused: the node aborted the SDO transfer, or the run answered an error\n"
           "  2   no answer in time, or the drive did not reach the state\n"
           "  3   interrupted by SIGINT or SIGTERM before the command finished\n"
           "  4   the drive is in Fault (comaster drive NODE fault-reset clears it)\n"
           "  64  wrong arguments: an unknown command or option, a bad node-id, object or\n"
           "      type\n"
           "  65  bad data: a value that does not fit its type (given, or read from the\n"
           "      node), a malformed EDS, DCF or network description, a node that is not the\n"
           "      device its DCF describes\n"
           "  66  a file (EDS, DCF, domain) cannot be read\n"
           "  69  no such interface or no SocketCAN, or no run answers on the control socket\n"
           "  70  internal error\n"
           "  71  system error (out of memory, a system call failed)\n"
           "  73  the --output file or the control socket cannot be created\n"
           "  76  the run closed the control socket without a reply\n");
}

/* "read, write, ...": the commands of the table, for error messages. */
static const char *command_names(void)
{
    static char names[256];
    size_t used = 0;
    for (size_t i = 0; i < COMMAND_COUNT && used < sizeof names; i++)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                                 commands[i].name);
    return names;
}

static const comaster_command_t *find_command(const char *name)
{
    for (size_t i = 0; i < COMMAND_COUNT; i++) {
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    }
    return NULL;
}

/* The global options before the command; returns the index of the command, or -(exit status)-1
 * when the program is done (help, version, usage error). */
static int parse_global(comaster_options_t *opts, int argc, char **argv)
{
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            print_usage();
            return -1;
        } else if (strcmp(arg, "-V") == 0 || strcmp(arg, "--version") == 0) {
            printf("comaster %s\n", COMASTER_VERSION);
            return -1;
        } else if (strcmp(arg, "--json") == 0) {
            opts->json = true;
        } else if (strcmp(arg, "-i") == 0 || strcmp(arg, "--interface") == 0 ||
                   strcmp(arg, "--timeout") == 0 || strcmp(arg, "--eds") == 0 ||
                   strcmp(arg, "--eds-dir") == 0) {
            if (!value)
                return -comaster_missing_value(opts, arg) - 1;
            i++; /* the command's parser reads them (main hands them over) */
        } else {
            return -comaster_fail(opts, EX_USAGE, "unknown option '%s'", arg) - 1;
        }
    }
    if (i == argc)
        return -comaster_fail(opts, EX_USAGE, "no command: give one of %s", command_names()) - 1;
    return i;
}

int main(int argc, char **argv)
{
    co_log_setup("comaster", CO_LOG_WARN);
    comaster_options_t opts = {
        .iface = getenv("COMASTER_IFACE") && getenv("COMASTER_IFACE")[0] ? getenv("COMASTER_IFACE")
                                                                         : COMASTER_DEFAULT_IFACE,
        .timeout_ms = COMASTER_DEFAULT_TIMEOUT_MS,
    };
    int at = parse_global(&opts, argc, argv);
    if (at < 0)
        return -at - 1;
    const comaster_command_t *command = find_command(argv[at]);
    if (!command)
        return comaster_fail(&opts, EX_USAGE, "unknown command '%s': give one of %s", argv[at],
                             command_names());
    opts.command = command->name;
    /* The command's argv: its name, the global options (its parser reads them like its own),
     * then its arguments. */
    char **args = calloc((size_t)argc + 1, sizeof *args);
    if (!args)
        return comaster_fail(&opts, EX_OSERR, "out of memory");
    int n = 0;
    args[n++] = argv[at];
    for (int i = 1; i < argc; i++) {
        if (i != at)
            args[n++] = argv[i];
    }
    int rc = command->run(&opts, n, args);
    free(args);
    return rc;
}
