/* SDO server: expedited, segmented and block transfers (CiA 301 section 7.2.4) on the default SDO
 * channel 0x600+id / 0x580+id, with the protocol timeout and the complete set of abort codes. */
#ifndef CO_SDO_H
#define CO_SDO_H

#include "co_config.h"
#include "co_od.h"

typedef struct co_sdo_server {
    uint8_t state;
    uint16_t index;
    uint8_t subindex;
    co_time_t timeout_us; /* protocol timeout, restarted by every received frame */
    co_time_t deadline;
    uint8_t buffer[CO_CONFIG_SDO_BUFFER];
} co_sdo_server_t;

void co_sdo_reset(co_node_t *node);
bool co_sdo_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_sdo_process(co_node_t *node, co_time_t now);
uint32_t co_sdo_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);

/* Sets the server's protocol timeout (default CO_CONFIG_SDO_TIMEOUT_US). */
void co_sdo_set_timeout(co_node_t *node, co_time_t timeout_us);

#endif
