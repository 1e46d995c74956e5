/* SPDX-License-Identifier: Apache-2.0 */
/* DeviceNet identifiers: the message groups 1-3 (and 4's range) of the 11-bit CAN identifier,
 * composed and decomposed, and the CAN-IDs of the predefined master/slave connection set for a
 * slave's MAC ID 0..63. No OS headers, no state. */
#ifndef DN_LINK_H
#define DN_LINK_H

#include <stdint.h>

#include "dn_cip.h"

/* Group 1: message ID 0..15, source MAC ID. */
static inline uint16_t dn_group1_id(uint8_t message_id, uint8_t mac_id)
{
    return (uint16_t)(DN_GROUP1_BASE | (message_id & 0xFu) << 6 | (mac_id & DN_MAC_ID_MAX));
}

/* Group 2: MAC ID (destination, or the bit-strobe master's source), message ID 0..7. */
static inline uint16_t dn_group2_id(uint8_t mac_id, uint8_t message_id)
{
    return (uint16_t)(DN_GROUP2_BASE | (mac_id & DN_MAC_ID_MAX) << 3 | (message_id & 7u));
}

/* Group 3: message ID 0..6 (7 would be group 4's range), source MAC ID. */
static inline uint16_t dn_group3_id(uint8_t message_id, uint8_t mac_id)
{
    return (uint16_t)(DN_GROUP3_BASE | (message_id & 7u) << 6 | (mac_id & DN_MAC_ID_MAX));
}

/* An identifier taken apart. group 0: not a DeviceNet identifier (0x7F0-0x7FF, or more than
 * 11 bits); group 4 has no MAC ID (0). */
typedef struct dn_can_id {
    uint8_t group;      /* 1..4, 0: invalid */
    uint8_t message_id; /* group 1: 0..15, 2: 0..7, 3: 0..6, 4: 0..0x2F */
    uint8_t mac_id;
} dn_can_id_t;

dn_can_id_t dn_can_id_decode(uint32_t can_id);

/* The predefined master/slave connection set's CAN-IDs of the slave with this MAC ID. */
typedef struct dn_predefined_ids {
    uint16_t poll_command;      /* group 2 msg 5: master's poll command or COS/cyclic data */
    uint16_t explicit_request;  /* group 2 msg 4 */
    uint16_t explicit_response; /* group 2 msg 3: explicit and unconnected responses */
    uint16_t unconnected;       /* group 2 msg 6: Allocate, Release */
    uint16_t duplicate_mac;     /* group 2 msg 7 */
    uint16_t cos_ack;           /* group 2 msg 2: master's acknowledge of the slave's COS */
    uint16_t poll_response;     /* group 1 msg 0xF: poll response or COS/cyclic acknowledge */
    uint16_t cos_cyclic;        /* group 1 msg 0xD: the slave's COS/cyclic data */
} dn_predefined_ids_t;

dn_predefined_ids_t dn_predefined_ids(uint8_t mac_id);

#endif
