/* SPDX-License-Identifier: Apache-2.0 */
/* The message router: finds the object of a request among the library's classes and then the
 * application's table, checks the instance and, for Get/Set_Attribute_Single, the attribute
 * against the object's table, then hands the request to the object's handler. */
#include "devicenet/slave/dn_slave.h"

/* Binary search of the application's classes, sorted by class_first (dn_node_init checks). */
static const dn_object_t *application_object(const dn_config_t *config, uint8_t class_id)
{
    size_t low = 0, high = config->object_count;
    while (low < high) {
        size_t mid = (low + high) / 2;
        const dn_object_t *o = &config->objects[mid];
        if (class_id < o->class_first)
            high = mid;
        else if (class_id > o->class_last)
            low = mid + 1;
        else
            return o;
    }
    return NULL;
}

/* The attribute's entry, its instance's own before the one every instance has; *level_known
 * says whether the level (class or instance) has any attribute. */
static const dn_attribute_t *find_attribute(const dn_object_t *object, uint8_t instance, uint8_t id,
                                            bool *level_known)
{
    const dn_attribute_t *every = NULL;
    *level_known = false;
    for (uint8_t i = 0; i < object->attribute_count; i++) {
        const dn_attribute_t *a = &object->attributes[i];
        bool class_entry = a->instance == 0;
        if (class_entry != (instance == 0))
            continue;
        if (a->instance != instance && a->instance != DN_EVERY_INSTANCE)
            continue;
        *level_known = true;
        if (a->id != id)
            continue;
        if (a->instance == instance)
            return a;
        every = a;
    }
    return every;
}

static dn_status_t check_attribute(const dn_object_t *object, const dn_request_t *request)
{
    bool level_known;
    const dn_attribute_t *a =
        find_attribute(object, request->instance, request->attribute, &level_known);
    if (a == NULL)
        return DN_ERROR(level_known ? DN_GS_ATTRIBUTE_NOT_SUPPORTED : DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->service == DN_SVC_GET_ATTRIBUTE_SINGLE)
        return request->len ? DN_ERROR(DN_GS_TOO_MUCH_DATA) : DN_OK;
    if (!(a->access & DN_SET))
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
    if (a->size && request->len < a->size)
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    if (a->size && request->len > a->size)
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    return DN_OK;
}

dn_status_t dn_route(dn_node_t *node, const dn_request_t *request, dn_reply_t *reply)
{
    const dn_object_t *object = dn_standard_object(request->class_id);
    if (object == NULL)
        object = application_object(node->config, request->class_id);
    if (object == NULL || request->instance > object->max_instance)
        return DN_ERROR(DN_GS_OBJECT_DOES_NOT_EXIST);
    bool attribute_service = request->service == DN_SVC_GET_ATTRIBUTE_SINGLE ||
                             request->service == DN_SVC_SET_ATTRIBUTE_SINGLE;
    if (attribute_service && object->attributes != NULL) {
        dn_status_t status = check_attribute(object, request);
        if (status != DN_OK)
            return status;
    }
    dn_status_t status = object->handler(node, object, request, reply);
    if (status == DN_OK && reply->overflow)
        return DN_ERROR(DN_GS_REPLY_DATA_TOO_LARGE);
    return status;
}
