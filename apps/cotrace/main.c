/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace: says what every frame of a candump -L log or a live SocketCAN interface means in
 * CANopen terms, or with --devicenet in DeviceNet terms, one line per frame (docs/cotrace.md). */
#include "atv58/atv58_emcy.h"
#include "cli/co_cli.h"
#include "co_linux/can_frame.h"
#include "co_linux/candump.h"
#include "co_linux/log.h"
#include "co_linux/loop.h"
#include "trace/decoder.h"
#include "trace/devicenet_decoder.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

/* The ID#DATA field is padded to this width so that the meanings line up (11-bit frames). */
#define FRAME_FIELD_WIDTH 20
#define MEANING_MAX 1024

static const char usage_text[] =
    "usage: cotrace [FILE... | -i IFACE] [--eds FILE --node N | --devicenet] [options]\n"
    "\n"
    "Says what every CANopen frame means (or DeviceNet frame: --devicenet), one line\n"
    "per frame: NMT, SYNC, TIME, EMCY,\n"
    "SDO (segmented and block transfers followed across frames), PDO, heartbeat,\n"
    "node guarding. Reads candump -L logs (atv312d --trace, candump -L) or a live\n"
    "SocketCAN interface.\n"
    "\n"
    "  FILE                candump -L log to decode; none or '-' reads standard input\n"
    "  -i, --interface IFACE\n"
    "                      decode the frames of a live SocketCAN interface (e.g.\n"
    "                      vcan0) until SIGINT or SIGTERM\n"
    "  --eds FILE          EDS or DCF of the node given with --node: object names on\n"
    "                      its SDO lines, its PDOs decoded into objects and values by\n"
    "                      their mapping\n"
    "  --node N            node-id 1..127 of the --eds file (resolves $NODEID)\n"
    "  --emcy-table T      consult a vendor's EMCY code table before CiA 301/402:\n"
    "                      atv58 (Altivar 58 CANopen card manual)\n"
    "  --devicenet         the bus is a DeviceNet bus: each frame by message group,\n"
    "                      message ID and MAC ID, explicit messages (fragments\n"
    "                      reassembled), I/O data by the assemblies selected\n"
    "  --assemblies OUT,IN with --devicenet: the assemblies in use until the trace\n"
    "                      selects others, OUT 20, 21 or 100, IN 70, 71 or 101\n"
    "                      (default 21,71)\n"
    "  --strict            stop at the first line that is not a candump -L line\n"
    "  -h, --help          show this help\n"
    "  -V, --version       show the version\n"
    "\n"
    "Each output line is the frame as candump -L prints it (its ID#DATA padded to 20\n"
    "characters), two spaces and the meaning; docs/cotrace.md lists them all.\n"
    "\n"
    "Example: atv312d vcan0 --node-id 4 --trace - | cotrace --eds eds/ATV312.eds --node 4\n"
    "\n"
    "An error is one line on stderr, 'cotrace: error: ' then what is wrong and what\n"
    "would be right; after wrong arguments a second line names the --help to read.\n"
    "See docs/cotrace.md.\n"
    "\n"
    "Exit status:\n"
    "  0   every line decoded (with -i: stopped by SIGINT or SIGTERM)\n"
    "  64  wrong arguments: an unknown option, a bad node-id or assemblies, options\n"
    "      that do not go together\n"
    "  65  bad data: a line was not a candump -L line (skipped, or --strict stopped\n"
    "      there), or the EDS is malformed\n"
    "  66  a FILE or the EDS cannot be read\n"
    "  69  no such interface, or no SocketCAN\n"
    "  71  system error\n"
    "  74  the output could not be written\n";

typedef struct options {
    const char *iface;
    const char *eds_path;
    unsigned long node;
    const char *emcy_table;
    bool devicenet;
    unsigned consumed_assembly; /* --assemblies, 0: the default */
    unsigned produced_assembly;
    bool strict;
    char **files;
    int file_count;
} options_t;

/* The options that take a value, and what --help calls it. */
static const cli_valued_option_t valued[] = {{"-i", "IFACE"},       {"--interface", "IFACE"},
                                             {"--eds", "FILE"},     {"--node", "N"},
                                             {"--emcy-table", "T"}, {"--assemblies", "OUT,IN"}};

/* --assemblies OUT,IN: an output (consumed) and an input (produced) assembly of the card. */
static bool parse_assemblies(const char *value, options_t *opts)
{
    unsigned out, in;
    int end = 0;
    if (sscanf(value, "%u,%u%n", &out, &in, &end) != 2 || value[end] != '\0')
        return false;
    if (out != 20 && out != 21 && out != 100)
        return false;
    if (in != 70 && in != 71 && in != 101)
        return false;
    opts->consumed_assembly = out;
    opts->produced_assembly = in;
    return true;
}

/* Returns -1 to go on, else the exit status (help, version, usage error). */
static int parse_args(int argc, char **argv, options_t *opts)
{
    memset(opts, 0, sizeof *opts);
    opts->files = calloc((size_t)argc, sizeof *opts->files);
    if (!opts->files)
        return cli_fail(NULL, EX_OSERR, "out of memory");
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        bool has_value = i + 1 < argc;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            fputs(usage_text, stdout);
            return 0;
        } else if (strcmp(arg, "-V") == 0 || strcmp(arg, "--version") == 0) {
            printf("cotrace %s\n", COTRACE_VERSION);
            return 0;
        } else if (strcmp(arg, "--strict") == 0) {
            opts->strict = true;
        } else if (strcmp(arg, "--devicenet") == 0) {
            opts->devicenet = true;
        } else if (cli_value_name(valued, sizeof valued / sizeof valued[0], arg)) {
            if (!has_value || argv[i + 1][0] == '\0')
                return cli_fail(NULL, EX_USAGE, "option %s needs a value: give %s %s", arg, arg,
                                cli_value_name(valued, sizeof valued / sizeof valued[0], arg));
            const char *value = argv[++i];
            if (arg[1] == 'i' || strcmp(arg, "--interface") == 0)
                opts->iface = value;
            else if (strcmp(arg, "--eds") == 0)
                opts->eds_path = value;
            else if (strcmp(arg, "--emcy-table") == 0)
                opts->emcy_table = value;
            else if (strcmp(arg, "--assemblies") == 0) {
                if (!parse_assemblies(value, opts))
                    return cli_fail(NULL, EX_USAGE,
                                    "--assemblies: '%s' is not OUT,IN: OUT 20, 21 or 100, IN 70, "
                                    "71 or 101, e.g. 100,101",
                                    value);
            } else {
                char *end;
                errno = 0;
                opts->node = strtoul(value, &end, 0);
                if (errno || *end || end == value || opts->node < 1 || opts->node > 127)
                    return cli_fail(NULL, EX_USAGE,
                                    "--node: '%s' is not a node-id: use a number 1..127", value);
            }
        } else if (arg[0] == '-' && arg[1] != '\0') {
            return cli_fail(NULL, EX_USAGE, "unknown option '%s'", arg);
        } else {
            opts->files[opts->file_count++] = argv[i];
        }
    }
    if (opts->iface && opts->file_count)
        return cli_fail(NULL, EX_USAGE, "give either files or -i %s, not both", opts->iface);
    if (opts->eds_path && !opts->node)
        return cli_fail(NULL, EX_USAGE, "--eds %s needs --node N: the node-id the EDS describes",
                        opts->eds_path);
    if (opts->node && !opts->eds_path)
        return cli_fail(NULL, EX_USAGE,
                        "--node %lu needs --eds FILE: without an EDS there is nothing to apply it "
                        "to",
                        opts->node);
    if (opts->devicenet && (opts->eds_path || opts->emcy_table))
        return cli_fail(NULL, EX_USAGE,
                        "--devicenet: an EDS and an EMCY table are CANopen's, not DeviceNet's");
    if (opts->consumed_assembly && !opts->devicenet)
        return cli_fail(NULL, EX_USAGE,
                        "--assemblies needs --devicenet: assemblies are DeviceNet's");
    if (opts->emcy_table && strcmp(opts->emcy_table, "atv58") != 0)
        return cli_fail(NULL, EX_USAGE, "--emcy-table: unknown table '%s': the tables are atv58",
                        opts->emcy_table);
    return -1;
}

/* The decoder of the bus's protocol. */
typedef struct decoder {
    cotrace_decoder_t *canopen; /* NULL: DeviceNet */
    cotrace_dn_decoder_t *devicenet;
} decoder_t;

static void decode(decoder_t *dec, const struct can_frame *frame, char *out, size_t cap)
{
    if (dec->canopen)
        cotrace_decode(dec->canopen, frame, out, cap);
    else
        cotrace_dn_decode(dec->devicenet, frame, out, cap);
}

/* One output line: the frame as candump -L prints it, its field padded, then the meaning. */
static void print_frame(decoder_t *dec, const struct timespec *wall, const char *iface,
                        const struct can_frame *frame)
{
    char line[CO_CANDUMP_LINE_MAX];
    char meaning[MEANING_MAX];
    size_t len = co_candump_format(line, sizeof line, wall, iface, frame);
    if (len == 0)
        return;
    line[len - 1] = '\0';
    const char *field = strrchr(line, ' ') + 1;
    decode(dec, frame, meaning, sizeof meaning);
    printf("%s%*s  %s\n", line, FRAME_FIELD_WIDTH - (int)strlen(field), "", meaning);
}

/* Returns 0, or EX_DATAERR when a line was malformed (after the first with --strict). */
static int decode_stream(decoder_t *dec, FILE *in, const char *name, bool strict)
{
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    unsigned long number = 0;
    int rc = 0;
    while ((n = getline(&line, &cap, in)) >= 0) {
        number++;
        if (n == 0 || line[0] == '\n')
            continue;
        struct timespec wall;
        char iface[IFNAMSIZ];
        struct can_frame frame;
        if (co_candump_parse(line, &wall, iface, &frame)) {
            print_frame(dec, &wall, iface, &frame);
            continue;
        }
        if (line[n - 1] == '\n')
            line[n - 1] = '\0';
        rc = cli_fail(NULL, EX_DATAERR,
                      "%s:%lu: not a candump -L line: '%.80s': expected '(SECONDS.FRACTION) IFACE "
                      "ID#DATA', e.g. (1700000000.000100) vcan0 604#4008100000000000",
                      name, number, line);
        if (strict)
            break;
    }
    free(line);
    return rc;
}

/* A pipe or a terminal is read as it comes (`atv312d --trace - | cotrace`): each line is written
 * at once. Files are decoded with full buffering. */
static void buffer_output_for(FILE *in)
{
    struct stat st;
    if (fstat(fileno(in), &st) == 0 && !S_ISREG(st.st_mode))
        setvbuf(stdout, NULL, _IOLBF, 0);
}

static int decode_files(decoder_t *dec, const options_t *opts)
{
    if (opts->file_count == 0) {
        buffer_output_for(stdin);
        return decode_stream(dec, stdin, "<stdin>", opts->strict);
    }
    for (int i = 0; i < opts->file_count; i++) {
        if (strcmp(opts->files[i], "-") == 0)
            buffer_output_for(stdin);
    }
    int rc = 0;
    for (int i = 0; i < opts->file_count; i++) {
        const char *path = opts->files[i];
        bool is_stdin = strcmp(path, "-") == 0;
        FILE *in = is_stdin ? stdin : fopen(path, "re");
        if (!in)
            return cli_fail(NULL, EX_NOINPUT, "cannot read '%s': %s", path, strerror(errno));
        int file_rc = decode_stream(dec, in, is_stdin ? "<stdin>" : path, opts->strict);
        if (!is_stdin)
            fclose(in);
        if (file_rc) {
            rc = file_rc;
            if (opts->strict)
                break;
        }
    }
    return rc;
}

/* ---- live: a device of the runtime's loop that only listens ------------------------------- */

typedef struct monitor {
    co_linux_device_t device;
    co_linux_loop_t *loop;
    decoder_t *dec;
} monitor_t;

static void monitor_start(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
}

/* The loop keeps the wall clock only for its own trace (off here): the time is read per frame. */
static struct timespec wall_now(void)
{
    struct timespec wall;
    clock_gettime(CLOCK_REALTIME, &wall);
    return wall;
}

static void monitor_receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    monitor_t *m = ctx;
    struct can_frame cf;
    struct timespec wall = wall_now();
    (void)now;
    co_linux_frame_to_can(frame, &cf);
    print_frame(m->dec, &wall, m->loop->iface, &cf);
}

static co_time_t monitor_process(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
    return CO_TIME_NEVER;
}

/* The loop turns CAN error frames into conditions; they are shown as such. */
static void monitor_bus_event(void *ctx, uint16_t emcy_code, bool active)
{
    monitor_t *m = ctx;
    char line[CO_CANDUMP_LINE_MAX];
    struct timespec wall = wall_now();
    int n = snprintf(line, sizeof line, "(%010lld.%06ld) %s", (long long)wall.tv_sec,
                     wall.tv_nsec / 1000, m->loop->iface);
    if (n > 0)
        printf("%s %-*s  CAN bus: %s %s\n", line, FRAME_FIELD_WIDTH, "error",
               co_emcy_code_text(emcy_code), active ? "began" : "ended");
}

static const co_linux_device_ops_t monitor_ops = {
    .start = monitor_start,
    .restart = monitor_start,
    .receive = monitor_receive,
    .process = monitor_process,
    .bus_event = monitor_bus_event,
};

static int report_open_error(const co_linux_loop_t *loop, co_linux_open_result_t result)
{
    char message[512];
    int status = cli_open_error_text(loop, result, NULL, message, sizeof message);
    return cli_fail(NULL, status, "%s", message);
}

static int decode_live(decoder_t *dec, const char *iface)
{
    static co_linux_loop_t loop;
    static monitor_t monitor;
    co_linux_loop_config_t config = {.iface = iface};
    co_linux_open_result_t opened = co_linux_loop_open(&loop, &config);
    if (opened != CO_LINUX_OPEN_OK)
        return report_open_error(&loop, opened);
    setvbuf(stdout, NULL, _IOLBF, 0);
    monitor.loop = &loop;
    monitor.dec = dec;
    co_linux_loop_add(&loop, &monitor.device, &monitor_ops, &monitor);
    int rc = co_linux_loop_run(&loop);
    co_linux_loop_close(&loop);
    return rc;
}

int main(int argc, char **argv)
{
    co_log_setup("cotrace", CO_LOG_WARN);
    options_t opts;
    int rc = parse_args(argc, argv, &opts);
    if (rc >= 0) {
        free(opts.files);
        return rc;
    }
    static eds_t eds;
    static cotrace_decoder_t canopen;
    static cotrace_dn_decoder_t devicenet;
    decoder_t dec = {NULL, &devicenet};
    char err[512];
    eds_result_t loaded = EDS_OK;
    if (opts.eds_path)
        loaded = eds_load(&eds, opts.eds_path, (uint8_t)opts.node, err, sizeof err);
    if (loaded != EDS_OK) {
        free(opts.files);
        return cli_fail(NULL, loaded == EDS_CANNOT_READ ? EX_NOINPUT : EX_DATAERR, "%s", err);
    }
    if (opts.devicenet) {
        cotrace_dn_decoder_init(&devicenet, (uint16_t)opts.consumed_assembly,
                                (uint16_t)opts.produced_assembly);
    } else {
        cotrace_decoder_init(&canopen, opts.eds_path ? &eds : NULL, (uint8_t)opts.node,
                             opts.emcy_table ? &atv58_emcy_table : NULL);
        dec.canopen = &canopen;
    }
    rc = opts.iface ? decode_live(&dec, opts.iface) : decode_files(&dec, &opts);
    if (fflush(stdout) != 0 && rc == 0)
        rc = cli_fail(NULL, EX_IOERR, "cannot write the output: %s", strerror(errno));
    eds_free(&eds);
    free(opts.files);
    return rc;
}
