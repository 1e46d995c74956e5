/* SPDX-License-Identifier: Apache-2.0 */
/* co_storage_t on flash pages: two pages per storage area, so that a save never touches the image
 * in force. An image is complete only once its header is programmed, last. */
#ifndef FLASH_STORAGE_H
#define FLASH_STORAGE_H

#include "co/co_store.h"

typedef struct flash_storage {
    uint8_t area;    /* of the save under way */
    unsigned page;   /* the page being written */
    uint32_t length; /* bytes of image written so far */
    bool failed;
} flash_storage_t;

/* The area of the LSS configuration (CiA 305 store configuration: node-id and bit timing), past
 * the three of 1010h/1011h (CO_STORE_AREA_*), through the same functions of the storage. */
#define FLASH_STORAGE_AREA_LSS 5u

/* The storage of 1010h/1011h and of the LSS configuration; ctx is the flash_storage_t. */
void flash_storage_init(co_storage_t *storage, flash_storage_t *flash);

#endif
