/* SPDX-License-Identifier: Apache-2.0 */
/* Store and restore parameters (1010h / 1011h, CiA 301 sections 7.5.2.13-14) and the storage
 * interface the runtime implements (a file, a flash page...).
 *
 * 1010h:n = "save" stores group n, 1011h:n = "load" erases it so the defaults apply at the next
 * reset; both read as 1 ("on command" / "restorable"). Group 1 is all parameters, 2 the
 * communication area 1000h..1FFFh, 3 the standard profile area 6000h..9FFFh, 4 the manufacturer
 * area 2000h..5FFFh. Any other value aborts 0x08000020, as does a node without storage or a
 * sub-index above 4; a storage failure aborts 0x06060000.
 *
 * Storage works by AREA, never by group: the core passes only the area numbers 2 (1000h..1FFFh),
 * 3 (6000h..9FFFh) and 4 (2000h..5FFFh) to the backend, and group 1 means the three of them.
 *
 * What is stored: every parameter of the area, that is every writable (CO_OD_WRITE) entry except
 * the process data the dictionary marks CO_OD_PROCESS (commands, references: they always start
 * from their defaults) and the commands and history that are not parameters (1003h, 1010h,
 * 1011h), as a self-describing image:
 *
 *     "COS" 0x02 sequence (u32 LE) kind (u8)              9-byte header
 *     index (u16 LE) sub (u8) len (u16 LE) value[len]     one record per entry, in table order
 *
 * A view (an entry whose read hook computes it from others: 6046h of LSP/HSP) is stored as read.
 * `sequence` orders the saves and restores of a node; `kind` is CO_STORE_IMAGE_VALUES, or
 * CO_STORE_IMAGE_DEFAULTS (no records) for an area restored alone by 1011h (restoring all areas
 * erases every image). Version 1 images ("COS" 0x01 then records) load as the oldest values.
 *
 * At a reset (nmt.c) the defaults of the areas in scope are restored first; then their images
 * apply, oldest first, so that when two areas cover one value (a view and what it stands for) the
 * later save or restore wins. An image is first checked whole (co_store_image_check: its header;
 * every record inside it, of an object of its area, after the one before it in table order; the
 * last one ending exactly at its end) and ignored entirely if it fails, reported through
 * `image_refused`, or if the backend reports it damaged. Its records then go through the same
 * checks, hooks and service rules as an SDO write (co_od_write, origin CO_OD_ORIGIN_STORE), in the
 * order of the CiA 301 mapping procedure: every PDO the image configures is made invalid with an
 * empty mapping, then the values are written, then the numbers of mapped objects, then the COB-IDs.
 * A record refused because of another not yet applied is tried again after the others; a record
 * still refused (unknown entry, size changed, process data, out of its limits, refused by a hook)
 * is reported through `refused` and skipped, the entry keeping its value; a PDO whose COB-ID is
 * refused stays invalid. A defaults image writes the default of each view of its area through its
 * hook.
 *
 * Images are streamed from and to the dictionary's own bytes; a value is staged in a buffer of
 * CO_CONFIG_STORE_VALUE_MAX bytes on the stack while it is checked. */
#ifndef CO_STORE_H
#define CO_STORE_H

#include "co_od.h"

/* Signatures written to 1010h / 1011h, as the little-endian value of the ASCII bytes. */
#define CO_STORE_SIGNATURE_SAVE 0x65766173u /* "save" */
#define CO_STORE_SIGNATURE_LOAD 0x64616F6Cu /* "load" */

/* Storage areas passed to the backend. */
#define CO_STORE_AREA_COMMUNICATION 2u /* 1000h..1FFFh */
#define CO_STORE_AREA_PROFILE 3u       /* 6000h..9FFFh */
#define CO_STORE_AREA_MANUFACTURER 4u  /* 2000h..5FFFh */

/* Image format version 2: "COS", the version byte, the sequence and the kind. */
#define CO_STORE_IMAGE_HEADER_SIZE 9u
#define CO_STORE_RECORD_HEADER_SIZE 5u
#define CO_STORE_IMAGE_VALUES 0u   /* the records hold the area's saved values */
#define CO_STORE_IMAGE_DEFAULTS 1u /* the area was restored: its defaults apply */

/* Why a stored image is refused whole, before any of it applies. */
typedef enum co_store_fault {
    CO_STORE_FAULT_NONE,         /* well formed, or no image to apply */
    CO_STORE_FAULT_AREA,         /* not a storage area: 2, 3 or 4 */
    CO_STORE_FAULT_UNREADABLE,   /* load_read failed */
    CO_STORE_FAULT_HEADER,       /* not "COS" version 1, or version 2 with a known kind */
    CO_STORE_FAULT_CUT_SHORT,    /* a record runs past the end of the image */
    CO_STORE_FAULT_OUTSIDE_AREA, /* a record of an object outside the image's area */
    CO_STORE_FAULT_ORDER         /* a record not after the one before it: a duplicate, or out of
                                    table order */
} co_store_fault_t;

typedef struct co_store_image_fault {
    co_store_fault_t reason;
    uint8_t area;
    uint16_t area_first, area_last; /* the indexes of the area (0 for CO_STORE_FAULT_AREA) */
    uint32_t offset;                /* byte of the image where the record at fault starts */
    uint16_t index;                 /* that record's object, when its header could be read */
    uint8_t subindex;
} co_store_image_fault_t;

/* Implemented by the runtime; every callback gets `ctx`. Calls never nest and never interleave:
 * a save is save_begin, save_write..., save_end; a load is load_size then load_read... of the
 * same area. All callbacks return 0 (or a length) on success and -1 on failure. */
typedef struct co_storage {
    void *ctx;
    /* Starts a new image of an area; the previous image stays in force until save_end commits. */
    int (*save_begin)(void *ctx, uint8_t area);
    /* Appends bytes to the image being written. */
    int (*save_write)(void *ctx, const uint8_t *data, size_t len);
    /* commit = true: atomically replaces the stored image of the area by the written one (a
     * crash before or during it leaves the old image, never a mix). commit = false: discards
     * the written bytes (a save_write failed). */
    int (*save_end)(void *ctx, bool commit);
    /* Length of the stored image of an area after the backend verified it (CRC or the like): >
     * 0, 0 when none is stored, -1 when the stored image is damaged (it is then ignored). */
    long (*load_size)(void *ctx, uint8_t area);
    /* Copies len bytes of the verified image at offset into buf. */
    int (*load_read)(void *ctx, uint8_t area, uint32_t offset, uint8_t *buf, size_t len);
    /* Forgets an area (no image: the defaults apply). Erasing a missing image succeeds. */
    int (*erase)(void *ctx, uint8_t area);
    /* Optional (may be NULL): a stored value was refused while an image was applied and skipped;
     * `value` holds its len bytes (NULL when it could not be read), abort says why as an SDO
     * abort code. co_od_name() names the entry. */
    void (*refused)(void *ctx, const co_node_t *node, uint16_t index, uint8_t subindex,
                    const uint8_t *value, size_t len, uint32_t abort);
    /* Optional (both or neither may be NULL): bracket the areas that one 1010h or 1011h write
     * saves or erases (1010h:01 saves three, 1011h:01 erases three). Between them, save_end(true)
     * and erase only stage their change; group_end(ctx, true) then makes every staged change
     * durable at once, atomically (a crash before or during it leaves every old image, never
     * some areas old and some new), and group_end(ctx, false) discards them (an area failed).
     * Loads see the committed images only. Without them each area commits alone, and a crash
     * between two areas of one write leaves a mixture of the old and the new parameters. */
    int (*group_begin)(void *ctx);
    int (*group_end)(void *ctx, bool commit);
    /* Optional (may be NULL): an image was refused whole while the stored images were applied
     * (co_store_image_check says why); nothing of it applied. */
    void (*image_refused)(void *ctx, const co_node_t *node, const co_store_image_fault_t *fault);
} co_storage_t;

/* Write handler of 1010h / 1011h. */
uint32_t co_store_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len);
/* Checks the stored image of an area as co_store_apply does before applying any of it: a
 * backend may run it on images it did not write (a file read at start). CO_STORE_FAULT_NONE
 * when it is well formed, when there is none (load_size 0) and when the backend reports it
 * damaged (-1); *fault is filled in every case. */
co_store_fault_t co_store_image_check(const co_storage_t *s, uint8_t area,
                                      co_store_image_fault_t *fault);
/* Applies the stored images of the areas that lie in [first, last], after their defaults were
 * restored. Without storage, or without a usable image, the defaults stay. */
void co_store_apply(co_node_t *node, uint16_t first, uint16_t last);

#endif
