/* SPDX-License-Identifier: Apache-2.0 */
/* The LSS vocabulary both sides use (co_lss.h): the frame layout, bit timing table 0 and the
 * names of the command specifiers. */
#include "co/co_lss.h"

#include <string.h>

/* CiA 305 bit timing table 0, kbit/s by index; 5 is reserved, 9 is automatic detection. */
static const uint16_t table0_kbit[CO_LSS_BIT_TIMING_INDEX_MAX + 1] = {1000, 800, 500, 250, 125,
                                                                      0,    50,  20,  10,  0};

uint16_t co_lss_bit_rate_kbit(uint8_t index)
{
    return index <= CO_LSS_BIT_TIMING_INDEX_MAX ? table0_kbit[index] : 0;
}

uint8_t co_lss_bit_timing_index(uint16_t kbit)
{
    uint8_t i = 0;
    while (i <= CO_LSS_BIT_TIMING_INDEX_MAX && (kbit == 0 || table0_kbit[i] != kbit))
        i++;
    return i;
}

void co_lss_frame(co_frame_t *frame, uint32_t id, uint8_t cs, const uint8_t *data, size_t len)
{
    memset(frame, 0, sizeof(*frame));
    frame->id = id;
    frame->len = CO_LSS_FRAME_LEN;
    frame->data[0] = cs;
    if (len > 0)
        memcpy(&frame->data[1], data, len);
}

const char *co_lss_cs_name(uint8_t cs)
{
    switch (cs) {
    case CO_LSS_CS_SWITCH_GLOBAL:
        return "switch state global";
    case CO_LSS_CS_CONFIGURE_NODE_ID:
        return "configure node-ID";
    case CO_LSS_CS_CONFIGURE_BIT_TIMING:
        return "configure bit timing";
    case CO_LSS_CS_ACTIVATE_BIT_TIMING:
        return "activate bit timing";
    case CO_LSS_CS_STORE:
        return "store configuration";
    case CO_LSS_CS_SWITCH_SELECTIVE_VENDOR:
        return "switch state selective vendor-ID";
    case CO_LSS_CS_SWITCH_SELECTIVE_PRODUCT:
        return "switch state selective product code";
    case CO_LSS_CS_SWITCH_SELECTIVE_REVISION:
        return "switch state selective revision";
    case CO_LSS_CS_SWITCH_SELECTIVE_SERIAL:
        return "switch state selective serial";
    case CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE:
        return "switch state selective response";
    case CO_LSS_CS_IDENTIFY_VENDOR:
        return "identify remote slave vendor-ID";
    case CO_LSS_CS_IDENTIFY_PRODUCT:
        return "identify remote slave product code";
    case CO_LSS_CS_IDENTIFY_REVISION_LOW:
        return "identify remote slave revision low";
    case CO_LSS_CS_IDENTIFY_REVISION_HIGH:
        return "identify remote slave revision high";
    case CO_LSS_CS_IDENTIFY_SERIAL_LOW:
        return "identify remote slave serial low";
    case CO_LSS_CS_IDENTIFY_SERIAL_HIGH:
        return "identify remote slave serial high";
    case CO_LSS_CS_IDENTIFY_NON_CONFIGURED:
        return "identify non-configured remote slave";
    case CO_LSS_CS_IDENTIFY_SLAVE:
        return "identify slave";
    case CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE:
        return "identify non-configured slave";
    case CO_LSS_CS_FASTSCAN:
        return "fastscan";
    case CO_LSS_CS_INQUIRE_VENDOR:
        return "inquire vendor-ID";
    case CO_LSS_CS_INQUIRE_PRODUCT:
        return "inquire product code";
    case CO_LSS_CS_INQUIRE_REVISION:
        return "inquire revision";
    case CO_LSS_CS_INQUIRE_SERIAL:
        return "inquire serial";
    case CO_LSS_CS_INQUIRE_NODE_ID:
        return "inquire node-ID";
    default:
        return NULL;
    }
}
