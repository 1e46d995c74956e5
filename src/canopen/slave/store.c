/* SPDX-License-Identifier: Apache-2.0 */
/* Store and restore parameters: 1010h / 1011h (CiA 301 sections 7.5.2.13-14), the
 * self-describing images described in co_store.h, and their application at a reset through the
 * dictionary's write path. */
#include "co/co_node.h"

#include <string.h>

#define STORE_GROUP_ALL 1u
#define STORE_GROUP_LAST 4u

/* Image format: version 2 adds the save sequence and the kind; version 1 images (records only)
 * still load, as the oldest values. */
#define IMAGE_VERSION_1 1u
#define IMAGE_VERSION 2u
#define IMAGE_V1_HEADER_SIZE 4u

typedef struct store_area {
    uint8_t area;
    uint16_t first;
    uint16_t last;
} store_area_t;

static const store_area_t areas[] = {
    {CO_STORE_AREA_COMMUNICATION, CO_IDX_COMM_FIRST, CO_IDX_COMM_LAST},
    {CO_STORE_AREA_MANUFACTURER, 0x2000, 0x5FFF},
    {CO_STORE_AREA_PROFILE, 0x6000, 0x9FFF},
};

#define AREA_COUNT (sizeof(areas) / sizeof(areas[0]))

static const uint8_t image_magic[3] = {'C', 'O', 'S'};

/* Group 1 is every area; groups 2..4 are one area each. */
static bool group_has_area(uint8_t group, const store_area_t *a)
{
    return group == STORE_GROUP_ALL || group == a->area;
}

/* Parameters only: not the process data the application marks (commands, references), not the
 * error history and the store/restore commands (1003h, 1010h, 1011h). */
/* A streamed DOMAIN's value lives in the application, which keeps it itself. */
static bool entry_is_stored(const co_od_entry_t *e)
{
    return (e->flags & CO_OD_WRITE) && !(e->flags & CO_OD_PROCESS) && !(e->flags & CO_OD_STREAM) &&
           e->index != CO_IDX_ERROR_HISTORY && e->index != CO_IDX_STORE &&
           e->index != CO_IDX_RESTORE;
}

/* An entry whose read hook computes its value from other entries (6046h of LSP/HSP): its stored
 * bytes are not its value, so it is saved as read and restored as written. */
static bool entry_is_view(const co_od_entry_t *e)
{
    return e->hook != NULL && e->hook->read != NULL;
}

/* What an image header says. */
typedef struct image_info {
    uint32_t size;     /* bytes, 0: no usable image */
    uint32_t sequence; /* order of the save or restore that wrote it */
    uint8_t kind;      /* CO_STORE_IMAGE_VALUES or CO_STORE_IMAGE_DEFAULTS */
    uint32_t records;  /* offset of the first record */
} image_info_t;

/* Reads the header of an area's image into *info. No image, or one the backend reports damaged
 * (it reports that itself), is no fault: info->size is then 0, as it is after a fault. */
static co_store_fault_t read_header(const co_storage_t *s, uint8_t area, image_info_t *info)
{
    long size = s->load_size(s->ctx, area);
    *info = (image_info_t){0};
    if (size <= 0)
        return CO_STORE_FAULT_NONE;
    uint8_t h[CO_STORE_IMAGE_HEADER_SIZE];
    uint32_t want = (unsigned long)size < sizeof(h) ? (uint32_t)size : (uint32_t)sizeof(h);
    if ((unsigned long)size > UINT32_MAX || want < IMAGE_V1_HEADER_SIZE)
        return CO_STORE_FAULT_HEADER;
    if (s->load_read(s->ctx, area, 0, h, want) != 0)
        return CO_STORE_FAULT_UNREADABLE;
    if (h[0] != image_magic[0] || h[1] != image_magic[1] || h[2] != image_magic[2])
        return CO_STORE_FAULT_HEADER;
    if (h[3] == IMAGE_VERSION_1) {
        *info = (image_info_t){(uint32_t)size, 0, CO_STORE_IMAGE_VALUES, IMAGE_V1_HEADER_SIZE};
        return CO_STORE_FAULT_NONE;
    }
    if (h[3] != IMAGE_VERSION || want < sizeof(h) || h[8] > CO_STORE_IMAGE_DEFAULTS)
        return CO_STORE_FAULT_HEADER;
    *info = (image_info_t){(uint32_t)size, co_get_u32(&h[4]), h[8], CO_STORE_IMAGE_HEADER_SIZE};
    return CO_STORE_FAULT_NONE;
}

/* The sequence number of the next save or restore: after every image stored. */
static uint32_t next_sequence(const co_node_t *node)
{
    uint32_t next = 1;
    for (size_t i = 0; i < AREA_COUNT; i++) {
        image_info_t info;
        if (read_header(node->storage, areas[i].area, &info) == CO_STORE_FAULT_NONE &&
            info.sequence >= next)
            next = info.sequence + 1;
    }
    return next;
}

static int write_header(const co_storage_t *s, uint32_t sequence, uint8_t kind)
{
    uint8_t h[CO_STORE_IMAGE_HEADER_SIZE] = {image_magic[0], image_magic[1], image_magic[2],
                                             IMAGE_VERSION};
    co_put_u32(&h[4], sequence);
    h[8] = kind;
    return s->save_write(s->ctx, h, sizeof(h));
}

static int save_entry(co_node_t *node, const co_od_entry_t *e)
{
    const co_storage_t *s = node->storage;
    if (entry_is_view(e) && e->hook->read(node, e) != CO_SDO_OK)
        return -1;
    uint8_t record[CO_STORE_RECORD_HEADER_SIZE];
    co_put_u16(&record[0], e->index);
    record[2] = e->subindex;
    co_put_u16(&record[3], e->size);
    int rc = s->save_write(s->ctx, record, sizeof(record));
    return rc == 0 ? s->save_write(s->ctx, co_od_bytes(node, e), e->size) : rc;
}

static int save_area(co_node_t *node, const store_area_t *a, uint32_t sequence, uint8_t kind)
{
    const co_storage_t *s = node->storage;
    if (s->save_begin(s->ctx, a->area) != 0)
        return -1;
    int rc = write_header(s, sequence, kind);
    for (uint16_t i = 0; rc == 0 && kind == CO_STORE_IMAGE_VALUES && i < node->od->count; i++) {
        const co_od_entry_t *e = &node->od->entries[i];
        if (e->index >= a->first && e->index <= a->last && entry_is_stored(e))
            rc = save_entry(node, e);
    }
    if (s->save_end(s->ctx, rc == 0) != 0)
        return -1;
    return rc;
}

/* The areas of one 1010h / 1011h write commit together when the backend can (group_begin). */
static uint32_t group_begin(const co_storage_t *s)
{
    return s->group_begin != NULL && s->group_begin(s->ctx) != 0 ? CO_SDO_ABORT_HARDWARE
                                                                 : CO_SDO_OK;
}

static uint32_t group_end(const co_storage_t *s, uint32_t abort)
{
    if (s->group_end != NULL && s->group_end(s->ctx, abort == CO_SDO_OK) != 0 && abort == CO_SDO_OK)
        return CO_SDO_ABORT_HARDWARE;
    return abort;
}

static uint32_t save_group(co_node_t *node, uint8_t group)
{
    uint32_t sequence = next_sequence(node);
    uint32_t abort = group_begin(node->storage);
    if (abort != CO_SDO_OK)
        return abort;
    for (size_t i = 0; i < AREA_COUNT && abort == CO_SDO_OK; i++)
        if (group_has_area(group, &areas[i]) &&
            save_area(node, &areas[i], sequence++, CO_STORE_IMAGE_VALUES) != 0)
            abort = CO_SDO_ABORT_HARDWARE;
    return group_end(node->storage, abort);
}

/* Restoring every area forgets every image. Restoring one area stores a defaults image for it:
 * the defaults then apply in their place in the save order, so they also win over older saved
 * values of another area that its views stand for (1011h:03 restores 6046h, hence LSP/HSP). */
static uint32_t restore_group(co_node_t *node, uint8_t group)
{
    const co_storage_t *s = node->storage;
    uint32_t sequence = group == STORE_GROUP_ALL ? 0 : next_sequence(node);
    uint32_t abort = group_begin(s);
    if (abort != CO_SDO_OK)
        return abort;
    for (size_t i = 0; i < AREA_COUNT && abort == CO_SDO_OK; i++) {
        if (!group_has_area(group, &areas[i]))
            continue;
        int rc = group == STORE_GROUP_ALL
                     ? s->erase(s->ctx, areas[i].area)
                     : save_area(node, &areas[i], sequence, CO_STORE_IMAGE_DEFAULTS);
        if (rc != 0)
            abort = CO_SDO_ABORT_HARDWARE;
    }
    return group_end(s, abort);
}

/* CiA 301 1010h / 1011h: only the "save" / "load" signature is accepted (0x08000020 otherwise,
 * and when there is nowhere to store); the stored value stays 1, so the write is handled here. */
uint32_t co_store_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len)
{
    (void)len;
    if (entry->subindex == 0)
        return CO_SDO_OK;
    bool save = entry->index == CO_IDX_STORE;
    uint32_t signature = save ? CO_STORE_SIGNATURE_SAVE : CO_STORE_SIGNATURE_LOAD;
    if (co_get_u32(data) != signature || node->storage == NULL ||
        entry->subindex > STORE_GROUP_LAST)
        return CO_SDO_ABORT_DATA_STORE;
    uint32_t abort =
        save ? save_group(node, entry->subindex) : restore_group(node, entry->subindex);
    return abort != CO_SDO_OK ? abort : CO_OD_HANDLED;
}

typedef struct image_record {
    uint16_t index;
    uint8_t subindex;
    uint16_t len;
    uint32_t value_offset;
} image_record_t;

/* Reads the record header at *offset and moves *offset past the record; a fault when the header
 * cannot be read or the record does not lie inside the image. */
static co_store_fault_t read_record(const co_storage_t *s, uint8_t area, uint32_t size,
                                    uint32_t *offset, image_record_t *r)
{
    uint8_t h[CO_STORE_RECORD_HEADER_SIZE];
    if (size - *offset < sizeof(h))
        return CO_STORE_FAULT_CUT_SHORT;
    if (s->load_read(s->ctx, area, *offset, h, sizeof(h)) != 0)
        return CO_STORE_FAULT_UNREADABLE;
    r->index = co_get_u16(&h[0]);
    r->subindex = h[2];
    r->len = co_get_u16(&h[3]);
    r->value_offset = *offset + (uint32_t)sizeof(h);
    if (size - r->value_offset < r->len)
        return CO_STORE_FAULT_CUT_SHORT;
    *offset = r->value_offset + r->len;
    return CO_STORE_FAULT_NONE;
}

/* A record's place in the table order: index, then sub-index. */
static uint32_t record_key(const image_record_t *r)
{
    return (uint32_t)r->index << 8 | r->subindex;
}

/* The whole image must be as the core writes it before any of it is applied: a header, then one
 * record per entry of the area, in table order, the last one ending at the image's end. A record
 * of another area would be applied by the resets of this one (a reset communication writing a
 * manufacturer parameter); a record twice, or out of order, was not written by the core. Fills
 * *info on success; *fault says where it failed otherwise. */
static co_store_fault_t check_image(const co_storage_t *s, const store_area_t *a,
                                    image_info_t *info, co_store_image_fault_t *fault)
{
    *fault =
        (co_store_image_fault_t){.area = a->area, .area_first = a->first, .area_last = a->last};
    fault->reason = read_header(s, a->area, info);
    uint32_t offset = info->records;
    uint32_t previous = 0; /* below the key of any record of an area: none read yet */
    while (fault->reason == CO_STORE_FAULT_NONE && offset < info->size) {
        image_record_t r = {0};
        fault->offset = offset;
        fault->reason = read_record(s, a->area, info->size, &offset, &r);
        fault->index = r.index;
        fault->subindex = r.subindex;
        if (fault->reason == CO_STORE_FAULT_NONE && (r.index < a->first || r.index > a->last))
            fault->reason = CO_STORE_FAULT_OUTSIDE_AREA;
        else if (fault->reason == CO_STORE_FAULT_NONE && record_key(&r) <= previous)
            fault->reason = CO_STORE_FAULT_ORDER;
        previous = record_key(&r);
    }
    if (fault->reason != CO_STORE_FAULT_NONE)
        info->size = 0;
    return fault->reason;
}

static const store_area_t *find_area(uint8_t area)
{
    for (size_t i = 0; i < AREA_COUNT; i++)
        if (areas[i].area == area)
            return &areas[i];
    return NULL;
}

co_store_fault_t co_store_image_check(const co_storage_t *s, uint8_t area,
                                      co_store_image_fault_t *fault)
{
    const store_area_t *a = find_area(area);
    if (a == NULL) {
        *fault = (co_store_image_fault_t){.reason = CO_STORE_FAULT_AREA, .area = area};
        return fault->reason;
    }
    image_info_t info;
    return check_image(s, a, &info, fault);
}

static void report_refused(co_node_t *node, uint16_t index, uint8_t subindex, const uint8_t *data,
                           size_t len, uint32_t abort)
{
    const co_storage_t *s = node->storage;
    if (s->refused != NULL)
        s->refused(s->ctx, node, index, subindex, data, len, abort);
}

/* The order of the CiA 301 configuration procedures. Some parameters may change only while
 * another one disables what they configure: a PDO's mapping and timing while its COB-ID is
 * invalid (7.5.2.35-38), the EMCY CAN-ID while 1014h is invalid (7.5.2.21), 1019h while 1006h is
 * 0 (7.5.2.41); the mapping entries while the number of entries is 0. So the records apply in
 * phases: the values, then the numbers of mapping entries (checked against the entries), then
 * the enabling parameters (COB-IDs, the SYNC period). */
enum record_phase { PHASE_VALUES, PHASE_MAP_COUNT, PHASE_ENABLE, PHASE_COUNT };

static bool is_cob_id_with_valid_bit(uint16_t index, uint8_t subindex)
{
    bool pdo = subindex == 1 && ((index >= CO_PDO_RPDO_COMM && index < CO_PDO_RPDO_MAP) ||
                                 (index >= CO_PDO_TPDO_COMM && index < CO_PDO_TPDO_MAP));
    return pdo || (index == CO_IDX_EMCY_COB_ID && subindex == 0);
}

static bool is_pdo_map_count(uint16_t index, uint8_t subindex)
{
    return subindex == 0 && ((index >= CO_PDO_RPDO_MAP && index < CO_PDO_TPDO_COMM) ||
                             (index >= CO_PDO_TPDO_MAP && index <= CO_PDO_LAST_INDEX));
}

static enum record_phase record_phase(uint16_t index, uint8_t subindex)
{
    if (is_cob_id_with_valid_bit(index, subindex) || (index == CO_IDX_SYNC_PERIOD && subindex == 0))
        return PHASE_ENABLE;
    if (is_pdo_map_count(index, subindex))
        return PHASE_MAP_COUNT;
    return PHASE_VALUES;
}

/* Opens the procedures of an image: each enabling parameter it holds is set to its disabled form
 * (COB-ID invalid, SYNC period 0, no mapping entry), which the write rules always accept. */
static void open_procedures(co_node_t *node, uint8_t area, const image_info_t *info)
{
    uint32_t offset = info->records;
    image_record_t r;
    while (offset < info->size &&
           read_record(node->storage, area, info->size, &offset, &r) == CO_STORE_FAULT_NONE) {
        const co_od_entry_t *e = co_od_find(node->od, r.index, r.subindex);
        if (e == NULL || !entry_is_stored(e) || record_phase(r.index, r.subindex) == PHASE_VALUES ||
            e->size > sizeof(uint32_t))
            continue;
        uint32_t disabled = 0;
        if (is_cob_id_with_valid_bit(r.index, r.subindex))
            disabled = (uint32_t)co_od_get(node, e) | CO_COB_ID_INVALID;
        uint8_t data[sizeof(uint32_t)];
        co_put_u32(data, disabled);
        co_od_write(node, r.index, r.subindex, data, e->size, CO_OD_ORIGIN_STORE);
    }
}

/* The checks of an entry before a stored value goes through the write path. */
static uint32_t record_entry(const co_node_t *node, const image_record_t *r,
                             const co_od_entry_t **entry)
{
    uint32_t abort = co_od_lookup(node->od, r->index, r->subindex, entry);
    if (abort != CO_SDO_OK)
        return abort;
    if (!entry_is_stored(*entry))
        return CO_SDO_ABORT_DATA_STORE;
    if ((*entry)->size != r->len)
        return CO_SDO_ABORT_TYPE_LENGTH;
    /* A value longer than the stack buffer (a string, a domain: no limits, no service rule) loads
     * in place; one with a hook cannot be checked. */
    if (r->len > CO_CONFIG_STORE_VALUE_MAX && (*entry)->hook != NULL)
        return CO_SDO_ABORT_NO_MEMORY;
    return CO_SDO_OK;
}

/* Loads a value longer than the stack buffer straight into its entry; on a read failure the
 * entry gets its default back, never a part of the stored value. */
static uint32_t load_in_place(co_node_t *node, uint8_t area, const image_record_t *r,
                              const co_od_entry_t *e)
{
    const co_storage_t *s = node->storage;
    if (s->load_read(s->ctx, area, r->value_offset, co_od_bytes(node, e), r->len) == 0)
        return CO_SDO_OK;
    co_od_restore_defaults(node, e->index, e->index);
    return CO_SDO_ABORT_HARDWARE;
}

typedef struct apply_pass {
    unsigned refused; /* values refused */
    bool report;      /* report the refused values */
} apply_pass_t;

/* Applies one stored (or default) value through the same checks and hooks as an SDO write. A
 * value that equals the current one, as read, is already applied and is not written again. */
static void apply_value(co_node_t *node, const co_od_entry_t *e, const uint8_t *value, size_t len,
                        apply_pass_t *pass)
{
    uint32_t abort = entry_is_view(e) ? e->hook->read(node, e) : CO_SDO_OK;
    if (abort == CO_SDO_OK && memcmp(co_od_bytes(node, e), value, len) == 0)
        return;
    if (abort == CO_SDO_OK)
        abort = co_od_write_entry(node, e, value, len, CO_OD_ORIGIN_STORE);
    if (abort == CO_SDO_OK)
        return;
    pass->refused++;
    if (pass->report)
        report_refused(node, e->index, e->subindex, value, len, abort);
}

static void apply_record(co_node_t *node, uint8_t area, const image_record_t *r, apply_pass_t *pass)
{
    const co_storage_t *s = node->storage;
    uint8_t value[CO_CONFIG_STORE_VALUE_MAX];
    const co_od_entry_t *e = NULL;
    uint32_t abort = record_entry(node, r, &e);
    if (abort == CO_SDO_OK && r->len > sizeof(value))
        abort = load_in_place(node, area, r, e);
    else if (abort == CO_SDO_OK && s->load_read(s->ctx, area, r->value_offset, value, r->len) != 0)
        abort = CO_SDO_ABORT_HARDWARE;
    else if (abort == CO_SDO_OK) {
        apply_value(node, e, value, r->len, pass);
        return;
    }
    if (abort == CO_SDO_OK)
        return;
    pass->refused++;
    if (pass->report)
        report_refused(node, r->index, r->subindex, NULL, 0, abort);
}

static void apply_phase(co_node_t *node, uint8_t area, const image_info_t *info,
                        enum record_phase phase, apply_pass_t *pass)
{
    uint32_t offset = info->records;
    image_record_t r;
    while (offset < info->size &&
           read_record(node->storage, area, info->size, &offset, &r) == CO_STORE_FAULT_NONE)
        if (record_phase(r.index, r.subindex) == phase)
            apply_record(node, area, &r, pass);
}

static void apply_pass(co_node_t *node, uint8_t area, const image_info_t *info, apply_pass_t *pass)
{
    for (int phase = 0; phase < PHASE_COUNT; phase++)
        apply_phase(node, area, info, (enum record_phase)phase, pass);
}

/* Applies an image's records in the order of the mapping procedure. A record refused because of
 * another one not applied yet (LSP above the default HSP) is tried again: passes repeat while
 * fewer records are refused; those still refused then are reported and skipped. */
static void apply_values(co_node_t *node, uint8_t area, const image_info_t *info)
{
    open_procedures(node, area, info);
    apply_pass_t pass = {0};
    unsigned before;
    do {
        before = pass.refused;
        pass = (apply_pass_t){0};
        apply_pass(node, area, info, &pass);
    } while (pass.refused > 0 && (before == 0 || pass.refused < before));
    if (pass.refused > 0) {
        pass = (apply_pass_t){.report = true};
        apply_pass(node, area, info, &pass);
    }
}

/* A restored area at its place in the save order: its defaults again (an older image of another
 * area may have changed what its views stand for), and its views' defaults written through their
 * hooks to what they stand for. */
static void apply_area_defaults(co_node_t *node, const store_area_t *a)
{
    apply_pass_t pass = {.report = true};
    const co_od_t *od = node->od;
    co_od_restore_defaults(node, a->first, a->last);
    for (uint16_t i = 0; i < od->count; i++) {
        const co_od_entry_t *e = &od->entries[i];
        if (e->index >= a->first && e->index <= a->last && entry_is_stored(e) && entry_is_view(e))
            apply_value(node, e, od->defaults + e->offset, e->size, &pass);
    }
}

void co_store_apply(co_node_t *node, uint16_t first, uint16_t last)
{
    if (node->storage == NULL)
        return;
    const co_storage_t *s = node->storage;
    image_info_t info[AREA_COUNT] = {0};
    for (size_t i = 0; i < AREA_COUNT; i++) {
        const store_area_t *a = &areas[i];
        co_store_image_fault_t fault;
        if (a->first < first || a->last > last ||
            check_image(s, a, &info[i], &fault) == CO_STORE_FAULT_NONE)
            continue;
        if (s->image_refused != NULL)
            s->image_refused(s->ctx, node, &fault);
    }
    /* Oldest first, so that of two areas covering one value (a view and what it stands for)
     * the later save or restore wins. */
    for (;;) {
        size_t next = AREA_COUNT;
        for (size_t i = 0; i < AREA_COUNT; i++)
            if (info[i].size != 0 && (next == AREA_COUNT || info[i].sequence < info[next].sequence))
                next = i;
        if (next == AREA_COUNT)
            return;
        if (info[next].kind == CO_STORE_IMAGE_DEFAULTS)
            apply_area_defaults(node, &areas[next]);
        else
            apply_values(node, areas[next].area, &info[next]);
        info[next].size = 0;
    }
}
