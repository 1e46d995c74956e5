/* SPDX-License-Identifier: Apache-2.0 */
/* What several floors of the slave reach of the application: the frames they send, the I/O
 * events, the assembly table and the store of the stored values. The slave's lowest floor, so
 * that the connections and the objects reach them without calling up to the node. */
#include "devicenet/common/frame_send.h"
#include "devicenet/slave/dn_slave.h"

void dn_send(dn_node_t *node, uint16_t can_id, const uint8_t *data, uint8_t len)
{
    const dn_app_t *app = node->config->app;
    dn_frame_send(app->send, app->user, can_id, data, len);
}

void dn_io_event(dn_node_t *node, dn_io_event_t event)
{
    const dn_app_t *app = node->config->app;
    if (app->io_event)
        app->io_event(app->user, event);
}

const dn_assembly_t *dn_node_assembly(const dn_node_t *node, uint16_t instance)
{
    for (uint8_t i = 0; i < node->config->assembly_count; i++)
        if (node->config->assemblies[i].instance == instance)
            return &node->config->assemblies[i];
    return NULL;
}

/* Keeps a new value of a stored attribute through the application, or refuses it (0x19). */
dn_status_t dn_store(dn_node_t *node, const dn_stored_t *stored)
{
    const dn_app_t *app = node->config->app;
    if (app->store == NULL || !app->store(app->user, stored))
        return DN_ERROR(DN_GS_STORE_OPERATION_FAILURE);
    node->stored = *stored;
    return DN_OK;
}
