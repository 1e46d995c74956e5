/* EMCY producer: 1014h COB-ID, 1015h inhibit time, 1001h error register, 1003h pre-defined error
 * field (history), and the application API to raise and clear errors (CiA 301 section 7.2.7). */
#ifndef CO_EMCY_H
#define CO_EMCY_H

#include "co_config.h"
#include "co_od.h"

/* Error register 1001h bits (CiA 301 table 48). */
#define CO_ERR_REG_GENERIC 0x01u
#define CO_ERR_REG_CURRENT 0x02u
#define CO_ERR_REG_VOLTAGE 0x04u
#define CO_ERR_REG_TEMPERATURE 0x08u
#define CO_ERR_REG_COMMUNICATION 0x10u
#define CO_ERR_REG_PROFILE 0x20u
#define CO_ERR_REG_MANUFACTURER 0x80u

/* Emergency error codes used by the stack (CiA 301 table 21). */
enum co_emcy_code {
    CO_EMCY_NO_ERROR = 0x0000,
    CO_EMCY_GENERIC = 0x1000,
    CO_EMCY_CAN_OVERRUN = 0x8110,
    CO_EMCY_CAN_PASSIVE = 0x8120,
    CO_EMCY_HEARTBEAT = 0x8130, /* life guard or heartbeat error */
    CO_EMCY_BUS_OFF = 0x8140,   /* recovered from bus-off */
    CO_EMCY_PDO_LENGTH = 0x8210,
    CO_EMCY_PDO_LENGTH_EXCEEDED = 0x8220,
    CO_EMCY_SYNC_LENGTH = 0x8240,
    CO_EMCY_RPDO_TIMEOUT = 0x8250
};

typedef struct co_emcy_error {
    uint16_t code;
    uint8_t reg;
} co_emcy_error_t;

typedef struct co_emcy {
    co_emcy_error_t active[CO_CONFIG_EMCY_HISTORY];
    uint8_t active_count;
} co_emcy_t;

void co_emcy_reset(co_node_t *node);
co_time_t co_emcy_process(co_node_t *node, co_time_t now);
uint32_t co_emcy_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                          size_t len);

/* Raises an error: sets the register bits, records it in 1003h and sends the EMCY frame
 * (subject to the inhibit time). msef may be NULL (five zero bytes). Raising an error that is
 * already active does nothing. */
void co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg, const uint8_t msef[5]);
/* Clears an active error; when the last one clears, the "error reset" EMCY (code 0) is sent. */
void co_emcy_clear(co_node_t *node, uint16_t code);
bool co_emcy_is_active(const co_node_t *node, uint16_t code);

#endif
