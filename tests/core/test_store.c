/* Store and restore (1010h / 1011h) with an in-memory storage double: save then reset restores,
 * "load" then reset gives defaults, wrong signatures, no storage, storage failures, damaged or
 * malformed images, images from another dictionary version. */
#include "check_main.h"
#include "test_bus.h"

#include <stdlib.h>
#include <string.h>

static test_node_t t;

#define AREAS 5
#define IMAGE_MAX 4096

/* The double: one committed image per area, a staging image for the save in progress. */
typedef struct memory_storage {
    uint8_t image[AREAS][IMAGE_MAX];
    long size[AREAS]; /* 0: none */
    uint8_t staging[IMAGE_MAX];
    size_t staged;
    uint8_t saving;
    bool damaged;
    bool fail_write;
    bool fail_erase;
    int reads_before_failure; /* < 0: never fail */
    unsigned saves, erases;
} memory_storage_t;

static memory_storage_t mem;

static int save_begin(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    ck_assert_uint_lt(area, AREAS);
    m->saving = area;
    m->staged = 0;
    return 0;
}

static int save_write(void *ctx, const uint8_t *data, size_t len)
{
    memory_storage_t *m = ctx;
    if (m->fail_write || m->staged + len > IMAGE_MAX)
        return -1;
    memcpy(m->staging + m->staged, data, len);
    m->staged += len;
    return 0;
}

static int save_end(void *ctx, bool commit)
{
    memory_storage_t *m = ctx;
    if (commit) {
        memcpy(m->image[m->saving], m->staging, m->staged);
        m->size[m->saving] = (long)m->staged;
        m->saves++;
    }
    return 0;
}

static long load_size(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    ck_assert_uint_lt(area, AREAS);
    return m->damaged && m->size[area] != 0 ? -1 : m->size[area];
}

static int load_read(void *ctx, uint8_t area, uint32_t offset, uint8_t *buf, size_t len)
{
    memory_storage_t *m = ctx;
    ck_assert_uint_le(offset + len, (size_t)m->size[area]);
    if (m->reads_before_failure == 0)
        return -1;
    if (m->reads_before_failure > 0)
        m->reads_before_failure--;
    memcpy(buf, m->image[area] + offset, len);
    return 0;
}

static int erase(void *ctx, uint8_t area)
{
    memory_storage_t *m = ctx;
    if (m->fail_erase)
        return -1;
    m->size[area] = 0;
    m->erases++;
    return 0;
}

static const co_storage_t storage = {&mem,      save_begin, save_write, save_end,
                                     load_size, load_read,  erase};

#define SAVE CO_STORE_SIGNATURE_SAVE
#define LOAD CO_STORE_SIGNATURE_LOAD

static void setup(void)
{
    memset(&mem, 0, sizeof(mem));
    mem.reads_before_failure = -1;
    test_node_start(&t, 4, NULL, &storage);
}

/* Non-default values in each area. */
static void change_values(void)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1017, 0, 500, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x100C, 0, 250, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x2000, 0x07, 0x12345678, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x203C, 0x02, 1000, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x6042, 0x00, 1500, 2), 0);
}

static void reset_node(void)
{
    test_rx(&t, "000#8104");
    test_expect(&t, "704#00");
}

static void expect_changed(bool comm, bool manufacturer, bool profile)
{
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), comm ? 500 : 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), comm ? 250 : 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), manufacturer ? 0x12345678 : 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), manufacturer ? 1000 : 30);
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), profile ? 1500 : 0);
}

START_TEST(save_all_then_reset_restores)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    ck_assert_uint_eq(mem.saves, 3);
    reset_node();
    expect_changed(true, true, true);
    /* The restored producer time runs: first heartbeat one period after the boot-up. */
    test_advance(&t, 500000);
    test_expect(&t, "704#7F");
    /* The signatures never overwrite the stored value: reads give 1. */
    uint32_t v;
    ck_assert_uint_eq(test_sdo_read(&t, 0x1010, 1, &v), 0);
    ck_assert_uint_eq(v, 1);
    ck_assert_uint_eq(test_sdo_read(&t, 0x1011, 1, &v), 0);
    ck_assert_uint_eq(v, 1);
}
END_TEST

START_TEST(save_one_group)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0); /* manufacturer */
    ck_assert_uint_eq(mem.saves, 1);
    reset_node();
    expect_changed(false, true, false);
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0); /* communication */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 3, SAVE, 4), 0); /* profile */
    test_rx(&t, "000#8204"); /* reset communication: only 1000h..1FFFh reloaded */
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 500);
    reset_node();
    expect_changed(true, true, true);
}
END_TEST

START_TEST(stored_image_is_self_describing)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1017, 0, 0x1234, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    const uint8_t *img = mem.image[CO_STORE_AREA_COMMUNICATION];
    ck_assert_mem_eq(img, "COS\x01", 4);
    /* Find the 1017h record: index, sub, length 2, value. */
    const uint8_t want[] = {0x17, 0x10, 0x00, 0x02, 0x00, 0x34, 0x12};
    bool found = false;
    for (long i = 4; i + (long)sizeof(want) <= mem.size[CO_STORE_AREA_COMMUNICATION]; i++)
        found = found || memcmp(img + i, want, sizeof(want)) == 0;
    ck_assert(found);
    /* Every record is a writable parameter: not the 1003h history, not the 1010h/1011h
     * commands, no read-only entry. */
    unsigned records = 0;
    for (long i = 4; i < mem.size[CO_STORE_AREA_COMMUNICATION]; records++) {
        uint16_t index = co_get_u16(img + i);
        const co_od_entry_t *e = co_od_find(t.node.od, index, img[i + 2]);
        ck_assert_ptr_nonnull(e);
        ck_assert(e->flags & CO_OD_WRITE);
        ck_assert(index != 0x1003 && index != 0x1010 && index != 0x1011);
        ck_assert_uint_eq(co_get_u16(img + i + 3), e->size);
        i += 5 + e->size;
    }
    ck_assert_uint_gt(records, 10);
}
END_TEST

START_TEST(load_then_reset_gives_defaults)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 4, LOAD, 4), 0);
    reset_node();
    expect_changed(true, false, true);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, LOAD, 4), 0);
    reset_node();
    expect_changed(false, false, false);
}
END_TEST

START_TEST(wrong_signatures_abort)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, 0x6E6F7277, 4),
                      SDO_ABORT_DATA_STORE); /* wron */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, 0x6C6F6164, 4),
                      SDO_ABORT_DATA_STORE); /* daol */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, LOAD, 4), SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, SAVE, 4), SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(mem.saves + mem.erases, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1010, 1), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1011, 1), 1);
}
END_TEST

START_TEST(no_storage_aborts)
{
    test_node_start(&t, 4, NULL, NULL);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, LOAD, 4), SDO_ABORT_DATA_STORE);
}
END_TEST

START_TEST(storage_failures_abort_hardware)
{
    change_values();
    mem.fail_write = true;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), SDO_ABORT_HARDWARE);
    ck_assert_uint_eq(mem.saves, 0); /* nothing committed */
    mem.fail_write = false;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    mem.fail_erase = true;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, LOAD, 4), SDO_ABORT_HARDWARE);
}
END_TEST

START_TEST(damaged_image_ignored_entirely)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    mem.damaged = true;
    reset_node();
    expect_changed(false, false, false);
}
END_TEST

START_TEST(malformed_image_ignored_entirely)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    /* Truncated in the middle of the last record: nothing of it applies. */
    mem.size[CO_STORE_AREA_MANUFACTURER] -= 1;
    reset_node();
    expect_changed(false, false, false);
    /* Wrong header. */
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    mem.image[CO_STORE_AREA_MANUFACTURER][3] = 2;
    reset_node();
    expect_changed(false, false, false);
}
END_TEST

START_TEST(read_failure_while_applying_undoes_the_area)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    unsigned records = 0;
    const uint8_t *img = mem.image[CO_STORE_AREA_MANUFACTURER];
    for (long i = 4; i < mem.size[CO_STORE_AREA_MANUFACTURER]; records++)
        i += 5 + co_get_u16(img + i + 3);
    /* The check reads the header and each record header (1 + records), applying reads each
     * record header and value (2 x records): let every read but the last value succeed. */
    mem.reads_before_failure = (int)(3 * records);
    reset_node();
    expect_changed(false, false, false);
}
END_TEST

/* An image from another dictionary version: unknown entries and changed sizes are skipped. */
START_TEST(dictionary_change_never_misloads)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    uint8_t *img = mem.image[CO_STORE_AREA_MANUFACTURER];
    long size = mem.size[CO_STORE_AREA_MANUFACTURER];
    for (long i = 4; i < size; i += 5 + co_get_u16(img + i + 3)) {
        uint16_t index = co_get_u16(img + i);
        uint8_t sub = img[i + 2];
        if (index == 0x2000 && sub == 0x07)
            img[i + 2] = 0x7F;                /* entry that no longer exists */
        if (index == 0x203C && sub == 0x02) { /* now a 2-byte value for the u32 2000:07 */
            co_put_u16(img + i, 0x2000);
            img[i + 2] = 0x07;
        }
    }
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), 30);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x03), 30);
}
END_TEST

/* The CCT's SYNC "save and reset": 1005h, 1006h, 1007h and 1019h are stored with the communication
 * parameters. */
START_TEST(sync_parameters_survive_reset_node)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1005, 0, 0x81, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1019, 0, 7, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1006, 0, 10000, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1007, 0, 5000, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x1005, 0), 0x81);
    ck_assert_int_eq(co_od_value(&t.node, 0x1006, 0), 10000);
    ck_assert_int_eq(co_od_value(&t.node, 0x1007, 0), 5000);
    ck_assert_int_eq(co_od_value(&t.node, 0x1019, 0), 7);
}
END_TEST

/* 100Eh is a communication parameter like the others: reset communication gives back the stored
 * value, and the default once the stored one is erased; guarding follows it. */
START_TEST(guarding_cob_id_stored_with_the_communication_parameters)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x100E, 0, 0x123, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x100E, 0, 0x124, 4), 0);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x100E, 0), 0x123);
    test_rx(&t, "123#R");
    test_expect(&t, "123#7F");
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 2, LOAD, 4), 0);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x100E, 0), 0x704);
    test_rx(&t, "704#R");
    test_expect(&t, "704#7F");
}
END_TEST

START_TEST(no_image_keeps_defaults)
{
    change_values();
    reset_node();
    expect_changed(false, false, false);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("store");
    TCase *tc = tcase_create("store");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, save_all_then_reset_restores);
    tcase_add_test(tc, save_one_group);
    tcase_add_test(tc, stored_image_is_self_describing);
    tcase_add_test(tc, load_then_reset_gives_defaults);
    tcase_add_test(tc, wrong_signatures_abort);
    tcase_add_test(tc, no_storage_aborts);
    tcase_add_test(tc, storage_failures_abort_hardware);
    tcase_add_test(tc, damaged_image_ignored_entirely);
    tcase_add_test(tc, malformed_image_ignored_entirely);
    tcase_add_test(tc, read_failure_while_applying_undoes_the_area);
    tcase_add_test(tc, dictionary_change_never_misloads);
    tcase_add_test(tc, sync_parameters_survive_reset_node);
    tcase_add_test(tc, guarding_cob_id_stored_with_the_communication_parameters);
    tcase_add_test(tc, no_image_keeps_defaults);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
