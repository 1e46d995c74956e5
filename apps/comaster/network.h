/* SPDX-License-Identifier: Apache-2.0 */
/* The network description of comaster run and boot (docs/comaster.md "Network description"): the
 * master's options from an INI file ([Master], [NodeN]), the slaves from the CiA 306-3 nodelist
 * (.cpj) it names, each read from its DCF (dcf.c: its configuration and identity), and the
 * process image of their PDOs with its variables (the names of the objects the PDOs map). Turned
 * into the core's co_net_master_config_t. No bus: tests/comaster tests it on files. */
#ifndef COMASTER_NETWORK_H
#define COMASTER_NETWORK_H

#include "co/co_net_master.h"
#include "comaster/dcf.h"

#include <net/if.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The PLC300's 512 bytes of network input and of output markers. */
#define COMASTER_IMAGE_SIZE 512u
/* PDOs of one direction: at most one per byte of the image. */
#define COMASTER_PDO_MAX COMASTER_IMAGE_SIZE
#define COMASTER_VARIABLE_MAX COMASTER_IMAGE_SIZE
#define COMASTER_CONTROL_PATH_MAX 108u /* sockaddr_un.sun_path */
/* comaster_network_t.bit_rate when [Master] gives none. */
#define COMASTER_BIT_RATE_NONE 0xFFu

/* One object a PDO maps, at its place in the input or output image. */
typedef struct comaster_variable {
    const char *name; /* the DCF's Denotation, else its ParameterName (owned by the slave's DCF) */
    uint8_t node_id;
    uint16_t index;
    uint8_t sub;
    uint16_t data_type;
    bool output; /* in an RPDO of the slave: written by the master */
    uint16_t offset;
    uint8_t size; /* bytes */
} comaster_variable_t;

typedef struct comaster_network {
    char net_name[COMASTER_NAME_MAX];
    char iface[IFNAMSIZ];                    /* [Master] interface, "" when not given */
    char control[COMASTER_CONTROL_PATH_MAX]; /* [Master] control, "" when not given */
    /* [Master] bit_rate, the PLC300's code (CO_NET_BIT_RATE_*), or COMASTER_BIT_RATE_NONE: what
     * the run reports as its bit rate marker; the interface's own is ip link's. */
    uint8_t bit_rate;
    size_t slave_count;
    comaster_slave_t slave[CO_NMT_MASTER_NODE_ID_MAX];
    co_net_slave_config_t slave_config[CO_NMT_MASTER_NODE_ID_MAX];
    co_net_slave_t slave_state[CO_NMT_MASTER_NODE_ID_MAX];
    co_net_pdo_t input_pdo[COMASTER_PDO_MAX];
    co_net_pdo_t output_pdo[COMASTER_PDO_MAX];
    uint8_t input_image[COMASTER_IMAGE_SIZE];
    uint8_t output_image[COMASTER_IMAGE_SIZE];
    comaster_variable_t variable[COMASTER_VARIABLE_MAX];
    size_t variable_count;
    /* Everything but send, user and event, which the program fills in. */
    co_net_master_config_t config;
} comaster_network_t;

/* Reads the INI file `path` ([Master] cpj=... and the options) into `net`, which holds no network
 * (new, or after comaster_network_free), the nodelist it names and every
 * DCF the nodelist names (paths relative to the file naming them). Returns 0, or EX_NOINPUT (a
 * file cannot be read) / EX_DATAERR (anything wrong in them) with a one-line message naming the
 * file, the line or the key. */
int comaster_network_load(comaster_network_t *net, const char *path, char *err, size_t err_len);

/* A network of one slave, node `node_id` configured by the DCF `dcf_path`, with the defaults of
 * every option (comaster boot). Same results. */
int comaster_network_single(comaster_network_t *net, uint8_t node_id, const char *dcf_path,
                            char *err, size_t err_len);

void comaster_network_free(comaster_network_t *net);

/* The variables of node `node_id` for `name` (a Denotation, a ParameterName or its first word, or
 * INDEX:SUB): *first is the first one, the result their count (an object mapped by two PDOs is
 * two variables). 0 with a one-line reason in err when there is none. */
size_t comaster_network_find(const comaster_network_t *net, uint8_t node_id, const char *name,
                             const comaster_variable_t **first, char *err, size_t err_len);

#endif
