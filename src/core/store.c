/* Store and restore parameters: 1010h / 1011h (CiA 301 sections 7.5.2.13-14) and the
 * self-describing images described in co_store.h, streamed without a buffer. */
#include "co/co_node.h"

#define STORE_GROUP_ALL 1u
#define STORE_GROUP_LAST 4u
#define IMAGE_VERSION 1u

typedef struct store_area {
    uint8_t area;
    uint16_t first;
    uint16_t last;
} store_area_t;

static const store_area_t areas[] = {
    {CO_STORE_AREA_COMMUNICATION, 0x1000, 0x1FFF},
    {CO_STORE_AREA_MANUFACTURER, 0x2000, 0x5FFF},
    {CO_STORE_AREA_PROFILE, 0x6000, 0x9FFF},
};

#define AREA_COUNT (sizeof(areas) / sizeof(areas[0]))

static const uint8_t image_header[CO_STORE_IMAGE_HEADER_SIZE] = {'C', 'O', 'S', IMAGE_VERSION};

/* Group 1 is every area; groups 2..4 are one area each. */
static bool group_has_area(uint8_t group, const store_area_t *a)
{
    return group == STORE_GROUP_ALL || group == a->area;
}

/* The error history and the store/restore commands are not parameters. */
static bool entry_is_stored(const co_od_entry_t *e)
{
    return (e->flags & CO_OD_WRITE) && e->index != 0x1003 && e->index != 0x1010 &&
           e->index != 0x1011;
}

static int save_area(co_node_t *node, const store_area_t *a)
{
    const co_storage_t *s = node->storage;
    if (s->save_begin(s->ctx, a->area) != 0)
        return -1;
    int rc = s->save_write(s->ctx, image_header, sizeof(image_header));
    for (uint16_t i = 0; rc == 0 && i < node->od->count; i++) {
        const co_od_entry_t *e = &node->od->entries[i];
        if (e->index < a->first || e->index > a->last || !entry_is_stored(e))
            continue;
        uint8_t record[CO_STORE_RECORD_HEADER_SIZE];
        co_put_u16(&record[0], e->index);
        record[2] = e->subindex;
        co_put_u16(&record[3], e->size);
        rc = s->save_write(s->ctx, record, sizeof(record));
        if (rc == 0)
            rc = s->save_write(s->ctx, co_od_bytes(node, e), e->size);
    }
    if (s->save_end(s->ctx, rc == 0) != 0)
        return -1;
    return rc;
}

static uint32_t save_group(co_node_t *node, uint8_t group)
{
    for (size_t i = 0; i < AREA_COUNT; i++)
        if (group_has_area(group, &areas[i]) && save_area(node, &areas[i]) != 0)
            return SDO_ABORT_HARDWARE;
    return CO_SDO_OK;
}

static uint32_t erase_group(co_node_t *node, uint8_t group)
{
    const co_storage_t *s = node->storage;
    for (size_t i = 0; i < AREA_COUNT; i++)
        if (group_has_area(group, &areas[i]) && s->erase(s->ctx, areas[i].area) != 0)
            return SDO_ABORT_HARDWARE;
    return CO_SDO_OK;
}

/* CiA 301 1010h / 1011h: only the "save" / "load" signature is accepted (0x08000020 otherwise,
 * and when there is nowhere to store); the stored value stays 1, so the write is handled here. */
uint32_t co_store_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len)
{
    (void)len;
    if (entry->subindex == 0)
        return CO_SDO_OK;
    bool save = entry->index == 0x1010;
    uint32_t signature = save ? CO_STORE_SIGNATURE_SAVE : CO_STORE_SIGNATURE_LOAD;
    if (co_get_u32(data) != signature || node->storage == NULL ||
        entry->subindex > STORE_GROUP_LAST)
        return SDO_ABORT_DATA_STORE;
    uint32_t abort = save ? save_group(node, entry->subindex) : erase_group(node, entry->subindex);
    return abort != CO_SDO_OK ? abort : CO_OD_HANDLED;
}

typedef struct image_record {
    uint16_t index;
    uint8_t subindex;
    uint16_t len;
    uint32_t value_offset;
} image_record_t;

/* Reads the record header at *offset; false when it does not lie inside the image. */
static bool read_record(const co_storage_t *s, uint8_t area, uint32_t size, uint32_t *offset,
                        image_record_t *r)
{
    uint8_t h[CO_STORE_RECORD_HEADER_SIZE];
    if (size - *offset < sizeof(h) || s->load_read(s->ctx, area, *offset, h, sizeof(h)) != 0)
        return false;
    r->index = co_get_u16(&h[0]);
    r->subindex = h[2];
    r->len = co_get_u16(&h[3]);
    r->value_offset = *offset + (uint32_t)sizeof(h);
    if (size - r->value_offset < r->len)
        return false;
    *offset = r->value_offset + r->len;
    return true;
}

/* The whole image must be well formed before any of it is applied. */
static bool image_is_valid(const co_storage_t *s, uint8_t area, uint32_t size)
{
    uint8_t header[CO_STORE_IMAGE_HEADER_SIZE];
    if (size < sizeof(header) || s->load_read(s->ctx, area, 0, header, sizeof(header)) != 0)
        return false;
    for (size_t i = 0; i < sizeof(header); i++)
        if (header[i] != image_header[i])
            return false;
    uint32_t offset = sizeof(header);
    image_record_t r;
    while (offset < size)
        if (!read_record(s, area, size, &offset, &r))
            return false;
    return true;
}

static const co_od_entry_t *record_target(const co_node_t *node, const image_record_t *r,
                                          uint16_t first, uint16_t last)
{
    if (r->index < first || r->index > last)
        return NULL;
    const co_od_entry_t *e = co_od_find(node->od, r->index, r->subindex);
    if (e == NULL || !entry_is_stored(e) || e->size != r->len)
        return NULL;
    return e;
}

static void apply_area(co_node_t *node, const store_area_t *a, uint16_t first, uint16_t last)
{
    const co_storage_t *s = node->storage;
    long size = s->load_size(s->ctx, a->area);
    if (size <= 0 || (unsigned long)size > UINT32_MAX ||
        !image_is_valid(s, a->area, (uint32_t)size))
        return;
    uint32_t offset = CO_STORE_IMAGE_HEADER_SIZE;
    image_record_t r;
    while (offset < (uint32_t)size) {
        bool read = read_record(s, a->area, (uint32_t)size, &offset, &r);
        const co_od_entry_t *e = read ? record_target(node, &r, first, last) : NULL;
        if (!read || (e != NULL && s->load_read(s->ctx, a->area, r.value_offset,
                                                co_od_bytes(node, e), r.len) != 0)) {
            /* The image read fine a moment ago: undo the part applied, never keep half. */
            co_od_restore_defaults(node, first, last);
            return;
        }
    }
}

void co_store_apply(co_node_t *node, uint16_t first, uint16_t last)
{
    if (node->storage == NULL)
        return;
    for (size_t i = 0; i < AREA_COUNT; i++) {
        const store_area_t *a = &areas[i];
        if (a->last < first || a->first > last)
            continue;
        uint16_t from = a->first > first ? a->first : first;
        uint16_t to = a->last < last ? a->last : last;
        apply_area(node, a, from, to);
    }
}
