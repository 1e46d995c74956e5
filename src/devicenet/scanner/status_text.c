/* The CIP general status codes in words, for the scanner's users (dnscan's errors). */
#include "dn/dn_scanner.h"

static const char *const texts[] = {
    [0x00] = "success",
    [0x01] = "connection failure",
    [0x02] = "resource unavailable",
    [0x03] = "invalid parameter value",
    [0x04] = "path segment error",
    [0x05] = "path destination unknown",
    [0x06] = "partial transfer",
    [0x07] = "connection lost",
    [0x08] = "service not supported",
    [0x09] = "invalid attribute value",
    [0x0A] = "attribute list error",
    [0x0B] = "already in the requested mode or state",
    [0x0C] = "object state conflict",
    [0x0D] = "object already exists",
    [0x0E] = "attribute not settable",
    [0x0F] = "privilege violation",
    [0x10] = "device state conflict",
    [0x11] = "reply data too large",
    [0x12] = "fragmentation of a primitive value",
    [0x13] = "not enough data",
    [0x14] = "attribute not supported",
    [0x15] = "too much data",
    [0x16] = "object does not exist",
    [0x17] = "service fragmentation sequence not in progress",
    [0x18] = "no stored attribute data",
    [0x19] = "store operation failure",
    [0x1A] = "routing failure, request too large",
    [0x1B] = "routing failure, response too large",
    [0x1C] = "missing attribute list entry data",
    [0x1D] = "invalid attribute value list",
    [0x1E] = "embedded service error",
    [0x1F] = "vendor specific error",
    [0x20] = "invalid parameter",
    [0x21] = "write-once value already written",
    [0x22] = "invalid reply received",
};

const char *dn_cip_status_text(uint8_t general)
{
    if (general < sizeof(texts) / sizeof(texts[0]) && texts[general])
        return texts[general];
    return "unknown status";
}
