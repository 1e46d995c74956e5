/* SPDX-License-Identifier: Apache-2.0 */
/* The CRC of SDO block transfers, computed by the server and the client alike. */
#include "co/co_sdo.h"

uint16_t co_sdo_crc16_update(uint16_t crc, const uint8_t *data, size_t len)
{
    for (size_t i = 0; i < len; i++) {
        crc ^= (uint16_t)(data[i] << 8);
        for (int bit = 0; bit < 8; bit++)
            crc = (crc & 0x8000u) ? (uint16_t)((crc << 1) ^ 0x1021u) : (uint16_t)(crc << 1);
    }
    return crc;
}

uint16_t co_sdo_crc16(const uint8_t *data, size_t len)
{
    return co_sdo_crc16_update(0, data, len);
}
