/* SPDX-License-Identifier: Apache-2.0 */
/* The --store file opened at start (storage.h). */
#include "atv312d/storage.h"

#include "co/co_store.h"
#include "co_linux/log.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

/* A store that can never be saved is a mistake better reported at start than at the first 1010h
 * write: the directory must exist and be writable. */
static int check_store_directory(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    if (access(dir, W_OK | X_OK) == 0)
        return 0;
    co_log(CO_LOG_ERROR,
           "store %s: its directory %s is not usable (%s): create it or give a writable --store "
           "path",
           path, dir, strerror(errno));
    return EX_CANTCREAT;
}

/* One line per node of a loaded store: which save wrote each image, so that after a crash the log
 * says whether the old or the new parameters came back. "area 2 save 7, area 3 save 8 (defaults)"
 * (co_store.h: the sequence and kind of each image header; "format 1" images have neither). */
static void log_store_images(const char *path, const co_file_store_t *store)
{
    for (size_t i = 0; i < store->count;) {
        uint8_t node_id = store->records[i].node_id;
        char line[512];
        size_t used = 0;
        for (; i < store->count && store->records[i].node_id == node_id; i++) {
            const co_file_record_t *r = &store->records[i];
            const char *sep = used ? ", " : "";
            if (used >= sizeof line || r->area == CO_FILE_STORE_AREA_DEVICENET)
                continue;
            if (r->len >= CO_STORE_IMAGE_HEADER_SIZE && memcmp(r->data, "COS\x02", 4) == 0)
                used +=
                    (size_t)snprintf(line + used, sizeof line - used, "%sarea %u save %lu%s", sep,
                                     r->area, (unsigned long)co_get_u32(r->data + 4),
                                     r->data[8] == CO_STORE_IMAGE_DEFAULTS ? " (defaults)" : "");
            else
                used += (size_t)snprintf(
                    line + used, sizeof line - used, "%sarea %u %s", sep, r->area,
                    r->len >= 4 && memcmp(r->data, "COS\x01", 4) == 0 ? "format 1"
                                                                      : "unknown format");
        }
        if (used)
            co_log(CO_LOG_INFO, "store %s: node %u: %s", path, node_id, line);
    }
    for (uint8_t mac_id = 0; mac_id <= CO_FILE_STORE_MAC_ID_MAX; mac_id++) {
        co_file_devicenet_t dn;
        if (!co_file_store_get_devicenet(store, mac_id, &dn))
            continue;
        char consumed[8] = "default", produced[8] = "default";
        if (dn.consumed_assembly)
            snprintf(consumed, sizeof consumed, "%u", dn.consumed_assembly);
        if (dn.produced_assembly)
            snprintf(produced, sizeof produced, "%u", dn.produced_assembly);
        co_log(CO_LOG_INFO,
               "store %s: MAC ID %u: consumed assembly %s, produced assembly %s, Quick Connect %s",
               path, mac_id, consumed, produced, dn.quick_connect ? "on" : "off");
    }
}

int atv312d_storage_open(const char *path, co_file_store_t *store)
{
    int rc = check_store_directory(path);
    if (rc != 0)
        return rc;
    switch (co_file_store_open(store, path)) {
    case CO_FILE_STORE_LOADED:
        co_log(CO_LOG_INFO, "store %s: %zu stored image(s) loaded", path, store->count);
        log_store_images(path, store);
        return 0;
    case CO_FILE_STORE_MISSING:
        co_log(CO_LOG_INFO, "store %s: no file yet, defaults apply until a save (1010h)", path);
        return 0;
    case CO_FILE_STORE_IGNORED:
        co_log(CO_LOG_WARN, "store %s: ignored, defaults apply: %s", path, store->reason);
        return 0;
    case CO_FILE_STORE_ERROR:
        break;
    }
    co_log(CO_LOG_ERROR, "store %s: cannot be read: %s", path, store->reason);
    co_file_store_close(store);
    return EX_NOINPUT;
}
