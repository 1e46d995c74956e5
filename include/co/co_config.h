/* SPDX-License-Identifier: Apache-2.0 */
/* Compile-time sizes of the core. Every array in a node is sized here, so a node's RAM is known at
 * build time; override any of them with -D on the compiler command line, for instance to the PDOs
 * of a firmware's one dictionary (co_node_init refuses a dictionary with more: CO_NODE_ERR_TABLES).
 * The core's library and everything including co_node.h must see the same values. */
#ifndef CO_CONFIG_H
#define CO_CONFIG_H

#ifndef CO_CONFIG_RPDO_MAX
#define CO_CONFIG_RPDO_MAX 8 /* RPDOs a node can have (1400h..) */
#endif
#ifndef CO_CONFIG_TPDO_MAX
#define CO_CONFIG_TPDO_MAX 8 /* TPDOs a node can have (1800h..) */
#endif
#ifndef CO_CONFIG_PDO_MAP_MAX
#define CO_CONFIG_PDO_MAP_MAX 8 /* mapping entries per PDO (sub 1..8) */
#endif
#ifndef CO_CONFIG_HB_CONSUMERS
#define CO_CONFIG_HB_CONSUMERS 8 /* heartbeat consumers (1016h sub 1..) */
#endif
#ifndef CO_CONFIG_EMCY_HISTORY
#define CO_CONFIG_EMCY_HISTORY 8 /* active errors remembered by the EMCY producer */
#endif
#ifndef CO_CONFIG_EMCY_QUEUE
#define CO_CONFIG_EMCY_QUEUE 4 /* EMCY frames waiting for the inhibit time (1015h) */
#endif
#ifndef CO_CONFIG_SDO_BUFFER
/* Each node's own SDO transfer buffer, used when the application gives none
 * (co_node_config_t.sdo_buffer): its largest segmented or block transfer, bytes. 0 removes it from
 * co_node_t, and every node then needs an application buffer, which several nodes may share. */
#define CO_CONFIG_SDO_BUFFER 1024
#endif
#ifndef CO_CONFIG_SDO_SERVERS_MAX
/* Most additional SDO server channels (1201h..) a node may be given (co_sdo_servers_t): they size
 * the consumed COB-ID list (co_consumers.h), not co_node_t; CiA 301 allows up to 127. */
#define CO_CONFIG_SDO_SERVERS_MAX 8
#endif
#ifndef CO_CONFIG_SDO_CLIENTS_MAX
/* Most SDO client channels (1280h..) a node may be given (co_sdo_clients_t): they size the
 * consumed COB-ID list (co_consumers.h), not co_node_t; CiA 301 allows up to 128. */
#define CO_CONFIG_SDO_CLIENTS_MAX 4
#endif
#ifndef CO_CONFIG_STORE_VALUE_MAX
#define CO_CONFIG_STORE_VALUE_MAX 64 /* largest stored value checked at a reset, bytes */
#endif
#ifndef CO_CONFIG_SDO_TIMEOUT_US
#define CO_CONFIG_SDO_TIMEOUT_US 1000000u /* default SDO server timeout */
#endif

#endif
