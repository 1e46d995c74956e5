/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/file_store.h"
#include "co/co_node.h"
#include "co_linux/log.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Larger files are not store files: a node's image is a few hundred bytes. */
#define FILE_SIZE_MAX (16u * 1024u * 1024u)

uint32_t co_crc32(const uint8_t *data, size_t len)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < len; i++) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; bit++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static bool fail(char *reason, size_t reason_len, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static bool fail(char *reason, size_t reason_len, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(reason, reason_len, format, args);
    va_end(args);
    return false;
}

static void free_records(co_file_record_t *records, size_t count)
{
    for (size_t i = 0; i < count; i++)
        free(records[i].data);
    free(records);
}

static int record_order(const co_file_record_t *a, uint8_t node_id, uint8_t area)
{
    if (a->node_id != node_id)
        return a->node_id < node_id ? -1 : 1;
    if (a->area != area)
        return a->area < area ? -1 : 1;
    return 0;
}

/* The header and the CRC, before any record is looked at. *records_len is set on every path. */
static bool check_envelope(const uint8_t *file, size_t size, uint32_t *records_len, char *reason,
                           size_t reason_len)
{
    *records_len = 0;
    size_t minimum = CO_FILE_STORE_HEADER_SIZE + CO_FILE_STORE_CRC_SIZE;
    if (size < minimum)
        return fail(reason, reason_len, "truncated: %zu bytes, a store file has at least %zu", size,
                    minimum);
    if (memcmp(file, CO_FILE_STORE_MAGIC, 4) != 0)
        return fail(reason, reason_len, "wrong magic: not a store file (expected \"%s\")",
                    CO_FILE_STORE_MAGIC);
    uint16_t version = co_get_u16(file + 4);
    if (version != CO_FILE_STORE_VERSION)
        return fail(reason, reason_len, "unsupported format version %u (this build reads %u)",
                    version, CO_FILE_STORE_VERSION);
    *records_len = co_get_u32(file + 8);
    if ((uint64_t)*records_len + minimum != size)
        return fail(reason, reason_len,
                    "%s: the header announces %u bytes of records, the file has %zu",
                    (uint64_t)*records_len + minimum > size ? "truncated" : "length mismatch",
                    *records_len, size - minimum);
    uint32_t stored = co_get_u32(file + size - CO_FILE_STORE_CRC_SIZE);
    uint32_t computed = co_crc32(file, size - CO_FILE_STORE_CRC_SIZE);
    if (stored != computed)
        return fail(reason, reason_len, "bad CRC-32: stored %08X, computed %08X", stored, computed);
    return true;
}

/* Checks every record header; fills records only when all of them are valid. */
static bool check_records(const uint8_t *p, uint32_t len, uint16_t count, co_file_record_t *records,
                          char *reason, size_t reason_len)
{
    uint32_t offset = 0;
    for (uint16_t i = 0; i < count; i++) {
        if (len - offset < CO_FILE_STORE_RECORD_HEADER_SIZE)
            return fail(reason, reason_len, "record %u of %u is cut short", i + 1, count);
        const uint8_t *h = p + offset;
        co_file_record_t r = {.node_id = h[0], .area = h[1], .len = co_get_u32(h + 4)};
        offset += CO_FILE_STORE_RECORD_HEADER_SIZE;
        bool id_valid = r.area == CO_FILE_STORE_AREA_DEVICENET
                            ? r.node_id <= CO_FILE_STORE_MAC_ID_MAX
                            : r.node_id != 0 && r.node_id != CO_FILE_STORE_UNCONFIGURED_KEY;
        if (!id_valid || r.area == 0 || co_get_u16(h + 2) != 0)
            return fail(reason, reason_len,
                        "record %u: node-id %u, area %u or reserved bytes are invalid", i + 1,
                        r.node_id, r.area);
        if (i > 0 && record_order(&records[i - 1], r.node_id, r.area) >= 0)
            return fail(reason, reason_len, "record %u (node %u, area %u) is out of order", i + 1,
                        r.node_id, r.area);
        if (r.len > len - offset)
            return fail(reason, reason_len, "record %u: %u bytes announced, %u left", i + 1, r.len,
                        len - offset);
        r.data = (uint8_t *)(p + offset); /* borrowed until copied */
        records[i] = r;
        offset += r.len;
    }
    if (offset != len)
        return fail(reason, reason_len, "%u bytes follow the last of %u records", len - offset,
                    count);
    return true;
}

/* What co_store_image_check found, in words. */
static void describe_image_fault(const co_store_image_fault_t *f, char *text, size_t len)
{
    switch (f->reason) {
    case CO_STORE_FAULT_NONE:
        snprintf(text, len, "no fault");
        break;
    case CO_STORE_FAULT_AREA:
        snprintf(text, len, "not a storage area (2, 3 or 4)");
        break;
    case CO_STORE_FAULT_UNREADABLE:
        snprintf(text, len, "unreadable at byte %u", (unsigned)f->offset);
        break;
    case CO_STORE_FAULT_HEADER:
        snprintf(text, len, "not an image of parameters (header \"COS\" version 1 or 2)");
        break;
    case CO_STORE_FAULT_CUT_SHORT:
        snprintf(text, len, "the record at byte %u runs past the end of the image",
                 (unsigned)f->offset);
        break;
    case CO_STORE_FAULT_OUTSIDE_AREA:
        snprintf(text, len, "record %04Xh:%02X at byte %u lies outside the area (%04Xh..%04Xh)",
                 f->index, f->subindex, (unsigned)f->offset, f->area_first, f->area_last);
        break;
    case CO_STORE_FAULT_ORDER:
        snprintf(text, len,
                 "record %04Xh:%02X at byte %u does not follow the one before it (a duplicate, "
                 "or out of order)",
                 f->index, f->subindex, (unsigned)f->offset);
        break;
    }
}

/* A DeviceNet record: its length and its Quick Connect flag (the assemblies are the node's to
 * check: an unknown one falls back to its default). */
static bool check_devicenet(const co_file_record_t *r, char *reason, size_t reason_len)
{
    if (r->len != CO_FILE_STORE_DEVICENET_SIZE)
        return fail(reason, reason_len, "MAC ID %u (DeviceNet): %u bytes, its record has %u",
                    r->node_id, r->len, CO_FILE_STORE_DEVICENET_SIZE);
    if (r->data[4] > 1)
        return fail(reason, reason_len, "MAC ID %u (DeviceNet): Quick Connect %u is not 0 or 1",
                    r->node_id, r->data[4]);
    return true;
}

/* An LSS record: its length, a node-id CiA 305 can configure, an index of bit timing table 0. */
static bool check_lss(const co_file_record_t *r, char *reason, size_t reason_len)
{
    if (r->len != CO_FILE_STORE_LSS_SIZE)
        return fail(reason, reason_len, "node %u (LSS): %u bytes, its record has %u", r->node_id,
                    r->len, CO_FILE_STORE_LSS_SIZE);
    uint8_t id = r->data[0];
    if (!((id >= 1 && id <= CO_NODE_ID_MAX) || id == CO_LSS_NODE_ID_UNCONFIGURED) ||
        r->data[1] > CO_LSS_BIT_TIMING_INDEX_MAX)
        return fail(reason, reason_len, "node %u (LSS): node-id %u or bit timing %u is invalid",
                    r->node_id, id, r->data[1]);
    return true;
}

/* Every image as the core checks it before applying it: a file that holds one the core would
 * refuse is ignored whole, as for a bad CRC, rather than applied in part. */
static bool check_images(co_file_record_t *records, size_t count, char *reason, size_t reason_len)
{
    co_file_store_t parsed = {.records = records, .count = count};
    for (size_t i = 0; i < count; i++) {
        if (records[i].area == CO_FILE_STORE_AREA_DEVICENET) {
            if (!check_devicenet(&records[i], reason, reason_len))
                return false;
            continue;
        }
        if (records[i].area == CO_FILE_STORE_AREA_LSS) {
            if (!check_lss(&records[i], reason, reason_len))
                return false;
            continue;
        }
        co_file_store_node_t node;
        co_storage_t storage;
        co_store_image_fault_t fault;
        co_file_store_bind(&parsed, records[i].node_id, &node, &storage);
        co_store_fault_t found = co_store_image_check(&storage, records[i].area, &fault);
        co_file_store_unbind(&node);
        if (found != CO_STORE_FAULT_NONE) {
            char text[128];
            describe_image_fault(&fault, text, sizeof text);
            return fail(reason, reason_len, "node %u area %u: %s", records[i].node_id,
                        records[i].area, text);
        }
    }
    return true;
}

bool co_file_store_parse(const uint8_t *file, size_t size, co_file_record_t **records,
                         size_t *count, char *reason, size_t reason_len)
{
    uint32_t records_len;
    if (!check_envelope(file, size, &records_len, reason, reason_len))
        return false;
    uint16_t n = co_get_u16(file + 6);
    co_file_record_t *parsed = calloc(n ? n : 1, sizeof *parsed);
    if (!parsed)
        return fail(reason, reason_len, "out of memory");
    if (!check_records(file + CO_FILE_STORE_HEADER_SIZE, records_len, n, parsed, reason,
                       reason_len) ||
        !check_images(parsed, n, reason, reason_len)) {
        free(parsed);
        return false;
    }
    for (uint16_t i = 0; i < n; i++) {
        uint8_t *copy = malloc(parsed[i].len ? parsed[i].len : 1);
        if (!copy) {
            for (uint16_t j = 0; j < i; j++)
                free(parsed[j].data);
            free(parsed);
            return fail(reason, reason_len, "out of memory");
        }
        memcpy(copy, parsed[i].data, parsed[i].len);
        parsed[i].data = copy;
    }
    *records = parsed;
    *count = n;
    return true;
}

/* *content (NULL on failure, the caller frees it otherwise) and *size are set on every path. */
static bool read_whole_file(int fd, uint8_t **content, size_t *size, char *reason,
                            size_t reason_len)
{
    *content = NULL;
    *size = 0;
    struct stat st;
    if (fstat(fd, &st) != 0)
        return fail(reason, reason_len, "fstat: %s", strerror(errno));
    if (st.st_size > (off_t)FILE_SIZE_MAX)
        return fail(reason, reason_len, "%lld bytes is too large for a store file",
                    (long long)st.st_size);
    *content = malloc((size_t)st.st_size + 1);
    if (!*content)
        return fail(reason, reason_len, "out of memory");
    size_t done = 0;
    while (done < (size_t)st.st_size) {
        ssize_t n = read(fd, *content + done, (size_t)st.st_size - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        done += (size_t)n;
    }
    *size = done;
    if (done != (size_t)st.st_size && errno) {
        free(*content);
        *content = NULL;
        return fail(reason, reason_len, "read: %s", strerror(errno));
    }
    return true;
}

co_file_store_status_t co_file_store_open(co_file_store_t *store, const char *path)
{
    memset(store, 0, sizeof *store);
    store->path = strdup(path);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT)
            return CO_FILE_STORE_MISSING;
        snprintf(store->reason, sizeof store->reason, "open: %s", strerror(errno));
        return CO_FILE_STORE_ERROR;
    }
    uint8_t *content;
    size_t size;
    errno = 0;
    bool read_ok = read_whole_file(fd, &content, &size, store->reason, sizeof store->reason);
    close(fd);
    if (!read_ok)
        return CO_FILE_STORE_ERROR;
    bool valid = co_file_store_parse(content, size, &store->records, &store->count, store->reason,
                                     sizeof store->reason);
    free(content);
    if (!valid) {
        store->damaged = true;
        return CO_FILE_STORE_IGNORED;
    }
    return CO_FILE_STORE_LOADED;
}

void co_file_store_close(co_file_store_t *store)
{
    free_records(store->records, store->count);
    free(store->path);
    memset(store, 0, sizeof *store);
}

const co_file_record_t *co_file_store_find(const co_file_store_t *store, uint8_t node_id,
                                           uint8_t area)
{
    for (size_t i = 0; i < store->count; i++) {
        if (record_order(&store->records[i], node_id, area) == 0)
            return &store->records[i];
    }
    return NULL;
}

static uint8_t *serialize(const co_file_record_t *records, size_t count, size_t *size)
{
    size_t records_len = 0;
    for (size_t i = 0; i < count; i++)
        records_len += CO_FILE_STORE_RECORD_HEADER_SIZE + records[i].len;
    *size = CO_FILE_STORE_HEADER_SIZE + records_len + CO_FILE_STORE_CRC_SIZE;
    uint8_t *file = malloc(*size);
    if (!file)
        return NULL;
    memcpy(file, CO_FILE_STORE_MAGIC, 4);
    co_put_u16(file + 4, CO_FILE_STORE_VERSION);
    co_put_u16(file + 6, (uint16_t)count);
    co_put_u32(file + 8, (uint32_t)records_len);
    uint8_t *p = file + CO_FILE_STORE_HEADER_SIZE;
    for (size_t i = 0; i < count; i++) {
        p[0] = records[i].node_id;
        p[1] = records[i].area;
        co_put_u16(p + 2, 0);
        co_put_u32(p + 4, records[i].len);
        memcpy(p + CO_FILE_STORE_RECORD_HEADER_SIZE, records[i].data, records[i].len);
        p += CO_FILE_STORE_RECORD_HEADER_SIZE + records[i].len;
    }
    co_put_u32(p, co_crc32(file, (size_t)(p - file)));
    return file;
}

static int write_all(int fd, const uint8_t *data, size_t len)
{
    while (len) {
        ssize_t n = write(fd, data, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return -1;
        data += n;
        len -= (size_t)n;
    }
    return 0;
}

/* The rename is only durable once the directory entry is on disk too. */
static int sync_directory(const char *path)
{
    char dir[PATH_MAX];
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

static int replace_file(co_file_store_t *store, const uint8_t *content, size_t size)
{
    char tmp[PATH_MAX];
    if (snprintf(tmp, sizeof tmp, "%s.XXXXXX", store->path) >= (int)sizeof tmp) {
        fail(store->reason, sizeof store->reason, "path too long");
        return -1;
    }
    int fd = mkostemp(tmp, O_CLOEXEC);
    if (fd < 0) {
        fail(store->reason, sizeof store->reason, "cannot create %s: %s", tmp, strerror(errno));
        return -1;
    }
    const char *step = NULL;
    if (write_all(fd, content, size) != 0)
        step = "write";
    else if (fchmod(fd, 0644) != 0)
        step = "fchmod";
    else if (fsync(fd) != 0)
        step = "fsync";
    int saved = errno;
    if (close(fd) != 0 && !step) {
        step = "close";
        saved = errno;
    }
    if (!step && store->damaged) {
        char bad[PATH_MAX];
        snprintf(bad, sizeof bad, "%s.bad", store->path);
        if (rename(store->path, bad) == 0)
            co_log(CO_LOG_WARN, "store %s: the damaged file is kept as %s", store->path, bad);
    }
    if (!step && rename(tmp, store->path) != 0) {
        step = "rename";
        saved = errno;
    }
    if (step) {
        unlink(tmp);
        fail(store->reason, sizeof store->reason, "%s of %s: %s", step, tmp, strerror(saved));
        return -1;
    }
    if (sync_directory(store->path) != 0)
        co_log(CO_LOG_WARN, "store %s: fsync of its directory: %s", store->path, strerror(errno));
    store->damaged = false;
    return 0;
}

/* The record set with one change applied (data NULL: the record removed), sharing the other
 * records' data. */
static co_file_record_t *changed_records(const co_file_record_t *in, size_t in_count,
                                         const co_file_record_t *change, size_t *count)
{
    co_file_record_t *out = calloc(in_count + 1, sizeof *out);
    if (!out)
        return NULL;
    size_t n = 0;
    bool placed = change->data == NULL;
    for (size_t i = 0; i < in_count; i++) {
        int order = record_order(&in[i], change->node_id, change->area);
        if (!placed && order > 0) {
            out[n++] = *change;
            placed = true;
        }
        if (order != 0)
            out[n++] = in[i];
    }
    if (!placed)
        out[n++] = *change;
    *count = n;
    return out;
}

int co_file_store_update_many(co_file_store_t *store, const co_file_record_t *changes, size_t n)
{
    size_t count = store->count, size = 0;
    co_file_record_t *records = NULL;
    bool ok = true;
    for (size_t i = 0; i < n && ok; i++) {
        co_file_record_t *next =
            changed_records(records ? records : store->records, count, &changes[i], &count);
        free(records); /* the previous step's array only: the data is shared */
        records = next;
        ok = next != NULL;
    }
    uint8_t *content = ok && records ? serialize(records, count, &size) : NULL;
    int rc = -1;
    if (n == 0)
        rc = 0;
    else if (!content)
        fail(store->reason, sizeof store->reason, "out of memory");
    else
        rc = replace_file(store, content, size);
    free(content);
    if (rc != 0 || n == 0) {
        if (rc != 0) {
            char areas[32] = "";
            for (size_t i = 0, used = 0; i < n && used < sizeof areas; i++)
                used += (size_t)snprintf(areas + used, sizeof areas - used, "%s%u", i ? ", " : "",
                                         changes[i].area);
            co_log(CO_LOG_ERROR, "store %s: node %u area%s %s not saved: %s", store->path,
                   n ? changes[0].node_id : 0, n > 1 ? "s" : "", areas, store->reason);
        }
        free(records);
        for (size_t i = 0; i < n; i++)
            free(changes[i].data);
        return rc;
    }
    for (size_t i = 0; i < n; i++) {
        const co_file_record_t *old =
            co_file_store_find(store, changes[i].node_id, changes[i].area);
        if (old)
            free(old->data);
    }
    free(store->records);
    store->records = records;
    store->count = count;
    return 0;
}

int co_file_store_update(co_file_store_t *store, uint8_t node_id, uint8_t area, uint8_t *data,
                         uint32_t len)
{
    co_file_record_t change = {node_id, area, len, data};
    return co_file_store_update_many(store, &change, 1);
}

bool co_file_store_get_devicenet(const co_file_store_t *store, uint8_t mac_id,
                                 co_file_devicenet_t *values)
{
    const co_file_record_t *r = co_file_store_find(store, mac_id, CO_FILE_STORE_AREA_DEVICENET);
    if (!r)
        return false;
    *values = (co_file_devicenet_t){.consumed_assembly = co_get_u16(r->data),
                                    .produced_assembly = co_get_u16(r->data + 2),
                                    .quick_connect = r->data[4] != 0};
    return true;
}

int co_file_store_set_devicenet(co_file_store_t *store, uint8_t mac_id,
                                const co_file_devicenet_t *values)
{
    uint8_t *data = malloc(CO_FILE_STORE_DEVICENET_SIZE);
    if (!data) {
        snprintf(store->reason, sizeof store->reason, "out of memory");
        return -1;
    }
    co_put_u16(data, values->consumed_assembly);
    co_put_u16(data + 2, values->produced_assembly);
    data[4] = values->quick_connect ? 1u : 0u;
    return co_file_store_update(store, mac_id, CO_FILE_STORE_AREA_DEVICENET, data,
                                CO_FILE_STORE_DEVICENET_SIZE);
}

bool co_file_store_get_lss(const co_file_store_t *store, uint8_t key, uint8_t *node_id,
                           uint8_t *bit_timing)
{
    const co_file_record_t *r = co_file_store_find(store, key, CO_FILE_STORE_AREA_LSS);
    if (!r)
        return false;
    *node_id = r->data[0];
    *bit_timing = r->data[1];
    return true;
}

int co_file_store_set_lss(co_file_store_t *store, uint8_t key, uint8_t node_id, uint8_t bit_timing)
{
    uint8_t *data = malloc(CO_FILE_STORE_LSS_SIZE);
    if (!data) {
        snprintf(store->reason, sizeof store->reason, "out of memory");
        return -1;
    }
    data[0] = node_id;
    data[1] = bit_timing;
    return co_file_store_update(store, key, CO_FILE_STORE_AREA_LSS, data, CO_FILE_STORE_LSS_SIZE);
}

/* A change of the node's area: written at once, or staged while a group is open. */
static int node_change(co_file_store_node_t *node, uint8_t area, uint8_t *data, uint32_t len)
{
    if (!node->grouping)
        return co_file_store_update(node->store, node->node_id, area, data, len);
    if (node->staged_count == sizeof node->staged / sizeof node->staged[0]) {
        free(data);
        return -1;
    }
    node->staged[node->staged_count++] = (co_file_record_t){node->node_id, area, len, data};
    return 0;
}

static int node_group_begin(void *ctx)
{
    co_file_store_node_t *node = ctx;
    node->grouping = true;
    node->staged_count = 0;
    return 0;
}

/* Every area of one 1010h / 1011h write in one file replacement: all or nothing. */
static int node_group_end(void *ctx, bool commit)
{
    co_file_store_node_t *node = ctx;
    size_t n = node->staged_count;
    node->grouping = false;
    node->staged_count = 0;
    if (commit)
        return co_file_store_update_many(node->store, node->staged, n);
    for (size_t i = 0; i < n; i++)
        free(node->staged[i].data);
    return 0;
}

static int node_save_begin(void *ctx, uint8_t area)
{
    co_file_store_node_t *node = ctx;
    node->saving_area = area;
    node->image_len = 0;
    return 0;
}

static int node_save_write(void *ctx, const uint8_t *data, size_t len)
{
    co_file_store_node_t *node = ctx;
    if (!node->saving_area || len > UINT32_MAX - node->image_len)
        return -1;
    if (node->image_len + len > node->image_cap) {
        size_t cap = node->image_cap ? node->image_cap : 256;
        while (cap < node->image_len + len)
            cap *= 2;
        uint8_t *grown = realloc(node->image, cap);
        if (!grown)
            return -1;
        node->image = grown;
        node->image_cap = cap;
    }
    memcpy(node->image + node->image_len, data, len);
    node->image_len += len;
    return 0;
}

static int node_save_end(void *ctx, bool commit)
{
    co_file_store_node_t *node = ctx;
    uint8_t area = node->saving_area;
    node->saving_area = 0;
    if (!commit || !area)
        return commit ? -1 : 0;
    uint8_t *image = malloc(node->image_len ? node->image_len : 1);
    if (!image)
        return -1;
    memcpy(image, node->image, node->image_len);
    return node_change(node, area, image, (uint32_t)node->image_len);
}

static long node_load_size(void *ctx, uint8_t area)
{
    co_file_store_node_t *node = ctx;
    const co_file_record_t *r = co_file_store_find(node->store, node->node_id, area);
    if (r)
        return (long)r->len;
    /* Whatever the ignored file held for this area is lost: say so rather than "none". */
    return node->store->damaged ? -1 : 0;
}

static int node_load_read(void *ctx, uint8_t area, uint32_t offset, uint8_t *buf, size_t len)
{
    co_file_store_node_t *node = ctx;
    const co_file_record_t *r = co_file_store_find(node->store, node->node_id, area);
    if (!r || offset > r->len || len > r->len - offset)
        return -1;
    memcpy(buf, r->data + offset, len);
    return 0;
}

static int node_erase(void *ctx, uint8_t area)
{
    co_file_store_node_t *node = ctx;
    if (!co_file_store_find(node->store, node->node_id, area) && !node->store->damaged)
        return 0;
    return node_change(node, area, NULL, 0);
}

/* A stored value the node refused while applying its image: logged by name, with the value and
 * the reason; the entry keeps its value (the default, at a reset). */
static void node_refused(void *ctx, const co_node_t *node, uint16_t index, uint8_t subindex,
                         const uint8_t *value, size_t len, uint32_t abort)
{
    const co_file_store_node_t *n = ctx;
    const char *name = co_od_name(node->od, index, subindex);
    char shown[2 * CO_CONFIG_STORE_VALUE_MAX + 8] = "unreadable";
    if (value != NULL && len > 0) {
        size_t max = len <= CO_CONFIG_STORE_VALUE_MAX ? len : CO_CONFIG_STORE_VALUE_MAX;
        /* Little-endian bytes shown most significant first, as the value reads. */
        size_t at = (size_t)snprintf(shown, sizeof shown, "0x");
        for (size_t i = max; i-- > 0;)
            at += (size_t)snprintf(shown + at, sizeof shown - at, "%02X", value[i]);
    }
    co_log(CO_LOG_WARN,
           "store %s: node %u: stored %04Xh:%02X%s%s%s = %s refused (SDO abort 0x%08X: %s); "
           "skipped, it keeps its default",
           n->store->path, n->node_id, index, subindex, name ? " (" : "", name ? name : "",
           name ? ")" : "", shown, (unsigned)abort, co_sdo_abort_text(abort));
}

void co_file_store_bind(co_file_store_t *store, uint8_t node_id, co_file_store_node_t *node,
                        co_storage_t *storage)
{
    memset(node, 0, sizeof *node);
    node->store = store;
    node->node_id = node_id;
    *storage = (co_storage_t){
        .ctx = node,
        .save_begin = node_save_begin,
        .save_write = node_save_write,
        .save_end = node_save_end,
        .load_size = node_load_size,
        .load_read = node_load_read,
        .erase = node_erase,
        .refused = node_refused,
        .group_begin = node_group_begin,
        .group_end = node_group_end,
    };
}

void co_file_store_unbind(co_file_store_node_t *node)
{
    for (size_t i = 0; i < node->staged_count; i++)
        free(node->staged[i].data);
    node->staged_count = 0;
    free(node->image);
    node->image = NULL;
    node->image_cap = node->image_len = 0;
}
