/* SPDX-License-Identifier: Apache-2.0 */
/* DeviceNet identifiers: the message groups taken apart, the predefined set of a MAC ID. */
#include "dn/dn_link.h"

dn_can_id_t dn_can_id_decode(uint32_t can_id)
{
    dn_can_id_t id = {0, 0, 0};
    if (can_id < DN_GROUP2_BASE) {
        id.group = 1;
        id.message_id = (uint8_t)(can_id >> 6);
        id.mac_id = (uint8_t)(can_id & DN_MAC_ID_MAX);
    } else if (can_id < DN_GROUP3_BASE) {
        id.group = 2;
        id.mac_id = (uint8_t)((can_id >> 3) & DN_MAC_ID_MAX);
        id.message_id = (uint8_t)(can_id & 7u);
    } else if (can_id < DN_GROUP4_BASE) {
        id.group = 3;
        id.message_id = (uint8_t)((can_id >> 6) & 7u);
        id.mac_id = (uint8_t)(can_id & DN_MAC_ID_MAX);
    } else if (can_id <= DN_GROUP4_END) {
        id.group = 4;
        id.message_id = (uint8_t)(can_id - DN_GROUP4_BASE);
    }
    return id;
}

dn_predefined_ids_t dn_predefined_ids(uint8_t mac_id)
{
    dn_predefined_ids_t ids;
    ids.poll_command = dn_group2_id(mac_id, DN_G2_MASTER_POLL_COS_CYCLIC);
    ids.explicit_request = dn_group2_id(mac_id, DN_G2_MASTER_EXPLICIT_REQUEST);
    ids.explicit_response = dn_group2_id(mac_id, DN_G2_SLAVE_EXPLICIT_RESPONSE);
    ids.unconnected = dn_group2_id(mac_id, DN_G2_UNCONNECTED_REQUEST);
    ids.duplicate_mac = dn_group2_id(mac_id, DN_G2_DUPLICATE_MAC_CHECK);
    ids.cos_ack = dn_group2_id(mac_id, DN_G2_MASTER_COS_CYCLIC_ACK);
    ids.poll_response = dn_group1_id(DN_G1_SLAVE_POLL_RESPONSE, mac_id);
    ids.cos_cyclic = dn_group1_id(DN_G1_SLAVE_COS_CYCLIC, mac_id);
    return ids;
}
