/* comaster set, get and status: requests to a comaster run through its control socket. */
#include "comaster.h"
#include "control.h"

#include <stdio.h>
#include <string.h>

static const char set_help[] =
    "usage: comaster set NODE NAME VALUE [--control PATH]\n"
    "\n"
    "Sets an output of the process image of a comaster run: the run sends the RPDO\n"
    "that maps it when its bytes change (and after each SYNC when it produces SYNC).\n"
    "\n"
    "  NAME            the object's Denotation in the DCF (speed), its ParameterName or\n"
    "                  first word, or INDEX:SUB (0x6042)\n"
    "  VALUE           a number in the object's data type\n"
    "  --control PATH  the run's control socket; default $XDG_RUNTIME_DIR (else /tmp)\n"
    "                  /comaster-IFACE.sock\n"
    "\n"
    "Example: comaster -i vcan0 set 4 speed 1200\n";

static const char get_help[] =
    "usage: comaster get NODE NAME [--control PATH]\n"
    "\n"
    "Prints a variable of the process image of a comaster run: an input (the last TPDO\n"
    "of the slave that maps it) or an output.\n"
    "\n"
    "Example: comaster -i vcan0 get 4 status\n";

static const char status_help[] =
    "usage: comaster status [--control PATH]\n"
    "\n"
    "Prints the status of a comaster run: the master's and each slave's status word\n"
    "(the PLC300's bits), each slave's step, the last SDO error and the last EMCY.\n"
    "\n"
    "Example: comaster -i vcan0 status\n";

/* Parses the command's arguments, sends the request (its fields joined by tabs) and prints the
 * reply; an "error: ..." reply exits 65. */
static int request(comaster_options_t *opts, int argc, char **argv, const char *help, int args_n)
{
    const char *control = NULL;
    if (!comaster_control_take_option(&argc, argv, &control))
        return comaster_fail(opts, EX_USAGE, "%s: option --control needs a value", argv[0]);
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, help, "", args_n, args_n);
    if (rc >= 0)
        return rc;
    uint8_t node;
    if (args_n > 0 && !comaster_parse_node(opts, args.positional[0], false, &node))
        return EX_USAGE;
    char line[COMASTER_CONTROL_LINE_MAX];
    size_t used = (size_t)snprintf(line, sizeof line, "%s", argv[0]);
    for (int i = 0; i < args.count && used < sizeof line; i++) {
        if (strchr(args.positional[i], '\t') || strchr(args.positional[i], '\n'))
            return comaster_fail(opts, EX_USAGE, "%s: '%s' has a tab or a newline", argv[0],
                                 args.positional[i]);
        used += (size_t)snprintf(line + used, sizeof line - used, "\t%s", args.positional[i]);
    }
    if (used >= sizeof line)
        return comaster_fail(opts, EX_USAGE, "%s: the request is too long", argv[0]);
    char path[COMASTER_CONTROL_PATH_MAX];
    if (!control) {
        comaster_control_default_path(opts->iface, path, sizeof path);
        control = path;
    }
    static char reply[COMASTER_CONTROL_REPLY_MAX];
    char err[512];
    rc = comaster_control_request(control, line, reply, sizeof reply, err, sizeof err);
    if (rc != 0)
        return comaster_fail(opts, rc, "%s", err);
    if (strncmp(reply, "error: ", 7) == 0)
        return comaster_fail(opts, EX_DATAERR, "%.*s", (int)strcspn(reply + 7, "\n"), reply + 7);
    fputs(reply, stdout);
    return COMASTER_EXIT_OK;
}

int comaster_set_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, set_help, 3);
}

int comaster_get_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, get_help, 2);
}

int comaster_status_main(comaster_options_t *opts, int argc, char **argv)
{
    return request(opts, argc, argv, status_help, 0);
}
