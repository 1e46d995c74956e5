/* SPDX-License-Identifier: Apache-2.0 */
/* Conversions between the core's co_frame_t and SocketCAN's struct can_frame. */
#ifndef CO_LINUX_CAN_FRAME_H
#define CO_LINUX_CAN_FRAME_H

#include "co/co_types.h"

#include <linux/can.h>
#include <string.h>

/* The first `len` (at most CAN_MAX_DLEN) data bytes, the rest zero, without a call into the C
 * library per frame, as a memcpy of a variable length is: the eight bytes are copied whole and
 * masked with a window into a row of 0xFF bytes followed by zero bytes, which keeps byte order. */
static inline void co_linux_copy_data(uint8_t *out, const uint8_t *in, size_t len)
{
    static const uint8_t window[2 * CAN_MAX_DLEN] = {0xFF, 0xFF, 0xFF, 0xFF,
                                                     0xFF, 0xFF, 0xFF, 0xFF};
    uint64_t data, mask;
    memcpy(&data, in, sizeof data);
    memcpy(&mask, &window[CAN_MAX_DLEN - len], sizeof mask);
    data &= mask;
    memcpy(out, &data, sizeof data);
}

static inline void co_linux_frame_to_can(const co_frame_t *in, struct can_frame *out)
{
    memset(out, 0, sizeof *out);
    if (in->flags & CO_FRAME_EFF)
        out->can_id = (in->id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    else
        out->can_id = in->id & CAN_SFF_MASK;
    if (in->flags & CO_FRAME_RTR)
        out->can_id |= CAN_RTR_FLAG;
    out->len = in->len > CAN_MAX_DLEN ? CAN_MAX_DLEN : in->len;
    co_linux_copy_data(out->data, in->data, in->flags & CO_FRAME_RTR ? 0 : out->len);
}

/* Error frames are not CANopen frames: the caller handles CAN_ERR_FLAG before converting. */
static inline void co_linux_frame_from_can(const struct can_frame *in, co_frame_t *out)
{
    memset(out, 0, sizeof *out);
    if (in->can_id & CAN_EFF_FLAG) {
        out->id = in->can_id & CAN_EFF_MASK;
        out->flags |= CO_FRAME_EFF;
    } else {
        out->id = in->can_id & CAN_SFF_MASK;
    }
    if (in->can_id & CAN_RTR_FLAG)
        out->flags |= CO_FRAME_RTR;
    out->len = in->len > CAN_MAX_DLEN ? CAN_MAX_DLEN : in->len;
    co_linux_copy_data(out->data, in->data, in->can_id & CAN_RTR_FLAG ? 0 : out->len);
}

#endif
