/* SPDX-License-Identifier: Apache-2.0 */
/* comaster set, get and status: requests to a comaster run through its control socket. */
#include "co/co_image_address.h"
#include "comaster/comaster.h"
#include "comaster/run_control.h"

#include <stdio.h>
#include <string.h>

static const char set_help[] =
    "usage: comaster set NODE NAME VALUE [--control PATH]\n"
    "       comaster set MARKER VALUE [--control PATH]\n"
    "\n"
    "Sets an output of the process image of a comaster run: the run sends the RPDO\n"
    "that maps it when its bytes change (and after each SYNC when it produces SYNC).\n"
    "\n"
    "  NAME            the object's Denotation in the DCF (speed), its ParameterName or\n"
    "                  first word, or INDEX:SUB (0x6042)\n"
    "  MARKER          the 512-byte output image as the PLC300's markers: %QB byte,\n"
    "                  %QW word, %QD double word, bytes 2000..2511, least significant\n"
    "                  first (a word at an even address, a double word at 2000 + 4n:\n"
    "                  %QW2002, %QD2004)\n"
    "  VALUE           a number in the object's data type (a marker's: UNSIGNED8/16/32)\n"
    "  --control PATH  the run's control socket; default $XDG_RUNTIME_DIR (else /tmp)\n"
    "                  /comaster-IFACE.sock\n"
    "\n"
    "Examples: comaster -i vcan0 set 4 speed 1200\n"
    "          comaster -i vcan0 set %QW2002 1200\n";

static const char get_help[] =
    "usage: comaster get NODE NAME [--control PATH]\n"
    "       comaster get MARKER [--control PATH]\n"
    "\n"
    "Prints a variable of the process image of a comaster run: an input (the last TPDO\n"
    "of the slave that maps it) or an output; a MARKER (%IB, %IW, %ID inputs, %QB,\n"
    "%QW, %QD outputs: the PLC300's, see comaster set --help) prints the unsigned\n"
    "number of the byte, word or double word at that address.\n"
    "\n"
    "Examples: comaster -i vcan0 get 4 status\n"
    "          comaster -i vcan0 get %IW2000\n";

static const char status_help[] =
    "usage: comaster status [--control PATH]\n"
    "\n"
    "Prints the status of a comaster run: the master's and each slave's status word\n"
    "(the PLC300's bits), each slave's step, the last SDO error and the last EMCY.\n"
    "\n"
    "Example: comaster -i vcan0 status\n";

static const char disable_help[] =
    "usage: comaster disable [--control PATH]\n"
    "\n"
    "Disables the communication of a comaster run (the PLC300's DisableComm): its\n"
    "master sends nothing more (heartbeat, SYNC, PDOs, NMT, SDO), takes no frame,\n"
    "stops supervising the slaves and clears the status words, the last SDO error\n"
    "and EMCY; its status shows bit 15 (disabled). Prints the master's status word.\n"
    "\n"
    "Example: comaster -i vcan0 disable\n";

static const char enable_help[] =
    "usage: comaster enable [--control PATH]\n"
    "\n"
    "Enables the communication of a disabled comaster run: its master boots the\n"
    "network again from the start (reset communication, identify, configure, start).\n"
    "\n"
    "Example: comaster -i vcan0 enable\n";

static const char can_help[] =
    "usage: comaster can [--control PATH]\n"
    "\n"
    "Prints the CAN controller's state as a comaster run sees it (error-active,\n"
    "warning, error-passive, bus-off, or no bus power when the interface is down)\n"
    "and its counters: frames received and sent, frames dropped, error frames,\n"
    "bus-offs.\n"
    "\n"
    "Example: comaster -i vcan0 can\n";

static const char configure_help[] =
    "usage: comaster configure NODE|all [--control PATH]\n"
    "\n"
    "Asks a comaster run to configure a slave again, or every slave: CiA 302's\n"
    "configuration request 1F25h (\"conf\" to the node's sub-index, 128 for all). The\n"
    "master resets the slave (communication) and boots it again: identity checked,\n"
    "its concise DCF downloaded, error control and start.\n"
    "\n"
    "Example: comaster -i vcan0 configure 5\n";

/* The exit status a reply's first word says, and the length of that word with its ": ". */
static int reply_status(const char *reply, size_t *prefix)
{
    static const struct {
        const char *word;
        int status;
    } words[] = {{"error: ", CLI_EXIT_REFUSED},
                 {"abort: ", CLI_EXIT_REFUSED},
                 {"timeout: ", CLI_EXIT_TIMEOUT}};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        *prefix = strlen(words[i].word);
        if (strncmp(reply, words[i].word, *prefix) == 0)
            return words[i].status;
    }
    *prefix = 0;
    return CLI_EXIT_OK;
}

int comaster_control_forward(comaster_options_t *opts, const char *path, const char *const *fields,
                             size_t count)
{
    char line[COMASTER_CONTROL_LINE_MAX];
    size_t used = (size_t)snprintf(line, sizeof line, "%s", opts->json ? "json\t" : "");
    for (size_t i = 0; i < count && used < sizeof line; i++) {
        if (strchr(fields[i], '\t') || strchr(fields[i], '\n'))
            return comaster_fail(opts, EX_USAGE, "%s: '%s' has a tab or a newline", fields[0],
                                 fields[i]);
        used += (size_t)snprintf(line + used, sizeof line - used, "%s%s", i ? "\t" : "", fields[i]);
    }
    if (used >= sizeof line)
        return comaster_fail(opts, EX_USAGE, "%s: the request is too long", fields[0]);
    char default_path[COMASTER_CONTROL_PATH_MAX];
    if (!path) {
        comaster_control_default_path(opts->iface, default_path, sizeof default_path);
        path = default_path;
    }
    static char reply[COMASTER_CONTROL_REPLY_MAX];
    char err[512];
    int rc = comaster_control_request(path, line, reply, sizeof reply, err, sizeof err);
    if (rc != 0)
        return comaster_fail(opts, rc, "%s", err);
    size_t prefix;
    rc = reply_status(reply, &prefix);
    if (rc != CLI_EXIT_OK)
        return comaster_fail(opts, rc, "%.*s", (int)strcspn(reply + prefix, "\n"), reply + prefix);
    fputs(reply, stdout);
    return CLI_EXIT_OK;
}

bool comaster_run_option(int *argc, char **argv, bool *via_run, const char **path)
{
    for (int i = 1; i < *argc; i++) {
        if (strcmp(argv[i], "--run") != 0)
            continue;
        *via_run = true;
        memmove(&argv[i], &argv[i + 1], (size_t)(*argc - i - 1) * sizeof *argv);
        (*argc)--;
        break;
    }
    const char *given = NULL;
    if (!comaster_control_take_option(argc, argv, &given))
        return false;
    if (given) {
        *via_run = true;
        *path = given;
    }
    return true;
}

/* Parses the command's arguments and sends them, fields of the request after its name. With
 * `marker`, a PLC300 marker (%QW2000) may stand for NODE NAME: one argument fewer. */
static int request(comaster_options_t *opts, int argc, char **argv, const char *help, int args_n,
                   bool marker)
{
    const char *control = NULL;
    if (!comaster_control_take_option(&argc, argv, &control))
        return comaster_missing_value(opts, "--control");
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, help, "", marker ? args_n - 1 : args_n,
                                 args_n);
    if (rc >= 0)
        return rc;
    bool by_marker = marker && args.positional[0][0] == '%';
    /* Each form has its own count: parsed again for the usual usage error. */
    if (marker && args.count != (by_marker ? args_n - 1 : args_n)) {
        int n = by_marker ? args_n - 1 : args_n;
        rc = comaster_parse_args(opts, &args, argc, argv, help, "", n, n);
        if (rc >= 0)
            return rc;
    }
    co_image_address_t address;
    if (by_marker && !co_image_address_parse(args.positional[0], &address))
        return comaster_fail(opts, EX_USAGE, "%s: '%s' is not a process image address: %s", argv[0],
                             args.positional[0], COMASTER_MARKER_SYNTAX);
    uint8_t node;
    if (args_n > 0 && !by_marker && !comaster_parse_node(opts, args.positional[0], false, &node))
        return EX_USAGE;
    const char *fields[COMASTER_MAX_ARGS + 1] = {argv[0]};
    for (int i = 0; i < args.count; i++)
        fields[i + 1] = args.positional[i];
    return comaster_control_forward(opts, control, fields, (size_t)args.count + 1);
}

int comaster_set_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, set_help, 3, true);
}

int comaster_get_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, get_help, 2, true);
}

int comaster_status_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, status_help, 0, false);
}

int comaster_disable_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, disable_help, 0, false);
}

int comaster_enable_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, enable_help, 0, false);
}

int comaster_can_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, can_help, 0, false);
}

int comaster_configure_main(comaster_options_t *opts, int argc, char **argv)
{
    const char *control = NULL;
    if (!comaster_control_take_option(&argc, argv, &control))
        return comaster_missing_value(opts, "--control");
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, configure_help, "", 1, 1);
    if (rc >= 0)
        return rc;
    uint8_t node;
    if (!comaster_parse_node(opts, args.positional[0], true, &node))
        return EX_USAGE;
    const char *fields[] = {argv[0], args.positional[0]};
    return comaster_control_forward(opts, control, fields, 2);
}
