/* SPDX-License-Identifier: Apache-2.0 */
/* NMT slave state machine (CiA 301 section 7.3.2.2, figure 48). */
#include "co/co_consumers.h"
#include "co/co_node.h"

#define NMT_COMMAND_LEN 2u
#define NMT_BROADCAST 0u

static void reset_services(co_node_t *node, co_nmt_reset_t scope)
{
    co_sdo_reset(node);
    co_sync_reset(node);
    co_emcy_reset(node, scope);
    co_heartbeat_reset(node);
    co_guarding_reset(node);
    co_pdo_reset(node);
    if (node->time_stamp != NULL)
        node->time_stamp->reset(node);
}

void co_nmt_enter(co_node_t *node, co_nmt_state_t state)
{
    if (node->nmt_state == state)
        return;
    node->nmt_state = state;
    co_node_reschedule(node);
    co_sdo_reset(node); /* a transfer does not survive a state change (none in Stopped) */
    co_pdo_restart(node);
    if (node->hooks != NULL && node->hooks->nmt_state != NULL)
        node->hooks->nmt_state(node, state);
}

/* CiA 301 7.3.2.2.2: reset node restores the whole dictionary, reset communication only the
 * communication area; each area gets its defaults, then its stored values. CiA 305: both make
 * the LSS pending node-id the active one, and a node left without one (FFh) stays in
 * Initialising, silent but for LSS, with its defaults loaded for the boot that LSS starts. */
void co_nmt_reset(co_node_t *node, co_nmt_reset_t scope)
{
    node->nmt_state = CO_NMT_INITIALISING;
    if (node->lss != NULL)
        node->node_id = node->lss->pending_node_id;
    if (node->hooks != NULL && node->hooks->reset != NULL)
        node->hooks->reset(node, scope);
    if (scope == CO_NMT_RESET_NODE) {
        co_od_restore_defaults(node, 0x2000, 0xFFFF);
        co_store_apply(node, 0x2000, 0xFFFF);
    }
    co_od_restore_defaults(node, CO_IDX_COMM_FIRST, CO_IDX_COMM_LAST);
    co_store_apply(node, CO_IDX_COMM_FIRST, CO_IDX_COMM_LAST);
    /* Every reset changes the consumed set, a node left without node-id's too (7E5h alone); the
     * runtime reads the set after the reset. */
    co_consumers_changed(node);
    if (node->node_id == CO_LSS_NODE_ID_UNCONFIGURED)
        return;
    reset_services(node, scope);
    co_node_send_byte(node, CO_CAN_ID_ERROR_CONTROL + node->node_id, 0);
    co_nmt_enter(node, CO_NMT_PRE_OPERATIONAL);
    if (node->nmt_startup != NULL)
        node->nmt_startup->booted(node);
}

/* CiA 301 7.2.8.3.1: an NMT command is exactly two bytes; anything else is not one. A node of
 * 8-byte frames (CO_NODE_PAD_DLC8) takes the command from the first two bytes of DLC 2..8. */
static bool nmt_command_shaped(const co_node_t *node, const co_frame_t *frame)
{
    if (frame->flags & CO_FRAME_RTR)
        return false;
    if (node->options & CO_NODE_PAD_DLC8)
        return frame->len >= NMT_COMMAND_LEN;
    return frame->len == NMT_COMMAND_LEN;
}

bool co_nmt_receive(co_node_t *node, const co_frame_t *frame)
{
    if (frame->id != CO_CAN_ID_NMT)
        return false;
    if (!nmt_command_shaped(node, frame))
        return true;
    uint8_t target = frame->data[1];
    if (target != NMT_BROADCAST && target != node->node_id)
        return true;
    switch (frame->data[0]) {
    case CO_NMT_CS_START:
        co_nmt_enter(node, CO_NMT_OPERATIONAL);
        break;
    case CO_NMT_CS_STOP:
        co_nmt_enter(node, CO_NMT_STOPPED);
        break;
    case CO_NMT_CS_DISCONNECT:
        /* DS301 before V4 had a Disconnected state; V4 has none, and the nearest is Stopped: no
         * SDO, PDO or EMCY, still answering NMT and node guarding (docs/error-control.md). */
        if (node->options & CO_NODE_NMT_DISCONNECT)
            co_nmt_enter(node, CO_NMT_STOPPED);
        break;
    case CO_NMT_CS_ENTER_PRE_OPERATIONAL:
        co_nmt_enter(node, CO_NMT_PRE_OPERATIONAL);
        break;
    case CO_NMT_CS_RESET_NODE:
        co_nmt_reset(node, CO_NMT_RESET_NODE);
        break;
    case CO_NMT_CS_RESET_COMMUNICATION:
        co_nmt_reset(node, CO_NMT_RESET_COMMUNICATION);
        break;
    default:
        break;
    }
    return true;
}

const char *co_nmt_state_name(uint8_t state)
{
    switch (state) {
    case CO_NMT_INITIALISING:
        return "Initialising";
    case CO_NMT_STOPPED:
        return "Stopped";
    case CO_NMT_OPERATIONAL:
        return "Operational";
    case CO_NMT_PRE_OPERATIONAL:
        return "Pre-operational";
    default:
        return NULL;
    }
}
