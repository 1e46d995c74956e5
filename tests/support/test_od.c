/* SPDX-License-Identifier: Apache-2.0 */
#include "test_od.h"

#include "co/co_sync.h"

#include <stddef.h>
#include <string.h>

/* Every value is a byte array in CANopen (little-endian) order, so the struct has no padding. */
typedef struct test_od_data {
    uint8_t x1000[4], x1001[1], x1003_0[1], x1003[5][4], x1005[4], x1006[4], x1007[4];
    uint8_t x1008[6], x100a[4], x100b[4], x100c[2], x100d[1], x100e[4];
    uint8_t x1010_0[1], x1010[4][4], x1011_0[1], x1011[4][4], x1012[4], x1013[4], x1014[4],
        x1015[2];
    uint8_t x1016_0[1], x1016[2][4], x1017[2], x1018_0[1], x1018[4][4], x1019[1];
    uint8_t x1029_0[1], x1029[2][1];
    uint8_t x1200_0[1], x1200[2][4];
    uint8_t x1400_0[1], x1400_1[4], x1400_2[1];
    uint8_t x1405_0[1], x1405_1[4], x1405_2[1], x1405_5[2];
    uint8_t x1600_0[1], x1600[1][4], x1605_0[1], x1605[4][4];
    uint8_t x1800_0[1], x1800_1[4], x1800_2[1], x1800_3[2], x1800_4[1], x1800_5[2];
    uint8_t x1805_0[1], x1805_1[4], x1805_2[1], x1805_3[2], x1805_4[1], x1805_5[2], x1805_6[1];
    uint8_t x1a00_0[1], x1a00[1][4], x1a05_0[1], x1a05[4][4];
    uint8_t x2000_0[1], i8[1], i16[2], i32[4], i64[8], u8lim[1], u16lim[2], u32[4], u64[8];
    uint8_t r32[4], boolean[1], wo[4], vstring[32], ostring[200], i16lim[2], u16zero[2];
    uint8_t hooked[2], r64[8], bigstring[1000];
    uint8_t x2002_0[1], lcr[2], otr[2], x203c_0[1], acc[2], dec[2];
    uint8_t x1f80[4];
    uint8_t x6040[2], x6041[2], x6042[2], x6044[2], x6046_0[1], x6046[2][4];
} test_od_data_t;

#define U8(v)                                                                                      \
    {                                                                                              \
        (uint8_t)(v)                                                                               \
    }
#define U16(v)                                                                                     \
    {                                                                                              \
        (uint8_t)(v), (uint8_t)((v) >> 8)                                                          \
    }
#define U32(v)                                                                                     \
    {                                                                                              \
        (uint8_t)(v), (uint8_t)((v) >> 8), (uint8_t)((v) >> 16), (uint8_t)((v) >> 24)              \
    }

static const test_od_data_t defaults = {
    .x1000 = U32(0x00010192),
    .x1003_0 = U8(0),
    .x1005 = U32(0x80),
    .x1008 = "ATV312",
    .x100a = "0301",
    .x100e = U32(0x700),
    .x1010_0 = U8(4),
    .x1010 = {U32(1), U32(1), U32(1), U32(1)},
    .x1011_0 = U8(4),
    .x1011 = {U32(1), U32(1), U32(1), U32(1)},
    .x1012 = U32(0x100),
    .x1014 = U32(0x80),
    .x1016_0 = U8(2),
    .x1018_0 = U8(4),
    .x1018 = {U32(0x5F), U32(0x312), U32(0x00010002), U32(0x12345678)},
    .x1029_0 = U8(2),
    .x1200_0 = U8(2),
    .x1200 = {U32(0x600), U32(0x580)},
    .x1400_0 = U8(2),
    .x1400_1 = U32(0x200),
    .x1400_2 = U8(255),
    .x1405_0 = U8(5),
    .x1405_1 = U32(0x80000300),
    .x1405_2 = U8(255),
    .x1600_0 = U8(1),
    .x1600 = {U32(0x60400010)},
    .x1605_0 = U8(2),
    .x1605 = {U32(0x60400010), U32(0x60420010), U32(0), U32(0)},
    .x1800_0 = U8(5),
    .x1800_1 = U32(0x180),
    .x1800_2 = U8(255),
    .x1800_3 = U16(300),
    .x1800_5 = U16(100),
    .x1805_0 = U8(6),
    .x1805_1 = U32(0x80000280),
    .x1805_2 = U8(255),
    .x1805_3 = U16(300),
    .x1805_5 = U16(100),
    .x1a00_0 = U8(1),
    .x1a00 = {U32(0x60410010)},
    .x1a05_0 = U8(2),
    .x1a05 = {U32(0x60410010), U32(0x60440010), U32(0), U32(0)},
    .x1f80 = U32(0x04),
    .x2000_0 = U8(0x12),
    .u8lim = U8(50),
    .u16lim = U16(1000),
    .vstring = "short",
    .u16zero = U16(0),
    .x2002_0 = U8(9),
    .x203c_0 = U8(3),
    .acc = U16(30),
    .dec = U16(30),
    .x6046_0 = U8(2),
    .x6046 = {U32(10000), U32(1500)},
};

#define E(idx, sub, type, flags, field, limits, hook)                                              \
    {                                                                                              \
        idx, sub, type, flags, sizeof(((test_od_data_t *)0)->field),                               \
            offsetof(test_od_data_t, field), limits, hook                                          \
    }

#define RO CO_OD_ACCESS_RO
#define RW CO_OD_ACCESS_RW
#define WO CO_OD_ACCESS_WO
#define CONST CO_OD_ACCESS_CONST
#define RWR (CO_OD_ACCESS_RW | CO_OD_TPDO)
#define RWW (CO_OD_ACCESS_RW | CO_OD_RPDO)
#define ROT (CO_OD_ACCESS_RO | CO_OD_TPDO)
#define NID CO_OD_NODEID

static const co_od_limits_t lim_u8 = {10, 200};
static const co_od_limits_t lim_u16 = {100, 5000};
static const co_od_limits_t lim_i16 = {(uint64_t)-100, 100};
static const co_od_limits_t lim_min_100 = {100, 65535};
static const co_od_limits_t lim_0_4 = {0, 4};

unsigned test_od_hook_reads;

static uint32_t refuse_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                             size_t len, co_od_origin_t origin)
{
    (void)node;
    (void)entry;
    (void)data;
    (void)len;
    (void)origin;
    return CO_SDO_ABORT_DATA_LOCAL;
}

static uint32_t count_read(co_node_t *node, const co_od_entry_t *entry)
{
    (void)node;
    (void)entry;
    test_od_hook_reads++;
    return 0;
}

static const co_od_hook_t hook_refuse = {refuse_write, count_read};

/* 6046h:01 is a view of 2000:06 (u16lim) x 10, like the ATV312's 6046h of LSP/HSP. */
#define VIEW_SCALE 10u

static uint32_t view_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len, co_od_origin_t origin)
{
    (void)entry, (void)len, (void)origin;
    uint32_t value = co_get_u32(data) / VIEW_SCALE;
    uint8_t raw[2];
    co_put_u16(raw, (uint16_t)(value > UINT16_MAX ? UINT16_MAX : value));
    uint32_t abort = co_od_write(node, 0x2000, 0x06, raw, sizeof(raw), CO_OD_ORIGIN_APP);
    return abort == CO_SDO_OK ? CO_OD_HANDLED : abort;
}

static uint32_t view_read(co_node_t *node, const co_od_entry_t *entry)
{
    co_od_set(node, entry, co_od_value(node, 0x2000, 0x06) * VIEW_SCALE);
    return CO_SDO_OK;
}

static const co_od_hook_t hook_view = {view_write, view_read};

static const co_od_entry_t entries[] = {
    E(0x1000, 0, CO_DT_UNSIGNED32, RO, x1000, NULL, NULL),
    E(0x1001, 0, CO_DT_UNSIGNED8, ROT, x1001, NULL, NULL),
    E(0x1003, 0, CO_DT_UNSIGNED8, RW, x1003_0, NULL, NULL),
    E(0x1003, 1, CO_DT_UNSIGNED32, RO, x1003[0], NULL, NULL),
    E(0x1003, 2, CO_DT_UNSIGNED32, RO, x1003[1], NULL, NULL),
    E(0x1003, 3, CO_DT_UNSIGNED32, RO, x1003[2], NULL, NULL),
    E(0x1003, 4, CO_DT_UNSIGNED32, RO, x1003[3], NULL, NULL),
    E(0x1003, 5, CO_DT_UNSIGNED32, RO, x1003[4], NULL, NULL),
    E(0x1005, 0, CO_DT_UNSIGNED32, RW, x1005, NULL, NULL),
    E(0x1006, 0, CO_DT_UNSIGNED32, RW, x1006, NULL, NULL),
    E(0x1007, 0, CO_DT_UNSIGNED32, RW, x1007, NULL, NULL),
    E(0x1008, 0, CO_DT_VISIBLE_STRING, CONST, x1008, NULL, NULL),
    E(0x100A, 0, CO_DT_VISIBLE_STRING, CONST, x100a, NULL, NULL),
    E(0x100B, 0, CO_DT_UNSIGNED32, RO | NID, x100b, NULL, NULL),
    E(0x100C, 0, CO_DT_UNSIGNED16, RW, x100c, NULL, NULL),
    E(0x100D, 0, CO_DT_UNSIGNED8, RW, x100d, NULL, NULL),
    E(0x100E, 0, CO_DT_UNSIGNED32, RW | NID, x100e, NULL, NULL),
    E(0x1010, 0, CO_DT_UNSIGNED8, RO, x1010_0, NULL, NULL),
    E(0x1010, 1, CO_DT_UNSIGNED32, RW, x1010[0], NULL, NULL),
    E(0x1010, 2, CO_DT_UNSIGNED32, RW, x1010[1], NULL, NULL),
    E(0x1010, 3, CO_DT_UNSIGNED32, RW, x1010[2], NULL, NULL),
    E(0x1010, 4, CO_DT_UNSIGNED32, RW, x1010[3], NULL, NULL),
    E(0x1011, 0, CO_DT_UNSIGNED8, RO, x1011_0, NULL, NULL),
    E(0x1011, 1, CO_DT_UNSIGNED32, RW, x1011[0], NULL, NULL),
    E(0x1011, 2, CO_DT_UNSIGNED32, RW, x1011[1], NULL, NULL),
    E(0x1011, 3, CO_DT_UNSIGNED32, RW, x1011[2], NULL, NULL),
    E(0x1011, 4, CO_DT_UNSIGNED32, RW, x1011[3], NULL, NULL),
    E(0x1012, 0, CO_DT_UNSIGNED32, RW, x1012, NULL, NULL),
    E(0x1013, 0, CO_DT_UNSIGNED32, RW, x1013, NULL, NULL),
    E(0x1014, 0, CO_DT_UNSIGNED32, RW | NID, x1014, NULL, NULL),
    E(0x1015, 0, CO_DT_UNSIGNED16, RW, x1015, NULL, NULL),
    E(0x1016, 0, CO_DT_UNSIGNED8, RO, x1016_0, NULL, NULL),
    E(0x1016, 1, CO_DT_UNSIGNED32, RW, x1016[0], NULL, NULL),
    E(0x1016, 2, CO_DT_UNSIGNED32, RW, x1016[1], NULL, NULL),
    E(0x1017, 0, CO_DT_UNSIGNED16, RW, x1017, NULL, NULL),
    E(0x1018, 0, CO_DT_UNSIGNED8, RO, x1018_0, NULL, NULL),
    E(0x1018, 1, CO_DT_UNSIGNED32, RO, x1018[0], NULL, NULL),
    E(0x1018, 2, CO_DT_UNSIGNED32, RO, x1018[1], NULL, NULL),
    E(0x1018, 3, CO_DT_UNSIGNED32, RO, x1018[2], NULL, NULL),
    E(0x1018, 4, CO_DT_UNSIGNED32, RO, x1018[3], NULL, NULL),
    E(0x1019, 0, CO_DT_UNSIGNED8, RW, x1019, NULL, NULL),
    E(0x1029, 0, CO_DT_UNSIGNED8, RO, x1029_0, NULL, NULL),
    E(0x1029, 1, CO_DT_UNSIGNED8, RW, x1029[0], NULL, NULL),
    E(0x1029, 2, CO_DT_UNSIGNED8, RW, x1029[1], NULL, NULL),
    E(0x1200, 0, CO_DT_UNSIGNED8, RO, x1200_0, NULL, NULL),
    E(0x1200, 1, CO_DT_UNSIGNED32, RO | NID, x1200[0], NULL, NULL),
    E(0x1200, 2, CO_DT_UNSIGNED32, RO | NID, x1200[1], NULL, NULL),
    E(0x1400, 0, CO_DT_UNSIGNED8, RO, x1400_0, NULL, NULL),
    E(0x1400, 1, CO_DT_UNSIGNED32, RW | NID, x1400_1, NULL, NULL),
    E(0x1400, 2, CO_DT_UNSIGNED8, RO, x1400_2, NULL, NULL),
    E(0x1405, 0, CO_DT_UNSIGNED8, RO, x1405_0, NULL, NULL),
    E(0x1405, 1, CO_DT_UNSIGNED32, RW | NID, x1405_1, NULL, NULL),
    E(0x1405, 2, CO_DT_UNSIGNED8, RW, x1405_2, NULL, NULL),
    E(0x1405, 5, CO_DT_UNSIGNED16, RW, x1405_5, NULL, NULL),
    E(0x1600, 0, CO_DT_UNSIGNED8, RO, x1600_0, NULL, NULL),
    E(0x1600, 1, CO_DT_UNSIGNED32, RO, x1600[0], NULL, NULL),
    E(0x1605, 0, CO_DT_UNSIGNED8, RW, x1605_0, &lim_0_4, NULL),
    E(0x1605, 1, CO_DT_UNSIGNED32, RW, x1605[0], NULL, NULL),
    E(0x1605, 2, CO_DT_UNSIGNED32, RW, x1605[1], NULL, NULL),
    E(0x1605, 3, CO_DT_UNSIGNED32, RW, x1605[2], NULL, NULL),
    E(0x1605, 4, CO_DT_UNSIGNED32, RW, x1605[3], NULL, NULL),
    E(0x1800, 0, CO_DT_UNSIGNED8, RO, x1800_0, NULL, NULL),
    E(0x1800, 1, CO_DT_UNSIGNED32, RW | NID, x1800_1, NULL, NULL),
    E(0x1800, 2, CO_DT_UNSIGNED8, RO, x1800_2, NULL, NULL),
    E(0x1800, 3, CO_DT_UNSIGNED16, RW | CO_OD_ZERO_OK, x1800_3, &lim_min_100, NULL),
    E(0x1800, 4, CO_DT_UNSIGNED8, RW, x1800_4, NULL, NULL),
    E(0x1800, 5, CO_DT_UNSIGNED16, RW, x1800_5, NULL, NULL),
    E(0x1805, 0, CO_DT_UNSIGNED8, RO, x1805_0, NULL, NULL),
    E(0x1805, 1, CO_DT_UNSIGNED32, RW | NID, x1805_1, NULL, NULL),
    E(0x1805, 2, CO_DT_UNSIGNED8, RW, x1805_2, NULL, NULL),
    E(0x1805, 3, CO_DT_UNSIGNED16, RW | CO_OD_ZERO_OK, x1805_3, &lim_min_100, NULL),
    E(0x1805, 4, CO_DT_UNSIGNED8, RW, x1805_4, NULL, NULL),
    E(0x1805, 5, CO_DT_UNSIGNED16, RW, x1805_5, NULL, NULL),
    E(0x1805, 6, CO_DT_UNSIGNED8, RW, x1805_6, NULL, NULL),
    E(0x1A00, 0, CO_DT_UNSIGNED8, RO, x1a00_0, NULL, NULL),
    E(0x1A00, 1, CO_DT_UNSIGNED32, RO, x1a00[0], NULL, NULL),
    E(0x1A05, 0, CO_DT_UNSIGNED8, RW, x1a05_0, &lim_0_4, NULL),
    E(0x1A05, 1, CO_DT_UNSIGNED32, RW, x1a05[0], NULL, NULL),
    E(0x1A05, 2, CO_DT_UNSIGNED32, RW, x1a05[1], NULL, NULL),
    E(0x1A05, 3, CO_DT_UNSIGNED32, RW, x1a05[2], NULL, NULL),
    E(0x1A05, 4, CO_DT_UNSIGNED32, RW, x1a05[3], NULL, NULL),
    E(0x1F80, 0, CO_DT_UNSIGNED32, RW, x1f80, NULL, NULL),
    E(0x2000, 0x00, CO_DT_UNSIGNED8, RO, x2000_0, NULL, NULL),
    E(0x2000, 0x01, CO_DT_INTEGER8, RWR, i8, NULL, NULL),
    E(0x2000, 0x02, CO_DT_INTEGER16, RWR, i16, NULL, NULL),
    E(0x2000, 0x03, CO_DT_INTEGER32, RWR, i32, NULL, NULL),
    E(0x2000, 0x04, CO_DT_INTEGER64, RW, i64, NULL, NULL),
    E(0x2000, 0x05, CO_DT_UNSIGNED8, RWW, u8lim, &lim_u8, NULL),
    E(0x2000, 0x06, CO_DT_UNSIGNED16, RW, u16lim, &lim_u16, NULL),
    E(0x2000, 0x07, CO_DT_UNSIGNED32, RW | CO_OD_TPDO | CO_OD_RPDO, u32, NULL, NULL),
    E(0x2000, 0x08, CO_DT_UNSIGNED64, RW, u64, NULL, NULL),
    E(0x2000, 0x09, CO_DT_REAL32, RW, r32, NULL, NULL),
    E(0x2000, 0x0A, CO_DT_BOOLEAN, RW, boolean, NULL, NULL),
    E(0x2000, 0x0B, CO_DT_UNSIGNED32, WO | CO_OD_RPDO, wo, NULL, NULL),
    E(0x2000, 0x0C, CO_DT_VISIBLE_STRING, RW, vstring, NULL, NULL),
    E(0x2000, 0x0D, CO_DT_OCTET_STRING, RW, ostring, NULL, NULL),
    E(0x2000, 0x0E, CO_DT_INTEGER16, RW, i16lim, &lim_i16, NULL),
    E(0x2000, 0x0F, CO_DT_UNSIGNED16, RW | CO_OD_ZERO_OK, u16zero, &lim_min_100, NULL),
    E(0x2000, 0x10, CO_DT_UNSIGNED16, RW, hooked, NULL, &hook_refuse),
    E(0x2000, 0x11, CO_DT_REAL64, RW, r64, NULL, NULL),
    E(0x2000, 0x12, CO_DT_VISIBLE_STRING, RW, bigstring, NULL, NULL),
    E(0x2002, 0x00, CO_DT_UNSIGNED8, RO, x2002_0, NULL, NULL),
    E(0x2002, 0x04, CO_DT_UNSIGNED16, ROT, lcr, NULL, NULL),
    E(0x2002, 0x09, CO_DT_UNSIGNED16, ROT, otr, NULL, NULL),
    E(0x203C, 0x00, CO_DT_UNSIGNED8, RO, x203c_0, NULL, NULL),
    E(0x203C, 0x02, CO_DT_UNSIGNED16, RWW, acc, NULL, NULL),
    E(0x203C, 0x03, CO_DT_UNSIGNED16, RWW, dec, NULL, NULL),
    E(0x6040, 0x00, CO_DT_UNSIGNED16, RWW | CO_OD_PROCESS, x6040, NULL, NULL),
    E(0x6041, 0x00, CO_DT_UNSIGNED16, ROT, x6041, NULL, NULL),
    E(0x6042, 0x00, CO_DT_INTEGER16, RWW | CO_OD_PROCESS, x6042, NULL, NULL),
    E(0x6044, 0x00, CO_DT_INTEGER16, ROT, x6044, NULL, NULL),
    E(0x6046, 0x00, CO_DT_UNSIGNED8, RO, x6046_0, NULL, NULL),
    E(0x6046, 0x01, CO_DT_UNSIGNED32, RW, x6046[0], NULL, &hook_view),
    E(0x6046, 0x02, CO_DT_UNSIGNED32, RW, x6046[1], NULL, NULL),
};

#define ENTRY_COUNT (sizeof(entries) / sizeof(entries[0]))

const co_od_t test_od = {
    .name = "test",
    .entries = entries,
    .count = ENTRY_COUNT,
    .data_size = sizeof(test_od_data_t),
    .defaults = (const uint8_t *)&defaults,
    .dummy_types = CO_OD_DUMMY(CO_DT_INTEGER8) | CO_OD_DUMMY(CO_DT_INTEGER16) |
                   CO_OD_DUMMY(CO_DT_INTEGER32) | CO_OD_DUMMY(CO_DT_UNSIGNED8) |
                   CO_OD_DUMMY(CO_DT_UNSIGNED16) | CO_OD_DUMMY(CO_DT_UNSIGNED32),
    .sync_producer = co_sync_produce,
};

const co_od_t *test_od_without(uint16_t index)
{
    static co_od_entry_t kept[ENTRY_COUNT];
    static co_od_t od;
    uint16_t count = 0;
    for (size_t i = 0; i < ENTRY_COUNT; i++) {
        if (entries[i].index != index)
            kept[count++] = entries[i];
    }
    od = test_od;
    od.entries = kept;
    od.count = count;
    if (index == 0x1006) /* as the generator leaves it out */
        od.sync_producer = NULL;
    return &od;
}

/* Two SDO parameter records (1201h/1202h or 1280h/1281h): sub-index 0 (3), the two COB-IDs, the
 * other side's node-id. */
typedef struct sdo_param_data {
    uint8_t sub0[1], cob_id[2][4], node_id[1];
} sdo_param_data_t;

#define SDO_PARAM_ENTRIES 4u

/* A dictionary built once in `built`: test_od with two SDO parameter records at `first` and
 * `first` + 1, right after 1200h:02 (and 1201h.. when first is 1280h, which the test dictionary
 * lacks), their data after test_od's. */
typedef struct with_records {
    co_od_entry_t all[ENTRY_COUNT + 2 * SDO_PARAM_ENTRIES];
    uint8_t data_defaults[sizeof(test_od_data_t) + 2 * sizeof(sdo_param_data_t)];
    co_od_t od;
} with_records_t;

static const co_od_t *with_sdo_records(with_records_t *built, uint16_t first,
                                       const sdo_param_data_t records[2])
{
    static const uint8_t types[SDO_PARAM_ENTRIES] = {CO_DT_UNSIGNED8, CO_DT_UNSIGNED32,
                                                     CO_DT_UNSIGNED32, CO_DT_UNSIGNED8};
    static const uint32_t offsets[SDO_PARAM_ENTRIES] = {
        offsetof(sdo_param_data_t, sub0), offsetof(sdo_param_data_t, cob_id[0]),
        offsetof(sdo_param_data_t, cob_id[1]), offsetof(sdo_param_data_t, node_id)};
    uint16_t count = 0;
    for (size_t i = 0; i < ENTRY_COUNT; i++) {
        built->all[count++] = entries[i];
        if (entries[i].index != 0x1200 || entries[i].subindex != 2)
            continue;
        for (uint16_t n = 0; n < 2; n++) {
            for (uint8_t sub = 0; sub < SDO_PARAM_ENTRIES; sub++) {
                built->all[count++] = (co_od_entry_t){
                    .index = (uint16_t)(first + n),
                    .subindex = sub,
                    .type = types[sub],
                    .flags = sub == 0 ? RO : RW,
                    .size = (uint16_t)co_od_type_size(types[sub]),
                    .offset = (uint32_t)(sizeof(test_od_data_t) + n * sizeof(sdo_param_data_t) +
                                         offsets[sub]),
                };
            }
        }
    }
    memcpy(built->data_defaults, &defaults, sizeof(defaults));
    memcpy(built->data_defaults + sizeof(defaults), records, 2 * sizeof(sdo_param_data_t));
    built->od = test_od;
    built->od.entries = built->all;
    built->od.count = count;
    built->od.data_size = sizeof(built->data_defaults);
    built->od.defaults = built->data_defaults;
    return &built->od;
}

const co_od_t *test_od_with_sdo_servers(void)
{
    static const sdo_param_data_t records[2] = {
        {.sub0 = U8(3), .cob_id = {U32(0x690), U32(0x6A0)}},
        {.sub0 = U8(3), .cob_id = {U32(0x80000000u), U32(0x80000000u)}},
    };
    static with_records_t built;
    return with_sdo_records(&built, 0x1201, records);
}

const co_od_t *test_od_with_sdo_clients(void)
{
    static const sdo_param_data_t records[2] = {
        {.sub0 = U8(3), .cob_id = {U32(0x605), U32(0x585)}, .node_id = U8(5)},
        {.sub0 = U8(3), .cob_id = {U32(0x80000000u), U32(0x80000000u)}, .node_id = U8(6)},
    };
    static with_records_t built;
    return with_sdo_records(&built, 0x1280, records);
}
