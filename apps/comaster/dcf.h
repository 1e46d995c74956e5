/* SPDX-License-Identifier: Apache-2.0 */
/* A slave of comaster's network as its DCF describes it (docs/comaster.md "Network description"):
 * the identity checks and error control the DCF implies, and its configuration (the
 * ParameterValue entries) as the writes of the boot, in file order, a PDO's as one group
 * (docs/decisions.md, D-DCF-PDO). Below the network (network.c), which lays the slaves' PDOs out
 * in its process image. */
#ifndef COMASTER_DCF_H
#define COMASTER_DCF_H

#include "co/co_net_master.h"
#include "eds/eds_reader.h"

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define COMASTER_NAME_MAX 64u

typedef struct comaster_slave {
    char name[COMASTER_NAME_MAX];
    char dcf_path[PATH_MAX];
    eds_t dcf;
    /* The DCF's configuration in file order, a PDO's as one group: the slave's concise DCF (CiA
     * 302's 1F22h), which its co_net_slave_config_t points at. */
    uint8_t *concise;
    size_t concise_len;
} comaster_slave_t;

/* Reads the DCF `path` of node `node_id` into s (named `name`) and what it implies into c: the
 * identity to check, the error control to start, the configuration as a concise DCF; the other
 * members of c are the defaults. Returns 0, or EX_NOINPUT (the file cannot be read) / EX_DATAERR
 * (anything wrong in it) / EX_OSERR with a one-line message naming the file, the line or the key. s
 * holds what it read either way: comaster_slave_free frees it. */
int comaster_slave_load(comaster_slave_t *s, co_net_slave_config_t *c, uint8_t node_id,
                        const char *name, const char *path, char *err, size_t err_len);

void comaster_slave_free(comaster_slave_t *s);

/* The value of the DCF's entry index:sub (its ParameterValue, else its DefaultValue); *found
 * false, and 0, when it has none. */
uint32_t comaster_dcf_u32(const eds_t *dcf, uint16_t index, uint8_t sub, bool *found);

#endif
