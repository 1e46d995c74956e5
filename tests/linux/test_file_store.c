/* SPDX-License-Identifier: Apache-2.0 */
/* The storage file: save/load round trip through the co_storage_t callbacks, several nodes in
 * one file, atomic replacement, and files that fail a check (truncated, bad CRC, wrong magic,
 * unknown version, bad record, an image the core would refuse) ignored as a whole with the
 * reason; DeviceNet and LSS records beside the images. */
#include "check_main.h"
#include "co/co_lss.h"
#include "co_linux/file_store.h"
#include "test_bus.h"

#include <check.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[64];
static char path[128];

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/co_file_store_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/drives.store", dir);
}

static void teardown(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char name[512];
    while (d && (e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        snprintf(name, sizeof name, "%s/%s", dir, e->d_name);
        unlink(name);
    }
    if (d)
        closedir(d);
    rmdir(dir);
}

static size_t files_in_dir(void)
{
    size_t n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

/* An image the core accepts and no string ends early: a restored area's image (co_store.h,
 * kind 1, no records) whose save number is four characters, which tell the images apart. */
#define IMAGE(tag) "COS\x02" tag "\x01"

static void save(const co_storage_t *s, uint8_t area, const char *image)
{
    ck_assert_int_eq(s->save_begin(s->ctx, area), 0);
    /* In two pieces, as the core streams it. */
    size_t half = strlen(image) / 2;
    ck_assert_int_eq(s->save_write(s->ctx, (const uint8_t *)image, half), 0);
    ck_assert_int_eq(s->save_write(s->ctx, (const uint8_t *)image + half, strlen(image) - half), 0);
    ck_assert_int_eq(s->save_end(s->ctx, true), 0);
}

static void assert_loads(const co_storage_t *s, uint8_t area, const char *image)
{
    ck_assert_int_eq(s->load_size(s->ctx, area), (long)strlen(image));
    char buf[64] = {0};
    ck_assert_int_eq(s->load_read(s->ctx, area, 0, (uint8_t *)buf, strlen(image)), 0);
    ck_assert_str_eq(buf, image);
}

static size_t read_file(uint8_t *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(buf, 1, cap, f);
    fclose(f);
    return n;
}

static void write_file(const uint8_t *buf, size_t len)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(buf, 1, len, f), len);
    fclose(f);
}

/* A file holding node 4 area 2 = IMAGE("COMM"), node 5 area 4 = IMAGE("MANU"). */
static size_t make_valid_file(uint8_t *buf, size_t cap)
{
    co_file_store_t store;
    co_file_store_node_t n4, n5;
    co_storage_t s4, s5;
    unlink(path);
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_MISSING);
    co_file_store_bind(&store, 4, &n4, &s4);
    co_file_store_bind(&store, 5, &n5, &s5);
    save(&s5, 4, IMAGE("MANU"));
    save(&s4, 2, IMAGE("COMM"));
    co_file_store_unbind(&n4);
    co_file_store_unbind(&n5);
    co_file_store_close(&store);
    return read_file(buf, cap);
}

/* Opens the file, expects it ignored with a reason containing `why`, and nothing loaded. */
static void assert_ignored(const char *why)
{
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_IGNORED);
    ck_assert_msg(strstr(store.reason, why) != NULL, "reason \"%s\" lacks \"%s\"", store.reason,
                  why);
    ck_assert_uint_eq(store.count, 0);
    co_file_store_bind(&store, 4, &n4, &s4);
    ck_assert_int_eq(s4.load_size(s4.ctx, 2), -1);
    co_file_store_close(&store);
}

START_TEST(round_trip_several_nodes)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    co_file_store_t store;
    co_file_store_node_t n4, n5, n6;
    co_storage_t s4, s5, s6;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    ck_assert_uint_eq(store.count, 2);
    co_file_store_bind(&store, 4, &n4, &s4);
    co_file_store_bind(&store, 5, &n5, &s5);
    co_file_store_bind(&store, 6, &n6, &s6);
    assert_loads(&s4, 2, IMAGE("COMM"));
    assert_loads(&s5, 4, IMAGE("MANU"));
    ck_assert_int_eq(s4.load_size(s4.ctx, 4), 0);
    ck_assert_int_eq(s6.load_size(s6.ctx, 2), 0);
    uint8_t out[8];
    ck_assert_int_eq(s4.load_read(s4.ctx, 2, 7, out, 3), -1); /* beyond the image */
    ck_assert_int_eq(s4.load_read(s4.ctx, 2, 6, out, 2), 0);
    ck_assert_mem_eq(out, "MM", 2);
    co_file_store_close(&store);
}
END_TEST

START_TEST(exact_file_layout)
{
    co_file_store_t store;
    co_file_store_node_t n;
    co_storage_t s;
    co_file_store_open(&store, path);
    co_file_store_bind(&store, 0x7F, &n, &s);
    save(&s, 3, "AB");
    co_file_store_unbind(&n);
    co_file_store_close(&store);
    uint8_t buf[64];
    ck_assert_uint_eq(read_file(buf, sizeof buf), 12 + 8 + 2 + 4);
    static const uint8_t expected[22] = {'C', 'o',  'S', 'F', 1, 0, 1, 0, 10, 0,   0,
                                         0,   0x7F, 3,   0,   0, 2, 0, 0, 0,  'A', 'B'};
    ck_assert_mem_eq(buf, expected, sizeof expected);
    uint32_t crc = co_crc32(buf, 22);
    ck_assert_uint_eq(co_get_u32(buf + 22), crc);
    /* The check value of CRC-32/ISO-HDLC. */
    ck_assert_uint_eq(co_crc32((const uint8_t *)"123456789", 9), 0xCBF43926u);
}
END_TEST

START_TEST(save_replaces_atomically)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    struct stat before, after;
    ck_assert_int_eq(stat(path, &before), 0);
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_store_bind(&store, 4, &n4, &s4);
    save(&s4, 2, IMAGE("NEWC"));
    ck_assert_int_eq(stat(path, &after), 0);
    /* A new file was renamed over the old one: never rewritten in place. */
    ck_assert_uint_ne(before.st_ino, after.st_ino);
    ck_assert_uint_eq(files_in_dir(), 1); /* no temporary file left */
    co_file_store_unbind(&n4);
    co_file_store_close(&store);

    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_store_bind(&store, 4, &n4, &s4);
    assert_loads(&s4, 2, IMAGE("NEWC"));
    co_file_store_node_t n5;
    co_storage_t s5;
    co_file_store_bind(&store, 5, &n5, &s5);
    assert_loads(&s5, 4, IMAGE("MANU")); /* the other node's record survives */
    co_file_store_close(&store);
}
END_TEST

/* The areas of one 1010h write (group_begin .. group_end) reach the file together: until
 * group_end the file on disk is untouched, then one replacement holds them all; a discarded group
 * leaves nothing. */
START_TEST(grouped_saves_replace_the_file_once)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    struct stat before, during, after;
    ck_assert_int_eq(stat(path, &before), 0);
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_store_bind(&store, 4, &n4, &s4);
    ck_assert_int_eq(s4.group_begin(s4.ctx), 0);
    save(&s4, 2, IMAGE("GRPC"));
    save(&s4, 4, IMAGE("GRPM"));
    ck_assert_int_eq(stat(path, &during), 0);
    ck_assert_uint_eq(before.st_ino, during.st_ino); /* nothing written yet */
    ck_assert_int_eq(s4.group_end(s4.ctx, true), 0);
    ck_assert_int_eq(stat(path, &after), 0);
    ck_assert_uint_ne(before.st_ino, after.st_ino);
    ck_assert_uint_eq(files_in_dir(), 1);
    ck_assert_int_eq(s4.group_begin(s4.ctx), 0);
    save(&s4, 2, "DISCARDED");
    ck_assert_int_eq(s4.group_end(s4.ctx, false), 0);
    co_file_store_unbind(&n4);
    co_file_store_close(&store);

    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_store_bind(&store, 4, &n4, &s4);
    assert_loads(&s4, 2, IMAGE("GRPC"));
    assert_loads(&s4, 4, IMAGE("GRPM"));
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
}
END_TEST

START_TEST(failed_save_changes_nothing)
{
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    char missing[160];
    snprintf(missing, sizeof missing, "%s/no-such-dir/drives.store", dir);
    ck_assert_int_eq(co_file_store_open(&store, missing), CO_FILE_STORE_MISSING);
    co_file_store_bind(&store, 4, &n4, &s4);
    ck_assert_int_eq(s4.save_begin(s4.ctx, 2), 0);
    ck_assert_int_eq(s4.save_write(s4.ctx, (const uint8_t *)"X", 1), 0);
    ck_assert_int_eq(s4.save_end(s4.ctx, true), -1);
    ck_assert(strstr(store.reason, "cannot create") != NULL);
    ck_assert_int_eq(s4.load_size(s4.ctx, 2), 0);
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
}
END_TEST

START_TEST(discarded_save_and_erase)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    co_file_store_open(&store, path);
    co_file_store_bind(&store, 4, &n4, &s4);
    ck_assert_int_eq(s4.save_begin(s4.ctx, 2), 0);
    ck_assert_int_eq(s4.save_write(s4.ctx, (const uint8_t *)"LOST", 4), 0);
    ck_assert_int_eq(s4.save_end(s4.ctx, false), 0);
    assert_loads(&s4, 2, IMAGE("COMM"));
    ck_assert_int_eq(s4.erase(s4.ctx, 2), 0);
    ck_assert_int_eq(s4.load_size(s4.ctx, 2), 0);
    ck_assert_int_eq(s4.erase(s4.ctx, 3), 0); /* nothing stored: succeeds */
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    ck_assert_uint_eq(store.count, 1);
    ck_assert_ptr_null(co_file_store_find(&store, 4, 2));
    ck_assert_ptr_nonnull(co_file_store_find(&store, 5, 4));
    co_file_store_close(&store);
}
END_TEST

START_TEST(truncated_file_is_ignored)
{
    uint8_t buf[256];
    size_t len = make_valid_file(buf, sizeof buf);
    write_file(buf, len - 1);
    assert_ignored("truncated");
    write_file(buf, 10);
    assert_ignored("truncated: 10 bytes");
    write_file(buf, 0);
    assert_ignored("truncated: 0 bytes");
}
END_TEST

START_TEST(bad_crc_is_ignored)
{
    uint8_t buf[256];
    size_t len = make_valid_file(buf, sizeof buf);
    buf[len - 6] ^= 0x01; /* one bit of the last image */
    write_file(buf, len);
    assert_ignored("bad CRC-32");
}
END_TEST

START_TEST(wrong_magic_or_version_is_ignored)
{
    uint8_t buf[256];
    size_t len = make_valid_file(buf, sizeof buf);
    uint8_t copy[256];
    memcpy(copy, buf, len);
    copy[0] = 'X';
    write_file(copy, len);
    assert_ignored("wrong magic");
    memcpy(copy, buf, len);
    copy[4] = 2;
    write_file(copy, len);
    assert_ignored("unsupported format version 2");
}
END_TEST

START_TEST(bad_record_with_good_crc_is_ignored)
{
    uint8_t buf[256];
    size_t len = make_valid_file(buf, sizeof buf);
    buf[12] = 0; /* node-id 0 in the first record */
    co_put_u32(buf + len - 4, co_crc32(buf, len - 4));
    write_file(buf, len);
    assert_ignored("node-id 0");

    len = make_valid_file(buf, sizeof buf);
    co_put_u16(buf + 6, 3); /* one record more than the file has */
    co_put_u32(buf + len - 4, co_crc32(buf, len - 4));
    write_file(buf, len);
    assert_ignored("record 3 of 3 is cut short");
}
END_TEST

/* Writes a file of node 4's images, unchecked, as another program could. */
static void write_images(const co_file_record_t *images, size_t n)
{
    co_file_store_t store;
    unlink(path);
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_MISSING);
    co_file_record_t copies[3];
    for (size_t i = 0; i < n; i++) {
        copies[i] = images[i];
        copies[i].data = malloc(images[i].len);
        memcpy(copies[i].data, images[i].data, images[i].len);
    }
    ck_assert_int_eq(co_file_store_update_many(&store, copies, n), 0);
    co_file_store_close(&store);
}

/* Issue 22 item 9 through the file: node 4's communication image holds a record of 2000:05, a
 * manufacturer parameter that every reset communication would write back. The file is ignored
 * whole, as for a bad CRC, with the reason the daemon prints ("store FILE: ignored, defaults
 * apply: <reason>"), and the node starts with every default: 1017h, 2000:05, and 203C:02 of its
 * sound manufacturer image alike. */
START_TEST(image_with_a_record_outside_its_area_is_ignored)
{
    static uint8_t comm[] = {
        'C',  'O',  'S',  2,    1,    0,    0,    0, 0, /* save 1, values */
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01,       /* 1017h = 500 */
        0x00, 0x20, 0x05, 0x01, 0x00, 0x64,             /* 2000:05 = 100 */
    };
    static uint8_t manuf[] = {
        'C',  'O',  'S',  2,    2,    0,    0,    0, 0, /* save 2, values */
        0x3C, 0x20, 0x02, 0x02, 0x00, 0xE8, 0x03,       /* 203C:02 = 1000 */
    };
    const co_file_record_t images[] = {{4, CO_STORE_AREA_COMMUNICATION, sizeof comm, comm},
                                       {4, CO_STORE_AREA_MANUFACTURER, sizeof manuf, manuf}};
    write_images(images, 2);
    co_file_store_t store;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_IGNORED);
    ck_assert_str_eq(store.reason,
                     "node 4 area 2: record 2000h:05 at byte 16 lies outside the area "
                     "(1000h..1FFFh)");
    co_file_store_node_t n4;
    co_storage_t s4;
    co_file_store_bind(&store, 4, &n4, &s4);
    test_node_t t;
    test_node_start(&t, 4, NULL, &s4);
    ck_assert_int_eq(co_od_value(&t.node, 0x1017, 0), 0);
    ck_assert_int_eq(co_od_value(&t.node, 0x2000, 0x05), 50);
    ck_assert_int_eq(co_od_value(&t.node, 0x203C, 0x02), 30);
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
}
END_TEST

/* The other images the core would refuse: a record twice, and bytes that are no image at all. */
START_TEST(duplicate_record_or_foreign_image_is_ignored)
{
    static uint8_t duplicate[] = {
        'C',  'O',  'S',  2,    1,    0,    0,    0, 0, /* save 1, values */
        0x17, 0x10, 0x00, 0x02, 0x00, 0xF4, 0x01,       /* 1017h = 500 */
        0x17, 0x10, 0x00, 0x02, 0x00, 0x58, 0x02,       /* 1017h = 600 */
    };
    co_file_record_t image = {4, CO_STORE_AREA_COMMUNICATION, sizeof duplicate, duplicate};
    write_images(&image, 1);
    assert_ignored("node 4 area 2: record 1017h:00 at byte 16 does not follow the one before it "
                   "(a duplicate, or out of order)");
    static uint8_t foreign[] = "COMM";
    image = (co_file_record_t){4, CO_STORE_AREA_MANUFACTURER, 4, foreign};
    write_images(&image, 1);
    assert_ignored("node 4 area 4: not an image of parameters (header \"COS\" version 1 or 2)");
    image = (co_file_record_t){4, 5, 4, foreign};
    write_images(&image, 1);
    assert_ignored("node 4 area 5: not a storage area (2, 3 or 4)");
}
END_TEST

START_TEST(damaged_file_is_kept_aside_at_next_save)
{
    uint8_t buf[256];
    size_t len = make_valid_file(buf, sizeof buf);
    buf[len - 1] ^= 0xFF;
    write_file(buf, len);
    co_file_store_t store;
    co_file_store_node_t n4;
    co_storage_t s4;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_IGNORED);
    co_file_store_bind(&store, 4, &n4, &s4);
    save(&s4, 3, IMAGE("PROF"));
    ck_assert_int_eq(s4.load_size(s4.ctx, 2), 0); /* the file is sound again */
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
    char bad[160];
    snprintf(bad, sizeof bad, "%s.bad", path);
    struct stat st;
    ck_assert_int_eq(stat(bad, &st), 0);
    ck_assert_int_eq(st.st_size, (off_t)len);
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    ck_assert_uint_eq(store.count, 1);
    co_file_store_close(&store);
}
END_TEST

/* A DeviceNet drive's record (atv312d --devicenet): keyed by MAC ID, 0 included, beside the
 * CANopen images of the same file; byte for byte, and read back after a reopen. */
START_TEST(devicenet_records_beside_images)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    co_file_store_t store;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_devicenet_t values;
    ck_assert(!co_file_store_get_devicenet(&store, 4, &values));
    co_file_devicenet_t mac0 = {100, 101, true};
    co_file_devicenet_t mac4 = {20, 70, false};
    ck_assert_int_eq(co_file_store_set_devicenet(&store, 0, &mac0), 0);
    ck_assert_int_eq(co_file_store_set_devicenet(&store, 4, &mac4), 0);
    co_file_store_close(&store);

    size_t len = read_file(buf, sizeof buf);
    /* Sorted by id then area: MAC 0, node 4 area 2, MAC 4 (area 0x80), node 5 area 4. */
    static const uint8_t mac0_record[13] = {0, 0x80, 0, 0, 5, 0, 0, 0, 100, 0, 101, 0, 1};
    ck_assert_mem_eq(buf + 12, mac0_record, sizeof mac0_record);
    static const uint8_t mac4_record[13] = {4, 0x80, 0, 0, 5, 0, 0, 0, 20, 0, 70, 0, 0};
    size_t image = 8 + strlen(IMAGE("COMM"));
    ck_assert_mem_eq(buf + 12 + 13 + image, mac4_record, sizeof mac4_record);
    ck_assert_uint_eq(co_get_u32(buf + len - 4), co_crc32(buf, len - 4));

    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    ck_assert_uint_eq(store.count, 4);
    ck_assert(co_file_store_get_devicenet(&store, 0, &values));
    ck_assert_uint_eq(values.consumed_assembly, 100);
    ck_assert_uint_eq(values.produced_assembly, 101);
    ck_assert(values.quick_connect);
    ck_assert(co_file_store_get_devicenet(&store, 4, &values));
    ck_assert_uint_eq(values.consumed_assembly, 20);
    ck_assert_uint_eq(values.produced_assembly, 70);
    ck_assert(!values.quick_connect);
    co_file_store_node_t n4;
    co_storage_t s4;
    co_file_store_bind(&store, 4, &n4, &s4);
    assert_loads(&s4, 2, IMAGE("COMM"));
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
}
END_TEST

/* Writes a file of one record, its CRC right, as another program could. */
static void write_one_record(uint8_t key, uint8_t area, const uint8_t *data, uint32_t len)
{
    uint8_t buf[64];
    ck_assert_uint_le(len, sizeof buf - 24);
    memcpy(buf, "CoSF", 4);
    co_put_u16(buf + 4, 1);
    co_put_u16(buf + 6, 1);
    co_put_u32(buf + 8, 8 + len);
    uint8_t header[8] = {key, area, 0, 0, (uint8_t)len, 0, 0, 0};
    memcpy(buf + 12, header, 8);
    memcpy(buf + 20, data, len);
    co_put_u32(buf + 20 + len, co_crc32(buf, 20 + len));
    write_file(buf, 24 + len);
}

/* A DeviceNet record with a MAC ID above 63, another length or a Quick Connect other than 0/1
 * makes the file ignored like any other bad record. */
START_TEST(bad_devicenet_record_is_ignored)
{
    static const struct {
        uint8_t mac_id;
        uint8_t data[6];
        uint32_t len;
        const char *why;
    } cases[] = {
        {64, {21, 0, 71, 0, 0}, 5, "record 1: node-id 64, area 128"},
        {25, {21, 0, 71, 0}, 4, "MAC ID 25 (DeviceNet): 4 bytes, its record has 5"},
        {25, {21, 0, 71, 0, 0, 0}, 6, "MAC ID 25 (DeviceNet): 6 bytes, its record has 5"},
        {25, {21, 0, 71, 0, 2}, 5, "MAC ID 25 (DeviceNet): Quick Connect 2 is not 0 or 1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_one_record(cases[i].mac_id, CO_FILE_STORE_AREA_DEVICENET, cases[i].data,
                         cases[i].len);
        assert_ignored(cases[i].why);
    }
}
END_TEST

/* An LSS record (CiA 305 store configuration, docs/lss.md): under a node-id's key or an
 * unconfigured node's (80h + k), beside the images, byte for byte, and read back after a
 * reopen; a node-id FFh (none) and the table's last bit timing are values it can hold. */
START_TEST(lss_records_round_trip)
{
    uint8_t buf[256];
    make_valid_file(buf, sizeof buf);
    co_file_store_t store;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    uint8_t node_id = 0, bit_timing = 0;
    ck_assert(!co_file_store_get_lss(&store, 4, &node_id, &bit_timing));
    const uint8_t unconfigured = CO_FILE_STORE_UNCONFIGURED_KEY + 1;
    ck_assert_int_eq(co_file_store_set_lss(&store, 4, 20, 2), 0);
    ck_assert_int_eq(co_file_store_set_lss(&store, unconfigured, CO_LSS_NODE_ID_UNCONFIGURED,
                                           CO_LSS_BIT_TIMING_INDEX_MAX),
                     0);
    co_file_store_close(&store);

    size_t len = read_file(buf, sizeof buf);
    /* Sorted by key then area: node 4 area 2, node 4 LSS (area 81h), node 5 area 4, key 81h. */
    static const uint8_t node4_lss[10] = {4, 0x81, 0, 0, 2, 0, 0, 0, 20, 2};
    size_t image = 8 + strlen(IMAGE("COMM"));
    ck_assert_mem_eq(buf + 12 + image, node4_lss, sizeof node4_lss);
    static const uint8_t key81_lss[10] = {0x81, 0x81, 0, 0, 2, 0, 0, 0, 0xFF, 9};
    ck_assert_mem_eq(buf + len - 4 - sizeof key81_lss, key81_lss, sizeof key81_lss);

    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    ck_assert_uint_eq(store.count, 4);
    ck_assert(co_file_store_get_lss(&store, 4, &node_id, &bit_timing));
    ck_assert_uint_eq(node_id, 20);
    ck_assert_uint_eq(bit_timing, 2);
    ck_assert(co_file_store_get_lss(&store, unconfigured, &node_id, &bit_timing));
    ck_assert_uint_eq(node_id, CO_LSS_NODE_ID_UNCONFIGURED);
    ck_assert_uint_eq(bit_timing, CO_LSS_BIT_TIMING_INDEX_MAX);
    ck_assert(!co_file_store_get_lss(&store, 5, &node_id, &bit_timing));
    co_file_store_node_t n4;
    co_storage_t s4;
    co_file_store_bind(&store, 4, &n4, &s4);
    assert_loads(&s4, 2, IMAGE("COMM"));
    co_file_store_unbind(&n4);
    co_file_store_close(&store);
}
END_TEST

/* An LSS record of another length, a node-id LSS cannot configure (0, 128) or a bit timing
 * beyond table 0 makes the file ignored like any other bad record. */
START_TEST(bad_lss_record_is_ignored)
{
    static const struct {
        uint8_t data[3];
        uint32_t len;
        const char *why;
    } cases[] = {
        {{20}, 1, "node 4 (LSS): 1 bytes, its record has 2"},
        {{20, 2, 0}, 3, "node 4 (LSS): 3 bytes, its record has 2"},
        {{0, 2}, 2, "node 4 (LSS): node-id 0 or bit timing 2 is invalid"},
        {{128, 2}, 2, "node 4 (LSS): node-id 128 or bit timing 2 is invalid"},
        {{20, CO_LSS_BIT_TIMING_INDEX_MAX + 1},
         2,
         "node 4 (LSS): node-id 20 or bit timing 10 is invalid"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_one_record(4, CO_FILE_STORE_AREA_LSS, cases[i].data, cases[i].len);
        assert_ignored(cases[i].why);
    }
}
END_TEST

/* An unconfigured node's parameters are kept under its key (80h + k), which no node-id is;
 * 80h itself is no node's key. */
START_TEST(parameters_under_an_unconfigured_key)
{
    const char *comm = IMAGE("COMM");
    write_one_record(CO_FILE_STORE_UNCONFIGURED_KEY + 1, CO_STORE_AREA_COMMUNICATION,
                     (const uint8_t *)comm, (uint32_t)strlen(comm));
    co_file_store_t store;
    ck_assert_int_eq(co_file_store_open(&store, path), CO_FILE_STORE_LOADED);
    co_file_store_node_t node;
    co_storage_t storage;
    co_file_store_bind(&store, CO_FILE_STORE_UNCONFIGURED_KEY + 1, &node, &storage);
    assert_loads(&storage, CO_STORE_AREA_COMMUNICATION, comm);
    co_file_store_unbind(&node);
    co_file_store_close(&store);
    write_one_record(CO_FILE_STORE_UNCONFIGURED_KEY, CO_STORE_AREA_COMMUNICATION,
                     (const uint8_t *)comm, (uint32_t)strlen(comm));
    assert_ignored("record 1: node-id 128, area 2");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("file_store");
    TCase *tc = tcase_create("file_store");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, round_trip_several_nodes);
    tcase_add_test(tc, exact_file_layout);
    tcase_add_test(tc, save_replaces_atomically);
    tcase_add_test(tc, grouped_saves_replace_the_file_once);
    tcase_add_test(tc, failed_save_changes_nothing);
    tcase_add_test(tc, discarded_save_and_erase);
    tcase_add_test(tc, truncated_file_is_ignored);
    tcase_add_test(tc, bad_crc_is_ignored);
    tcase_add_test(tc, wrong_magic_or_version_is_ignored);
    tcase_add_test(tc, bad_record_with_good_crc_is_ignored);
    tcase_add_test(tc, image_with_a_record_outside_its_area_is_ignored);
    tcase_add_test(tc, duplicate_record_or_foreign_image_is_ignored);
    tcase_add_test(tc, damaged_file_is_kept_aside_at_next_save);
    tcase_add_test(tc, devicenet_records_beside_images);
    tcase_add_test(tc, bad_devicenet_record_is_ignored);
    tcase_add_test(tc, lss_records_round_trip);
    tcase_add_test(tc, bad_lss_record_is_ignored);
    tcase_add_test(tc, parameters_under_an_unconfigured_key);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
