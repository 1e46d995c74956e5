/* PDO engine: RPDOs and TPDOs configured by 1400h/1600h/1800h/1A00h, their transmission types,
 * inhibit and event timers, SYNC start value, change-of-state detection and the CiA 301 dynamic
 * mapping procedure (CiA 301 section 7.2.2). */
#ifndef CO_PDO_H
#define CO_PDO_H

#include "co_config.h"
#include "co_od.h"

typedef struct co_rpdo {
    uint8_t state;
} co_rpdo_t;

typedef struct co_tpdo {
    uint8_t state;
} co_tpdo_t;

typedef struct co_pdo {
    co_rpdo_t rpdo[CO_CONFIG_RPDO_MAX];
    co_tpdo_t tpdo[CO_CONFIG_TPDO_MAX];
} co_pdo_t;

void co_pdo_reset(co_node_t *node);
bool co_pdo_receive(co_node_t *node, const co_frame_t *frame);
co_time_t co_pdo_process(co_node_t *node, co_time_t now);
uint32_t co_pdo_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len);
/* Called by the SYNC consumer for every SYNC received or produced (counter 0 when none). */
void co_pdo_sync(co_node_t *node, uint8_t counter);

#endif
