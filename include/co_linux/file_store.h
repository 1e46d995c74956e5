/* SPDX-License-Identifier: Apache-2.0 */
/* The storage file behind `--store FILE`: the stored images of every node of the process, one
 * record per (node-id, area), in one file that is replaced atomically (temporary file in the same
 * directory, fsync, rename, fsync of the directory) and verified completely (magic, version,
 * length, CRC-32, every record, every image as the core checks it: co_store_image_check) before
 * anything in it is used. A file that fails a check is
 * reported with the reason and ignored as a whole; at the next save it is kept as FILE.bad and
 * replaced. Format: docs/atv312d.md, "Storage file". */
#ifndef CO_LINUX_FILE_STORE_H
#define CO_LINUX_FILE_STORE_H

#include "co/co_store.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define CO_FILE_STORE_MAGIC "CoSF"
#define CO_FILE_STORE_VERSION 1u
#define CO_FILE_STORE_HEADER_SIZE 12u       /* magic, version, record count, records length */
#define CO_FILE_STORE_RECORD_HEADER_SIZE 8u /* node-id, area, reserved u16, length u32 */
#define CO_FILE_STORE_CRC_SIZE 4u

/* A DeviceNet drive's record (atv312d --devicenet): not an image of 1010h's areas but the
 * DeviceNet node's stored values, keyed by MAC ID (0..63) in the node-id field with this area,
 * which no 1010h sub-index has. Its data: consumed assembly (u16, Connection class attribute
 * 100), produced assembly (u16, attribute 101), Quick Connect (u8, 0 or 1, DeviceNet attribute
 * 10); an assembly 0 is the device's default. */
#define CO_FILE_STORE_AREA_DEVICENET 0x80u
#define CO_FILE_STORE_DEVICENET_SIZE 5u
#define CO_FILE_STORE_MAC_ID_MAX 63u

/* A node's LSS configuration (CiA 305 store configuration, docs/lss.md): the node-id (1..127,
 * or FFh: none) and the bit timing index of table 0 it starts with, in its own area. */
#define CO_FILE_STORE_AREA_LSS 0x81u
#define CO_FILE_STORE_LSS_SIZE 2u
/* The key of the records of atv312d's k-th node started without node-id (--unconfigured, k =
 * 1..127): this plus k, since such a node has no node-id to be keyed by and keeps its records
 * across the node-ids LSS gives it. Keys 1..127 are node-ids. */
#define CO_FILE_STORE_UNCONFIGURED_KEY 0x80u

typedef struct co_file_devicenet {
    uint16_t consumed_assembly;
    uint16_t produced_assembly;
    bool quick_connect;
} co_file_devicenet_t;

typedef struct co_file_record {
    uint8_t node_id;
    uint8_t area;
    uint32_t len;
    uint8_t *data;
} co_file_record_t;

typedef struct co_file_store {
    char *path;
    co_file_record_t *records; /* sorted by node-id, then area */
    size_t count;
    bool damaged;     /* the file on disk failed a check and was ignored */
    char reason[160]; /* why it was ignored, or why the last operation failed */
} co_file_store_t;

/* Per-node view of the store, the ctx of that node's co_storage_t. */
typedef struct co_file_store_node {
    co_file_store_t *store;
    uint8_t node_id;
    uint8_t saving_area; /* 0 when no save is in progress */
    uint8_t *image;      /* the image being written */
    size_t image_len, image_cap;
    bool grouping;              /* between group_begin and group_end (co_store.h) */
    co_file_record_t staged[3]; /* the areas saved or erased in the group, written at its end */
    size_t staged_count;
} co_file_store_node_t;

typedef enum co_file_store_status {
    CO_FILE_STORE_LOADED,  /* the file was read and verified (it may hold no record) */
    CO_FILE_STORE_MISSING, /* no file yet: the first save creates it */
    CO_FILE_STORE_IGNORED, /* the file failed a check: reason says which; nothing was loaded */
    CO_FILE_STORE_ERROR    /* it could not be read (errno and reason say why) */
} co_file_store_status_t;

/* Reads and verifies the file. Nothing of a file that fails is kept. */
co_file_store_status_t co_file_store_open(co_file_store_t *store, const char *path);

void co_file_store_close(co_file_store_t *store);

/* Checks a whole file image; on success, and only then, fills records (heap) and count. Returns
 * false with the reason otherwise. */
bool co_file_store_parse(const uint8_t *file, size_t size, co_file_record_t **records,
                         size_t *count, char *reason, size_t reason_len);

/* The record of a node's area, or NULL. */
const co_file_record_t *co_file_store_find(const co_file_store_t *store, uint8_t node_id,
                                           uint8_t area);

/* Replaces (data != NULL) or removes (data == NULL) the record of a node's area and rewrites the
 * file atomically. The store takes ownership of data in every case. 0, or -1 with the reason
 * (the file and the records in memory then stay as they were). */
int co_file_store_update(co_file_store_t *store, uint8_t node_id, uint8_t area, uint8_t *data,
                         uint32_t len);

/* Applies several such changes (in order) and rewrites the file once: all of them or none. The
 * store takes ownership of every change's data. */
int co_file_store_update_many(co_file_store_t *store, const co_file_record_t *changes, size_t n);

/* The DeviceNet record of a MAC ID: true and *values when there is one. */
bool co_file_store_get_devicenet(const co_file_store_t *store, uint8_t mac_id,
                                 co_file_devicenet_t *values);
/* Replaces the DeviceNet record of a MAC ID and rewrites the file atomically; 0 or -1 as
 * co_file_store_update. */
int co_file_store_set_devicenet(co_file_store_t *store, uint8_t mac_id,
                                const co_file_devicenet_t *values);

/* The LSS record of a node's key: true and the stored node-id and bit timing when there is
 * one. */
bool co_file_store_get_lss(const co_file_store_t *store, uint8_t key, uint8_t *node_id,
                           uint8_t *bit_timing);
/* Replaces the LSS record of a key and rewrites the file atomically; 0 or -1 as
 * co_file_store_update. */
int co_file_store_set_lss(co_file_store_t *store, uint8_t key, uint8_t node_id, uint8_t bit_timing);

/* Fills a co_storage_t for one node of the store: the areas of one 1010h / 1011h write are
 * staged and written together in one file replacement (group_begin / group_end). */
void co_file_store_bind(co_file_store_t *store, uint8_t node_id, co_file_store_node_t *node,
                        co_storage_t *storage);

/* Releases a node's save buffer. */
void co_file_store_unbind(co_file_store_node_t *node);

/* CRC-32 as in IEEE 802.3 and zlib (reflected polynomial 0xEDB88320, initial and final value
 * 0xFFFFFFFF). */
uint32_t co_crc32(const uint8_t *data, size_t len);

#endif
