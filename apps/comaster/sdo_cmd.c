/* SPDX-License-Identifier: Apache-2.0 */
/* comaster read and write: one SDO upload or download, the value printed or parsed by its data
 * type (given, from the EDS, or guessed from the size). */
#include "cli/co_cli.h"
#include "comaster/comaster.h"
#include "comaster/run_control.h"
#include "comaster/value.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The largest value read or written: a DOMAIN of a file. */
#define VALUE_MAX (1024u * 1024u)

static const char read_help[] =
    "usage: comaster read NODE OBJECT [TYPE] [--block] [--output FILE]\n"
    "\n"
    "Reads an object of node NODE (1..127) over SDO and prints its value.\n"
    "\n"
    "  OBJECT         INDEX:SUB in hexadecimal (0x203C:2, 1008) or, with an EDS, a\n"
    "                 ParameterName or its first word (ACC, \"Acceleration time\")\n"
    "  TYPE           how to print it: bool i8 i16 i32 i64 u8 u16 u32 u64 f32 f64\n"
    "                 string octets domain (or UNSIGNED16, REAL32, VISIBLE_STRING ...);\n"
    "                 default the EDS's DataType, else unsigned by the size, else bytes\n"
    "  --block        block transfer whatever the size\n"
    "  --output FILE  write the value's bytes to FILE (a DOMAIN) instead of printing\n"
    "  --run          read it through the comaster run on the interface: its master's\n"
    "                 own SDO client, after the boot of its slaves (names from the\n"
    "                 slave's DCF); --control PATH: the run listening on PATH\n"
    "\n"
    "The EDS is --eds FILE, else the one of the EDS directory whose VendorNumber and\n"
    "ProductNumber are the node's 1018h:01/02.\n"
    "\n"
    "Example: comaster -i vcan0 read 4 0x1008 string\n";

static const char write_help[] =
    "usage: comaster write NODE OBJECT [TYPE] VALUE [--block]\n"
    "\n"
    "Writes VALUE to an object of node NODE (1..127) over SDO: expedited up to 4\n"
    "bytes, segmented above, block with --block.\n"
    "\n"
    "  OBJECT         INDEX:SUB in hexadecimal (0x203C:2) or, with an EDS, a name\n"
    "  TYPE           the data type VALUE is written as (see comaster read --help);\n"
    "                 may be left out when the EDS gives it\n"
    "  VALUE          a number (decimal or 0x hexadecimal) in the type's range, true or\n"
    "                 false, a string, hexadecimal bytes for octets (01 02 0A); for\n"
    "                 domain the name of the file to send ('-': standard input)\n"
    "  --block        block transfer whatever the size\n"
    "  --run          write it through the comaster run on the interface (see\n"
    "                 comaster read --help); --control PATH: the run on PATH\n"
    "\n"
    "Example: comaster -i vcan0 write 4 ACC u16 50\n";

typedef struct sdo_request {
    uint8_t node;
    comaster_object_t object;
    const comaster_type_t *type;
    co_sdo_client_mode_t mode;
} sdo_request_t;

static uint8_t value_buffer[VALUE_MAX];

/* Node, EDS and object of a read or write; returns -1 to go on, else the exit status. */
static int resolve(comaster_bus_t *bus, comaster_options_t *opts, const comaster_args_t *args,
                   const char *type_name, eds_t *eds, sdo_request_t *req)
{
    if (!comaster_parse_node(opts, args->positional[0], false, &req->node))
        return EX_USAGE;
    req->mode = args->block ? CO_SDO_CLIENT_BLOCK : CO_SDO_CLIENT_AUTO;
    if (type_name) {
        req->type = comaster_type_by_name(type_name);
        if (!req->type)
            return comaster_fail(opts, EX_USAGE, "'%s' is not a data type: give one of %s",
                                 type_name, comaster_type_names());
    }
    int rc = comaster_bus_open(bus, opts);
    if (rc != 0)
        return rc;
    const char *text = args->positional[1];
    comaster_object_t numeric;
    char err[512];
    bool by_index = comaster_object_parse(text, NULL, &numeric, err, sizeof err);
    if (opts->eds_path || !by_index || !req->type) {
        rc = comaster_load_eds(bus, opts, req->node, eds);
        if (rc > 0)
            return rc;
    }
    if (!comaster_object_parse(text, eds, &req->object, err, sizeof err))
        return comaster_fail(opts, EX_USAGE, "%s", err);
    if (!req->type && req->object.data_type)
        req->type = comaster_type_by_code(req->object.data_type);
    return -1;
}

/* Without TYPE or an EDS: unsigned by the size, else bytes. */
static const comaster_type_t *type_by_size(uint32_t size)
{
    switch (size) {
    case 1:
        return comaster_type_by_code(CO_DT_UNSIGNED8);
    case 2:
        return comaster_type_by_code(CO_DT_UNSIGNED16);
    case 4:
        return comaster_type_by_code(CO_DT_UNSIGNED32);
    case 8:
        return comaster_type_by_code(CO_DT_UNSIGNED64);
    default:
        return comaster_type_by_code(CO_DT_OCTET_STRING);
    }
}

static void print_json_head(const sdo_request_t *req)
{
    printf("{\"node\": %u, \"index\": \"0x%04X\", \"subindex\": %u, ", req->node, req->object.index,
           req->object.sub);
    if (req->object.name) {
        printf("\"name\": ");
        cli_json_string(stdout, req->object.name);
        printf(", ");
    }
    printf("\"type\": \"%s\"", req->type->name);
}

static int save_output(const comaster_options_t *opts, const sdo_request_t *req, const char *path,
                       uint32_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(value_buffer, 1, size, f) != size || fclose(f) != 0)
        return comaster_fail(opts, EX_CANTCREAT, "cannot write '%s': %s", path, strerror(errno));
    if (opts->json) {
        print_json_head(req);
        printf(", \"size\": %u, \"file\": ", size);
        cli_json_string(stdout, path);
        printf("}\n");
    }
    return 0;
}

static int print_value(const comaster_options_t *opts, const sdo_request_t *req, uint32_t size)
{
    static char text[3 * VALUE_MAX + 1];
    bool is_text;
    if (!comaster_value_format(req->type, value_buffer, size, COMASTER_VALUE_DECIMAL, text,
                               sizeof text, &is_text))
        return comaster_fail(opts, EX_DATAERR, "node %u, %04X:%02X: %s: read it as octets",
                             req->node, req->object.index, req->object.sub, text);
    if (!opts->json) {
        printf("%s\n", text);
        return 0;
    }
    print_json_head(req);
    printf(", \"value\": ");
    if (is_text)
        cli_json_string(stdout, text);
    else
        fputs(text, stdout);
    printf("}\n");
    return 0;
}

/* read: the upload, its value printed (by its type, else unsigned by its size) or saved. */
static int upload(comaster_bus_t *bus, const comaster_options_t *opts, const comaster_args_t *args,
                  sdo_request_t *req)
{
    co_sdo_client_result_t result;
    int rc = comaster_sdo_upload(bus, req->node, req->object.index, req->object.sub, value_buffer,
                                 VALUE_MAX, req->mode, opts->timeout_ms, &result);
    if (rc == 0)
        rc = comaster_sdo_status(opts, req->node, &result);
    if (rc != 0)
        return rc;
    if (!req->type)
        req->type = type_by_size(result.size);
    return args->output ? save_output(opts, req, args->output, result.size)
                        : print_value(opts, req, result.size);
}

/* A DOMAIN's value: the bytes of a file ('-': standard input). */
static int read_domain_file(const comaster_options_t *opts, const char *path, size_t *len)
{
    bool is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f)
        return comaster_fail(opts, EX_NOINPUT, "cannot read '%s': %s", path, strerror(errno));
    *len = fread(value_buffer, 1, VALUE_MAX, f);
    bool too_long = *len == VALUE_MAX && fgetc(f) != EOF;
    bool failed = ferror(f);
    if (!is_stdin)
        fclose(f);
    if (failed)
        return comaster_fail(opts, EX_NOINPUT, "cannot read '%s'", path);
    if (too_long)
        return comaster_fail(opts, EX_DATAERR,
                             "'%s' is larger than %u bytes, the most comaster "
                             "sends",
                             path, VALUE_MAX);
    return 0;
}

static int parse_value(const comaster_options_t *opts, const sdo_request_t *req, const char *text,
                       size_t *len)
{
    if (req->type->code == CO_DT_DOMAIN)
        return read_domain_file(opts, text, len);
    char err[256];
    if (!comaster_value_parse(req->type, text, value_buffer, VALUE_MAX, len, err, sizeof err))
        return comaster_fail(opts, EX_DATAERR, "node %u, %04X:%02X: %s", req->node,
                             req->object.index, req->object.sub, err);
    return 0;
}

/* write: VALUE parsed by its type, then the download. */
static int download(comaster_bus_t *bus, const comaster_options_t *opts,
                    const comaster_args_t *args, sdo_request_t *req)
{
    if (!req->type)
        return comaster_fail(opts, EX_USAGE,
                             "write %s %s: give the TYPE of the value (no EDS names its data "
                             "type): one of %s",
                             args->positional[0], args->positional[1], comaster_type_names());
    size_t len = 0;
    int rc = parse_value(opts, req, args->positional[args->count - 1], &len);
    if (rc != 0)
        return rc;
    co_sdo_client_result_t result;
    rc = comaster_sdo_download(bus, req->node, req->object.index, req->object.sub, value_buffer,
                               (uint32_t)len, req->mode, opts->timeout_ms, &result);
    if (rc == 0)
        rc = comaster_sdo_status(opts, req->node, &result);
    if (rc == 0 && opts->json) {
        print_json_head(req);
        printf(", \"written\": %zu}\n", len);
    }
    return rc;
}

/* What read and write do not share: their command line and their transfer. */
typedef struct sdo_command {
    const char *help;
    const char *flags;
    int min_args;
    int max_args; /* TYPE is the third argument when all are given */
    int (*transfer)(comaster_bus_t *bus, const comaster_options_t *opts,
                    const comaster_args_t *args, sdo_request_t *req);
} sdo_command_t;

/* Through a run: the request "read NODE OBJECT [TYPE]" or "write NODE OBJECT [TYPE] VALUE",
 * which the run's master queues on its own SDO client. */
static int through_run(comaster_options_t *opts, const char *control, const char *name,
                       const comaster_args_t *args)
{
    if (args->block || args->output)
        return comaster_fail(opts, EX_USAGE,
                             "%s through a run: --block and --output are not for a run's client",
                             name);
    uint8_t node;
    if (!comaster_parse_node(opts, args->positional[0], false, &node))
        return EX_USAGE;
    const char *fields[COMASTER_MAX_ARGS + 1] = {name};
    for (int i = 0; i < args->count; i++)
        fields[i + 1] = args->positional[i];
    return comaster_control_forward(opts, control, fields, (size_t)args->count + 1);
}

static int run_sdo_command(const sdo_command_t *command, comaster_options_t *opts, int argc,
                           char **argv)
{
    const char *control = NULL;
    bool via_run = false;
    if (!comaster_run_option(&argc, argv, &via_run, &control))
        return comaster_missing_value(opts, "--control");
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, command->help, command->flags,
                                 command->min_args, command->max_args);
    if (rc >= 0)
        return rc;
    if (via_run)
        return through_run(opts, control, argv[0], &args);
    static comaster_bus_t bus;
    eds_t eds = {0};
    sdo_request_t req = {0};
    const char *type_name = args.count == command->max_args ? args.positional[2] : NULL;
    rc = resolve(&bus, opts, &args, type_name, &eds, &req);
    if (rc < 0)
        rc = command->transfer(&bus, opts, &args, &req);
    comaster_bus_close(&bus);
    eds_free(&eds);
    return rc;
}

int comaster_read_main(comaster_options_t *opts, int argc, char **argv)
{
    static const sdo_command_t read_command = {read_help, "--block --output", 2, 3, upload};
    return run_sdo_command(&read_command, opts, argc, argv);
}

int comaster_write_main(comaster_options_t *opts, int argc, char **argv)
{
    static const sdo_command_t write_command = {write_help, "--block", 3, 4, download};
    return run_sdo_command(&write_command, opts, argc, argv);
}
