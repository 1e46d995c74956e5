/* SPDX-License-Identifier: Apache-2.0 */
/* The texts of the CIP vocabulary (cip_text.h): service names as the CIP specification spells
 * them, the general status codes of its appendix, the classes of dn_cip.h. */
#include "trace/cip_text.h"

#include <stddef.h>

#include "dn/dn_cip.h"

typedef struct code_text {
    uint8_t code;
    const char *text;
} code_text_t;

static const char *lookup(const code_text_t *table, size_t count, uint8_t code)
{
    for (size_t i = 0; i < count; i++) {
        if (table[i].code == code)
            return table[i].text;
    }
    return NULL;
}

#define LOOKUP(table, code) lookup(table, sizeof(table) / sizeof((table)[0]), code)

const char *cip_service_name(uint8_t service)
{
    static const code_text_t services[] = {
        {DN_SVC_GET_ATTRIBUTES_ALL, "Get_Attributes_All"},
        {DN_SVC_RESET, "Reset"},
        {DN_SVC_APPLY_ATTRIBUTES, "Apply_Attributes"},
        {DN_SVC_GET_ATTRIBUTE_SINGLE, "Get_Attribute_Single"},
        {DN_SVC_SET_ATTRIBUTE_SINGLE, "Set_Attribute_Single"},
        {DN_SVC_ERROR_RESPONSE, "Error_Response"},
        {DN_SVC_ALLOCATE, "Allocate_Master/Slave_Connection_Set"},
        {DN_SVC_RELEASE, "Release_Group_2_Identifier_Set"},
    };
    return LOOKUP(services, service & DN_SERVICE_CODE);
}

/* The general status codes 00h-29h of the CIP specification's appendix. */
const char *cip_general_status_text(uint8_t status)
{
    static const code_text_t statuses[] = {
        {DN_GS_SUCCESS, "success"},
        {0x01, "connection failure"},
        {DN_GS_RESOURCE_UNAVAILABLE, "resource unavailable"},
        {0x03, "invalid parameter value"},
        {0x04, "path segment error"},
        {DN_GS_PATH_DESTINATION_UNKNOWN, "path destination unknown"},
        {0x06, "partial transfer"},
        {0x07, "connection lost"},
        {DN_GS_SERVICE_NOT_SUPPORTED, "service not supported"},
        {DN_GS_INVALID_ATTRIBUTE_VALUE, "invalid attribute value"},
        {0x0A, "attribute list error"},
        {DN_GS_ALREADY_IN_STATE, "already in requested mode/state"},
        {DN_GS_OBJECT_STATE_CONFLICT, "object state conflict"},
        {0x0D, "object already exists"},
        {DN_GS_ATTRIBUTE_NOT_SETTABLE, "attribute not settable"},
        {0x0F, "privilege violation"},
        {DN_GS_DEVICE_STATE_CONFLICT, "device state conflict"},
        {DN_GS_REPLY_DATA_TOO_LARGE, "reply data too large"},
        {0x12, "fragmentation of a primitive value"},
        {DN_GS_NOT_ENOUGH_DATA, "not enough data"},
        {DN_GS_ATTRIBUTE_NOT_SUPPORTED, "attribute not supported"},
        {DN_GS_TOO_MUCH_DATA, "too much data"},
        {DN_GS_OBJECT_DOES_NOT_EXIST, "object does not exist"},
        {0x17, "service fragmentation sequence not in progress"},
        {0x18, "no stored attribute data"},
        {DN_GS_STORE_OPERATION_FAILURE, "store operation failure"},
        {0x1A, "routing failure, request packet too large"},
        {0x1B, "routing failure, response packet too large"},
        {0x1C, "missing attribute list entry data"},
        {0x1D, "invalid attribute value list"},
        {0x1E, "embedded service error"},
        {DN_GS_VENDOR_SPECIFIC, "vendor specific error"},
        {DN_GS_INVALID_PARAMETER, "invalid parameter"},
        {0x21, "write-once value or medium already written"},
        {0x22, "invalid reply received"},
        {0x25, "key failure in path"},
        {0x26, "path size invalid"},
        {0x27, "unexpected attribute in list"},
        {0x28, "invalid member ID"},
        {0x29, "member not settable"},
    };
    const char *text = LOOKUP(statuses, status);
    return text ? text : "reserved";
}

const char *cip_class_name(uint8_t class_id)
{
    static const code_text_t classes[] = {
        {DN_CLASS_IDENTITY, "Identity"},
        {DN_CLASS_MESSAGE_ROUTER, "Message router"},
        {DN_CLASS_DEVICENET, "DeviceNet"},
        {DN_CLASS_ASSEMBLY, "Assembly"},
        {DN_CLASS_CONNECTION, "Connection"},
        {DN_CLASS_MOTOR_DATA, "Motor data"},
        {DN_CLASS_CONTROL_SUPERVISOR, "Control supervisor"},
        {DN_CLASS_AC_DC_DRIVE, "AC/DC drive"},
        {DN_CLASS_ACK_HANDLER, "Acknowledge handler"},
    };
    return LOOKUP(classes, class_id);
}
