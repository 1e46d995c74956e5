/* SPDX-License-Identifier: Apache-2.0 */
/* The DeviceNet and CIP wire vocabulary the slave library, its tests and later the scanner and the
 * trace decoder name instead of keeping copies: message groups and message IDs of the predefined
 * master/slave connection set, explicit message header and fragmentation bits, CIP services,
 * general status codes, class codes, allocation choice bits and connection states. Values after
 * the public descriptions of DeviceNet (IEC 62026-3, Wireshark's DeviceNet dissector) and the
 * Altivar 312 DeviceNet manual (docs/devicenet.md). */
#ifndef DN_CIP_H
#define DN_CIP_H

/* Message groups of the 11-bit CAN identifier. */
#define DN_GROUP1_BASE 0x000u /* 0x000-0x3FF: message ID (4 bits) << 6 | source MAC ID */
#define DN_GROUP2_BASE 0x400u /* 0x400-0x5FF: 0x400 | MAC ID << 3 | message ID (3 bits) */
#define DN_GROUP3_BASE 0x600u /* 0x600-0x7BF: 0x600 | message ID (3 bits) << 6 | source MAC ID */
#define DN_GROUP4_BASE 0x7C0u /* 0x7C0-0x7EF: message ID (6 bits), the offline connection set */
#define DN_GROUP4_END 0x7EFu
#define DN_MAC_ID_MAX 63u
#define DN_MAC_ID_DEFAULT 63u
#define DN_MAC_ID_NONE 0xFFu /* allocation information: not allocated */

/* Group 1 message IDs of the predefined master/slave connection set (the slave sends them). */
#define DN_G1_SLAVE_MULTICAST_POLL_RESPONSE 0xCu
#define DN_G1_SLAVE_COS_CYCLIC 0xDu
#define DN_G1_SLAVE_BIT_STROBE_RESPONSE 0xEu
#define DN_G1_SLAVE_POLL_RESPONSE 0xFu /* also the slave's COS/cyclic acknowledge */

/* Group 2 message IDs; the MAC ID field is the slave's (the bit-strobe's is the master's). */
#define DN_G2_MASTER_BIT_STROBE 0u
#define DN_G2_MASTER_MULTICAST_POLL 1u
#define DN_G2_MASTER_COS_CYCLIC_ACK 2u
#define DN_G2_SLAVE_EXPLICIT_RESPONSE 3u /* explicit and unconnected responses */
#define DN_G2_MASTER_EXPLICIT_REQUEST 4u
#define DN_G2_MASTER_POLL_COS_CYCLIC 5u /* the poll command, or the master's COS/cyclic data */
#define DN_G2_UNCONNECTED_REQUEST 6u    /* group 2 only unconnected explicit request port */
#define DN_G2_DUPLICATE_MAC_CHECK 7u

/* Group 3 message IDs: 0..4 those of the connections the UCMM opens, 5 and 6 the UCMM's own. */
#define DN_G3_CONNECTED_LAST 4u
#define DN_G3_UNCONNECTED_RESPONSE 5u
#define DN_G3_UNCONNECTED_REQUEST 6u

/* The UCMM's Open Explicit Messaging Connection request body: byte 0 the requested message body
 * format (low nibble), byte 1 the group select (high nibble) and the client's source message ID
 * (low nibble); the response: the actual body format, the destination message ID (high nibble,
 * the client's) and the server's source message ID (low nibble), the connection instance (UINT).
 * Close carries the connection instance (UINT). */
#define DN_UCMM_BODY_FORMAT 0x0Fu
#define DN_UCMM_GROUP_SHIFT 4u
#define DN_UCMM_MESSAGE_ID 0x0Fu
#define DN_UCMM_GROUP_3 3u
#define DN_BODY_FORMAT_8_8 0u

/* Duplicate MAC ID check message: byte 0 request/response flag and physical port number, then
 * vendor ID (UINT) and serial number (UDINT), 7 bytes. */
#define DN_DUP_MAC_RESPONSE 0x80u
#define DN_DUP_MAC_LEN 7u
#define DN_DUP_MAC_WAIT_US 1000000u /* one second after each of the two requests */

/* Explicit message header (byte 0) and service byte (byte 1). */
#define DN_HDR_FRAG 0x80u
#define DN_HDR_XID 0x40u
#define DN_HDR_MAC 0x3Fu
#define DN_SERVICE_RESPONSE 0x80u
#define DN_SERVICE_CODE 0x7Fu

/* Fragmentation protocol byte (byte 1 of a fragment): type and 6-bit fragment count. */
#define DN_FRAG_TYPE 0xC0u
#define DN_FRAG_FIRST 0x00u
#define DN_FRAG_MIDDLE 0x40u
#define DN_FRAG_LAST 0x80u
#define DN_FRAG_ACK 0xC0u
#define DN_FRAG_COUNT 0x3Fu
#define DN_FRAG_ACK_SUCCESS 0x00u
#define DN_FRAG_ACK_TOO_MUCH_DATA 0x01u
#define DN_FRAG_BODY 6u /* message body bytes per explicit fragment */

/* CIP services. */
#define DN_SVC_GET_ATTRIBUTES_ALL 0x01u
#define DN_SVC_RESET 0x05u
#define DN_SVC_APPLY_ATTRIBUTES 0x0Du
#define DN_SVC_GET_ATTRIBUTE_SINGLE 0x0Eu
#define DN_SVC_SET_ATTRIBUTE_SINGLE 0x10u
#define DN_SVC_ERROR_RESPONSE 0x14u /* sent as 0x94, with the response bit */
#define DN_SVC_ALLOCATE 0x4Bu       /* Allocate_Master/Slave_Connection_Set */
#define DN_SVC_RELEASE 0x4Cu        /* Release_Group_2_Identifier_Set */
#define DN_SVC_OPEN_EXPLICIT 0x4Bu  /* the UCMM's Open Explicit Messaging Connection (group 3) */
#define DN_SVC_CLOSE 0x4Cu          /* the UCMM's Close Connection (group 3) */

/* CIP general status codes. */
#define DN_GS_SUCCESS 0x00u
#define DN_GS_RESOURCE_UNAVAILABLE 0x02u
#define DN_GS_PATH_DESTINATION_UNKNOWN 0x05u
#define DN_GS_SERVICE_NOT_SUPPORTED 0x08u
#define DN_GS_INVALID_ATTRIBUTE_VALUE 0x09u
#define DN_GS_ALREADY_IN_STATE 0x0Bu
#define DN_GS_OBJECT_STATE_CONFLICT 0x0Cu
#define DN_GS_ATTRIBUTE_NOT_SETTABLE 0x0Eu
#define DN_GS_DEVICE_STATE_CONFLICT 0x10u
#define DN_GS_REPLY_DATA_TOO_LARGE 0x11u
#define DN_GS_NOT_ENOUGH_DATA 0x13u
#define DN_GS_ATTRIBUTE_NOT_SUPPORTED 0x14u
#define DN_GS_TOO_MUCH_DATA 0x15u
#define DN_GS_OBJECT_DOES_NOT_EXIST 0x16u
#define DN_GS_STORE_OPERATION_FAILURE 0x19u
#define DN_GS_VENDOR_SPECIFIC 0x1Fu
#define DN_GS_INVALID_PARAMETER 0x20u
#define DN_AC_NONE 0xFFu /* additional code: none */

/* The DeviceNet object's additional codes of an Allocate or Release refusal. */
#define DN_AC_ALLOCATION_CONFLICT 0x01u    /* allocated by another master */
#define DN_AC_INVALID_CHOICE 0x02u         /* a choice not supported, or already allocated */
#define DN_AC_INVALID_GROUP2_MESSAGE 0x03u /* a group 2 only server got another service */
#define DN_AC_RESOURCE_UNAVAILABLE 0x04u

/* CIP classes. */
#define DN_CLASS_IDENTITY 0x01u
#define DN_CLASS_MESSAGE_ROUTER 0x02u
#define DN_CLASS_DEVICENET 0x03u
#define DN_CLASS_ASSEMBLY 0x04u
#define DN_CLASS_CONNECTION 0x05u
#define DN_CLASS_MOTOR_DATA 0x28u
#define DN_CLASS_CONTROL_SUPERVISOR 0x29u
#define DN_CLASS_AC_DC_DRIVE 0x2Au
#define DN_CLASS_ACK_HANDLER 0x2Bu

/* Allocation and release choice byte. */
#define DN_ALLOC_EXPLICIT 0x01u
#define DN_ALLOC_POLLED 0x02u
#define DN_ALLOC_BIT_STROBE 0x04u
#define DN_ALLOC_MULTICAST_POLL 0x08u
#define DN_ALLOC_COS 0x10u
#define DN_ALLOC_CYCLIC 0x20u
#define DN_ALLOC_ACK_SUPPRESSION 0x40u

/* Connection object: the predefined set's instances, states, watchdog timeout actions. */
#define DN_CONN_EXPLICIT 1u
#define DN_CONN_POLL 2u
#define DN_CONN_BIT_STROBE 3u
#define DN_CONN_COS_CYCLIC 4u
#define DN_CONN_UCMM_FIRST 10u /* the explicit server instances 10-14 the UCMM opens */
#define DN_CONN_UCMM_LAST 14u
#define DN_CONN_ATTR_STATE 1u
#define DN_CONN_ATTR_EXPECTED_PACKET_RATE 9u
#define DN_CONN_ATTR_PRODUCED_PATH 14u
#define DN_CONN_ATTR_CONSUMED_PATH 16u

typedef enum dn_conn_state {
    DN_CONN_NON_EXISTENT = 0,
    DN_CONN_CONFIGURING = 1,
    DN_CONN_WAITING_FOR_ID = 2,
    DN_CONN_ESTABLISHED = 3,
    DN_CONN_TIMED_OUT = 4,
    DN_CONN_DEFERRED_DELETE = 5
} dn_conn_state_t;

#define DN_WATCHDOG_TIMED_OUT 0u
#define DN_WATCHDOG_AUTO_DELETE 1u
#define DN_WATCHDOG_AUTO_RESET 2u
#define DN_WATCHDOG_DEFERRED_DELETE 3u

/* Identity status word (instance attribute 5). */
#define DN_STATUS_OWNED 0x0001u
#define DN_STATUS_CONFIGURED 0x0004u
#define DN_STATUS_EXTENDED_SHIFT 4u
#define DN_STATUS_MINOR_RECOVERABLE 0x0100u
#define DN_STATUS_MINOR_UNRECOVERABLE 0x0200u
#define DN_STATUS_MAJOR_RECOVERABLE 0x0400u
#define DN_STATUS_MAJOR_UNRECOVERABLE 0x0800u
#define DN_EXT_UNKNOWN 0x0u
#define DN_EXT_FAULTED_IO 0x2u
#define DN_EXT_NO_IO 0x3u
#define DN_EXT_NV_BAD 0x4u
#define DN_EXT_MAJOR_FAULT 0x5u
#define DN_EXT_RUN 0x6u
#define DN_EXT_IDLE 0x7u

#endif
