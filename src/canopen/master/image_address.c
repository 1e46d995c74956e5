/* SPDX-License-Identifier: Apache-2.0 */
/* The PLC300's network markers over the process image (co_image_address.h). */
#include "co/co_image_address.h"

/* The address's size letter: B byte, W word, D double word; 0 for another letter. */
static uint8_t size_of_letter(char c)
{
    switch (c) {
    case 'B':
    case 'b':
        return 1;
    case 'W':
    case 'w':
        return 2;
    case 'D':
    case 'd':
        return 4;
    default:
        return 0;
    }
}

bool co_image_address_parse(const char *text, co_image_address_t *address)
{
    if (text == NULL || text[0] != '%')
        return false;
    co_image_area_t area;
    if (text[1] == 'I' || text[1] == 'i')
        area = CO_IMAGE_INPUT;
    else if (text[1] == 'Q' || text[1] == 'q')
        area = CO_IMAGE_OUTPUT;
    else
        return false;
    uint8_t size = size_of_letter(text[2]);
    if (size == 0)
        return false;
    /* Four digits: every number of the manual's tables (2000 .. 2511) has four. */
    const char *digit = text + 3;
    uint32_t number = 0;
    for (size_t n = 0; n < 4; n++) {
        if (digit[n] < '0' || digit[n] > '9')
            return false;
        number = number * 10u + (uint32_t)(digit[n] - '0');
    }
    if (digit[4] != '\0' || number < CO_IMAGE_ADDRESS_FIRST)
        return false;
    uint32_t offset = number - CO_IMAGE_ADDRESS_FIRST;
    /* The manual's tables number words 2000, 2002 .. 2510 and double words 2000, 2004 .. 2508. */
    if (offset % size != 0 || offset + size > CO_IMAGE_ADDRESS_IMAGE_SIZE)
        return false;
    address->area = area;
    address->size = size;
    address->offset = (uint16_t)offset;
    return true;
}

uint32_t co_image_address_get(const uint8_t *image, const co_image_address_t *address)
{
    uint32_t value = 0;
    for (uint8_t k = address->size; k > 0; k--)
        value = (value << 8) | image[address->offset + k - 1u];
    return value;
}

bool co_image_address_bytes(const co_image_address_t *address, uint32_t value, uint8_t *bytes)
{
    if (address->size < 4 && value >> (8u * address->size) != 0)
        return false;
    for (uint8_t k = 0; k < address->size; k++)
        bytes[k] = (uint8_t)(value >> (8u * k));
    return true;
}
