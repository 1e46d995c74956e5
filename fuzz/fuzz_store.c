/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of the storage file loader: the input is a whole `--store` file. It goes
 * through co_file_store_parse; in a file that passes, every LSS record must read back through
 * co_file_store_get_lss as a node-id 1..127 or FFh and a bit timing of table 0, and the file is
 * bound as the storage of an ATV312 drive of the first record keyed by a node-id (1..127; an
 * unconfigured node's key, 80h + k, or a DeviceNet MAC ID 0 is none), whose boot applies the
 * images (co_store_apply through the file store's callbacks), and that drive is then reset by NMT
 * and compared with a fresh one on the same file (rig.h has the invariants). Each input is tried
 * as is, then with its CRC-32 made right: a mutation almost never keeps the CRC valid, and the
 * record checks and the images behind it are what needs fuzzing. Seeds: fuzz/seeds.py. */
#include "co/co_lss.h"
#include "co_linux/file_store.h"
#include "co_linux/log.h"
#include "rig.h"

#include <stdlib.h>
#include <string.h>

static rig_t rig, fresh;

static void load(const uint8_t *data, size_t size)
{
    co_file_store_t store = {0};
    char reason[sizeof store.reason];
    if (!co_file_store_parse(data, size, &store.records, &store.count, reason, sizeof reason)) {
        rig_check(reason[0] != '\0', "a file refused without a reason");
        return;
    }
    for (size_t i = 0; i < store.count; i++) {
        uint8_t key = store.records[i].node_id, node_id, bit_timing;
        bool lss = co_file_store_get_lss(&store, key, &node_id, &bit_timing);
        rig_check(lss || store.records[i].area != CO_FILE_STORE_AREA_LSS,
                  "an LSS record co_file_store_get_lss does not find");
        rig_check(!lss || ((node_id >= 1 && node_id <= CO_NODE_ID_MAX) ||
                           node_id == CO_LSS_NODE_ID_UNCONFIGURED),
                  "a stored LSS node-id outside 1..127 and FFh");
        rig_check(!lss || bit_timing <= CO_LSS_BIT_TIMING_INDEX_MAX,
                  "a stored LSS bit timing beyond table 0");
    }
    /* A record's key may be an unconfigured node's (80h + k, an LSS-stored node-id:
     * docs/atv312d.md), which no drive starts with: the first keyed by a node-id is bound. */
    size_t first = 0;
    while (first < store.count &&
           !(store.records[first].node_id >= 1 && store.records[first].node_id <= CO_NODE_ID_MAX))
        first++;
    if (first < store.count) {
        co_file_store_node_t node, fresh_node;
        co_storage_t storage, fresh_storage;
        uint8_t node_id = store.records[first].node_id;
        co_file_store_bind(&store, node_id, &node, &storage);
        co_file_store_bind(&store, node_id, &fresh_node, &fresh_storage);
        rig_start(&rig, node_id, &storage, 0);
        rig_check_reset(&rig, &fresh, &fresh_storage);
        co_file_store_unbind(&node);
        co_file_store_unbind(&fresh_node);
    }
    co_file_store_close(&store);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Refused stored values are logged as warnings: formatted, not printed millions of times. */
    co_log_setup("fuzz_store", CO_LOG_ERROR);
    load(data, size);
    if (size < CO_FILE_STORE_CRC_SIZE)
        return 0;
    uint8_t *file = malloc(size);
    rig_check(file != NULL, "out of memory");
    size_t covered = size - CO_FILE_STORE_CRC_SIZE;
    memcpy(file, data, covered);
    co_put_u32(file + covered, co_crc32(file, covered));
    load(file, size);
    free(file);
    return 0;
}
