/* SPDX-License-Identifier: Apache-2.0 */
/* An in-memory co_storage_t for tests: one committed image per area, a staging image for the
 * save in progress, failures on demand, the stored values and the images the node refused. */
#ifndef MEMORY_STORAGE_H
#define MEMORY_STORAGE_H

#include "co/co_node.h"

#define MEMORY_STORAGE_AREAS 5
#define MEMORY_STORAGE_IMAGE_MAX 4096
#define MEMORY_STORAGE_REFUSALS 16

typedef struct memory_refusal {
    uint16_t index;
    uint8_t subindex;
    size_t len;
    uint32_t abort;
} memory_refusal_t;

typedef struct memory_storage {
    uint8_t image[MEMORY_STORAGE_AREAS][MEMORY_STORAGE_IMAGE_MAX];
    long size[MEMORY_STORAGE_AREAS]; /* 0: none */
    uint8_t staging[MEMORY_STORAGE_IMAGE_MAX];
    size_t staged;
    uint8_t saving;
    bool damaged;     /* load_size reports every stored image damaged */
    bool fail_write;  /* save_write fails */
    bool fail_erase;  /* erase fails */
    long fail_offset; /* > 0: reads at this offset fail */
    unsigned saves, erases;
    memory_refusal_t refused[MEMORY_STORAGE_REFUSALS]; /* the first ones */
    unsigned refusals;                                 /* every one reported */
    co_store_image_fault_t image_fault;                /* the last image refused whole */
    unsigned images_refused;                           /* every one reported */
} memory_storage_t;

/* Empties the storage and fills *storage with callbacks on it. */
void memory_storage_init(memory_storage_t *m, co_storage_t *storage);

/* Offset of the value of an entry's record in an area's image (0 when absent). */
long memory_storage_record(const memory_storage_t *m, uint8_t area, uint16_t index,
                           uint8_t subindex);

/* The abort reported for an entry's refused value; fails the test when none was reported. */
uint32_t memory_storage_refusal(const memory_storage_t *m, uint16_t index, uint8_t subindex);

#endif
