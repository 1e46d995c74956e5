/* SPDX-License-Identifier: Apache-2.0 */
/* Flash pages as the co_storage_t of a node. Areas 2..4 (CO_STORE_AREA_*) and the LSS
 * configuration's (FLASH_STORAGE_AREA_LSS) each own two pages;
 * each page starts with a header (magic, sequence, length, CRC) and holds one image after it. A
 * save erases the page that is not in force, programs the image, then the header: a power cut
 * before the header leaves the old page in force, one during it leaves a header whose CRC or
 * magic fails, and the old page again wins. The page in force is the valid one with the higher
 * sequence. */
#include "flash_storage.h"

#include "board.h"
#include "co/co_sdo.h"

#include <string.h>

#define HEADER_MAGIC 0x31534643u /* "CFS1" */
#define HEADER_SIZE 16u
#define IMAGE_MAX (FLASH_PAGE_SIZE - HEADER_SIZE)

typedef struct header {
    uint32_t magic;
    uint32_t sequence;
    uint32_t length;
    uint32_t crc; /* co_sdo_crc16 of the image, in the low half: the CRC-16-CCITT of the core */
} header_t;

static unsigned first_page(uint8_t area)
{
    return (unsigned)(area - CO_STORE_AREA_COMMUNICATION) * 2u;
}

static bool page_valid(unsigned page, header_t *h)
{
    memcpy(h, flash_page(page), sizeof(*h));
    return h->magic == HEADER_MAGIC && h->length <= IMAGE_MAX &&
           h->crc == co_sdo_crc16(flash_page(page) + HEADER_SIZE, h->length);
}

/* The page in force of an area, -1 when none: an erased page (0xFF) or a half-written header is
 * not valid. */
static int page_in_force(uint8_t area, header_t *h)
{
    header_t other;
    unsigned p = first_page(area);
    bool a = page_valid(p, h);
    bool b = page_valid(p + 1, &other);
    if (b && (!a || other.sequence > h->sequence)) {
        *h = other;
        return (int)p + 1;
    }
    return a ? (int)p : -1;
}

static bool area_ok(uint8_t area)
{
    return area >= CO_STORE_AREA_COMMUNICATION && area <= FLASH_STORAGE_AREA_LSS;
}

static int save_begin(void *ctx, uint8_t area)
{
    flash_storage_t *f = ctx;
    if (!area_ok(area))
        return -1;
    header_t h;
    int current = page_in_force(area, &h);
    f->area = area;
    f->page = current == (int)first_page(area) ? first_page(area) + 1 : first_page(area);
    f->length = 0;
    f->failed = false;
    return flash_erase(f->page);
}

static int save_write(void *ctx, const uint8_t *data, size_t len)
{
    flash_storage_t *f = ctx;
    if (len > IMAGE_MAX - f->length ||
        flash_program(f->page, HEADER_SIZE + f->length, data, len) != 0) {
        f->failed = true;
        return -1;
    }
    f->length += (uint32_t)len;
    return 0;
}

static int save_end(void *ctx, bool commit)
{
    flash_storage_t *f = ctx;
    if (!commit)
        return 0; /* without its header the page never comes into force */
    if (f->failed)
        return -1;
    header_t old;
    header_t h = {.magic = HEADER_MAGIC,
                  .sequence = page_in_force(f->area, &old) >= 0 ? old.sequence + 1 : 1,
                  .length = f->length,
                  .crc = co_sdo_crc16(flash_page(f->page) + HEADER_SIZE, f->length)};
    return flash_program(f->page, 0, (const uint8_t *)&h, sizeof(h));
}

static long load_size(void *ctx, uint8_t area)
{
    (void)ctx;
    header_t h;
    if (!area_ok(area))
        return 0;
    return page_in_force(area, &h) >= 0 ? (long)h.length : 0;
}

static int load_read(void *ctx, uint8_t area, uint32_t offset, uint8_t *buf, size_t len)
{
    (void)ctx;
    header_t h;
    int page = area_ok(area) ? page_in_force(area, &h) : -1;
    if (page < 0 || offset > h.length || len > h.length - offset)
        return -1;
    memcpy(buf, flash_page((unsigned)page) + HEADER_SIZE + offset, len);
    return 0;
}

static int erase(void *ctx, uint8_t area)
{
    (void)ctx;
    if (!area_ok(area))
        return -1;
    return flash_erase(first_page(area)) == 0 && flash_erase(first_page(area) + 1) == 0 ? 0 : -1;
}

void flash_storage_init(co_storage_t *storage, flash_storage_t *flash)
{
    *storage = (co_storage_t){.ctx = flash,
                              .save_begin = save_begin,
                              .save_write = save_write,
                              .save_end = save_end,
                              .load_size = load_size,
                              .load_read = load_read,
                              .erase = erase};
}
