/* SPDX-License-Identifier: Apache-2.0 */
/* The drive's CIP classes, as the Altivar 312 DeviceNet manual lists them ("Supported CIP
 * objects"): Motor data 0x28, Control supervisor 0x29, AC/DC drive 0x2A and the application
 * objects that reach every parameter by its address. Each reads and writes the drive's
 * dictionary, as the card's requests do; a refusal of the drive is answered with its CIP status
 * (drive_dn_cip_status). */
#include "co/co_cia301.h"
#include "drive/devicenet/drive_dn_internal.h"

#define CLASS_REVISION 1u /* class attribute 1 of 0x28, 0x29 and the application objects */
#define INSTANCE 1u

uint16_t drive_dn_cip_status(uint32_t abort_code)
{
    switch (abort_code) {
    case 0:
        return DN_OK;
    case CO_SDO_ABORT_NO_OBJECT:
    case CO_SDO_ABORT_NO_SUBINDEX:
    case CO_SDO_ABORT_WRITE_ONLY:
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SUPPORTED);
    case CO_SDO_ABORT_READ_ONLY:
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
    case CO_SDO_ABORT_LENGTH_HIGH:
        return DN_ERROR(DN_GS_TOO_MUCH_DATA);
    case CO_SDO_ABORT_TYPE_LENGTH:
    case CO_SDO_ABORT_LENGTH_LOW:
        return DN_ERROR(DN_GS_NOT_ENOUGH_DATA);
    case CO_SDO_ABORT_VALUE_RANGE:
    case CO_SDO_ABORT_VALUE_HIGH:
    case CO_SDO_ABORT_VALUE_LOW:
    case CO_SDO_ABORT_MAX_LESS_MIN:
    case CO_SDO_ABORT_PARAM_INCOMPATIBLE:
    case CO_SDO_ABORT_INTERNAL_INCOMPATIBLE:
        return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
    case CO_SDO_ABORT_DATA_STATE:
    case CO_SDO_ABORT_DATA_LOCAL:
        return DN_ERROR(DN_GS_DEVICE_STATE_CONFLICT);
    case CO_SDO_ABORT_HARDWARE:
    case CO_SDO_ABORT_DATA_STORE:
        return DN_ERROR(DN_GS_STORE_OPERATION_FAILURE);
    default:
        return DN_ERROR(DN_GS_VENDOR_SPECIFIC);
    }
}

/* A dictionary entry read into the reply as it is stored (little-endian, its own size). */
static dn_status_t reply_entry(drive_t *drive, uint16_t index, uint8_t subindex, dn_reply_t *reply)
{
    const co_od_entry_t *entry;
    uint32_t abort_code = co_od_read_check(&drive->node, index, subindex, &entry);
    if (abort_code != 0)
        return drive_dn_cip_status(abort_code);
    dn_reply_bytes(reply, co_od_bytes(&drive->node, entry), co_od_length(&drive->node, entry));
    return DN_OK;
}

static dn_status_t write_entry(drive_t *drive, uint16_t index, uint8_t subindex,
                               const dn_request_t *request)
{
    return drive_dn_cip_status(
        co_od_write(&drive->node, index, subindex, request->data, request->len, CO_OD_ORIGIN_CARD));
}

static bool is_get(const dn_request_t *request)
{
    return request->service == DN_SVC_GET_ATTRIBUTE_SINGLE;
}

/* The services of every class here: Get_Attribute_Single and Set_Attribute_Single, and the
 * Control supervisor's Reset. */
static bool is_attribute_service(const dn_request_t *request)
{
    return request->service == DN_SVC_GET_ATTRIBUTE_SINGLE ||
           request->service == DN_SVC_SET_ATTRIBUTE_SINGLE;
}

/* ---- Motor data 0x28 ---- */

#define MOTOR_TYPE 3u
#define RATED_CURRENT 6u /* 100 mA: the drive's nominal current NCR, 0.1 A */
#define RATED_VOLTAGE 7u /* V */

static const dn_attribute_t motor_attributes[] = {
    {0, 1, DN_GET, 0},
    {INSTANCE, MOTOR_TYPE, DN_GET_SET, 1},
    {INSTANCE, RATED_CURRENT, DN_GET_SET, 2},
    {INSTANCE, RATED_VOLTAGE, DN_GET_SET, 2},
};

/* A motor data attribute is the drive's parameter (NCR, UnS): its limits and its rules. */
static dn_status_t param_access(drive_t *drive, drive_param_t param, const dn_request_t *request,
                                dn_reply_t *reply)
{
    return is_get(request) ? reply_entry(drive, param.index, param.subindex, reply)
                           : write_entry(drive, param.index, param.subindex, request);
}

static dn_status_t motor_handler(dn_node_t *node, const dn_object_t *object,
                                 const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    drive_dn_t *dn = object->user;
    if (!is_attribute_service(request))
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0) {
        dn_reply_u16(reply, CLASS_REVISION);
        return DN_OK;
    }
    switch (request->attribute) {
    case MOTOR_TYPE:
        if (is_get(request)) {
            dn_reply_u8(reply, dn->profile->motor_type);
            return DN_OK;
        }
        /* One motor type: the drive's asynchronous motor. */
        return request->data[0] == dn->profile->motor_type
                   ? DN_OK
                   : DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
    case RATED_CURRENT:
        return param_access(dn->drive, dn->drive->profile->nominal_current, request, reply);
    default:
        return param_access(dn->drive, dn->profile->rated_voltage, request, reply);
    }
}

/* ---- Control supervisor 0x29 ---- */

#define RUN1 3u
#define RUN2 4u
#define NET_CTRL 5u
#define STATE 6u
#define RUNNING1 7u
#define RUNNING2 8u
#define READY 9u
#define FAULTED 10u
#define WARNING 11u
#define FAULT_RST 12u
#define CTRL_FROM_NET 15u

static const dn_attribute_t supervisor_attributes[] = {
    {0, 1, DN_GET, 0},
    {INSTANCE, RUN1, DN_GET_SET, 1},
    {INSTANCE, RUN2, DN_GET_SET, 1},
    {INSTANCE, NET_CTRL, DN_GET_SET, 1},
    {INSTANCE, STATE, DN_GET, 0},
    {INSTANCE, RUNNING1, DN_GET, 0},
    {INSTANCE, RUNNING2, DN_GET, 0},
    {INSTANCE, READY, DN_GET, 0},
    {INSTANCE, FAULTED, DN_GET, 0},
    {INSTANCE, WARNING, DN_GET, 0},
    {INSTANCE, FAULT_RST, DN_GET_SET, 1},
    {INSTANCE, CTRL_FROM_NET, DN_GET, 0},
};

static uint8_t supervisor_value(const drive_dn_t *dn, uint8_t attribute)
{
    drive_dn_state_t state = drive_dn_state(dn);
    switch (attribute) {
    case RUN1:
        return dn->command.run1;
    case RUN2:
        return dn->command.run2;
    case NET_CTRL:
        return dn->command.net_ctrl;
    case STATE:
        return (uint8_t)state;
    case RUNNING1:
        return drive_dn_running1(state);
    case READY:
        return drive_dn_ready(state);
    case FAULTED:
        return drive_dn_faulted(dn->drive);
    case WARNING:
        return drive_dn_warning(dn->drive);
    case FAULT_RST:
        return dn->command.fault_reset;
    case CTRL_FROM_NET:
        return drive_dn_control_from_net(dn->drive);
    default: /* Running2: always 0, the reverse is the negative actual speed */
        return 0;
    }
}

/* A BOOL attribute of the command set: `flag` is its field in `next`, a copy of the command.
 * The caller picks the field by its own class's attribute number, since the numbers repeat across
 * classes (Run2 and NetRef are both attribute 4). */
static dn_status_t set_flag(drive_dn_t *dn, drive_dn_command_t *next, bool *flag, uint8_t value)
{
    if (value > 1)
        return DN_ERROR(DN_GS_INVALID_ATTRIBUTE_VALUE);
    *flag = value != 0;
    drive_dn_command(dn, next);
    return DN_OK;
}

/* The Control supervisor's settable BOOLs (Run1, Run2, NetCtrl, FaultRst). */
static dn_status_t supervisor_set(drive_dn_t *dn, uint8_t attribute, uint8_t value)
{
    drive_dn_command_t next = dn->command;
    bool *flag = attribute == RUN1       ? &next.run1
                 : attribute == RUN2     ? &next.run2
                 : attribute == NET_CTRL ? &next.net_ctrl
                                         : &next.fault_reset;
    return set_flag(dn, &next, flag, value);
}

/* Reset (the project's reading of the ODVA service, docs/decisions.md, D-DEVICENET-SUPERVISOR-
 * RESET): Run1 and Run2 off (the drive stops) and a fault reset, back to the start-up command. */
static dn_status_t supervisor_reset(drive_dn_t *dn)
{
    drive_dn_command_t next = dn->command;
    next.run1 = next.run2 = false;
    next.fault_reset = true;
    drive_dn_command(dn, &next);
    next.fault_reset = false;
    drive_dn_command(dn, &next);
    return DN_OK;
}

static dn_status_t supervisor_handler(dn_node_t *node, const dn_object_t *object,
                                      const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    drive_dn_t *dn = object->user;
    if (request->service == DN_SVC_RESET && request->instance == INSTANCE)
        return supervisor_reset(dn);
    if (!is_attribute_service(request))
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0) {
        dn_reply_u16(reply, CLASS_REVISION);
        return DN_OK;
    }
    if (!is_get(request))
        return supervisor_set(dn, request->attribute, request->data[0]);
    dn_reply_u8(reply, supervisor_value(dn, request->attribute));
    return DN_OK;
}

/* ---- AC/DC drive 0x2A: no class attribute ---- */

#define AT_REFERENCE 3u
#define NET_REF 4u
#define DRIVE_MODE 6u
#define SPEED_ACTUAL 7u
#define SPEED_REF 8u
#define REF_FROM_NET 29u
#define DRIVE_MODE_VENDOR 0u /* "Vendor specific mode" */

static const dn_attribute_t drive_attributes[] = {
    {INSTANCE, AT_REFERENCE, DN_GET, 0},  {INSTANCE, NET_REF, DN_GET_SET, 1},
    {INSTANCE, DRIVE_MODE, DN_GET, 0},    {INSTANCE, SPEED_ACTUAL, DN_GET, 0},
    {INSTANCE, SPEED_REF, DN_GET_SET, 2}, {INSTANCE, REF_FROM_NET, DN_GET, 0},
};

static dn_status_t drive_get(const drive_dn_t *dn, uint8_t attribute, dn_reply_t *reply)
{
    switch (attribute) {
    case AT_REFERENCE:
        dn_reply_u8(reply, drive_dn_at_reference(dn->drive));
        break;
    case NET_REF:
        dn_reply_u8(reply, dn->command.net_ref);
        break;
    case DRIVE_MODE:
        dn_reply_u8(reply, DRIVE_MODE_VENDOR);
        break;
    case SPEED_ACTUAL:
        dn_reply_u16(reply, (uint16_t)drive_dn_speed_actual(dn->drive));
        break;
    case SPEED_REF:
        dn_reply_u16(reply, (uint16_t)dn->command.speed_reference);
        break;
    default:
        dn_reply_u8(reply, drive_dn_reference_from_net(dn->drive));
        break;
    }
    return DN_OK;
}

static dn_status_t drive_handler(dn_node_t *node, const dn_object_t *object,
                                 const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    drive_dn_t *dn = object->user;
    if (!is_attribute_service(request))
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (is_get(request))
        return drive_get(dn, request->attribute, reply);
    drive_dn_command_t next = dn->command;
    if (request->attribute == NET_REF)
        return set_flag(dn, &next, &next.net_ref, request->data[0]);
    next.speed_reference = (int16_t)co_get_u16(request->data);
    drive_dn_command(dn, &next);
    return DN_OK;
}

/* ---- Application objects: every parameter by its address ---- */

static dn_status_t parameter_handler(dn_node_t *node, const dn_object_t *object,
                                     const dn_request_t *request, dn_reply_t *reply)
{
    (void)node;
    drive_dn_t *dn = object->user;
    const drive_dn_profile_t *p = dn->profile;
    if (!is_attribute_service(request))
        return DN_ERROR(DN_GS_SERVICE_NOT_SUPPORTED);
    if (request->instance == 0) {
        if (request->attribute != 1)
            return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SUPPORTED);
        if (!is_get(request))
            return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SETTABLE);
        dn_reply_u16(reply, CLASS_REVISION);
        return DN_OK;
    }
    if (request->attribute == 0 || request->attribute > p->addresses_per_class)
        return DN_ERROR(DN_GS_ATTRIBUTE_NOT_SUPPORTED);
    uint32_t offset = (uint32_t)(request->class_id - p->class_first) * p->addresses_per_class +
                      request->attribute - 1u;
    uint16_t index = (uint16_t)(p->index_first + offset / p->addresses_per_index);
    uint8_t subindex = (uint8_t)(offset % p->addresses_per_index + 1u);
    return is_get(request) ? reply_entry(dn->drive, index, subindex, reply)
                           : write_entry(dn->drive, index, subindex, request);
}

#define COUNT(table) ((uint8_t)(sizeof(table) / sizeof((table)[0])))

void drive_dn_objects(drive_dn_t *dn, dn_object_t objects[DRIVE_DN_OBJECT_COUNT])
{
    objects[0] =
        (dn_object_t){DN_CLASS_MOTOR_DATA, DN_CLASS_MOTOR_DATA, INSTANCE, COUNT(motor_attributes),
                      motor_attributes,    motor_handler,       dn};
    objects[1] = (dn_object_t){DN_CLASS_CONTROL_SUPERVISOR,
                               DN_CLASS_CONTROL_SUPERVISOR,
                               INSTANCE,
                               COUNT(supervisor_attributes),
                               supervisor_attributes,
                               supervisor_handler,
                               dn};
    objects[2] =
        (dn_object_t){DN_CLASS_AC_DC_DRIVE, DN_CLASS_AC_DC_DRIVE, INSTANCE, COUNT(drive_attributes),
                      drive_attributes,     drive_handler,        dn};
    objects[3] = (dn_object_t){dn->profile->class_first,
                               dn->profile->class_last,
                               INSTANCE,
                               0,
                               NULL,
                               parameter_handler,
                               dn};
}
