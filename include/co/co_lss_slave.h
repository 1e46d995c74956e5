/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS slave: a node's answers on 7E5h/7E4h in both LSS states, in every NMT state
 * including Initialising. Its LSS address is the node's identity object (1018h sub 1..4). It owns
 * the pending node-id (the active one is co_node_t.node_id, which takes the pending one at every
 * NMT reset) and the pending bit timing, the switch of the bit rate on its delays, and the store
 * of both through the application. A node has LSS when co_node_config_t.lss points at one of
 * these, prepared with co_lss_slave_init(); a node without links none of this module. Behaviour
 * and the choices where CiA 305 is silent: docs/lss.md. */
#ifndef CO_LSS_SLAVE_H
#define CO_LSS_SLAVE_H

#include "co_lss.h"

typedef struct co_node co_node_t;

/* What only the device knows; any of them may be NULL. */
typedef struct co_lss_slave_hooks {
    /* Configure bit timing: whether the device can run at this index of table 0 (0..9, not 5).
     * NULL: no bit timing but the present one can be configured (answer 1, not supported). */
    bool (*bit_timing_supported)(co_node_t *node, uint8_t index);
    /* Activate bit timing: switch the CAN controller to the index now. The core calls it one
     * switch delay after the command and sends nothing from the command until one more switch
     * delay after the call. NULL: the command is ignored. */
    void (*switch_bit_timing)(co_node_t *node, uint8_t index);
    /* Store configuration: keep the pending node-id and bit timing index across power cycles
     * (the application hands them back in at the next start). Returns CO_LSS_OK,
     * CO_LSS_STORE_MEDIA_ERROR or CO_LSS_SPECIFIC_ERROR with *specific set. NULL: store is not
     * supported (answer 1). */
    uint8_t (*store)(co_node_t *node, uint8_t node_id, uint8_t bit_timing, uint8_t *specific);
} co_lss_slave_hooks_t;

typedef struct co_lss_slave {
    /* The module's entries, set by co_lss_slave_init, so that the node calls them through these
     * pointers and a node without LSS links none of the module. */
    void (*receive)(co_node_t *node, const co_frame_t *frame);
    co_time_t (*process)(co_node_t *node, co_time_t now);
    const co_lss_slave_hooks_t *hooks;
    co_time_t switch_at;    /* activate bit timing: the switch, CO_TIME_NEVER when none is due */
    co_time_t resume_at;    /* the end of the silence after it, CO_TIME_NEVER when not silent */
    co_time_t switch_delay; /* its delay, us */
    uint8_t state;          /* co_lss_state_t */
    uint8_t pending_node_id;
    uint8_t bit_timing;    /* pending index of table 0 */
    uint8_t selected;      /* switch state selective: parts of the address matched in order */
    uint8_t identified;    /* identify remote slave: conditions met in order */
    uint8_t fastscan_part; /* fastscan: the part (LSS sub) this slave answers for */
} co_lss_slave_t;

/* Activate bit timing: no frame leaves the node from the command until one delay after the
 * switch, that is while a switch or the end of the silence is due. */
static inline bool co_lss_slave_silent(const co_lss_slave_t *lss)
{
    return lss->switch_at != CO_TIME_NEVER || lss->resume_at != CO_TIME_NEVER;
}

/* Prepares the slave in waiting state with the node's present bit timing (index of table 0) and
 * the hooks (NULL: none). co_node_init sets the pending node-id to the node's. */
void co_lss_slave_init(co_lss_slave_t *lss, const co_lss_slave_hooks_t *hooks, uint8_t bit_timing);

#endif
