/* SPDX-License-Identifier: Apache-2.0 */
/* How a DeviceNet frame leaves, the slave's and the scanner's alike: a data frame of the 11-bit
 * identifier and the bytes given, handed to the application's send callback. Inline, so that
 * each sender keeps it in its own frame path as before it was shared; not installed. */
#ifndef DN_FRAME_SEND_H
#define DN_FRAME_SEND_H

#include <string.h>

#include "co/co_types.h"

static inline void dn_frame_send(co_send_fn send, void *user, uint16_t can_id, const uint8_t *data,
                                 uint8_t len)
{
    co_frame_t frame;
    memset(&frame, 0, sizeof(frame));
    frame.id = can_id;
    frame.len = len;
    if (len)
        memcpy(frame.data, data, len);
    send(user, &frame);
}

#endif
