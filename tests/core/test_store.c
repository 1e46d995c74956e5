/* SPDX-License-Identifier: Apache-2.0 */
/* Store and restore (1010h / 1011h) with an in-memory storage double: save then reset restores,
 * "load" then reset gives defaults, wrong signatures, no storage, storage failures, damaged or
 * malformed images, images from another dictionary version, process data never stored, stored
 * values checked like SDO writes, views, PDOs restored by the mapping procedure. */
#include "check_main.h"
#include "memory_storage.h"
#include "test_bus.h"

#include <stdlib.h>
#include <string.h>

static test_node_t t;

static memory_storage_t mem;
static co_storage_t storage;

#define SAVE CO_STORE_SIGNATURE_SAVE
#define LOAD CO_STORE_SIGNATURE_LOAD

static void setup(void)
{
    memory_storage_init(&mem, &storage);
    test_node_start(&t, 4, NULL, &storage);
}

/* Non-default values in each area. */
static void change_values(void)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1017, 0, 500, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x100C, 0, 250, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x2000, 0x07, 0x12345678, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x203C, 0x02, 1000, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x6046, 0x02, 2000, 4), 0);
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
    ck_assert_int_eq(co_od_value(&t.node, 0x6046, 0x02), profile ? 2000 : 1500);
}

/* Writes a version 2 image of saved values of one area, written by save 1. */
static void put_image(uint8_t area, const uint8_t *records, size_t len)
{
    memcpy(mem.image[area], "COS\x02\x01\x00\x00\x00\x00", CO_STORE_IMAGE_HEADER_SIZE);
    memcpy(mem.image[area] + CO_STORE_IMAGE_HEADER_SIZE, records, len);
    mem.size[area] = (long)(CO_STORE_IMAGE_HEADER_SIZE + len);
}

/* The last image refused whole was of `area`, for `reason`, at the record of index:sub that
 * starts at byte `offset`. */
static void expect_image_refused(uint8_t area, co_store_fault_t reason, uint32_t offset,
                                 uint16_t index, uint8_t subindex)
{
    const co_store_image_fault_t *f = &mem.image_fault;
    ck_assert_uint_gt(mem.images_refused, 0);
    ck_assert_int_eq(f->reason, reason);
    ck_assert_uint_eq(f->area, area);
    ck_assert_uint_eq(f->offset, offset);
    ck_assert_uint_eq(f->index, index);
    ck_assert_uint_eq(f->subindex, subindex);
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
    ck_assert_mem_eq(img, "COS\x02\x01\x00\x00\x00\x00", 9); /* version 2, sequence 1, values */
    /* Find the 1017h record: index, sub, length 2, value. */
    const uint8_t want[] = {0x17, 0x10, 0x00, 0x02, 0x00, 0x34, 0x12};
    bool found = false;
    for (long i = 9; i + (long)sizeof(want) <= mem.size[CO_STORE_AREA_COMMUNICATION]; i++)
        found = found || memcmp(img + i, want, sizeof(want)) == 0;
    ck_assert(found);
    /* Every record is a writable parameter: not the 1003h history, not the 1010h/1011h
     * commands, no read-only entry. */
    unsigned records = 0;
    for (long i = 9; i < mem.size[CO_STORE_AREA_COMMUNICATION]; records++) {
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
                      CO_SDO_ABORT_DATA_STORE); /* wron */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, 0x6C6F6164, 4),
                      CO_SDO_ABORT_DATA_STORE); /* daol */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, LOAD, 4), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, SAVE, 4), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(mem.saves + mem.erases, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1010, 1), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1011, 1), 1);
}
END_TEST

START_TEST(no_storage_aborts)
{
    test_node_start(&t, 4, NULL, NULL);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, LOAD, 4), CO_SDO_ABORT_DATA_STORE);
}
END_TEST

START_TEST(storage_failures_abort_hardware)
{
    change_values();
    mem.fail_write = true;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), CO_SDO_ABORT_HARDWARE);
    ck_assert_uint_eq(mem.saves, 0); /* nothing committed */
    mem.fail_write = false;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    mem.fail_erase = true;
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 1, LOAD, 4), CO_SDO_ABORT_HARDWARE);
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
    /* Truncated in the middle of the last record (203C:03, 2 bytes): nothing of it applies. */
    long size = mem.size[CO_STORE_AREA_MANUFACTURER] -= 1;
    reset_node();
    expect_changed(false, false, false);
    expect_image_refused(CO_STORE_AREA_MANUFACTURER, CO_STORE_FAULT_CUT_SHORT, (uint32_t)size - 6,
                         0x203C, 0x03);
    /* Wrong header. */
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    mem.image[CO_STORE_AREA_MANUFACTURER][3] = 9; /* an unknown version */
    reset_node();
    expect_changed(false, false, false);
    expect_image_refused(CO_STORE_AREA_MANUFACTURER, CO_STORE_FAULT_HEADER, 0, 0, 0);
    ck_assert_uint_eq(mem.images_refused, 2);
}
END_TEST

/* The backend verified the image but one value cannot be read when it is applied: that record
 * is reported and skipped, the others apply. */
START_TEST(read_failure_while_applying_skips_the_record)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    mem.fail_offset = memory_storage_record(&mem, CO_STORE_AREA_MANUFACTURER, 0x203C, 0x02);
    ck_assert_int_gt(mem.fail_offset, 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), 30);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0x12345678);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x203C, 0x02), CO_SDO_ABORT_HARDWARE);
    ck_assert_uint_eq(mem.refusals, 1);
}
END_TEST

/* Process data (6040h, 6042h here) are never stored: after a save and a reset they are back at
 * their defaults, whatever they held. */
START_TEST(process_data_never_stored)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x6040, 0, 0x000F, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x6042, 0, 1200, 2), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    ck_assert_int_eq(memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6040, 0), 0);
    ck_assert_int_eq(memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6042, 0), 0);
    ck_assert_int_gt(memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6046, 2), 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), 0);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* Writes a version 1 image (the format before process data and sequences) of one area. */
static void put_v1_image(uint8_t area, const uint8_t *records, size_t len)
{
    memcpy(mem.image[area], "COS\x01", 4);
    memcpy(mem.image[area] + 4, records, len);
    mem.size[area] = (long)(4 + len);
}

/* An image written by an older build still loads its parameters; the process data it holds are
 * reported and skipped. */
START_TEST(version_1_image_loads_its_parameters_only)
{
    static const uint8_t records[] = {
        0x40, 0x60, 0x00, 0x02, 0x00, 0x0F, 0x00,             /* 6040h = 0x000F */
        0x42, 0x60, 0x00, 0x02, 0x00, 0xB0, 0x04,             /* 6042h = 1200 */
        0x46, 0x60, 0x02, 0x04, 0x00, 0xD0, 0x07, 0x00, 0x00, /* 6046h:02 = 2000 */
    };
    put_v1_image(CO_STORE_AREA_PROFILE, records, sizeof(records));
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x6046, 2), 2000);
    ck_assert_int_eq(co_od_value(&t.node, 0x6040, 0), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x6042, 0), 0);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x6040, 0), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x6042, 0), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(mem.refusals, 2);
}
END_TEST

/* A well-formed image with values a write would refuse (a hand edit, an older build): each is
 * refused as an SDO write would be, reported with its value and skipped; the rest applies. */
START_TEST(stored_values_checked_like_writes)
{
    change_values();
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 4, SAVE, 4), 0);
    uint8_t *img = mem.image[CO_STORE_AREA_MANUFACTURER];
    img[memory_storage_record(&mem, CO_STORE_AREA_MANUFACTURER, 0x2000, 0x05)] =
        5; /* below 10..200 */
    co_put_u16(img + memory_storage_record(&mem, CO_STORE_AREA_MANUFACTURER, 0x2000, 0x10),
               7); /* hook refuses */
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 50);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x10), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0x12345678);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), 1000);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2000, 0x05), CO_SDO_ABORT_VALUE_LOW);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2000, 0x10), CO_SDO_ABORT_DATA_LOCAL);
    ck_assert_uint_eq(mem.refusals, 2);
    ck_assert_uint_eq(mem.refused[0].len, 1);
}
END_TEST

/* A view is saved as read and restored through its hook: 6046h:01 stands for 2000:06 x 10, so
 * saving the profile area keeps 2000:06 even though the manufacturer area was not saved. */
START_TEST(view_saved_as_read_and_restored_through_its_hook)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x6046, 1, 20000, 4), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 2000);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 3, SAVE, 4), 0);
    const uint8_t *img = mem.image[CO_STORE_AREA_PROFILE];
    ck_assert_uint_eq(
        co_get_u32(img + memory_storage_record(&mem, CO_STORE_AREA_PROFILE, 0x6046, 1)), 20000);
    ck_assert_uint_eq(test_sdo_write(&t, 0x2000, 0x06, 1500, 2), 0); /* not saved */
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 2000);
    uint32_t v;
    ck_assert_uint_eq(test_sdo_read(&t, 0x6046, 1, &v), 0);
    ck_assert_uint_eq(v, 20000);
}
END_TEST

/* Two areas cover 2000:06 (itself, and the view 6046h:01): the later save or restore wins. */
START_TEST(restoring_an_area_restores_what_its_views_stand_for)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x6046, 1, 20000, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 3, LOAD, 4), 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 1000);
    /* Saved again, then the manufacturer area restored: the older profile image no longer
     * brings 2000:06 back. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x6046, 1, 20000, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1011, 4, LOAD, 4), 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 1000);
    /* And a profile save after that wins again. */
    ck_assert_uint_eq(test_sdo_write(&t, 0x6046, 1, 30000, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 3, SAVE, 4), 0);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x06), 3000);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* TPDO6 configured by the CiA 301 procedure and saved comes back valid, with its mapping, through
 * the same write rules (the mapping could not be written while the PDO is valid). */
START_TEST(pdo_restored_through_the_mapping_procedure)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 0, 0, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 1, 0x20000720, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1A05, 0, 1, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1805, 2, 1, 1), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1805, 1, 0x285, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    reset_node();
    ck_assert_uint_eq(mem.refusals, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 1), 0x285);
    ck_assert_int_eq(co_od_value(&t.node, 0x1A05, 0), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1A05, 1), 0x20000720);
    ck_assert_uint_eq(test_sdo_write(&t, 0x2000, 0x07, 0x0A0B0C0D, 4), 0);
    test_rx(&t, "000#0104");
    test_expect(&t, "184#0000"); /* TPDO1 on entering Operational */
    test_rx(&t, "080#");
    test_expect(&t, "285#0D0C0B0A");
}
END_TEST

/* The EMCY CAN-ID changes only while 1014h is invalid: a stored new CAN-ID goes through that
 * procedure too. */
START_TEST(emcy_cob_id_restored_through_its_procedure)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1014, 0, 0x80000090, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1014, 0, 0x90, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    reset_node();
    ck_assert_uint_eq(mem.refusals, 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x1014, 0), 0x90);
}
END_TEST

/* A stored COB-ID the write rules refuse (a restricted CAN-ID) leaves its PDO invalid. */
START_TEST(refused_pdo_cob_id_leaves_the_pdo_invalid)
{
    ck_assert_uint_eq(test_sdo_write(&t, 0x1805, 1, 0x285, 4), 0);
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 2, SAVE, 4), 0);
    uint8_t *img = mem.image[CO_STORE_AREA_COMMUNICATION];
    co_put_u32(img + memory_storage_record(&mem, CO_STORE_AREA_COMMUNICATION, 0x1805, 1), 0x701);
    reset_node();
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x1805, 1), CO_SDO_ABORT_VALUE_RANGE);
    ck_assert_int_eq(co_od_value(&t.node, 0x1805, 1), (int64_t)0x80000284);
}
END_TEST

/* An image from another dictionary version, where 2000:07 was 2 bytes long and 2000:13 and 2001h
 * existed: the records of entries that are gone or changed size are skipped, the others apply. */
START_TEST(dictionary_change_never_misloads)
{
    static const uint8_t records[] = {
        0x00, 0x20, 0x07, 0x02, 0x00, 0x34, 0x12, /* 2000:07 = 0x1234, now 4 bytes long */
        0x00, 0x20, 0x13, 0x01, 0x00, 0x05,       /* 2000:13, no longer exists */
        0x01, 0x20, 0x00, 0x01, 0x00, 0x05,       /* 2001h, no longer exists */
        0x3C, 0x20, 0x02, 0x02, 0x00, 0xE8, 0x03, /* 203C:02 = 1000 */
    };
    put_image(CO_STORE_AREA_MANUFACTURER, records, sizeof(records));
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x07), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), 1000);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2000, 0x07), CO_SDO_ABORT_TYPE_LENGTH);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2000, 0x13), CO_SDO_ABORT_NO_SUBINDEX);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x2001, 0x00), CO_SDO_ABORT_NO_OBJECT);
    ck_assert_uint_eq(mem.refusals, 3);
}
END_TEST

/* The records of a communication image that are not parameters: the device type (read-only) and
 * the "save" and "load" commands, which would save or erase the storage while it is applied.
 * Each is refused like any value a write would refuse; 1017h applies, nothing is saved or erased.
 */
START_TEST(stored_commands_and_read_only_values_never_apply)
{
    static const uint8_t records[] = {
        0x00, 0x10, 0x00, 0x04, 0x00, 0x34, 0x12, 0x00, 0x00, /* 1000h = 0x1234 */
        0x10, 0x10, 0x01, 0x04, 0x00, 's',  'a',  'v',  'e',  /* 1010h:01 = "save" */
        0x11, 0x10, 0x01, 0x04, 0x00, 'l',  'o',  'a',  'd',  /* 1011h:01 = "load" */
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01,             /* 1017h = 500 */
    };
    put_image(CO_STORE_AREA_COMMUNICATION, records, sizeof(records));
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 500);
    ck_assert_int_eq(co_od_value(&t.node, 0x1010, 1), 1);
    ck_assert_int_eq(co_od_value(&t.node, 0x1011, 1), 1);
    ck_assert_uint_eq(mem.saves + mem.erases, 0);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x1000, 0), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x1010, 1), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(memory_storage_refusal(&mem, 0x1011, 1), CO_SDO_ABORT_DATA_STORE);
    ck_assert_uint_eq(mem.refusals, 3);
}
END_TEST

/* Issue 22 item 9: a communication image holding a record of the manufacturer area (2000:05).
 * Applied, every reset communication would write that parameter back, though a reset
 * communication reloads the communication area only. The image is refused whole, before any of
 * it applies: 1017h keeps its default too, and no record is reported one by one. */
START_TEST(record_outside_its_area_refuses_the_image)
{
    static const uint8_t records[] = {
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01, /* 1017h = 500 */
        0x00, 0x20, 0x05, 0x01, 0x00, 0x64,       /* 2000:05 = 100 */
    };
    put_image(CO_STORE_AREA_COMMUNICATION, records, sizeof(records));
    ck_assert_uint_eq(test_sdo_write(&t, 0x2000, 0x05, 120, 1), 0);
    test_rx(&t, "000#8204");
    test_expect(&t, "704#00");
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 120);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_uint_eq(mem.images_refused, 1);
    expect_image_refused(CO_STORE_AREA_COMMUNICATION, CO_STORE_FAULT_OUTSIDE_AREA, 16, 0x2000,
                         0x05);
    ck_assert_uint_eq(mem.image_fault.area_first, 0x1000);
    ck_assert_uint_eq(mem.image_fault.area_last, 0x1FFF);
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 50);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_uint_eq(mem.images_refused, 2);
    ck_assert_uint_eq(mem.refusals, 0);
}
END_TEST

/* The core writes one record per entry, in table order: an image with a record twice, or with
 * records out of that order, was not written by it and is refused whole. */
START_TEST(duplicate_or_unordered_records_refuse_the_image)
{
    static const uint8_t duplicate[] = {
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01, /* 1017h = 500 */
        0x17, 0x10, 0x00, 0x02, 0x00, 0x58, 0x02, /* 1017h = 600 */
    };
    put_image(CO_STORE_AREA_COMMUNICATION, duplicate, sizeof(duplicate));
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    expect_image_refused(CO_STORE_AREA_COMMUNICATION, CO_STORE_FAULT_ORDER, 16, 0x1017, 0);
    static const uint8_t unordered[] = {
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01, /* 1017h = 500 */
        0x0C, 0x10, 0x00, 0x02, 0x00, 0xFA, 0x00, /* 100Ch = 250 */
    };
    put_image(CO_STORE_AREA_COMMUNICATION, unordered, sizeof(unordered));
    reset_node();
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x100C, 0), 0);
    expect_image_refused(CO_STORE_AREA_COMMUNICATION, CO_STORE_FAULT_ORDER, 16, 0x100C, 0);
    ck_assert_uint_eq(mem.images_refused, 2);
    ck_assert_uint_eq(mem.refusals, 0);
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

/* The check a backend runs on images it did not write: the same as before an image applies. */
START_TEST(image_check_without_a_node)
{
    co_store_image_fault_t fault;
    ck_assert_int_eq(co_store_image_check(&storage, CO_STORE_AREA_PROFILE, &fault),
                     CO_STORE_FAULT_NONE); /* no image */
    ck_assert_uint_eq(test_sdo_write(&t, 0x1010, 1, SAVE, 4), 0);
    for (uint8_t area = CO_STORE_AREA_COMMUNICATION; area <= CO_STORE_AREA_MANUFACTURER; area++)
        ck_assert_int_eq(co_store_image_check(&storage, area, &fault), CO_STORE_FAULT_NONE);
    ck_assert_int_eq(co_store_image_check(&storage, 5, &fault), CO_STORE_FAULT_AREA);
    ck_assert_uint_eq(fault.area, 5);
    static const uint8_t records[] = {
        0x46, 0x60, 0x02, 0x04, 0x00, 0xD0, 0x07, 0x00, 0x00, /* 6046h:02 = 2000 */
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01,             /* 1017h = 500 */
    };
    put_image(CO_STORE_AREA_PROFILE, records, sizeof(records));
    ck_assert_int_eq(co_store_image_check(&storage, CO_STORE_AREA_PROFILE, &fault),
                     CO_STORE_FAULT_OUTSIDE_AREA);
    ck_assert_uint_eq(fault.area_first, 0x6000);
    ck_assert_uint_eq(fault.area_last, 0x9FFF);
    ck_assert_uint_eq(fault.offset, 18);
    ck_assert_uint_eq(fault.index, 0x1017);
    mem.fail_offset = CO_STORE_IMAGE_HEADER_SIZE;
    ck_assert_int_eq(co_store_image_check(&storage, CO_STORE_AREA_PROFILE, &fault),
                     CO_STORE_FAULT_UNREADABLE);
    ck_assert_uint_eq(fault.offset, CO_STORE_IMAGE_HEADER_SIZE);
    ck_assert_uint_eq(mem.images_refused, 0);
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
    tcase_add_test(tc, read_failure_while_applying_skips_the_record);
    tcase_add_test(tc, dictionary_change_never_misloads);
    tcase_add_test(tc, stored_commands_and_read_only_values_never_apply);
    tcase_add_test(tc, record_outside_its_area_refuses_the_image);
    tcase_add_test(tc, duplicate_or_unordered_records_refuse_the_image);
    tcase_add_test(tc, sync_parameters_survive_reset_node);
    tcase_add_test(tc, guarding_cob_id_stored_with_the_communication_parameters);
    tcase_add_test(tc, no_image_keeps_defaults);
    tcase_add_test(tc, image_check_without_a_node);
    tcase_add_test(tc, process_data_never_stored);
    tcase_add_test(tc, version_1_image_loads_its_parameters_only);
    tcase_add_test(tc, stored_values_checked_like_writes);
    tcase_add_test(tc, view_saved_as_read_and_restored_through_its_hook);
    tcase_add_test(tc, restoring_an_area_restores_what_its_views_stand_for);
    tcase_add_test(tc, pdo_restored_through_the_mapping_procedure);
    tcase_add_test(tc, emcy_cob_id_restored_through_its_procedure);
    tcase_add_test(tc, refused_pdo_cob_id_leaves_the_pdo_invalid);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
