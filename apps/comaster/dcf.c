/* SPDX-License-Identifier: Apache-2.0 */
/* A slave of comaster's network from its DCF (docs/comaster.md "Network description"): the
 * identity checks and error control the DCF implies, and its configuration (the ParameterValue
 * entries) as the writes of the boot in file order, a PDO's as one group. */
#include "comaster/dcf.h"

#include "co/co_pdo.h"
#include "comaster/value.h"
#include "eds/ini_reader.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>

uint32_t comaster_dcf_u32(const eds_t *dcf, uint16_t index, uint8_t sub, bool *found)
{
    const eds_entry_t *e = eds_find(dcf, index, sub);
    *found = e && e->has_value;
    return *found ? (uint32_t)e->value : 0;
}

static bool is_configuration(const eds_entry_t *e)
{
    return e->configured && e->writable;
}

/* The configuration writes being built: their bytes in one buffer that grows, so a write's data
 * is an offset into it until the list is complete (load_concise). */
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

/* The writes as the slave's concise DCF (CiA 302's 1F22h), which the master downloads: its size is
 * known from the list, each entry's header and bytes. */
static int load_concise(comaster_slave_t *s, co_net_slave_config_t *c, char *err, size_t err_len)
{
    write_list_t l = {0};
    int rc = build_writes(&l, s, err, err_len);
    size_t size = CO_CONCISE_DCF_HEADER + l.count * CO_CONCISE_DCF_ENTRY_HEADER + l.used;
    if (rc == 0 && (s->concise = malloc(size)) == NULL) {
        snprintf(err, err_len, "out of memory");
        rc = EX_OSERR;
    }
    size_t used = rc == 0 ? co_concise_dcf_begin(s->concise, size) : 0;
    for (size_t k = 0; rc == 0 && k < l.count; k++) {
        co_concise_dcf_entry_t e = {l.writes[k].index, l.writes[k].sub, l.bytes + l.writes[k].at,
                                    (uint32_t)l.writes[k].len};
        used = co_concise_dcf_add(s->concise, size, used, &e);
    }
    free(l.writes);
    free(l.bytes);
    if (rc != 0)
        return rc;
    s->concise_len = used;
    c->concise_dcf = s->concise;
    c->concise_dcf_len = used;
    return 0;
}

/* Identity and error control that the DCF implies; the [NodeN] keys may change them. */
static void slave_defaults(const comaster_slave_t *s, co_net_slave_config_t *c)
{
    bool found;
    c->device_type = comaster_dcf_u32(&s->dcf, CO_IDX_DEVICE_TYPE, 0, &found);
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
    uint32_t producer = comaster_dcf_u32(&s->dcf, CO_IDX_HB_PRODUCER, 0, &found);
    if (producer != 0 && producer <= UINT16_MAX * 2u / 3u)
        c->heartbeat_ms = (uint16_t)(producer + (producer + 1) / 2);
    uint32_t guard = comaster_dcf_u32(&s->dcf, CO_IDX_GUARD_TIME, 0, &found);
    uint32_t factor = comaster_dcf_u32(&s->dcf, CO_IDX_LIFE_TIME_FACTOR, 0, &found);
    if (c->heartbeat_ms == 0 && guard != 0 && guard <= UINT16_MAX && factor != 0 &&
        factor <= UINT8_MAX) {
        c->guard_ms = (uint16_t)guard;
        c->life_time_factor = (uint8_t)factor;
    }
}

int comaster_slave_load(comaster_slave_t *s, co_net_slave_config_t *c, uint8_t node_id,
                        const char *name, const char *path, char *err, size_t err_len)
{
    *c = (co_net_slave_config_t){.node_id = node_id, .on_error = CO_NET_ON_ERROR_REBOOT};
    snprintf(s->name, sizeof s->name, "%s", name);
    snprintf(s->dcf_path, sizeof s->dcf_path, "%s", path);
    eds_result_t loaded = eds_load(&s->dcf, path, node_id, err, err_len);
    if (loaded != EDS_OK)
        return loaded == EDS_CANNOT_READ ? EX_NOINPUT : EX_DATAERR;
    slave_defaults(s, c);
    return load_concise(s, c, err, err_len);
}

void comaster_slave_free(comaster_slave_t *s)
{
    eds_free(&s->dcf);
    free(s->concise);
    s->concise = NULL;
    s->concise_len = 0;
}
