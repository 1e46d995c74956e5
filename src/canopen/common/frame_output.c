/* SPDX-License-Identifier: Apache-2.0 */
/* Every frame a node sends, through the application's callback: the services' frames, the SYNC
 * producer's, and the one-byte error control frames. Below the services, so that none of them
 * calls the node. */
#include "co/co_node.h"

void co_node_send(co_node_t *node, const co_frame_t *frame)
{
    /* CiA 305 activate bit timing: the node keeps still while the bit rate changes. */
    if (node->lss != NULL && co_lss_slave_silent(node->lss))
        return;
    if ((node->options & CO_NODE_PAD_DLC8) && !(frame->flags & CO_FRAME_RTR))
        node->options_code->send_padded(node, frame);
    else
        node->send(node->user, frame);
}

void co_node_send_byte(co_node_t *node, uint32_t id, uint8_t byte)
{
    co_frame_t frame = {.id = id, .len = 1, .data = {byte}};
    co_node_send(node, &frame);
}
