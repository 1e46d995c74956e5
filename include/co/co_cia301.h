/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 301 wire vocabulary in one place: the predefined connection set, the indexes of the
 * communication area, the SDO command layout and the SDO abort codes (CiA 301 v4.2, "CANopen
 * application layer and communication profile"). The core, the master, the frame decoder, the
 * programs and the tests name these instead of keeping copies. Named after the specification it
 * transcribes, as lwIP's include/lwip/prot/ names each protocol: another fieldbus gets its own
 * header beside it. Constants only, no functions. */
#ifndef CO_CIA301_H
#define CO_CIA301_H

#include <stdint.h>

/* Predefined connection set (CiA 301 7.3.3): the CAN-ID of a node's object is its function code
 * plus the node-id (1..127); NMT and SYNC are the same for every node. */
#define CO_CAN_ID_NMT 0x000u
#define CO_CAN_ID_SYNC 0x080u
#define CO_CAN_ID_EMCY 0x080u /* + node-id */
#define CO_CAN_ID_TIME 0x100u
#define CO_CAN_ID_TPDO1 0x180u /* + node-id; TPDO n and RPDO n follow each 100h apart */
#define CO_CAN_ID_RPDO1 0x200u
#define CO_CAN_ID_TPDO2 0x280u
#define CO_CAN_ID_RPDO2 0x300u
#define CO_CAN_ID_TPDO3 0x380u
#define CO_CAN_ID_RPDO3 0x400u
#define CO_CAN_ID_TPDO4 0x480u
#define CO_CAN_ID_RPDO4 0x500u
#define CO_CAN_ID_SDO_TX 0x580u /* + node-id: server -> client */
#define CO_CAN_ID_SDO_RX 0x600u /* + node-id: client -> server */
/* + node-id: NMT error control, the boot-up, the heartbeat and the node guarding reply. */
#define CO_CAN_ID_ERROR_CONTROL 0x700u
/* The span of one function code: node-ids 0..127. */
#define CO_CAN_ID_NODE_SPAN 0x80u
#define CO_NODE_ID_MASK 0x7Fu
#define CO_NODE_ID_MAX 127u

/* NMT error control (CiA 301 7.2.8.3): bit 7 of a node guarding reply is the toggle bit, bits
 * 6..0 the NMT state, which a heartbeat sends alone (0 for the boot-up). */
#define CO_GUARD_TOGGLE 0x80u
#define CO_NMT_STATE_MASK 0x7Fu

/* Communication area (CiA 301 7.5.2): the indexes the core's services own. */
#define CO_IDX_COMM_FIRST 0x1000u
#define CO_IDX_COMM_LAST 0x1FFFu
#define CO_IDX_DEVICE_TYPE 0x1000u
#define CO_IDX_ERROR_REGISTER 0x1001u
#define CO_IDX_ERROR_HISTORY 0x1003u
#define CO_IDX_SYNC_COB_ID 0x1005u
#define CO_IDX_SYNC_PERIOD 0x1006u
#define CO_IDX_SYNC_WINDOW 0x1007u
#define CO_IDX_DEVICE_NAME 0x1008u
#define CO_IDX_GUARD_TIME 0x100Cu
#define CO_IDX_LIFE_TIME_FACTOR 0x100Du
#define CO_IDX_GUARD_COB_ID 0x100Eu
#define CO_IDX_STORE 0x1010u
#define CO_IDX_RESTORE 0x1011u
#define CO_IDX_TIME_COB_ID 0x1012u
#define CO_IDX_EMCY_COB_ID 0x1014u
#define CO_IDX_EMCY_INHIBIT 0x1015u
#define CO_IDX_HB_CONSUMER 0x1016u
#define CO_IDX_HB_PRODUCER 0x1017u
#define CO_IDX_IDENTITY 0x1018u
/* The sub-indexes of the identity object 1018h. */
#define CO_IDENTITY_VENDOR 1u
#define CO_IDENTITY_PRODUCT 2u
#define CO_IDENTITY_REVISION 3u
#define CO_IDENTITY_SERIAL 4u
#define CO_IDX_SYNC_OVERFLOW 0x1019u
#define CO_IDX_SDO_SERVER 0x1200u
#define CO_IDX_SDO_SERVER_LAST 0x127Fu /* the last additional SDO server parameter */
/* Sub-indices of an SDO server parameter (CiA 301 7.5.2.33, 7.5.2.34) and of an SDO client
 * parameter (1280h..12FFh), whose sub-index 3 is the server's node-id. */
#define CO_SDO_PARAM_RX 1u      /* COB-ID client -> server */
#define CO_SDO_PARAM_TX 2u      /* COB-ID server -> client */
#define CO_SDO_PARAM_NODE_ID 3u /* node-id of the SDO client, 1..127 */
#define CO_IDX_SDO_CLIENT 0x1280u
#define CO_IDX_SDO_CLIENT_LAST 0x12FFu /* the last SDO client parameter */

/* PDO parameters (CiA 301 7.5.2.35-7.5.2.38): the RPDO communication (1400h) and mapping (1600h)
 * parameters, then the TPDO communication (1800h) and mapping (1A00h) parameters, each
 * CO_PDO_INDEX_SPAN indexes; a PDO's mapping follows its communication parameter by one span. */
#define CO_PDO_RPDO_COMM 0x1400u
#define CO_PDO_RPDO_MAP 0x1600u
#define CO_PDO_TPDO_COMM 0x1800u
#define CO_PDO_TPDO_MAP 0x1A00u
#define CO_PDO_INDEX_SPAN 0x200u
#define CO_PDO_LAST_INDEX 0x1BFFu

/* SDO command byte (CiA 301 7.2.4.3): the command specifier in bits 7..5, the rest bits of the
 * specifier's own. */
#define CO_SDO_CS_SHIFT 5u
#define CO_SDO_CS_MASK 0xE0u
#define CO_SDO_CS(command) ((uint8_t)(command) >> CO_SDO_CS_SHIFT)
#define CO_SDO_COMMAND(cs) ((uint8_t)((cs) << CO_SDO_CS_SHIFT))
/* Client command specifiers (ccs). */
#define CO_SDO_CCS_DOWNLOAD_SEGMENT 0u
#define CO_SDO_CCS_DOWNLOAD_INITIATE 1u
#define CO_SDO_CCS_UPLOAD_INITIATE 2u
#define CO_SDO_CCS_UPLOAD_SEGMENT 3u
#define CO_SDO_CCS_BLOCK_UPLOAD 5u
#define CO_SDO_CCS_BLOCK_DOWNLOAD 6u
/* Server command specifiers (scs). */
#define CO_SDO_SCS_UPLOAD_SEGMENT 0u
#define CO_SDO_SCS_DOWNLOAD_SEGMENT 1u
#define CO_SDO_SCS_UPLOAD_INITIATE 2u
#define CO_SDO_SCS_DOWNLOAD_INITIATE 3u
#define CO_SDO_SCS_BLOCK_DOWNLOAD 5u
#define CO_SDO_SCS_BLOCK_UPLOAD 6u
/* Either side: abort transfer. */
#define CO_SDO_CS_ABORT 4u

/* Bits of the command bytes. */
#define CO_SDO_EXPEDITED 0x02u      /* e, initiate */
#define CO_SDO_SIZE_INDICATED 0x01u /* s, initiate */
#define CO_SDO_TOGGLE 0x10u         /* t, segments */
#define CO_SDO_LAST_SEGMENT 0x01u   /* c, segments */
#define CO_SDO_BLOCK_CRC 0x04u      /* cc / sc */
#define CO_SDO_BLOCK_SIZE_INDICATED 0x02u
#define CO_SDO_BLOCK_LAST 0x80u  /* c of a block segment's sequence byte: no more segments */
#define CO_SDO_BLOCK_SEQNO 0x7Fu /* the block segment's sequence number, 1..127 */

/* Sub-commands of block transfers, bits 1..0 (upload) or bit 0 (download) of byte 0. */
#define CO_SDO_SUB_MASK 0x03u
#define CO_SDO_SUB_UPLOAD_INITIATE 0u
#define CO_SDO_SUB_UPLOAD_END 1u
#define CO_SDO_SUB_UPLOAD_ACK 2u
#define CO_SDO_SUB_UPLOAD_START 3u
#define CO_SDO_SUB_DOWNLOAD_INITIATE 0u
#define CO_SDO_SUB_DOWNLOAD_END 1u
#define CO_SDO_SUB_DOWNLOAD_ACK 2u /* the server's sub-block acknowledge */

/* Sizes: data bytes of a segment and of an expedited transfer, the largest block. */
#define CO_SDO_SEGMENT_BYTES 7u
#define CO_SDO_EXPEDITED_BYTES 4u
#define CO_SDO_BLKSIZE_MAX 127u

/* Smallest frames carrying what each request needs: command + index + sub-index, + 4-byte size. */
#define CO_SDO_INITIATE_LEN 4u
#define CO_SDO_INITIATE_SIZE_LEN 8u
#define CO_SDO_BLOCK_UPLOAD_INITIATE_LEN 5u /* + blksize; pst is 0 when absent */
#define CO_SDO_BLOCK_ACK_LEN 3u             /* cs, ackseq, blksize */
#define CO_SDO_BLOCK_END_CRC_LEN 3u         /* cs, CRC */

/* CiA 301 v4.2 section 7.2.4.3.17: SDO abort codes, the complete set. The names without CO_
 * (SDO_ABORT_*) are those of release 0.1 and stay for one more release: use CO_SDO_ABORT_*. */
enum co_sdo_abort {
    CO_SDO_OK = 0,
    CO_SDO_ABORT_TOGGLE = 0x05030000,
    CO_SDO_ABORT_TIMEOUT = 0x05040000,
    CO_SDO_ABORT_COMMAND = 0x05040001,
    CO_SDO_ABORT_BLOCK_SIZE = 0x05040002,
    CO_SDO_ABORT_SEQUENCE = 0x05040003,
    CO_SDO_ABORT_CRC = 0x05040004,
    CO_SDO_ABORT_NO_MEMORY = 0x05040005,
    CO_SDO_ABORT_UNSUPPORTED_ACCESS = 0x06010000,
    CO_SDO_ABORT_WRITE_ONLY = 0x06010001,
    CO_SDO_ABORT_READ_ONLY = 0x06010002,
    CO_SDO_ABORT_NO_OBJECT = 0x06020000,
    CO_SDO_ABORT_NOT_MAPPABLE = 0x06040041,
    CO_SDO_ABORT_PDO_LENGTH = 0x06040042,
    CO_SDO_ABORT_PARAM_INCOMPATIBLE = 0x06040043,
    CO_SDO_ABORT_INTERNAL_INCOMPATIBLE = 0x06040047,
    CO_SDO_ABORT_HARDWARE = 0x06060000,
    CO_SDO_ABORT_TYPE_LENGTH = 0x06070010,
    CO_SDO_ABORT_LENGTH_HIGH = 0x06070012,
    CO_SDO_ABORT_LENGTH_LOW = 0x06070013,
    CO_SDO_ABORT_NO_SUBINDEX = 0x06090011,
    CO_SDO_ABORT_VALUE_RANGE = 0x06090030,
    CO_SDO_ABORT_VALUE_HIGH = 0x06090031,
    CO_SDO_ABORT_VALUE_LOW = 0x06090032,
    CO_SDO_ABORT_MAX_LESS_MIN = 0x06090036,
    CO_SDO_ABORT_NO_RESOURCE = 0x060A0023,
    CO_SDO_ABORT_GENERAL = 0x08000000,
    CO_SDO_ABORT_DATA_STORE = 0x08000020,
    CO_SDO_ABORT_DATA_LOCAL = 0x08000021,
    CO_SDO_ABORT_DATA_STATE = 0x08000022,
    CO_SDO_ABORT_OD_MISSING = 0x08000023,
    CO_SDO_ABORT_NO_DATA = 0x08000024,
    SDO_ABORT_TOGGLE = CO_SDO_ABORT_TOGGLE,
    SDO_ABORT_TIMEOUT = CO_SDO_ABORT_TIMEOUT,
    SDO_ABORT_COMMAND = CO_SDO_ABORT_COMMAND,
    SDO_ABORT_BLOCK_SIZE = CO_SDO_ABORT_BLOCK_SIZE,
    SDO_ABORT_SEQUENCE = CO_SDO_ABORT_SEQUENCE,
    SDO_ABORT_CRC = CO_SDO_ABORT_CRC,
    SDO_ABORT_NO_MEMORY = CO_SDO_ABORT_NO_MEMORY,
    SDO_ABORT_UNSUPPORTED_ACCESS = CO_SDO_ABORT_UNSUPPORTED_ACCESS,
    SDO_ABORT_WRITE_ONLY = CO_SDO_ABORT_WRITE_ONLY,
    SDO_ABORT_READ_ONLY = CO_SDO_ABORT_READ_ONLY,
    SDO_ABORT_NO_OBJECT = CO_SDO_ABORT_NO_OBJECT,
    SDO_ABORT_NOT_MAPPABLE = CO_SDO_ABORT_NOT_MAPPABLE,
    SDO_ABORT_PDO_LENGTH = CO_SDO_ABORT_PDO_LENGTH,
    SDO_ABORT_PARAM_INCOMPATIBLE = CO_SDO_ABORT_PARAM_INCOMPATIBLE,
    SDO_ABORT_INTERNAL_INCOMPATIBLE = CO_SDO_ABORT_INTERNAL_INCOMPATIBLE,
    SDO_ABORT_HARDWARE = CO_SDO_ABORT_HARDWARE,
    SDO_ABORT_TYPE_LENGTH = CO_SDO_ABORT_TYPE_LENGTH,
    SDO_ABORT_LENGTH_HIGH = CO_SDO_ABORT_LENGTH_HIGH,
    SDO_ABORT_LENGTH_LOW = CO_SDO_ABORT_LENGTH_LOW,
    SDO_ABORT_NO_SUBINDEX = CO_SDO_ABORT_NO_SUBINDEX,
    SDO_ABORT_VALUE_RANGE = CO_SDO_ABORT_VALUE_RANGE,
    SDO_ABORT_VALUE_HIGH = CO_SDO_ABORT_VALUE_HIGH,
    SDO_ABORT_VALUE_LOW = CO_SDO_ABORT_VALUE_LOW,
    SDO_ABORT_MAX_LESS_MIN = CO_SDO_ABORT_MAX_LESS_MIN,
    SDO_ABORT_NO_RESOURCE = CO_SDO_ABORT_NO_RESOURCE,
    SDO_ABORT_GENERAL = CO_SDO_ABORT_GENERAL,
    SDO_ABORT_DATA_STORE = CO_SDO_ABORT_DATA_STORE,
    SDO_ABORT_DATA_LOCAL = CO_SDO_ABORT_DATA_LOCAL,
    SDO_ABORT_DATA_STATE = CO_SDO_ABORT_DATA_STATE,
    SDO_ABORT_OD_MISSING = CO_SDO_ABORT_OD_MISSING,
    SDO_ABORT_NO_DATA = CO_SDO_ABORT_NO_DATA
};

#endif
