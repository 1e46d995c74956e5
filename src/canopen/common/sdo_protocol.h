/* The SDO protocol's frame layout (CiA 301 section 7.2.4.3), shared by the server and the client
 * of the core: command specifiers, command bits, sizes. Private to src/canopen. */
#ifndef CO_SDO_PROTOCOL_H
#define CO_SDO_PROTOCOL_H

/* Command specifiers, bits 7..5 of byte 0 (CiA 301 7.2.4.3). */
#define CCS_DOWNLOAD_SEGMENT 0u
#define CCS_DOWNLOAD_INITIATE 1u
#define CCS_UPLOAD_INITIATE 2u
#define CCS_UPLOAD_SEGMENT 3u
#define CCS_BLOCK_UPLOAD 5u
#define CCS_BLOCK_DOWNLOAD 6u

#define SCS_UPLOAD_SEGMENT 0x00u
#define SCS_DOWNLOAD_SEGMENT 0x20u
#define SCS_UPLOAD_INITIATE 0x40u
#define SCS_DOWNLOAD_INITIATE 0x60u
#define CS_ABORT 0x80u
#define SCS_BLOCK_DOWNLOAD 0xA0u
#define SCS_BLOCK_UPLOAD 0xC0u

/* Bits of the initiate command bytes. */
#define SDO_EXPEDITED 0x02u      /* e */
#define SDO_SIZE_INDICATED 0x01u /* s */
#define SDO_TOGGLE 0x10u         /* t */
#define SDO_LAST 0x01u           /* c, segmented transfers */
#define BLOCK_CRC 0x04u          /* cc / sc */
#define BLOCK_SIZE_INDICATED 0x02u
#define BLOCK_LAST 0x80u /* c, block segments */
#define BLOCK_SEQNO 0x7Fu

/* Sub-commands of block transfers, bits 1..0 (upload) or bit 0 (download) of byte 0. */
#define BLOCK_UPLOAD_INITIATE 0u
#define BLOCK_UPLOAD_END 1u
#define BLOCK_UPLOAD_ACK 2u
#define BLOCK_UPLOAD_START 3u
#define BLOCK_DOWNLOAD_INITIATE 0u
#define BLOCK_DOWNLOAD_END 1u
#define BLOCK_DOWNLOAD_ACK 2u /* server's sub-block acknowledge */

#define SEGMENT_BYTES 7u
#define EXPEDITED_BYTES 4u
#define BLKSIZE_MAX 127u

/* Smallest frames carrying what each request needs: command + index + sub-index, + 4-byte size. */
#define INITIATE_LEN 4u
#define INITIATE_SIZE_LEN 8u
#define BLOCK_UPLOAD_INITIATE_LEN 5u /* + blksize; pst is 0 when absent */
#define BLOCK_ACK_LEN 3u             /* cs, ackseq, blksize */
#define BLOCK_END_CRC_LEN 3u         /* cs, CRC */

#endif
