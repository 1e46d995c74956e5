/* Store and restore parameters (1010h / 1011h, CiA 301 section 7.5.2.13-14): the "save" and "load"
 * signatures and the storage interface the runtime implements (a file, a flash page...). */
#ifndef CO_STORE_H
#define CO_STORE_H

#include "co_od.h"

/* Signatures written to 1010h / 1011h, as the little-endian value of the ASCII bytes. */
#define CO_STORE_SIGNATURE_SAVE 0x65766173u /* "save" */
#define CO_STORE_SIGNATURE_LOAD 0x64616F6Cu /* "load" */

/* Implemented by the runtime. Groups follow the 1010h sub-indexes: 1 = all parameters,
 * 2 = communication, 3 = application, 4..127 = manufacturer-defined. */
typedef struct co_storage {
    void *ctx;
    /* Replaces the stored image of a group atomically. Returns 0 on success. */
    int (*save)(void *ctx, uint8_t group, const uint8_t *image, size_t len);
    /* Copies a verified image of a group into buf. Returns its length, 0 when none is stored, or
     * -1 when the stored image is damaged (it is then ignored, never partly applied). */
    long (*load)(void *ctx, uint8_t group, uint8_t *buf, size_t cap);
    /* Forgets a group, so the next reset applies the defaults. Returns 0 on success. */
    int (*erase)(void *ctx, uint8_t group);
} co_storage_t;

uint32_t co_store_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len);
/* Applies stored values of the entries in [first, last] after their defaults were restored. */
void co_store_apply(co_node_t *node, uint16_t first, uint16_t last);

#endif
