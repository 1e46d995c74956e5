/* SPDX-License-Identifier: Apache-2.0 */
/* comaster concise: a DCF's configuration as the concise DCF (CiA 302's 1F22h) the network master
 * downloads, and a concise DCF back to a DCF: the device's EDS (or DCF) with each entry as the
 * ParameterValue of its object (docs/comaster.md "concise"). No bus. */
#include "comaster/comaster.h"
#include "comaster/network.h"
#include "comaster/value.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* The largest concise DCF read back: 1F22h is a DOMAIN, as large as a DCF's configuration. */
#define CONCISE_MAX (1024u * 1024u)

static const char concise_help[] =
    "usage: comaster concise encode NODE DCF FILE\n"
    "       comaster concise decode CDCF EDS FILE\n"
    "\n"
    "encode: writes the configuration of DCF for node NODE (1..127: $NODEID) as the\n"
    "concise DCF of CiA 302 (1F22h) that comaster run and boot download: its\n"
    "ParameterValue entries in file order, a PDO's as one group, each as index,\n"
    "sub-index, size and bytes.\n"
    "decode: writes the DCF that CDCF, a concise DCF, configures: the device's EDS\n"
    "(or DCF) with each entry as the ParameterValue of its object.\n"
    "\n"
    "  FILE  the file written, '-': standard output\n"
    "\n"
    "Example: comaster concise encode 4 examples/netmaster/drive4.dcf drive4.cdcf\n";

static FILE *open_output(const char *path)
{
    return strcmp(path, "-") == 0 ? stdout : fopen(path, "wb");
}

static int close_output(const comaster_options_t *opts, FILE *f, const char *path)
{
    bool failed = ferror(f) != 0;
    if (f != stdout)
        failed |= fclose(f) != 0;
    else
        failed |= fflush(f) != 0;
    return failed ? comaster_fail(opts, EX_CANTCREAT, "concise: cannot write %s", path) : 0;
}

static int encode(const comaster_options_t *opts, const char *node_text, const char *dcf,
                  const char *path)
{
    uint8_t node;
    if (!comaster_parse_node(opts, node_text, false, &node))
        return EX_USAGE;
    static comaster_network_t net;
    char err[512];
    int rc = comaster_network_single(&net, node, dcf, err, sizeof err);
    if (rc == 0) {
        FILE *f = open_output(path);
        if (f == NULL) {
            rc = comaster_fail(opts, EX_CANTCREAT, "concise: cannot write %s: %s", path,
                               strerror(errno));
        } else {
            fwrite(net.slave[0].concise, 1, net.slave[0].concise_len, f);
            rc = close_output(opts, f, path);
        }
    } else {
        rc = comaster_fail(opts, rc, "%s", err);
    }
    comaster_network_free(&net);
    return rc;
}

/* The entry's value as the ParameterValue of its object's data type, in value.c's form (an
 * unsigned integer in hexadecimal, as a DCF writes it); false for a type that comaster does not
 * write, one that has no ParameterValue form here (OCTET_STRING, DOMAIN), a size that is not the
 * type's, or a string that one line cannot hold. */
static bool parameter_value(const co_concise_dcf_entry_t *e, uint16_t data_type, char *out,
                            size_t cap)
{
    const comaster_type_t *type = comaster_type_by_code(data_type);
    if (type == NULL || data_type == CO_DT_OCTET_STRING || data_type == CO_DT_DOMAIN)
        return false;
    if (data_type == CO_DT_VISIBLE_STRING &&
        (memchr(e->data, '\n', e->len) != NULL || memchr(e->data, '\0', e->len) != NULL))
        return false;
    bool is_text;
    return comaster_value_format(type, e->data, e->len, COMASTER_VALUE_HEX, out, cap, &is_text);
}

/* "[1017]" -> 1017h:0, "[1405sub1]" -> 1405h:1 (CiA 306's object and sub-index sections). */
static bool section_object(const char *line, uint16_t *index, uint8_t *sub)
{
    unsigned long i, s = 0;
    char *end;
    if (line[0] != '[')
        return false;
    i = strtoul(line + 1, &end, 16);
    if (end != line + 5 || i > 0xFFFF)
        return false;
    if (strncasecmp(end, "sub", 3) == 0) {
        s = strtoul(end + 3, &end, 16);
        if (s > 0xFF)
            return false;
    }
    if (*end != ']')
        return false;
    *index = (uint16_t)i;
    *sub = (uint8_t)s;
    return true;
}

/* The entry of the concise DCF for index:sub, or NULL. */
static bool find_entry(const uint8_t *cdcf, size_t len, uint16_t index, uint8_t sub,
                       co_concise_dcf_entry_t *e)
{
    size_t pos = CO_CONCISE_DCF_HEADER;
    while (co_concise_dcf_next(cdcf, len, &pos, e)) {
        if (e->index == index && e->subindex == sub)
            return true;
    }
    return false;
}

/* The EDS text with ParameterValue lines: each object section of an entry gets its value after
 * its header, and loses the ParameterValue it had. */
static int write_dcf(const comaster_options_t *opts, const uint8_t *cdcf, size_t len,
                     const eds_t *eds, const char *eds_path, FILE *out)
{
    FILE *in = fopen(eds_path, "r");
    if (in == NULL)
        return comaster_fail(opts, EX_NOINPUT, "concise: cannot read %s: %s", eds_path,
                             strerror(errno));
    char line[1024], value[512];
    bool in_entry = false;
    int rc = 0;
    while (rc == 0 && fgets(line, sizeof line, in) != NULL) {
        uint16_t index;
        uint8_t sub;
        co_concise_dcf_entry_t e;
        if (line[0] == '[')
            in_entry = false;
        if (in_entry && strncasecmp(line, "ParameterValue", 14) == 0)
            continue;
        fputs(line, out);
        if (!section_object(line, &index, &sub) || !find_entry(cdcf, len, index, sub, &e))
            continue;
        const eds_entry_t *object = eds_find(eds, index, sub);
        if (object == NULL || !parameter_value(&e, object->data_type, value, sizeof value))
            rc = comaster_fail(opts, EX_DATAERR,
                               "concise: %04Xh:%02X, %u bytes, has no ParameterValue form as "
                               "DataType 0x%04X",
                               index, sub, e.len, object ? object->data_type : 0);
        else
            fprintf(out, "ParameterValue=%s\n", value);
        in_entry = true;
    }
    fclose(in);
    return rc;
}

/* Every entry must have its object in the EDS, or the DCF would lose it. */
static int check_objects(const comaster_options_t *opts, const uint8_t *cdcf, size_t len,
                         const eds_t *eds)
{
    size_t pos = CO_CONCISE_DCF_HEADER;
    co_concise_dcf_entry_t e;
    while (co_concise_dcf_next(cdcf, len, &pos, &e)) {
        if (eds_find(eds, e.index, e.subindex) == NULL)
            return comaster_fail(opts, EX_DATAERR,
                                 "concise: %04Xh:%02X is not an object of the EDS", e.index,
                                 e.subindex);
    }
    return 0;
}

static int decode(const comaster_options_t *opts, const char *cdcf_path, const char *eds_path,
                  const char *path)
{
    FILE *f = fopen(cdcf_path, "rb");
    if (f == NULL)
        return comaster_fail(opts, EX_NOINPUT, "concise: cannot read %s: %s", cdcf_path,
                             strerror(errno));
    static uint8_t cdcf[CONCISE_MAX + 1];
    size_t len = fread(cdcf, 1, sizeof cdcf, f);
    fclose(f);
    if (len > CONCISE_MAX || !co_concise_dcf_valid(cdcf, len, NULL))
        return comaster_fail(opts, EX_DATAERR, "concise: %s is not a concise DCF", cdcf_path);
    eds_t eds = {0};
    char err[512];
    eds_result_t loaded = eds_load(&eds, eds_path, 0, err, sizeof err);
    if (loaded != EDS_OK) {
        eds_free(&eds);
        return comaster_fail(opts, loaded == EDS_CANNOT_READ ? EX_NOINPUT : EX_DATAERR, "%s", err);
    }
    int rc = check_objects(opts, cdcf, len, &eds);
    FILE *out = rc == 0 ? open_output(path) : NULL;
    if (rc == 0 && out == NULL)
        rc = comaster_fail(opts, EX_CANTCREAT, "concise: cannot write %s: %s", path,
                           strerror(errno));
    if (out != NULL) {
        rc = write_dcf(opts, cdcf, len, &eds, eds_path, out);
        int closed = close_output(opts, out, path);
        rc = rc != 0 ? rc : closed;
    }
    eds_free(&eds);
    return rc;
}

int comaster_concise_main(comaster_options_t *opts, int argc, char **argv)
{
    comaster_args_t args;
    int rc = comaster_parse_args(opts, &args, argc, argv, concise_help, "", 4, 4);
    if (rc >= 0)
        return rc;
    const char *const *a = args.positional;
    if (strcmp(a[0], "encode") == 0)
        return encode(opts, a[1], a[2], a[3]);
    if (strcmp(a[0], "decode") == 0)
        return decode(opts, a[1], a[2], a[3]);
    comaster_fail(opts, EX_USAGE, "concise: '%s' is neither encode nor decode", a[0]);
    return EX_USAGE;
}
