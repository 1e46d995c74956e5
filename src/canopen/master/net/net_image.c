/* SPDX-License-Identifier: Apache-2.0 */
/* The network master's process image: the slaves' TPDOs into the input image, the output image
 * to their RPDOs, at once when bytes change and after each SYNC the master produces
 * (docs/net-master.md, "Process image"). */
#include "canopen/master/net/net_floors.h"

#include <string.h>

bool co_net_image_receive(co_net_master_t *m, const co_frame_t *frame)
{
    bool used = false;
    for (size_t p = 0; p < m->config.input_count; p++) {
        const co_net_pdo_t *pdo = &m->config.inputs[p];
        /* CiA 301: a PDO shorter than its mapping is not used; a longer one is (its first bytes
         * are the mapped ones). */
        if (pdo->can_id != frame->id || frame->len < pdo->len)
            continue;
        memcpy(m->config.input_image + pdo->offset, frame->data, pdo->len);
        co_net_report(m, CO_NET_EVENT_INPUT, pdo->node_id, p);
        used = true;
    }
    return used;
}

static void send_output(co_net_master_t *m, size_t p)
{
    const co_net_pdo_t *pdo = &m->config.outputs[p];
    co_frame_t frame = {.id = pdo->can_id, .len = pdo->len};
    memcpy(frame.data, m->config.output_image + pdo->offset, pdo->len);
    co_net_send(m, &frame);
}

/* A master that stopped all nodes is Stopped itself: no PDO. */
static bool output_live(const co_net_master_t *m, size_t p)
{
    size_t i = co_net_slave_index(m, m->config.outputs[p].node_id);
    return m->config.slave_state[i].step == CO_NET_STEP_OPERATIONAL && !m->stopped_all;
}

/* Nor SYNC while it is Stopped: its period goes on, unsent. */
void co_net_image_sync(co_net_master_t *m)
{
    co_frame_t frame;
    if (!co_sync_producer_take(&m->sync, m->now, &frame) || m->stopped_all)
        return;
    co_net_send(m, &frame);
    for (size_t p = 0; p < m->config.output_count; p++) {
        if (output_live(m, p))
            send_output(m, p);
    }
}

/* Sends output PDO `p` with the bytes offset..offset+len replaced by `data`, when they change
 * its content (the image itself is updated after every PDO was looked at). */
static void send_changed_output(co_net_master_t *m, size_t p, size_t offset, const uint8_t *data,
                                size_t len)
{
    const co_net_pdo_t *pdo = &m->config.outputs[p];
    co_frame_t frame = {.id = pdo->can_id, .len = pdo->len};
    memcpy(frame.data, m->config.output_image + pdo->offset, pdo->len);
    bool changed = false;
    for (size_t k = 0; k < pdo->len; k++) {
        size_t at = (size_t)pdo->offset + k;
        if (at >= offset && at < offset + len && frame.data[k] != data[at - offset]) {
            frame.data[k] = data[at - offset];
            changed = true;
        }
    }
    if (changed)
        co_net_send(m, &frame);
}

bool co_net_master_write_output(co_net_master_t *master, size_t offset, const uint8_t *data,
                                size_t len)
{
    if (data == NULL || master->config.output_image == NULL ||
        offset > master->config.output_size || len > master->config.output_size - offset)
        return false;
    for (size_t p = 0; p < master->config.output_count; p++) {
        if (output_live(master, p))
            send_changed_output(master, p, offset, data, len);
    }
    memcpy(master->config.output_image + offset, data, len);
    return true;
}
