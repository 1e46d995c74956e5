/* SPDX-License-Identifier: Apache-2.0 */
/* The network description: [Master] and [NodeN] of the INI file, [Topology] of the CiA 306-3
 * nodelist, the DCFs (docs/comaster.md "Network description"). */
#include "comaster/network.h"

#include "co/co_pdo.h"
#include "comaster/value.h"
#include "eds/ini_reader.h"

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
        if (!comaster_parse_number(line->value, CO_NMT_MASTER_NODE_ID_MAX, &t->nodes))
            return bad_value(line, "not a number of nodes 0..127", err, err_len);
        t->has_nodes = true;
    } else if (node_key(line->key, &node, &rest)) {
        if (strcasecmp(rest, "Present") == 0) {
            if (!comaster_parse_number(line->value, 1, &v))
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

/* ---- the process image: the slaves' PDOs ----------------------------------------------------- */

static const char *variable_name(const eds_t *dcf, uint16_t index, uint8_t sub)
{
    const eds_entry_t *e = eds_find(dcf, index, sub);
    if (e && e->denotation)
        return e->denotation;
    return eds_name(dcf, index, sub);
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
        uint32_t cob = comaster_dcf_u32(&s->dcf, (uint16_t)(comm + n), 1, &found);
        uint32_t objects = comaster_dcf_u32(&s->dcf, (uint16_t)(map + n), 0, &mapped);
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
            uint32_t m = comaster_dcf_u32(&s->dcf, (uint16_t)(map + n), k, &found);
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
    int rc = comaster_slave_load(&net->slave[i], &net->slave_config[i], node_id, name, dcf, err,
                                 err_len);
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
        if (!comaster_parse_number(line->value, CO_NET_SDO_TIMEOUT_MAX_MS, &v) ||
            v < CO_NET_SDO_TIMEOUT_MIN_MS)
            return bad_value(line, "give 5..5000 ms", err, err_len);
        c->sdo_timeout_ms = (uint16_t)v;
    } else if (strcasecmp(k, "boot_time") == 0) {
        if (!comaster_parse_number(line->value, 600000u, &c->boot_time_ms))
            return bad_value(line, "give 0..600000 ms", err, err_len);
    } else if (strcasecmp(k, "network_boot_time") == 0) {
        /* CiA 302-2's boot time 1F89h. */
        if (!comaster_parse_number(line->value, 3600000u, &c->boot_limit_ms))
            return bad_value(line, "give 0 (no limit) or 1..3600000 ms", err, err_len);
    } else if (strcasecmp(k, "retry_delay") == 0) {
        if (!comaster_parse_number(line->value, 600000u, &c->retry_delay_ms))
            return bad_value(line, "give 0..600000 ms", err, err_len);
    } else if (strcasecmp(k, "sync_period") == 0) {
        if (!comaster_parse_number(line->value, 60000u, &v))
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
    } else if (strcasecmp(k, "on_mandatory_error") == 0) {
        if (strcasecmp(line->value, "alone") == 0)
            c->on_mandatory_error = CO_NET_MANDATORY_ALONE;
        else if (strcasecmp(line->value, "stop_all") == 0)
            c->on_mandatory_error = CO_NET_MANDATORY_STOP_ALL;
        else if (strcasecmp(line->value, "reset_all") == 0)
            c->on_mandatory_error = CO_NET_MANDATORY_RESET_ALL;
        else
            return bad_value(line, "give alone, stop_all or reset_all", err, err_len);
    } else if (strcasecmp(k, "nmt_startup") == 0) {
        /* CiA 302-2's 1F80h, the object start and on_mandatory_error stand for. */
        if (!comaster_parse_number(line->value, UINT32_MAX, &v) ||
            !co_net_master_config_from_1f80(c, v))
            return bad_value(line,
                             "give CiA 302's 1F80h with bit 0 (NMT master) and any of bits 1 "
                             "(start all), 3 (start none), 4 (reset all), 6 (stop all)",
                             err, err_len);
    } else if (strcasecmp(k, "reset_all") == 0) {
        if (!parse_yes_no(line->value, &c->reset_all))
            return bad_value(line, "give yes or no", err, err_len);
    } else if (strcasecmp(k, "node_id") == 0) {
        if (!comaster_parse_number(line->value, CO_NMT_MASTER_NODE_ID_MAX, &v) || v < 1)
            return bad_value(line, "give the master's own node-id, 1..127", err, err_len);
        c->node_id = (uint8_t)v;
    } else if (strcasecmp(k, "heartbeat") == 0) {
        if (!comaster_parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0 (none) or 1..65535 ms", err, err_len);
        c->heartbeat_ms = (uint16_t)v;
    } else if (strcasecmp(k, "bit_rate") == 0) {
        if (!comaster_parse_number(line->value, UINT8_MAX, &v) || co_net_bit_rate((uint8_t)v) == 0)
            return bad_value(line,
                             "give the PLC300's code: 0 = 1 Mbit/s, 2 = 500, 3 = 250, 4 = 125, "
                             "5 = 100, 6 = 50, 7 = 20 kbit/s (1 is reserved)",
                             err, err_len);
        net->bit_rate = (uint8_t)v;
    } else {
        snprintf(err, err_len,
                 "%s:%u: unknown key '%s' in [Master] (cpj, interface, control, sdo_timeout, "
                 "boot_time, network_boot_time, retry_delay, sync_period, start, "
                 "on_mandatory_error, nmt_startup, "
                 "reset_all, node_id, heartbeat, bit_rate)",
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
    /* The keys of the expected identity are CiA 302-2's 1F84h..1F88h, in check_names' order;
     * 0 is no check of that value. */
    for (size_t i = 0; i < CHECK_NAMES; i++) {
        if (strcasecmp(k, check_names[i]) != 0)
            continue;
        if (!comaster_parse_number(line->value, UINT32_MAX, &v))
            return bad_value(line, "not a 32-bit number", err, err_len);
        return co_net_slave_config_set_expected(
            c, (uint16_t)(CO_NET_IDX_DEVICE_TYPE_IDENTIFICATION + i), v);
    }
    if (strcasecmp(k, "mandatory") == 0) {
        if (!parse_yes_no(line->value, &c->mandatory))
            return bad_value(line, "give yes or no", err, err_len);
    } else if (strcasecmp(k, "heartbeat") == 0) {
        if (!comaster_parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0..65535 ms", err, err_len);
        c->heartbeat_ms = (uint16_t)v;
    } else if (strcasecmp(k, "guard_time") == 0) {
        if (!comaster_parse_number(line->value, UINT16_MAX, &v))
            return bad_value(line, "give 0..65535 ms", err, err_len);
        c->guard_ms = (uint16_t)v;
    } else if (strcasecmp(k, "life_time_factor") == 0) {
        if (!comaster_parse_number(line->value, UINT8_MAX, &v))
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
    } else if (strcasecmp(k, "assignment") == 0) {
        /* CiA 302-2's 1F81h, the object mandatory, on_error, guard_time and life_time_factor
         * stand for. */
        if (!comaster_parse_number(line->value, UINT32_MAX, &v) ||
            !co_net_slave_config_from_1f81(c, v))
            return bad_value(line,
                             "give CiA 302's 1F81h with bit 0 (NMT slave) and any of bits 2 "
                             "(reboot on error), 3 (mandatory), 8..15 (retry factor), 16..31 "
                             "(guard time)",
                             err, err_len);
    } else {
        snprintf(err, err_len,
                 "%s:%u: unknown key '%s' in [%s] (mandatory, heartbeat, guard_time, "
                 "life_time_factor, on_error, assignment, check, device_type, vendor, product, "
                 "revision, serial)",
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
    net->bit_rate = COMASTER_BIT_RATE_NONE;
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

/* The master's own node-id (the PLC300's %CB3052), which no slave may have; its heartbeat is sent
 * on 700h + that node-id. */
static int check_master_node(const comaster_network_t *net, const char *path, char *err,
                             size_t err_len)
{
    const co_net_master_config_t *c = &net->config;
    if (c->heartbeat_ms != 0 && c->node_id == 0) {
        snprintf(err, err_len,
                 "%s: [Master] heartbeat = %u needs node_id = N, the master's own node-id (its "
                 "heartbeat is 700h + N)",
                 path, c->heartbeat_ms);
        return EX_DATAERR;
    }
    if (c->node_id != 0 && slave_of_node(net, c->node_id) != net->slave_count) {
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
    for (size_t i = 0; i < net->slave_count; i++)
        comaster_slave_free(&net->slave[i]);
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
