/* SPDX-License-Identifier: Apache-2.0 */
/* cotrace's DeviceNet decoder: says what one CAN frame means on a DeviceNet bus, one line per
 * frame (docs/cotrace.md, "DeviceNet"): its message group, message ID and MAC ID, then the
 * message of the predefined master/slave connection set it carries.
 *
 * It keeps what a meaning needs from earlier frames, per slave MAC ID: the explicit messages
 * being reassembled from fragments (each direction), the last request (a response names what it
 * answers), the connections allocated (the message ID 5 / 0xF frames are poll or COS/cyclic by
 * them) and the assemblies selected (I/O data decoded by them: a Set of Connection class
 * attributes 100/101 applies when the node restarts, seen as its duplicate MAC ID check). */
#ifndef COTRACE_DEVICENET_DECODER_H
#define COTRACE_DEVICENET_DECODER_H

#include "dn/dn_fragment.h" /* the reassembly, DN_MESSAGE_MAX */
#include "dn/dn_node.h"     /* the vocabulary of dn_cip.h */

#include <linux/can.h>
#include <stdbool.h>

/* The default assemblies of the Altivar 312 card (the manual): 21 out, 71 in. */
#define COTRACE_DN_CONSUMED_DEFAULT 21u
#define COTRACE_DN_PRODUCED_DEFAULT 71u

/* The last request of a master to a slave, for the response. */
typedef struct cotrace_dn_request {
    bool valid;
    uint8_t service, class_id, instance, attribute;
    bool has_attribute;
    uint8_t data[2]; /* the first bytes of its data: the choice of Allocate/Release, a UINT */
    uint8_t len;     /* the length of its whole data, which data holds only the start of */
} cotrace_dn_request_t;

/* What the trace showed of one slave. */
typedef struct cotrace_dn_node {
    dn_fragments_t request;  /* master to slave (group 2 message 4), reassembled as a slave does */
    dn_fragments_t response; /* slave to master (group 2 message 3), as a scanner does */
    cotrace_dn_request_t last;
    uint8_t allocation; /* the allocation choice bits allocated */
    uint16_t consumed;  /* the assemblies in use */
    uint16_t produced;
    uint16_t stored_consumed; /* Connection class attributes 100/101: used after a restart */
    uint16_t stored_produced;
} cotrace_dn_node_t;

typedef struct cotrace_dn_decoder {
    cotrace_dn_node_t node[DN_MAC_ID_MAX + 1];
} cotrace_dn_decoder_t;

/* Every node with these assemblies in use (0: the defaults, 21 and 71), nothing allocated. */
void cotrace_dn_decoder_init(cotrace_dn_decoder_t *dec, uint16_t consumed, uint16_t produced);

/* Writes the meaning of `frame` into out (always NUL-terminated, truncated to cap). */
void cotrace_dn_decode(cotrace_dn_decoder_t *dec, const struct can_frame *frame, char *out,
                       size_t cap);

#endif
