/* SPDX-License-Identifier: Apache-2.0 */
/* The meaning of each SDO abort code (CiA 301 section 7.2.4.3.17, table 22). */
#include "co/co_types.h"

const char *co_sdo_abort_text(uint32_t code)
{
    switch (code) {
    case CO_SDO_ABORT_TOGGLE:
        return "toggle bit not alternated";
    case CO_SDO_ABORT_TIMEOUT:
        return "SDO protocol timed out";
    case CO_SDO_ABORT_COMMAND:
        return "client/server command specifier not valid or unknown";
    case CO_SDO_ABORT_BLOCK_SIZE:
        return "invalid block size";
    case CO_SDO_ABORT_SEQUENCE:
        return "invalid sequence number";
    case CO_SDO_ABORT_CRC:
        return "CRC error";
    case CO_SDO_ABORT_NO_MEMORY:
        return "out of memory";
    case CO_SDO_ABORT_UNSUPPORTED_ACCESS:
        return "unsupported access to an object";
    case CO_SDO_ABORT_WRITE_ONLY:
        return "attempt to read a write only object";
    case CO_SDO_ABORT_READ_ONLY:
        return "attempt to write a read only object";
    case CO_SDO_ABORT_NO_OBJECT:
        return "object does not exist in the object dictionary";
    case CO_SDO_ABORT_NOT_MAPPABLE:
        return "object cannot be mapped to the PDO";
    case CO_SDO_ABORT_PDO_LENGTH:
        return "number and length of the objects to be mapped would exceed the PDO length";
    case CO_SDO_ABORT_PARAM_INCOMPATIBLE:
        return "general parameter incompatibility";
    case CO_SDO_ABORT_INTERNAL_INCOMPATIBLE:
        return "general internal incompatibility in the device";
    case CO_SDO_ABORT_HARDWARE:
        return "access failed due to a hardware error";
    case CO_SDO_ABORT_TYPE_LENGTH:
        return "data type does not match, length of service parameter does not match";
    case CO_SDO_ABORT_LENGTH_HIGH:
        return "data type does not match, length of service parameter too high";
    case CO_SDO_ABORT_LENGTH_LOW:
        return "data type does not match, length of service parameter too low";
    case CO_SDO_ABORT_NO_SUBINDEX:
        return "sub-index does not exist";
    case CO_SDO_ABORT_VALUE_RANGE:
        return "invalid value for parameter";
    case CO_SDO_ABORT_VALUE_HIGH:
        return "value of parameter written too high";
    case CO_SDO_ABORT_VALUE_LOW:
        return "value of parameter written too low";
    case CO_SDO_ABORT_MAX_LESS_MIN:
        return "maximum value is less than minimum value";
    case CO_SDO_ABORT_NO_RESOURCE:
        return "resource not available: SDO connection";
    case CO_SDO_ABORT_GENERAL:
        return "general error";
    case CO_SDO_ABORT_DATA_STORE:
        return "data cannot be transferred or stored to the application";
    case CO_SDO_ABORT_DATA_LOCAL:
        return "data cannot be transferred or stored to the application because of local control";
    case CO_SDO_ABORT_DATA_STATE:
        return "data cannot be transferred or stored to the application because of the present "
               "device state";
    case CO_SDO_ABORT_OD_MISSING:
        return "object dictionary dynamic generation fails or no object dictionary is present";
    case CO_SDO_ABORT_NO_DATA:
        return "no data available";
    default:
        return "unknown abort code";
    }
}
