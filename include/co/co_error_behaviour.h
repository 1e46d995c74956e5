/* SPDX-License-Identifier: Apache-2.0 */
/* The error behaviour object 1029h (CiA 301 7.5.2.32): what an error of each class does to the
 * node's NMT state. Sub-index 1 is the communication error (a heartbeat producer or life guarding
 * lost, an RPDO time-out, the recovery from bus off; co_node_communication_error), further
 * sub-indexes are the device profile's or the manufacturer's error classes. Selectable per node: a
 * node gets the service with co_node_config_t.error_behaviour = &co_error_behaviour, and one
 * without it links none of it; its application keeps CiA 301's behaviour without 1029h itself
 * (nodes/plain_node.h). docs/error-control.md. */
#ifndef CO_ERROR_BEHAVIOUR_H
#define CO_ERROR_BEHAVIOUR_H

#include "co_od.h"

#define CO_IDX_ERROR_BEHAVIOUR 0x1029u
/* 1029h:01, the class the core raises itself. */
#define CO_ERROR_CLASS_COMMUNICATION 1u

/* The values of a 1029h sub-index (CiA 301 7.5.2.32, table "Error behaviour value definition");
 * 3..127 are reserved, 128..255 manufacturer-specific. */
#define CO_ERROR_BEHAVIOUR_PRE_OPERATIONAL 0u /* only from Operational */
#define CO_ERROR_BEHAVIOUR_NO_CHANGE 1u
#define CO_ERROR_BEHAVIOUR_STOPPED 2u
#define CO_ERROR_BEHAVIOUR_RESERVED_LAST 127u

/* The service's code, for co_node_config_t.error_behaviour. */
typedef struct co_error_behaviour_code {
    /* An error of class `subindex` (CO_ERROR_CLASS_COMMUNICATION, or a device error class of the
     * dictionary's 1029h) occurred: the NMT state changes as 1029h:subindex says; an absent
     * sub-index behaves as 0, CiA 301's default. */
    void (*raise)(co_node_t *node, uint8_t subindex);
    /* The write rules of 1029h (co_node_t.parameter_write). */
    uint32_t (*od_write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
} co_error_behaviour_code_t;

extern const co_error_behaviour_code_t co_error_behaviour;

#endif
