/* SPDX-License-Identifier: Apache-2.0 */
/* The explicit messaging fragmentation protocol both ways (include/dn/dn_fragment.h), shared by
 * the slave's explicit server and the scanner's explicit client. */
#include "dn/dn_fragment.h"

#include <string.h>

void dn_fragment_start(dn_fragments_t *tx, uint8_t header, const uint8_t *body, uint8_t len)
{
    tx->active = true;
    tx->header = (uint8_t)(header | DN_HDR_FRAG);
    tx->count = 0;
    tx->offset = 0;
    tx->retries = 0;
    tx->len = len;
    memcpy(tx->body, body, len);
}

uint8_t dn_fragment_frame(const dn_fragments_t *tx, uint8_t frame[8])
{
    uint8_t left = (uint8_t)(tx->len - tx->offset);
    uint8_t chunk = left > DN_FRAG_BODY ? DN_FRAG_BODY : left;
    uint8_t type = tx->offset == 0 ? DN_FRAG_FIRST : chunk == left ? DN_FRAG_LAST : DN_FRAG_MIDDLE;
    frame[0] = tx->header;
    frame[1] = (uint8_t)(type | tx->count);
    memcpy(&frame[2], &tx->body[tx->offset], chunk);
    return (uint8_t)(2 + chunk);
}

dn_fragment_ack_t dn_fragment_acknowledged(dn_fragments_t *tx, uint8_t count, uint8_t status)
{
    if (!tx->active || count != tx->count)
        return DN_FRAGMENT_ACK_IGNORED;
    uint8_t left = (uint8_t)(tx->len - tx->offset);
    if (status != DN_FRAG_ACK_SUCCESS) {
        tx->active = false;
        return DN_FRAGMENT_ACK_REFUSED;
    }
    if (left <= DN_FRAG_BODY) {
        tx->active = false;
        return DN_FRAGMENT_ACK_DONE;
    }
    tx->offset = (uint8_t)(tx->offset + DN_FRAG_BODY);
    tx->count = (uint8_t)((tx->count + 1) & DN_FRAG_COUNT);
    tx->retries = 0;
    return DN_FRAGMENT_ACK_NEXT;
}

dn_fragment_rx_t dn_fragment_receive(dn_fragments_t *rx, const uint8_t *data, uint8_t len)
{
    uint8_t type = data[1] & DN_FRAG_TYPE;
    uint8_t count = data[1] & DN_FRAG_COUNT;
    uint8_t chunk = (uint8_t)(len - 2);
    if (type == DN_FRAG_FIRST) {
        rx->active = true;
        rx->len = 0;
        rx->header = data[0];
    } else if (!rx->active) {
        return DN_FRAGMENT_RX_IGNORED;
    } else if (count == rx->count) {
        return DN_FRAGMENT_RX_REPEATED;
    } else if (count != ((rx->count + 1u) & DN_FRAG_COUNT)) {
        rx->active = false;
        return DN_FRAGMENT_RX_LOST;
    }
    rx->count = count;
    if (chunk > DN_MESSAGE_MAX - rx->len) {
        rx->active = false;
        return DN_FRAGMENT_RX_TOO_MUCH;
    }
    memcpy(&rx->body[rx->len], &data[2], chunk);
    rx->len = (uint8_t)(rx->len + chunk);
    if (type != DN_FRAG_LAST)
        return DN_FRAGMENT_RX_TAKEN;
    rx->active = false;
    return DN_FRAGMENT_RX_COMPLETE;
}

uint8_t dn_fragment_ack_frame(uint8_t header, uint8_t count, uint8_t status, uint8_t frame[8])
{
    frame[0] = (uint8_t)(header | DN_HDR_FRAG);
    frame[1] = (uint8_t)(DN_FRAG_ACK | count);
    frame[2] = status;
    return 3;
}
