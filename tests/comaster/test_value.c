/* SPDX-License-Identifier: Apache-2.0 */
/* comaster's values and object names: every data type parsed from text into the bytes of a
 * download and printed from the bytes of an upload, range errors, objects by index and by name
 * through the project's EDS, and the EDS found for a node's identity. */
#include "check_main.h"
#include "comaster/value.h"

#include <stdio.h>
#include <string.h>

static const comaster_type_t *type(const char *name)
{
    const comaster_type_t *t = comaster_type_by_name(name);
    ck_assert_msg(t != NULL, "no type %s", name);
    return t;
}

/* Parses text as the type and checks the bytes, then prints them back and checks the text. */
static void round_trip(const char *type_name, const char *text, const uint8_t *bytes, size_t n,
                       const char *printed)
{
    uint8_t out[64];
    size_t len = 0;
    char err[256] = "";
    ck_assert_msg(
        comaster_value_parse(type(type_name), text, out, sizeof out, &len, err, sizeof err),
        "%s %s: %s", type_name, text, err);
    ck_assert_uint_eq(len, n);
    ck_assert_mem_eq(out, bytes, n);
    char back[256];
    bool is_text;
    ck_assert(comaster_value_format(type(type_name), out, len, COMASTER_VALUE_DECIMAL, back,
                                    sizeof back, &is_text));
    ck_assert_str_eq(back, printed);
}

static void parse_fails(const char *type_name, const char *text, const char *message)
{
    uint8_t out[8];
    size_t len;
    char err[256] = "";
    ck_assert(!comaster_value_parse(type(type_name), text, out, sizeof out, &len, err, sizeof err));
    ck_assert_str_eq(err, message);
}

START_TEST(integers)
{
    round_trip("u8", "255", (const uint8_t[]){0xFF}, 1, "255");
    round_trip("UNSIGNED16", "0x1234", (const uint8_t[]){0x34, 0x12}, 2, "4660");
    round_trip("u32", "65938", (const uint8_t[]){0x92, 0x01, 0x01, 0x00}, 4, "65938");
    round_trip("u64", "18446744073709551615",
               (const uint8_t[]){0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}, 8,
               "18446744073709551615");
    round_trip("i8", "-128", (const uint8_t[]){0x80}, 1, "-128");
    round_trip("i16", "-1500", (const uint8_t[]){0x24, 0xFA}, 2, "-1500");
    round_trip("INTEGER32", "-2", (const uint8_t[]){0xFE, 0xFF, 0xFF, 0xFF}, 4, "-2");
    round_trip("i64", "-1", (const uint8_t[]){0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}, 8,
               "-1");
    round_trip("bool", "true", (const uint8_t[]){1}, 1, "1");
    round_trip("BOOLEAN", "0", (const uint8_t[]){0}, 1, "0");
}
END_TEST

START_TEST(integer_errors)
{
    parse_fails("u8", "256", "256 is out of range for UNSIGNED8 (0..255)");
    parse_fails("u16", "-1", "'-1' is not a UNSIGNED16: give a number such as 12 or 0x1F");
    parse_fails("i16", "32768", "32768 is out of range for INTEGER16 (-32768..32767)");
    parse_fails("i8", "12x", "'12x' is not an integer: give a number such as -12 or 0x1F");
    parse_fails("bool", "2", "2 is out of range for BOOLEAN (0..1)");
    parse_fails("u32", "", "'' is not a UNSIGNED32: give a number such as 12 or 0x1F");
}
END_TEST

START_TEST(reals_strings_bytes)
{
    round_trip("f32", "1.5", (const uint8_t[]){0x00, 0x00, 0xC0, 0x3F}, 4, "1.5");
    round_trip("REAL64", "-2", (const uint8_t[]){0, 0, 0, 0, 0, 0, 0x00, 0xC0}, 8, "-2");
    round_trip("string", "ATV312", (const uint8_t *)"ATV312", 6, "ATV312");
    round_trip("octets", "01 02 0a", (const uint8_t[]){1, 2, 0x0A}, 3, "01 02 0A");
    round_trip("domain", "DEADBEEF", (const uint8_t[]){0xDE, 0xAD, 0xBE, 0xEF}, 4, "DE AD BE EF");
    parse_fails("f32", "nan", "'nan' is not a REAL32: give a finite number such as 1.5 or -2e3");
    /* Beyond a REAL32's finite range: refused, not written as an infinity. */
    parse_fails("f32", "-1e39",
                "-1e39 is out of range for REAL32 (at most 3.40282e+38 in magnitude)");
    parse_fails("octets", "0G", "'0G' is not hexadecimal bytes: give them as 01 02 0A or 01020A");
    parse_fails("octets", "010203040506070809", "more than 8 bytes");
}
END_TEST

START_TEST(format_errors_and_strings)
{
    char out[128];
    bool is_text;
    const uint8_t three[] = {1, 2, 3};
    ck_assert(!comaster_value_format(type("u16"), three, 3, COMASTER_VALUE_DECIMAL, out, sizeof out,
                                     &is_text));
    ck_assert_str_eq(out, "3 bytes do not fit UNSIGNED16 (2 bytes)");
    const uint8_t padded[] = {'A', 'T', 0, 'x'};
    ck_assert(comaster_value_format(type("string"), padded, 4, COMASTER_VALUE_DECIMAL, out,
                                    sizeof out, &is_text));
    ck_assert_str_eq(out, "AT");
    ck_assert(is_text);
    ck_assert(comaster_value_format(type("u8"), three, 1, COMASTER_VALUE_DECIMAL, out, sizeof out,
                                    &is_text));
    ck_assert(!is_text);
    const uint8_t nan32[] = {0x00, 0x00, 0xC0, 0x7F}, minus_inf[] = {0x00, 0x00, 0x80, 0xFF};
    ck_assert(comaster_value_format(type("f32"), nan32, 4, COMASTER_VALUE_DECIMAL, out, sizeof out,
                                    &is_text));
    ck_assert_str_eq(out, "nan");
    ck_assert(is_text); /* not a JSON number */
    ck_assert(comaster_value_format(type("f32"), minus_inf, 4, COMASTER_VALUE_DECIMAL, out,
                                    sizeof out, &is_text));
    ck_assert_str_eq(out, "-inf");
    ck_assert(is_text);
    const uint8_t minus_half[] = {0x00, 0x00, 0x00, 0xBF};
    ck_assert(comaster_value_format(type("f32"), minus_half, 4, COMASTER_VALUE_DECIMAL, out,
                                    sizeof out, &is_text));
    ck_assert_str_eq(out, "-0.5");
    ck_assert(!is_text);
    ck_assert_ptr_null(comaster_type_by_name("u7"));
    ck_assert_ptr_eq(comaster_type_by_code(CO_DT_INTEGER16), type("i16"));
}
END_TEST

/* A DCF's ParameterValue (comaster concise decode): BOOLEAN and the unsigned integers in 0x
 * hexadecimal, quoted by a JSON writer; signed integers and reals stay decimal numbers. */
START_TEST(format_hex_style)
{
    char out[64];
    bool is_text;
    const uint8_t u16[] = {0x64, 0x00}, u32[] = {0x84, 0x02, 0x00, 0x00}, one[] = {1};
    const uint8_t minus_one[] = {0xFF, 0xFF}, minus_half[] = {0x00, 0x00, 0x00, 0xBF};
    ck_assert(
        comaster_value_format(type("u16"), u16, 2, COMASTER_VALUE_HEX, out, sizeof out, &is_text));
    ck_assert_str_eq(out, "0x64");
    ck_assert(is_text);
    ck_assert(
        comaster_value_format(type("u32"), u32, 4, COMASTER_VALUE_HEX, out, sizeof out, &is_text));
    ck_assert_str_eq(out, "0x284");
    ck_assert(
        comaster_value_format(type("bool"), one, 1, COMASTER_VALUE_HEX, out, sizeof out, &is_text));
    ck_assert_str_eq(out, "0x1");
    ck_assert(comaster_value_format(type("i16"), minus_one, 2, COMASTER_VALUE_HEX, out, sizeof out,
                                    &is_text));
    ck_assert_str_eq(out, "-1");
    ck_assert(!is_text);
    ck_assert(comaster_value_format(type("f32"), minus_half, 4, COMASTER_VALUE_HEX, out, sizeof out,
                                    &is_text));
    ck_assert_str_eq(out, "-0.5");
    ck_assert(!is_text);
    ck_assert(comaster_value_format(type("u16"), u16, 2, COMASTER_VALUE_DECIMAL, out, sizeof out,
                                    &is_text));
    ck_assert_str_eq(out, "100");
    ck_assert(!is_text);
}
END_TEST

/* The numbers of the command line (lss) and of a network file: decimal, 0x or 0 octal, no sign,
 * nothing after them, 0..max. */
START_TEST(numbers)
{
    uint32_t v = 7;
    ck_assert(comaster_parse_number("0x5F", UINT32_MAX, &v));
    ck_assert_uint_eq(v, 0x5F);
    ck_assert(comaster_parse_number("4294967295", UINT32_MAX, &v));
    ck_assert_uint_eq(v, UINT32_MAX);
    ck_assert(comaster_parse_number("010", 127, &v));
    ck_assert_uint_eq(v, 8);
    ck_assert(comaster_parse_number("127", 127, &v));
    ck_assert_uint_eq(v, 127);
    v = 7;
    ck_assert(!comaster_parse_number("128", 127, &v));
    ck_assert(!comaster_parse_number("4294967296", UINT32_MAX, &v));
    ck_assert(!comaster_parse_number("-1", UINT32_MAX, &v));
    ck_assert(!comaster_parse_number("", UINT32_MAX, &v));
    ck_assert(!comaster_parse_number("12a", UINT32_MAX, &v));
    ck_assert(!comaster_parse_number("99999999999999999999999", UINT32_MAX, &v));
    ck_assert_uint_eq(v, 7); /* untouched when refused */
}
END_TEST

START_TEST(objects_by_index)
{
    comaster_object_t o;
    char err[512];
    ck_assert(comaster_object_parse("0x203C:2", NULL, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x203C);
    ck_assert_uint_eq(o.sub, 2);
    ck_assert(comaster_object_parse("1008", NULL, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x1008);
    ck_assert_uint_eq(o.sub, 0);
    ck_assert(comaster_object_parse("0x1A00:0x01", NULL, &o, err, sizeof err));
    ck_assert_uint_eq(o.sub, 1);
    ck_assert(!comaster_object_parse("0x203C:256", NULL, &o, err, sizeof err));
    ck_assert(!comaster_object_parse("ACC", NULL, &o, err, sizeof err));
    ck_assert_str_eq(err, "'ACC' is not an object: give INDEX:SUB such as 0x203C:2, or a name "
                          "with --eds FILE (or an EDS for the node's identity in the EDS "
                          "directory)");
}
END_TEST

static eds_t eds;

static void load_eds(void)
{
    char err[256];
    ck_assert_int_eq(eds_load(&eds, COMASTER_TEST_EDS_DIR "/ATV312.eds", 4, err, sizeof err),
                     EDS_OK);
}

static void free_eds(void)
{
    eds_free(&eds);
}

START_TEST(objects_by_name)
{
    comaster_object_t o;
    char err[512];
    ck_assert(comaster_object_parse("ACC", &eds, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x203C);
    ck_assert_uint_eq(o.sub, 2);
    ck_assert_uint_eq(o.data_type, CO_DT_UNSIGNED16);
    ck_assert_str_eq(o.name, "ACC acceleration time (0.1 s)");
    ck_assert(comaster_object_parse("acceleration time", &eds, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x203C);
    ck_assert(comaster_object_parse("Manufacturer device name", &eds, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x1008);
    ck_assert_uint_eq(o.data_type, CO_DT_VISIBLE_STRING);
    ck_assert(comaster_object_parse("0x1008", &eds, &o, err, sizeof err));
    ck_assert_str_eq(o.name, "Manufacturer device name");
    ck_assert(!comaster_object_parse("no such thing", &eds, &o, err, sizeof err));
    ck_assert_str_eq(err, "no object of the EDS is named 'no such thing': give its ParameterName "
                          "(or code, ACC), or INDEX:SUB such as 0x203C:2");
    ck_assert(!comaster_object_parse("time", &eds, &o, err, sizeof err));
    ck_assert_str_eq(err, "'time' names several objects of the EDS (one is 100C:00 'Guard time'): "
                          "give more of the name, or INDEX:SUB");
}
END_TEST

/* A name matches whole words of a ParameterName, not any part of one: "NOPE" is in "CANopen" but
 * names nothing; an unknown name is told with the parameter codes closest to it. */
START_TEST(names_match_words_and_unknown_ones_suggest_codes)
{
    comaster_object_t o;
    char err[512];
    ck_assert(!comaster_object_parse("NOPE", &eds, &o, err, sizeof err));
    ck_assert_str_eq(err, "no object of the EDS is named 'NOPE' (the closest code is NSP): give "
                          "its ParameterName (or code, ACC), or INDEX:SUB such as 0x203C:2");
    ck_assert(!comaster_object_parse("ACX", &eds, &o, err, sizeof err));
    ck_assert_str_eq(err, "no object of the EDS is named 'ACX' (the closest codes are ACC, AC2): "
                          "give its ParameterName (or code, ACC), or INDEX:SUB such as 0x203C:2");
    ck_assert(!comaster_object_parse("celeration", &eds, &o, err, sizeof err));
    ck_assert_str_eq(err, "no object of the EDS is named 'celeration': give its ParameterName "
                          "(or code, ACC), or INDEX:SUB such as 0x203C:2");
    ck_assert(comaster_object_parse("deceleration time", &eds, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x203C);
    ck_assert_uint_eq(o.sub, 3);
    ck_assert(comaster_object_parse("fault management", &eds, &o, err, sizeof err));
    ck_assert_uint_eq(o.index, 0x2022);
    ck_assert_uint_eq(o.sub, 2);
}
END_TEST

START_TEST(eds_for_identity)
{
    char path[4096];
    eds_identity_t atv31 = {0x5F, 0, "ATV31"};
    ck_assert(eds_find_for_identity(COMASTER_TEST_EDS_DIR, &atv31, path, sizeof path));
    ck_assert_str_eq(path, COMASTER_TEST_EDS_DIR "/ATV31.eds");
    eds_identity_t atv312 = {0x5F, 0, "ATV312"};
    ck_assert(eds_find_for_identity(COMASTER_TEST_EDS_DIR, &atv312, path, sizeof path));
    ck_assert_str_eq(path, COMASTER_TEST_EDS_DIR "/ATV312.eds");
    eds_identity_t other = {0x1234, 0, "ATV312"};
    ck_assert(!eds_find_for_identity(COMASTER_TEST_EDS_DIR, &other, path, sizeof path));
    ck_assert(!eds_find_for_identity("/nonexistent", &atv312, path, sizeof path));
    ck_assert_uint_eq(eds.vendor_number, 0x5F);
}
END_TEST

START_TEST(values_set_as_read_over_sdo)
{
    /* 1A05h:01 has a default; 1A05h:09 is not in the file: it is added. */
    ck_assert(eds_set_value(&eds, 0x1A05, 1, 0x60410010));
    ck_assert(eds_set_value(&eds, 0x1A05, 9, 0x12345678));
    const eds_entry_t *e = eds_find(&eds, 0x1A05, 1);
    ck_assert(e->has_value);
    ck_assert_uint_eq(e->value, 0x60410010);
    ck_assert_str_eq(e->name, eds_name(&eds, 0x1A05, 1));
    e = eds_find(&eds, 0x1A05, 9);
    ck_assert(e && e->has_value && e->value == 0x12345678);
    ck_assert_ptr_null(e->name);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("comaster_value");
    TCase *tc = tcase_create("value");
    tcase_add_test(tc, integers);
    tcase_add_test(tc, integer_errors);
    tcase_add_test(tc, reals_strings_bytes);
    tcase_add_test(tc, format_errors_and_strings);
    tcase_add_test(tc, format_hex_style);
    tcase_add_test(tc, numbers);
    tcase_add_test(tc, objects_by_index);
    suite_add_tcase(s, tc);
    TCase *named = tcase_create("names");
    tcase_add_checked_fixture(named, load_eds, free_eds);
    tcase_add_test(named, objects_by_name);
    tcase_add_test(named, names_match_words_and_unknown_ones_suggest_codes);
    tcase_add_test(named, eds_for_identity);
    tcase_add_test(named, values_set_as_read_over_sdo);
    suite_add_tcase(s, named);
    return check_run_suite(s);
}
