/* SPDX-License-Identifier: Apache-2.0 */
/* NMT slave: the node's state machine (Initialising, Pre-operational, Operational, Stopped), the
 * NMT commands addressed to this node or broadcast, the boot-up frame and the scope of each reset
 * (CiA 301 section 7.3.2). */
#ifndef CO_NMT_H
#define CO_NMT_H

#include "co_types.h"

typedef struct co_node co_node_t;

typedef enum co_nmt_state {
    CO_NMT_INITIALISING = 0x00,
    CO_NMT_STOPPED = 0x04,
    CO_NMT_OPERATIONAL = 0x05,
    CO_NMT_PRE_OPERATIONAL = 0x7F
} co_nmt_state_t;

/* NMT command specifiers (CiA 301 table 58; Disconnect from DS301 before V4, which a node obeys
 * only with CO_NODE_NMT_DISCONNECT). */
enum co_nmt_command {
    CO_NMT_CS_START = 0x01,
    CO_NMT_CS_STOP = 0x02,
    CO_NMT_CS_DISCONNECT = 0x03,
    CO_NMT_CS_ENTER_PRE_OPERATIONAL = 0x80,
    CO_NMT_CS_RESET_NODE = 0x81,
    CO_NMT_CS_RESET_COMMUNICATION = 0x82
};

typedef enum co_nmt_reset {
    CO_NMT_RESET_COMMUNICATION, /* communication area 1000h..1FFFh back to defaults / stored */
    CO_NMT_RESET_NODE           /* the whole dictionary, then reset communication */
} co_nmt_reset_t;

/* Handles a frame on COB-ID 0x000. Returns true when the frame was an NMT command. */
bool co_nmt_receive(co_node_t *node, const co_frame_t *frame);

/* Performs a reset of the given scope and ends in Pre-operational after sending the boot-up frame.
 */
void co_nmt_reset(co_node_t *node, co_nmt_reset_t scope);

/* Changes state (Pre-operational, Operational, Stopped), telling the services and the application.
 */
void co_nmt_enter(co_node_t *node, co_nmt_state_t state);

/* The name of an NMT state as a heartbeat or guarding reply gives it (co_nmt_state_t values:
 * "Initialising", "Stopped", "Operational", "Pre-operational"), NULL for any other byte. For logs
 * and tools; a firmware that never calls it links none of it. */
const char *co_nmt_state_name(uint8_t state);

#endif
