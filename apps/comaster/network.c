/* SPDX-License-Identifier: Apache-2.0 */
/* The network description: [Master] and [NodeN] of the INI file, [Topology] of the CiA 306-3
 * nodelist, the DCFs (docs/comaster.md "Network description"). */
#include "network.h"

#include "co/co_pdo.h"
#include "ini_reader.h"
#include "value.h"

#include <ctype.h>
#include <errno.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sysexits.h>

/* The defaults of the master's options (docs/comaster.md). */
#define DEFAULT_SDO_TIMEOUT_MS 500u
#define DEFAULT_BOOT_TIME_MS 1000u
#define DEFAULT_RETRY_DELAY_MS 1000u

/* ---- the option file and the nodelist, INI files --------------------------------------------- */

/* Reads an INI file of the network description: 0, EX_NOINPUT or EX_DATAERR. */
static int read_ini(const char *path, ini_line_fn on_key, void *ctx, char *err, size_t err_len)
{
    FILE *f = fopen(path, "re");
    if (!f) {
        snprintf(err, err_len, "cannot read '%s': %s", path, strerror(errno));
        return EX_NOINPUT;
    }
    /* Comments after a blank, as users write them in hand-made files. */
    const ini_reader_t syntax = {
        .trailing_comments = true, .key_line = "key = value", .on_key = on_key};
    bool ok = ini_read(f, path, &syntax, ctx, err, err_len);
    fclose(f);
    return ok ? 0 : EX_DATAERR;
}

static bool bad_value(const ini_line_t *line, const char *what, char *err, size_t err_len)
{
    snprintf(err, err_len, "%s:%u: %s = '%s': %s", line->path, line->number, line->key, line->value,
             what);
    return false;
}

static bool parse_number(const char *text, uint32_t max, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (end == text || *end != '\0' || errno != 0 || text[0] == '-' || v > max)
        return false;
    *out = (uint32_t)v;
    return true;
}

static bool parse_yes_no(const char *text, bool *out)
{
    if (strcasecmp(text, "yes") == 0 || strcasecmp(text, "true") == 0 || strcmp(text, "1") == 0)
        *out = true;
    else if (strcasecmp(text, "no") == 0 || strcasecmp(text, "false") == 0 ||
             strcmp(text, "0") == 0)
        *out = false;
    else
        return false;
    return true;
}

/* "dir/of/base" + "name" unless name is absolute. */
static bool relative_to(const char *base, const char *name, char *out, size_t len)
{
    if (name[0] == '/')
        return (size_t)snprintf(out, len, "%s", name) < len;
    char copy[PATH_MAX];
    snprintf(copy, sizeof copy, "%s", base);
    return (size_t)snprintf(out, len, "%s/%s", dirname(copy), name) < len;
}

/* ---- the nodelist (CiA 306-3 [Topology]) ------------------------------------------------------
 */

typedef struct topology {
    comaster_network_t *net;
    bool present[CO_NMT_MASTER_NODE_ID_MAX + 1];
    char name[CO_NMT_MASTER_NODE_ID_MAX + 1][COMASTER_NAME_MAX];
    char dcf[CO_NMT_MASTER_NODE_ID_MAX + 1][PATH_MAX];
    bool has_nodes;
    uint32_t nodes; /* the Nodes key: how many NodeXPresent there are */
} topology_t;

/* "Node12Present" -> 12 and "Present". */
static bool node_key(const char *key, uint32_t *node, const char **rest)
{
    if (strncasecmp(key, "Node", 4) != 0 || !isdigit((unsigned char)key[4]))
        return false;
    char *end;
    unsigned long n = strtoul(key + 4, &end, 10);
    if (n < 1 || n > CO_NMT_MASTER_NODE_ID_MAX)
        return false;
    *node = (uint32_t)n;
    *rest = end;
    return true;
}

static bool topology_key(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    topology_t *t = ctx;
    if (strcasecmp(line->section, "Topology") != 0)
        return true; /* other sections of a nodelist (a tool's own) do not concern the master */
    uint32_t node, v;
    const char *rest;
    if (strcasecmp(line->key, "NetName") == 0) {
        snprintf(t->net->net_name, sizeof t->net->net_name, "%s", line->value);
    } else if (strcasecmp(line->key, "Nodes") == 0) {
        if (!parse_number(line->value, CO_NMT_MASTER_NODE_ID_MAX, &t->nodes))
            return bad_value(line, "not a number of nodes 0..127", err, err_len);
        t->has_nodes = true;
    } else if (node_key(line->key, &node, &rest)) {
        if (strcasecmp(rest, "Present") == 0) {
            if (!parse_number(line->value, 1, &v))
                return bad_value(line, "give 0x01 (present) or 0x00", err, err_len);
            t->present[node] = v == 1;
        } else if (strcasecmp(rest, "Name") == 0) {
            snprintf(t->name[node], sizeof t->name[node], "%s", line->value);
        } else if (strcasecmp(rest, "DCFName") == 0) {
            if (!relative_to(line->path, line->value, t->dcf[node], sizeof t->dcf[node]))
                return bad_value(line, "path too long", err, err_len);
        }
    }
    return true;
}

/* ---- a slave from its DCF -------------------------------------------------------------------- */

static uint32_t dcf_u32(const eds_t *dcf, uint16_t index, uint8_t sub, bool *found)
{
    const eds_entry_t *e = eds_find(dcf, index, sub);
    *found = e && e->has_value;
    return *found ? (uint32_t)e->value : 0;
}

static const char *variable_name(const eds_t *dcf, uint16_t index, uint8_t sub)
{
    const eds_entry_t *e = eds_find(dcf, index, sub);
    if (e && e->denotation)
        return e->denotation;
    return eds_name(dcf, index, sub);
}

static bool is_configuration(const eds_entry_t *e)
{
    return e->configured && e->writable;
}

/* The configuration writes being built: their bytes in one buffer that grows, so a write's data
 * is an offset into it until the list is complete (load_writes). */
typedef struct pending_write {
    uint16_t index;
    uint8_t sub;
    size_t at, len;
} pending_write_t;

typedef struct write_list {
    pending_write_t *writes;
    size_t count, capacity;
    uint8_t *bytes;
    size_t used, bytes_capacity;
} write_list_t;

static bool grow(void **buffer, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity)
        return true;
    size_t more = needed > 2 * *capacity ? needed : 2 * *capacity;
    void *grown = realloc(*buffer, more * size);
    if (!grown)
        return false;
    *buffer = grown;
    *capacity = more;
    return true;
}

static int add_write(write_list_t *l, uint16_t index, uint8_t sub, const uint8_t *data, size_t len,
                     char *err, size_t err_len)
{
    if (!grow((void **)&l->writes, &l->capacity, l->count + 1, sizeof *l->writes) ||
        !grow((void **)&l->bytes, &l->bytes_capacity, l->used + len, 1)) {
        snprintf(err, err_len, "out of memory");
        return EX_OSERR;
    }
    memcpy(l->bytes + l->used, data, len);
    l->writes[l->count++] =
        (pending_write_t){.index = index, .sub = sub, .at = l->used, .len = len};
    l->used += len;
    return 0;
}

static int add_u32(write_list_t *l, uint16_t index, uint8_t sub, uint32_t value, size_t size,
                   char *err, size_t err_len)
{
    uint8_t b[4];
    for (size_t k = 0; k < size; k++)
        b[k] = (uint8_t)(value >> (8 * k));
    return add_write(l, index, sub, b, size, err, err_len);
}

/* "2005" for an object's section, "1A00sub1" for a sub-index's. */
static void section_name(const eds_entry_t *e, char *out, size_t len)
{
    if (e->sub == EDS_OBJECT)
        snprintf(out, len, "%04X", e->index);
    else
        snprintf(out, len, "%04Xsub%X", e->index, e->sub);
}

/* Adds the DCF entry's ParameterValue as the bytes of its DataType. */
static int add_configured(write_list_t *l, const comaster_slave_t *s, const eds_entry_t *e,
                          char *err, size_t err_len)
{
    uint8_t bytes[INI_LINE_MAX];
    size_t len;
    char why[256], section[16];
    if (!comaster_value_from_dcf(e, bytes, sizeof bytes, &len, why, sizeof why)) {
        section_name(e, section, sizeof section);
        snprintf(err, err_len, "%s:%u: [%s] ParameterValue = '%s': %s", s->dcf_path, e->value_line,
                 section, e->text ? e->text : "", why);
        return EX_DATAERR;
    }
    return add_write(l, e->index, e->sub == EDS_OBJECT ? 0 : (uint8_t)e->sub, bytes, len, err,
                     err_len);
}

/* ---- the configuration of a PDO (CiA 301 7.5.2.35-7.5.2.38) ----------------------------------
 * A slave refuses a change of a valid PDO's mapping, and may refuse one of its inhibit time and
 * other parameters (0x06090030, 0x06010000). Configuration tools and CiA 302 masters therefore
 * write a PDO whose parameters or mapping the DCF configures as one group, at the place of its
 * first configured entry: COB-ID with bit 31 (invalid), the communication parameters, the
 * mapping (sub-index 0 = 0, the entries, sub-index 0 = the count), the COB-ID as the DCF gives it
 * (docs/comaster.md, "The configuration of PDOs"). The invalidation writes the COB-ID the slave
 * holds (the DCF's DefaultValue: the slave was just reset) with bit 31 set, since a slave may
 * refuse any change of bits 0-29 of a valid PDO. A DCF that configures only a COB-ID writes it
 * alone, unless it gives a new CAN-ID to a PDO valid on the slave, which the slave refuses
 * (0x06090030): that PDO is invalidated first too (docs/decisions.md, D-DCF-PDO). */

#define PDO_COUNT (2u * CO_PDO_INDEX_SPAN)
#define PDO_SUB_COB_ID 1u
#define PDO_MAP_ENTRIES_MAX 64u
/* The bits of a COB-ID a slave may refuse to change while the PDO is valid (CiA 301 7.5.2.35). */
#define PDO_COB_ID_IDENTIFIER (~(CO_PDO_COBID_INVALID | CO_PDO_COBID_NO_RTR))

/* The communication parameter index of the PDO an index belongs to, 0 for another object. */
static uint16_t pdo_comm_of(uint16_t index)
{
    static const uint16_t bases[] = {CO_PDO_RPDO_COMM, CO_PDO_TPDO_COMM};
    for (size_t d = 0; d < 2; d++) {
        uint16_t comm = bases[d];
        if (index >= comm && index < comm + CO_PDO_INDEX_SPAN)
            return index;
        if (index >= comm + CO_PDO_INDEX_SPAN && index < comm + 2 * CO_PDO_INDEX_SPAN)
            return (uint16_t)(index - CO_PDO_INDEX_SPAN);
    }
    return 0;
}

/* A number for each PDO: RPDOs 0..511, TPDOs 512..1023. */
static size_t pdo_number(uint16_t comm)
{
    return comm < CO_PDO_TPDO_COMM ? comm - CO_PDO_RPDO_COMM
                                   : CO_PDO_INDEX_SPAN + (comm - CO_PDO_TPDO_COMM);
}

static bool configures_mapping(const eds_t *dcf, uint16_t map)
{
    for (size_t i = 0; i < dcf->count; i++) {
        const eds_entry_t *e = &dcf->entries[i];
        if (e->index == map && e->sub != EDS_OBJECT && is_configuration(e))
            return true;
    }
    return false;
}

/* The COB-ID the slave holds after its reset: the DCF's DefaultValue, else (a DCF without one)
 * the value it configures. */
static uint32_t held_cob_id(const eds_t *dcf, uint16_t comm, uint32_t configured)
{
    const eds_entry_t *e = eds_find(dcf, comm, PDO_SUB_COB_ID);
    return e && e->has_default && e->default_value <= UINT32_MAX ? (uint32_t)e->default_value
                                                                 : configured;
}

/* The DCF gives a PDO valid on the slave another identifier, which the slave refuses while the
 * PDO stays valid. */
static bool changes_valid_identifier(const eds_t *dcf, uint16_t comm)
{
    const eds_entry_t *e = eds_find(dcf, comm, PDO_SUB_COB_ID);
    if (!e || !is_configuration(e) || !e->has_value || e->negative || e->value > UINT32_MAX)
        return false;
    uint32_t configured = (uint32_t)e->value;
    uint32_t held = held_cob_id(dcf, comm, configured);
    return (held & CO_PDO_COBID_INVALID) == 0 && (configured & CO_PDO_COBID_INVALID) == 0 &&
           ((held ^ configured) & PDO_COB_ID_IDENTIFIER) != 0;
}

/* The DCF configures more of the PDO than its COB-ID, or a new identifier of a valid PDO. */
static bool needs_invalidation(const eds_t *dcf, uint16_t comm)
{
    for (size_t i = 0; i < dcf->count; i++) {
        const eds_entry_t *e = &dcf->entries[i];
        if (e->index == comm && e->sub != EDS_OBJECT && e->sub > PDO_SUB_COB_ID &&
            is_configuration(e))
            return true;
    }
    return configures_mapping(dcf, (uint16_t)(comm + CO_PDO_INDEX_SPAN)) ||
           changes_valid_identifier(dcf, comm);
}

static int pdo_value(const comaster_slave_t *s, uint16_t index, uint8_t sub, uint64_t max,
                     uint32_t *value, char *err, size_t err_len)
{
    const eds_entry_t *e = eds_find(&s->dcf, index, sub);
    if (!e || !e->has_value || e->negative || e->value > max) {
        snprintf(err, err_len,
                 "%s: [%04Xsub%X] has no value (ParameterValue or DefaultValue) to configure the "
                 "PDO with: the master writes it to invalidate and validate the PDO",
                 s->dcf_path, index, sub);
        return EX_DATAERR;
    }
    *value = (uint32_t)e->value;
    return 0;
}

/* The configured entries of `index` with a sub-index from `first` to `last`, in order. */
static int add_subs(write_list_t *l, const comaster_slave_t *s, uint16_t index, unsigned first,
                    unsigned last, char *err, size_t err_len)
{
    int rc = 0;
    for (unsigned sub = first; rc == 0 && sub <= last; sub++) {
        const eds_entry_t *e = eds_find(&s->dcf, index, (uint8_t)sub);
        if (e && e->sub == sub && is_configuration(e))
            rc = add_configured(l, s, e, err, err_len);
    }
    return rc;
}

static int add_pdo(write_list_t *l, const comaster_slave_t *s, uint16_t comm, char *err,
                   size_t err_len)
{
    uint16_t map = (uint16_t)(comm + CO_PDO_INDEX_SPAN);
    uint32_t cob_id, count = 0;
    int rc = pdo_value(s, comm, PDO_SUB_COB_ID, UINT32_MAX, &cob_id, err, err_len);
    if (rc == 0 && configures_mapping(&s->dcf, map))
        rc = pdo_value(s, map, 0, PDO_MAP_ENTRIES_MAX, &count, err, err_len);
    uint32_t invalid = held_cob_id(&s->dcf, comm, cob_id) | CO_PDO_COBID_INVALID;
    if (rc == 0)
        rc = add_u32(l, comm, PDO_SUB_COB_ID, invalid, 4, err, err_len);
    if (rc == 0)
        rc = add_subs(l, s, comm, PDO_SUB_COB_ID + 1, UINT8_MAX, err, err_len);
    if (rc == 0 && configures_mapping(&s->dcf, map)) {
        rc = add_u32(l, map, 0, 0, 1, err, err_len);
        if (rc == 0)
            rc = add_subs(l, s, map, 1, PDO_MAP_ENTRIES_MAX, err, err_len);
        if (rc == 0)
            rc = add_u32(l, map, 0, count, 1, err, err_len);
    }
    if (rc == 0 && cob_id != invalid)
        rc = add_u32(l, comm, PDO_SUB_COB_ID, cob_id, 4, err, err_len);
    return rc;
}

/* The DCF's configuration in file order, a PDO's at the place of its first entry. */
static int build_writes(write_list_t *l, const comaster_slave_t *s, char *err, size_t err_len)
{
    bool grouped[PDO_COUNT] = {false};
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < s->dcf.count; i++) {
        const eds_entry_t *e = &s->dcf.entries[i];
        if (!is_configuration(e))
            continue;
        uint16_t comm = pdo_comm_of(e->index);
        if (comm == 0 || !needs_invalidation(&s->dcf, comm)) {
            rc = add_configured(l, s, e, err, err_len);
        } else if (!grouped[pdo_number(comm)]) {
            grouped[pdo_number(comm)] = true;
            rc = add_pdo(l, s, comm, err, err_len);
        }
    }
    return rc;
}

static int load_writes(comaster_slave_t *s, co_net_slave_config_t *c, char *err, size_t err_len)
{
    write_list_t l = {0};
    int rc = build_writes(&l, s, err, err_len);
    if (rc == 0) {
        s->writes = calloc(l.count ? l.count : 1, sizeof *s->writes);
        if (!s->writes) {
            snprintf(err, err_len, "out of memory");
            rc = EX_OSERR;
        }
    }
    if (rc != 0) {
        free(l.writes);
        free(l.bytes);
        return rc;
    }
    for (size_t k = 0; k < l.count; k++)
        s->writes[k] = (co_net_write_t){.index = l.writes[k].index,
                                        .subindex = l.writes[k].sub,
                                        .data = l.bytes + l.writes[k].at,
                                        .len = (uint32_t)l.writes[k].len};
    free(l.writes);
    s->write_bytes = l.bytes;
    c->writes = s->writes;
    c->write_count = l.count;
    return 0;
}

/* Identity and error control that the DCF implies; the [NodeN] keys may change them. */
static void slave_defaults(const comaster_slave_t *s, co_net_slave_config_t *c)
{
    bool found;
    c->device_type = dcf_u32(&s->dcf, CO_IDX_DEVICE_TYPE, 0, &found);
    if (found)
        c->check |= CO_NET_CHECK_DEVICE_TYPE;
    /* Vendor and product are checked when the DCF gives them; revision and serial, which a
     * device's EDS gives only as an example, when the DCF configures them or [NodeN] asks. */
    for (uint8_t sub = 1; sub <= CO_NET_IDENTITY_SUBS; sub++) {
        const eds_entry_t *e = eds_find(&s->dcf, CO_IDX_IDENTITY, sub);
        if (!e || !e->has_value)
            continue;
        c->identity[sub - 1] = (uint32_t)e->value;
        if (sub <= 2 || e->configured)
            c->check |= (uint8_t)(CO_NET_CHECK_VENDOR << (sub - 1));
    }
    /* A heartbeat producer configured: consumed with half its time again as margin. */
    uint32_t producer = dcf_u32(&s->dcf, CO_IDX_HB_PRODUCER, 0, &found);
    if (producer != 0 && producer <= UINT16_MAX * 2u / 3u)
        c->heartbeat_ms = (uint16_t)(producer + (producer + 1) / 2);
    uint32_t guard = dcf_u32(&s->dcf, CO_IDX_GUARD_TIME, 0, &found);
    uint32_t factor = dcf_u32(&s->dcf, CO_IDX_LIFE_TIME_FACTOR, 0, &found);
    if (c->heartbeat_ms == 0 && guard != 0 && guard <= UINT16_MAX && factor != 0 &&
        factor <= UINT8_MAX) {
        c->guard_ms = (uint16_t)guard;
        c->life_time_factor = (uint8_t)factor;
    }
}

/* Appends the PDOs of one direction of a slave to the image and its variables. */
static int load_pdos(comaster_network_t *net, size_t si, bool output, char *err, size_t err_len)
{
    const comaster_slave_t *s = &net->slave[si];
    uint8_t node_id = net->slave_config[si].node_id;
    uint16_t comm = output ? CO_PDO_RPDO_COMM : CO_PDO_TPDO_COMM;
    uint16_t map = output ? CO_PDO_RPDO_MAP : CO_PDO_TPDO_MAP;
    co_net_pdo_t *pdos = output ? net->output_pdo : net->input_pdo;
    size_t *count = output ? &net->config.output_count : &net->config.input_count;
    size_t *size = output ? &net->config.output_size : &net->config.input_size;
    for (uint16_t n = 0; n < CO_PDO_INDEX_SPAN; n++) {
        bool found, mapped;
        uint32_t cob = dcf_u32(&s->dcf, (uint16_t)(comm + n), 1, &found);
        uint32_t objects = dcf_u32(&s->dcf, (uint16_t)(map + n), 0, &mapped);
        if (!found || (cob & CO_PDO_COBID_INVALID) != 0 || !mapped || objects == 0)
            continue;
        if ((cob & CO_PDO_COBID_FRAME) != 0 || objects > 64 ||
            co_can_id_restricted(cob & CO_PDO_COBID_CAN_ID)) {
            snprintf(err, err_len,
                     "%s: [%04Xsub1] COB-ID 0x%X: a 29-bit or restricted CAN-ID (CiA 301 7.3.5), "
                     "or more than 64 objects mapped: not a PDO comaster can exchange",
                     s->dcf_path, comm + n, cob);
            return EX_DATAERR;
        }
        uint16_t start = (uint16_t)*size;
        for (uint8_t k = 1; k <= objects; k++) {
            uint32_t m = dcf_u32(&s->dcf, (uint16_t)(map + n), k, &found);
            uint8_t bits = (uint8_t)m;
            if (bits == 0 || bits % 8 != 0) {
                snprintf(err, err_len,
                         "%s: [%04Xsub%X] maps %u bits: only whole bytes are "
                         "supported",
                         s->dcf_path, map + n, k, bits);
                return EX_DATAERR;
            }
            if (*size + bits / 8u > COMASTER_IMAGE_SIZE ||
                net->variable_count == COMASTER_VARIABLE_MAX) {
                snprintf(err, err_len, "%s: the PDOs need more than the %u bytes of the %s image",
                         s->dcf_path, COMASTER_IMAGE_SIZE, output ? "output" : "input");
                return EX_DATAERR;
            }
            uint16_t index = (uint16_t)(m >> 16);
            uint8_t sub = (uint8_t)(m >> 8);
            const char *name = variable_name(&s->dcf, index, sub);
            /* Dummy entries (index below 1000h) only hold their place in the frame. */
            if (index >= CO_IDX_DEVICE_TYPE && name) {
                const eds_entry_t *e = eds_find(&s->dcf, index, sub);
                net->variable[net->variable_count++] = (comaster_variable_t){
                    .name = name,
                    .node_id = node_id,
                    .index = index,
                    .sub = sub,
                    .data_type = e ? e->data_type : 0,
                    .output = output,
                    .offset = (uint16_t)*size,
                    .size = (uint8_t)(bits / 8u),
                };
            }
            *size += bits / 8u;
        }
        if (*size - start > CO_FRAME_DLC_MAX) {
            snprintf(err, err_len, "%s: [%04X] maps %zu bytes, more than the 8 of a frame",
                     s->dcf_path, map + n, *size - start);
            return EX_DATAERR;
        }
        pdos[(*count)++] = (co_net_pdo_t){.node_id = node_id,
                                          .can_id = (uint16_t)(cob & CO_PDO_COBID_CAN_ID),
                                          .len = (uint8_t)(*size - start),
                                          .offset = start};
    }
    return 0;
}

static int add_slave(comaster_network_t *net, uint8_t node_id, const char *name, const char *dcf,
                     char *err, size_t err_len)
{
    size_t i = net->slave_count++;
    comaster_slave_t *s = &net->slave[i];
    co_net_slave_config_t *c = &net->slave_config[i];
    *c = (co_net_slave_config_t){.node_id = node_id, .on_error = CO_NET_ON_ERROR_REBOOT};
    snprintf(s->name, sizeof s->name, "%s", name);
    snprintf(s->dcf_path, sizeof s->dcf_path, "%s", dcf);
    eds_result_t loaded = eds_load(&s->dcf, dcf, node_id, err, err_len);
    if (loaded != EDS_OK)
        return loaded == EDS_CANNOT_READ ? EX_NOINPUT : EX_DATAERR;
    slave_defaults(s, c);
    int rc = load_writes(s, c, err, err_len);
    if (rc == 0)
        rc = load_pdos(net, i, false, err, err_len);
    if (rc == 0)
        rc = load_pdos(net, i, true, err, err_len);
    return rc;
}

/* ---- the option file ------------------------------------------------------------------------- */

static size_t slave_of_node(const comaster_network_t *net, uint8_t node_id)
{
    for (size_t i = 0; i < net->slave_count; i++) {
        if (net->slave_config[i].node_id == node_id)
            return i;
    }
    return net->slave_count;
}

static bool master_key(comaster_network_t *net, const ini_line_t *line, char *err, size_t err_len)
{
    co_net_master_config_t *c = &net->config;
    uint32_t v;
    const char *k = line->key;
    if (strcasecmp(k, "cpj") == 0)
        return true; /* read first, by load */
    if (strcasecmp(k, "interface") == 0) {
        if (strlen(line->value) >= sizeof net->iface)
            return bad_value(line, "an interface name is at most 15 characters", err, err_len);
        snprintf(net->iface, sizeof net->iface, "%s", line->value);
    } else if (strcasecmp(k, "control") == 0) {
        if (strlen(line->value) >= sizeof net->control)
            return bad_value(line, "a socket path is at most 107 characters", err, err_len);
        snprintf(net->control, sizeof net->control, "%s", line->value);
    } else if (strcasecmp(k, "sdo_timeout") == 0) {
        if (!parse_number(line->value, CO_NET_SDO_TIMEOUT_MAX_MS, &v) ||
            v < CO_NET_SDO_TIMEOUT_MIN_MS)
            return bad_value(line, "give 5..5000 ms", err, err_len);
        c->sdo_timeout_ms = (uint16_t)v;
    } else if (strcasecmp(k, "boot_time") == 0) {
        if (!parse_number(line->value, 600000u, &c->boot_time_ms))
            return bad_value(line, "give 0..600000 ms", err, err_len);
    } else if (strcasecmp(k, "retry_delay") == 0) {
        if (!parse_number(line->value, 600000u, &c->retry_delay_ms))
            return bad_value(line, "give 0..600000 ms", err, err_len);
    } else if (strcasecmp(k, "sync_period") == 0) {
        if (!parse_number(line->value, 60000u, &v))
            return bad_value(line, "give 0 (no SYNC) or 1..60000 ms", err, err_len);
        c->sync_period_us = v * 1000u;
    } else if (strcasecmp(k, "start") == 0) {
        if (strcasecmp(line->value, "each") == 0)
            c->start = CO_NET_START_EACH;
        else if (strcasecmp(line->value, "all") == 0)
            c->start = CO_NET_START_ALL;
        else if (strcasecmp(line->value, "none") == 0)
            c->start = CO_NET_START_NONE;
        else
            return bad_value(line, "give each, all or none", err, err_len);
    } else if (strcasecmp(k, "reset_all") == 0) {
        if (!parse_yes_no(line->value, &c->reset_all))
            return bad_value(line, "give yes or no", err, err_len);
    } else if (strcasecmp(k, "node_id") == 0) {
        if (!parse_number(line->value, CO_NMT_MASTER_NODE_ID_MAX, &v) || v < 1)
            return bad_value(line, "give the master's own node-id, 1..127", err, err_len);
        c->node_id = (uint8_t)v;
    } else if (strcasecmp(k, "heartbeat") == 0) {
        if (!parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0 (none) or 1..65535 ms", err, err_len);
        c->heartbeat_ms = (uint16_t)v;
    } else {
        snprintf(err, err_len,
                 "%s:%u: unknown key '%s' in [Master] (cpj, interface, control, sdo_timeout, "
                 "boot_time, retry_delay, sync_period, start, reset_all, node_id, heartbeat)",
                 line->path, line->number, k);
        return false;
    }
    return true;
}

static const char *const check_names[] = {"device_type", "vendor", "product", "revision", "serial"};
#define CHECK_NAMES (sizeof check_names / sizeof check_names[0])

static bool parse_check(const ini_line_t *line, uint8_t *check, char *err, size_t err_len)
{
    char copy[INI_LINE_MAX];
    snprintf(copy, sizeof copy, "%s", line->value);
    *check = 0;
    for (char *save, *word = strtok_r(copy, " ,", &save); word;
         word = strtok_r(NULL, " ,", &save)) {
        if (strcasecmp(word, "none") == 0)
            continue;
        size_t k = 0;
        while (k < CHECK_NAMES && strcasecmp(word, check_names[k]) != 0)
            k++;
        if (k == CHECK_NAMES)
            return bad_value(line,
                             "give none or some of device_type vendor product revision serial", err,
                             err_len);
        *check |= (uint8_t)(1u << k);
    }
    return true;
}

static bool node_key_value(co_net_slave_config_t *c, const ini_line_t *line, char *err,
                           size_t err_len)
{
    uint32_t v;
    const char *k = line->key;
    for (size_t i = 0; i < CHECK_NAMES; i++) {
        if (strcasecmp(k, check_names[i]) != 0)
            continue;
        if (!parse_number(line->value, UINT32_MAX, &v))
            return bad_value(line, "not a 32-bit number", err, err_len);
        if (i == 0)
            c->device_type = v;
        else
            c->identity[i - 1] = v;
        c->check |= (uint8_t)(1u << i);
        return true;
    }
    if (strcasecmp(k, "mandatory") == 0) {
        if (!parse_yes_no(line->value, &c->mandatory))
            return bad_value(line, "give yes or no", err, err_len);
    } else if (strcasecmp(k, "heartbeat") == 0) {
        if (!parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0..65535 ms", err, err_len);
        c->heartbeat_ms = (uint16_t)v;
    } else if (strcasecmp(k, "guard_time") == 0) {
        if (!parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0..65535 ms", err, err_len);
        c->guard_ms = (uint16_t)v;
    } else if (strcasecmp(k, "life_time_factor") == 0) {
        if (!parse_number(line->value, UINT8_MAX, &v))
            return bad_value(line, "give 0..255", err, err_len);
        c->life_time_factor = (uint8_t)v;
    } else if (strcasecmp(k, "on_error") == 0) {
        if (strcasecmp(line->value, "reboot") == 0)
            c->on_error = CO_NET_ON_ERROR_REBOOT;
        else if (strcasecmp(line->value, "report") == 0)
            c->on_error = CO_NET_ON_ERROR_REPORT;
        else
            return bad_value(line, "give reboot or report", err, err_len);
    } else if (strcasecmp(k, "check") == 0) {
        return parse_check(line, &c->check, err, err_len);
    } else {
        snprintf(err, err_len,
                 "%s:%u: unknown key '%s' in [%s] (mandatory, heartbeat, guard_time, "
                 "life_time_factor, on_error, check, device_type, vendor, product, revision, "
                 "serial)",
                 line->path, line->number, k, line->section);
        return false;
    }
    return true;
}

static bool option_key(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    comaster_network_t *net = ctx;
    uint32_t node;
    const char *rest;
    if (strcasecmp(line->section, "Master") == 0)
        return master_key(net, line, err, err_len);
    if (node_key(line->section, &node, &rest) && *rest == '\0') {
        size_t i = slave_of_node(net, (uint8_t)node);
        if (i == net->slave_count) {
            snprintf(err, err_len, "%s:%u: [%s]: node %u is not present in the nodelist",
                     line->path, line->number, line->section, node);
            return false;
        }
        return node_key_value(&net->slave_config[i], line, err, err_len);
    }
    snprintf(err, err_len, "%s:%u: unknown section [%s] (give [Master] and [NodeN], N = 1..127)",
             line->path, line->number, line->section);
    return false;
}

/* Finds [Master] cpj before anything else, since the [NodeN] keys apply to its slaves. */
typedef struct cpj_lookup {
    char path[PATH_MAX];
} cpj_lookup_t;

static bool cpj_key(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    cpj_lookup_t *l = ctx;
    if (strcasecmp(line->section, "Master") == 0 && strcasecmp(line->key, "cpj") == 0 &&
        !relative_to(line->path, line->value, l->path, sizeof l->path))
        return bad_value(line, "path too long", err, err_len);
    return true;
}

static void network_init(comaster_network_t *net)
{
    memset(net, 0, sizeof *net);
    net->config = (co_net_master_config_t){
        .slaves = net->slave_config,
        .slave_state = net->slave_state,
        .sdo_timeout_ms = DEFAULT_SDO_TIMEOUT_MS,
        .boot_time_ms = DEFAULT_BOOT_TIME_MS,
        .retry_delay_ms = DEFAULT_RETRY_DELAY_MS,
        .start = CO_NET_START_EACH,
        .inputs = net->input_pdo,
        .input_image = net->input_image,
        .outputs = net->output_pdo,
        .output_image = net->output_image,
    };
}

static int load_topology(comaster_network_t *net, const char *cpj, char *err, size_t err_len)
{
    topology_t *t = calloc(1, sizeof *t);
    if (!t) {
        snprintf(err, err_len, "out of memory");
        return EX_OSERR;
    }
    t->net = net;
    int rc = read_ini(cpj, topology_key, t, err, err_len);
    uint32_t present = 0;
    for (uint8_t n = 1; rc == 0 && n <= CO_NMT_MASTER_NODE_ID_MAX; n++) {
        if (!t->present[n])
            continue;
        present++;
        if (t->dcf[n][0] == '\0') {
            snprintf(err, err_len, "%s: node %u is present but has no Node%uDCFName", cpj, n, n);
            rc = EX_DATAERR;
            break;
        }
        rc = add_slave(net, n, t->name[n], t->dcf[n], err, err_len);
    }
    if (rc == 0 && t->has_nodes && t->nodes != present) {
        snprintf(err, err_len, "%s: Nodes = %u but %u nodes are present", cpj, t->nodes, present);
        rc = EX_DATAERR;
    }
    if (rc == 0 && present == 0) {
        snprintf(err, err_len, "%s: no [Topology] NodeXPresent = 0x01: no slave to boot", cpj);
        rc = EX_DATAERR;
    }
    free(t);
    return rc;
}

/* The master's heartbeat is sent on 700h + its own node-id, which no slave may have. */
static int check_master_node(const comaster_network_t *net, const char *path, char *err,
                             size_t err_len)
{
    const co_net_master_config_t *c = &net->config;
    if (c->heartbeat_ms == 0)
        return 0;
    if (c->node_id == 0) {
        snprintf(err, err_len,
                 "%s: [Master] heartbeat = %u needs node_id = N, the master's own node-id (its "
                 "heartbeat is 700h + N)",
                 path, c->heartbeat_ms);
        return EX_DATAERR;
    }
    if (slave_of_node(net, c->node_id) != net->slave_count) {
        snprintf(err, err_len, "%s: [Master] node_id = %u is the node-id of a slave", path,
                 c->node_id);
        return EX_DATAERR;
    }
    return 0;
}

static void finish(comaster_network_t *net)
{
    net->config.slave_count = net->slave_count;
}

int comaster_network_load(comaster_network_t *net, const char *path, char *err, size_t err_len)
{
    network_init(net);
    net->config.reset_all = true;
    cpj_lookup_t cpj = {.path = ""};
    int rc = read_ini(path, cpj_key, &cpj, err, err_len);
    if (rc == 0 && cpj.path[0] == '\0') {
        snprintf(err, err_len, "%s: [Master] has no cpj = NODELIST (the CiA 306-3 nodelist)", path);
        rc = EX_DATAERR;
    }
    if (rc == 0)
        rc = load_topology(net, cpj.path, err, err_len);
    if (rc == 0)
        rc = read_ini(path, option_key, net, err, err_len);
    if (rc == 0)
        rc = check_master_node(net, path, err, err_len);
    if (rc != 0)
        comaster_network_free(net);
    finish(net);
    return rc;
}

int comaster_network_single(comaster_network_t *net, uint8_t node_id, const char *dcf_path,
                            char *err, size_t err_len)
{
    network_init(net);
    char name[COMASTER_NAME_MAX];
    snprintf(name, sizeof name, "node%u", node_id);
    int rc = add_slave(net, node_id, name, dcf_path, err, err_len);
    if (rc != 0)
        comaster_network_free(net);
    finish(net);
    return rc;
}

void comaster_network_free(comaster_network_t *net)
{
    for (size_t i = 0; i < net->slave_count; i++) {
        eds_free(&net->slave[i].dcf);
        free(net->slave[i].writes);
        free(net->slave[i].write_bytes);
        net->slave[i].writes = NULL;
        net->slave[i].write_bytes = NULL;
    }
    net->slave_count = 0;
    net->variable_count = 0;
}

size_t comaster_network_find(const comaster_network_t *net, uint8_t node_id, const char *name,
                             const comaster_variable_t **first, char *err, size_t err_len)
{
    *first = NULL;
    size_t i = slave_of_node(net, node_id);
    if (i == net->slave_count) {
        snprintf(err, err_len, "node %u is not a slave of the network", node_id);
        return 0;
    }
    comaster_object_t object;
    if (!comaster_object_parse(name, &net->slave[i].dcf, &object, err, err_len))
        return 0;
    size_t count = 0;
    for (size_t v = 0; v < net->variable_count; v++) {
        const comaster_variable_t *var = &net->variable[v];
        if (var->node_id == node_id && var->index == object.index && var->sub == object.sub) {
            if (!*first)
                *first = var;
            count++;
        }
    }
    if (count == 0)
        snprintf(err, err_len, "node %u: %04Xh:%02X (%s) is in none of its PDOs", node_id,
                 object.index, object.sub, name);
    return count;
}
