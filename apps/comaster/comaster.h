/* SPDX-License-Identifier: Apache-2.0 */
/* comaster: what its commands share. The table of commands (main.c), the common options, the
 * errors and --json output with the exit statuses scripts rely on (co_cli.h), and the bus: one
 * epoll loop of the Linux runtime on which each command runs its jobs (SDO transfers, waits for
 * frames) one after the other, each until it finishes or its deadline passes
 * (docs/comaster.md). */
#ifndef COMASTER_H
#define COMASTER_H

#include "cli/co_cli.h"
#include "co/co_sdo_client.h"
#include "co_linux/loop.h"
#include "eds/eds_reader.h"

#include <stdbool.h>
#include <stdint.h>

#define COMASTER_DEFAULT_IFACE "can0"
#define COMASTER_DEFAULT_TIMEOUT_MS 1000u
#define COMASTER_DEFAULT_EDS_DIR "share/canopen-atv312/eds"

/* The options every command takes, before the command or among its arguments. */
typedef struct comaster_options {
    const char *command; /* the command running, for the hint after a usage error; NULL before */
    const char *iface;
    uint32_t timeout_ms;
    bool json;
    const char *eds_path; /* --eds FILE */
    const char *eds_dir;  /* --eds-dir DIR, or NULL: the installed directory, then eds/ */
} comaster_options_t;

/* What a command's parser found: its own options and its positional arguments. */
#define COMASTER_MAX_ARGS 8
typedef struct comaster_args {
    const char *positional[COMASTER_MAX_ARGS];
    int count;
    bool block;            /* read / write: --block */
    bool rpdo;             /* drive: --rpdo */
    uint16_t heartbeat_ms; /* monitor: --heartbeat MS, 0 when not given */
    const char *output;    /* read: --output FILE for a DOMAIN */
    const char *listen;    /* gateway: --listen [ADDR:]PORT */
    const char *socket;    /* gateway: --socket PATH */
} comaster_args_t;

/* One command: its name, the line of the usage listing and its handler. */
typedef struct comaster_command {
    const char *name;
    const char *summary;
    int (*run)(comaster_options_t *opts, int argc, char **argv);
} comaster_command_t;

int comaster_read_main(comaster_options_t *opts, int argc, char **argv);
int comaster_write_main(comaster_options_t *opts, int argc, char **argv);
int comaster_nmt_main(comaster_options_t *opts, int argc, char **argv);
int comaster_scan_main(comaster_options_t *opts, int argc, char **argv);
int comaster_monitor_main(comaster_options_t *opts, int argc, char **argv);
int comaster_drive_main(comaster_options_t *opts, int argc, char **argv);
int comaster_boot_main(comaster_options_t *opts, int argc, char **argv);
int comaster_run_main(comaster_options_t *opts, int argc, char **argv);
int comaster_concise_main(comaster_options_t *opts, int argc, char **argv);
int comaster_set_main(comaster_options_t *opts, int argc, char **argv);
int comaster_get_main(comaster_options_t *opts, int argc, char **argv);
int comaster_status_main(comaster_options_t *opts, int argc, char **argv);
int comaster_disable_main(comaster_options_t *opts, int argc, char **argv);
int comaster_enable_main(comaster_options_t *opts, int argc, char **argv);
int comaster_can_main(comaster_options_t *opts, int argc, char **argv);
int comaster_configure_main(comaster_options_t *opts, int argc, char **argv);
int comaster_lss_main(comaster_options_t *opts, int argc, char **argv);
int comaster_time_main(comaster_options_t *opts, int argc, char **argv);
int comaster_gateway_main(comaster_options_t *opts, int argc, char **argv);

/* Parses a command's arguments (argv[0] is the command): the common options, --help (prints
 * `help` and returns 0), the command's flags named in `flags` (" --block --output "), and at
 * least min_args, at most max_args positional arguments. Returns -1 to go on, else the exit
 * status. */
int comaster_parse_args(comaster_options_t *opts, comaster_args_t *args, int argc, char **argv,
                        const char *help, const char *flags, int min_args, int max_args);

/* An error on stderr ("comaster: error: ...", then "Try 'comaster COMMAND --help'." after a
 * usage error) and, with --json, {"error": ...} on stdout (co_cli.h); returns `status`. */
int comaster_fail(const comaster_options_t *opts, int status, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/* The usage error of an option given without its value, naming what the value is
 * ("--timeout MS"); returns EX_USAGE. */
int comaster_missing_value(const comaster_options_t *opts, const char *option);

/* A node-id 1..127 (or "all" when allow_all: *node = 0). False after a usage error message. */
bool comaster_parse_node(const comaster_options_t *opts, const char *text, bool allow_all,
                         uint8_t *node);

/* An NMT command by the name comaster nmt takes (start, stop, preop, reset-node, reset-comm);
 * false for another name. And the name of a command. */
bool comaster_nmt_command(const char *name, uint8_t *command);
const char *comaster_nmt_name(uint8_t command);

/* ---- the bus --------------------------------------------------------------------------------- */

/* A job runs on the bus until it calls comaster_bus_finish: it gets every received frame and is
 * asked for its next deadline. */
typedef struct comaster_job {
    void (*receive)(void *ctx, const co_frame_t *frame, co_time_t now);
    co_time_t (*process)(void *ctx, co_time_t now);
    void *ctx;
} comaster_job_t;

typedef struct comaster_bus {
    co_linux_loop_t loop;
    co_linux_device_t device;
    const comaster_job_t *job;
    bool opened;
    const comaster_options_t *opts;
    bool signal_is_the_end; /* SIGINT/SIGTERM is how the command ends (monitor): no error */
} comaster_bus_t;

/* Opens the interface; returns 0 or the exit status after a one-line error. */
int comaster_bus_open(comaster_bus_t *bus, const comaster_options_t *opts);
/* Closes an opened bus; nothing for one that was not. */
void comaster_bus_close(comaster_bus_t *bus);

/* Runs `job` until it calls comaster_bus_finish (returns its status), a signal
 * (CLI_EXIT_INTERRUPTED, after a one-line error unless signal_is_the_end) or a failure of
 * the loop (EX_OSERR). */
int comaster_bus_run(comaster_bus_t *bus, const comaster_job_t *job);
void comaster_bus_finish(comaster_bus_t *bus, int status);

/* co_send_fn of the bus: pass the comaster_bus_t as user. */
void comaster_bus_send(void *bus, const co_frame_t *frame);

/* Runs the loop until `ms` milliseconds have passed (frames sent before are flushed). */
int comaster_bus_pause(comaster_bus_t *bus, uint32_t ms);

/* One SDO transfer to `node` on the default channel (600h/580h + node), run to its end. Returns
 * 0 with *result filled (which may be an abort), or CLI_EXIT_INTERRUPTED / EX_OSERR. */
int comaster_sdo_upload(comaster_bus_t *bus, uint8_t node, uint16_t index, uint8_t sub,
                        uint8_t *buf, uint32_t cap, co_sdo_client_mode_t mode, uint32_t timeout_ms,
                        co_sdo_client_result_t *result);
int comaster_sdo_download(comaster_bus_t *bus, uint8_t node, uint16_t index, uint8_t sub,
                          const uint8_t *data, uint32_t len, co_sdo_client_mode_t mode,
                          uint32_t timeout_ms, co_sdo_client_result_t *result);

/* The exit status of a transfer's result, after a one-line error naming node and object when it
 * failed: 0, CLI_EXIT_REFUSED (the server's abort) or CLI_EXIT_TIMEOUT (no answer). */
int comaster_sdo_status(const comaster_options_t *opts, uint8_t node,
                        const co_sdo_client_result_t *result);

/* Loads the EDS of --eds, or the one in the EDS directory matching the node's identity (read over
 * SDO: 1018h:01/02, 1008h). Returns 0 (eds loaded), -1 when there is none (eds empty, no error),
 * or an exit status after a one-line error. */
int comaster_load_eds(comaster_bus_t *bus, const comaster_options_t *opts, uint8_t node,
                      eds_t *eds);

#endif
