/* SPDX-License-Identifier: Apache-2.0 */
/* A test object dictionary shaped like the Altivar 312's (its communication objects, PDO1/PDO6,
 * the CiA 402 words, ACC/DEC, LCR/OTR), plus 2000h: one test object of every data type, limits,
 * a write-only entry and long strings for segmented and block transfers; 6040h and 6042h are
 * process data, 6046h:01 a view of 2000:06 (x 10) and 6046h:02 a plain profile parameter. Unlike
 * the ATV312's it has 1006h/1007h (a SYNC producer), 1012h/1013h (TIME, 1012h = 100h: neither
 * consumed nor produced), a writable 1014h and the dummy types 0002h..0007h. Hand-written so the
 * core tests do not depend on the EDS generator. */
#ifndef TEST_OD_H
#define TEST_OD_H

#include "co/co_od.h"

extern const co_od_t test_od;

/* test_od without the entries of one index, for the rules that depend on an optional object being
 * absent (a dictionary without 1006h, say); the data block is laid out as test_od's. The result
 * lives in static storage that the next call overwrites. */
const co_od_t *test_od_without(uint16_t index);

/* test_od with the parameters of two additional SDO servers (co_sdo_servers_t): 1201h valid,
 * 690h client -> server and 6A0h server -> client, and 1202h with both COB-IDs 80000000h (not
 * valid); sub-index 3 of each, the client's node-id, 0. Its data block is test_od's followed by
 * theirs. Static storage, built once. */
const co_od_t *test_od_with_sdo_servers(void);

/* test_od with two SDO client parameters (co_sdo_clients_t): 1280h valid, 605h client -> server,
 * 585h server -> client, server node-id 5, and 1281h with both COB-IDs 80000000h (not valid),
 * server node-id 6. Laid out as test_od_with_sdo_servers's. Static storage, built once. */
const co_od_t *test_od_with_sdo_clients(void);

/* A hook on 2000:10 that refuses every write with CO_SDO_ABORT_DATA_LOCAL, and counts reads. */
extern unsigned test_od_hook_reads;

#endif
