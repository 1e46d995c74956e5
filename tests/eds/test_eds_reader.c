/* SPDX-License-Identifier: Apache-2.0 */
/* The EDS/DCF reader's CiA 306 syntax, file by file through eds_load: comments only on lines of
 * their own, blanks and carriage returns around everything, keys and sections of any case, keys
 * outside object sections ignored, a repeated key's last value (but a ParameterValue wins over a
 * later DefaultValue), a repeated section read as a second entry, [DeviceInfo], object sections
 * named exactly as CiA 306 writes them, numbers as it writes them, and each syntax error with the
 * file and the line (counting comments and blank lines). */
#include "check_main.h"
#include "eds/eds_reader.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char path[] = "/tmp/eds-reader-test-XXXXXX";
static eds_t eds;
static char err[512];

static void setup(void)
{
    memcpy(path + strlen(path) - 6, "XXXXXX", 6);
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    err[0] = '\0';
}

static void teardown(void)
{
    eds_free(&eds);
    unlink(path);
}

static eds_result_t load(const char *text)
{
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
    eds_free(&eds);
    return eds_load(&eds, path, 4, err, sizeof err);
}

/* The error the reader gives for `text`, with the file's path taken off its front. */
static const char *error_of(const char *text)
{
    ck_assert_int_eq(load(text), EDS_MALFORMED);
    ck_assert_uint_eq(eds.count, 0);
    ck_assert_ptr_null(eds.entries);
    size_t len = strlen(path);
    ck_assert_msg(strncmp(err, path, len) == 0, "%s", err);
    return err + len;
}

START_TEST(comments_only_on_lines_of_their_own)
{
    ck_assert_int_eq(load("; CiA 306 comment\n"
                          "   # indented comment\n"
                          "[1000]\n"
                          "ParameterName=Device type ; not a comment\n"
                          "DefaultValue=0x00010192\n"
                          "[1008]\n"
                          "ParameterName=Name #1\n"),
                     EDS_OK);
    ck_assert_str_eq(eds_name(&eds, 0x1000, 0), "Device type ; not a comment");
    ck_assert_uint_eq(eds_find(&eds, 0x1000, 0)->value, 0x00010192);
    ck_assert_str_eq(eds_name(&eds, 0x1008, 0), "Name #1");
}
END_TEST

START_TEST(blanks_carriage_returns_and_case)
{
    ck_assert_int_eq(load("\r\n"
                          "  [ 1a00 ]  text after the bracket\r\n"
                          "  parametername  =  TPDO1 mapping  \r\n"
                          "[1A00SUB1]\r\n"
                          "DATATYPE = 0x0007\r\n"
                          "defaultvalue\t=\t0x60410010\r\n"
                          "accesstype = RW\r\n"
                          "[1a00Sub2]\n"
                          "PARAMETERVALUE = $nodeid + 0x10\n"),
                     EDS_OK);
    ck_assert_str_eq(eds_name(&eds, 0x1A00, 0), "TPDO1 mapping");
    const eds_entry_t *e = eds_find(&eds, 0x1A00, 1);
    ck_assert_ptr_nonnull(e);
    ck_assert_uint_eq(e->data_type, 0x0007);
    ck_assert_uint_eq(e->value, 0x60410010);
    ck_assert_str_eq(e->text, "0x60410010");
    ck_assert(e->writable);
    e = eds_find(&eds, 0x1A00, 2);
    ck_assert_ptr_nonnull(e);
    ck_assert_uint_eq(e->value, 0x14);
    ck_assert(e->configured);
}
END_TEST

START_TEST(keys_outside_object_sections_ignored)
{
    ck_assert_int_eq(load("DataType=before any section\n"
                          "[FileInfo]\n"
                          "FileName=x.eds\n"
                          "DataType=not a number\n"
                          "[1F22Value]\n"
                          "DataType=not a number\n"
                          "[1000]\n"
                          "ParameterName=Device type\n"
                          "ObjFlags=0\n"
                          "=no key\n"),
                     EDS_OK);
    ck_assert_uint_eq(eds.count, 1);
    ck_assert_str_eq(eds_name(&eds, 0x1000, 0), "Device type");
}
END_TEST

START_TEST(repeated_keys_and_sections)
{
    ck_assert_int_eq(load("[1000]\n"
                          "ParameterName=First\n"
                          "ParameterName=Second\n"
                          "DefaultValue=1\n"
                          "DefaultValue=2\n"
                          "[2000]\n"
                          "ParameterValue=7\n"
                          "DefaultValue=8\n"
                          "[1000]\n"
                          "ParameterName=Again\n"
                          "DefaultValue=3\n"),
                     EDS_OK);
    ck_assert_uint_eq(eds.count, 3);
    ck_assert_str_eq(eds_name(&eds, 0x1000, 0), "Second");
    ck_assert_uint_eq(eds_find(&eds, 0x1000, 0)->value, 2);
    ck_assert_str_eq(eds.entries[2].name, "Again");
    const eds_entry_t *e = eds_find(&eds, 0x2000, 0);
    ck_assert_uint_eq(e->value, 7);
    ck_assert_str_eq(e->text, "7");
    ck_assert(e->configured);
}
END_TEST

START_TEST(device_info_of_any_case)
{
    ck_assert_int_eq(load("[1000]\n"
                          "ParameterName=Device type\n"
                          "[deviceinfo]\n"
                          "vendornumber = 0x0500005A\n"
                          "ProductNumber=not a number\n"
                          "ParameterName=not an object's\n"
                          "[1018sub1]\n"
                          "VendorNumber=0x99\n"),
                     EDS_OK);
    ck_assert_uint_eq(eds.vendor_number, 0x0500005A);
    ck_assert_uint_eq(eds.product_number, 0);
    ck_assert_str_eq(eds_name(&eds, 0x1000, 0), "Device type");
}
END_TEST

START_TEST(syntax_errors_name_the_line)
{
    ck_assert_str_eq(error_of("; comment\n\n[1000]\nParameterName=x\n[1001\n"),
                     ":5: section header '[1001' has no ']'");
    ck_assert_str_eq(error_of("[1000]\n  junk line \n"),
                     ":2: 'junk line' is neither a [section] nor a key=value line");
    ck_assert_str_eq(error_of("; comment\n\n[1000]\nDataType=seven\n"),
                     ":4: DataType 'seven' is not a number such as 0x0006");
    ck_assert_str_eq(error_of("; only comments\n"),
                     ": no object sections such as [1000]: not an EDS or DCF");
}
END_TEST

/* Issue 22 item 10: an object's section is four hex digits, a sub-index's adds "sub" and one or
 * two, in any case. A name that starts as a number in another notation is refused with its line,
 * never read as some other object ([0x12] was 0012h); a name that goes on with a word ([1F22Value],
 * [DeviceInfo]) is a section of another kind, ignored. */
START_TEST(object_sections_named_as_cia306_writes_them)
{
    ck_assert_int_eq(load("[0012]\n"
                          "ParameterName=Type 12h\n"
                          "[1a00SUB0A]\n"
                          "ParameterName=Tenth\n"
                          "[1A00sub1]\n"
                          "ParameterName=First\n"
                          "[Bad1Name]\n"
                          "ParameterName=not an object's\n"),
                     EDS_OK);
    ck_assert_uint_eq(eds.count, 3);
    ck_assert_str_eq(eds_name(&eds, 0x0012, 0), "Type 12h");
    ck_assert_str_eq(eds_name(&eds, 0x1A00, 0x0A), "Tenth");
    ck_assert_str_eq(eds_name(&eds, 0x1A00, 0x01), "First");
    static const char *const refused[] = {
        "0x12",       "0X1018",    "12",        "01018",      "+1018",
        "-1018",      "1018sub",   "1018SUB",   "1018sub100", "1018sub 1",
        "1018sub0x1", "1018sub+1", "1018 sub1", "1018subG",   "BAD",
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        char text[128], want[160];
        snprintf(text, sizeof text, "; comment\n[1000]\nParameterName=x\n[%s]\n", refused[i]);
        snprintf(want, sizeof want,
                 ":4: section [%s] is not an object's: write its index in four hex digits "
                 "([1018]), a sub-index's with sub and one or two ([1018sub1])",
                 refused[i]);
        ck_assert_str_eq(error_of(text), want);
    }
}
END_TEST

/* CiA 306 numbers: decimal, 0x hex or octal, "+" only between the terms of a sum, no "+" before a
 * number, and no sum beyond 64 bits. */
START_TEST(numbers_as_cia306_writes_them)
{
    ck_assert_int_eq(load("[1000]\n"
                          "DefaultValue=+5\n"
                          "[1001]\n"
                          "DefaultValue=$NODEID++5\n"
                          "[1002]\n"
                          "DefaultValue=0xFFFFFFFFFFFFFFFF+1\n"
                          "[1003]\n"
                          "DefaultValue=$NODEID+0xFFFFFFFFFFFFFFFF\n"
                          "[1004]\n"
                          "DefaultValue=0x\n"
                          "[1005]\n"
                          "DefaultValue=0xFFFFFFFFFFFFFFFE+1\n"
                          "[1006]\n"
                          "DefaultValue=010 + $NODEID\n"),
                     EDS_OK);
    for (uint16_t index = 0x1000; index <= 0x1004; index++)
        ck_assert_msg(!eds_find(&eds, index, 0)->has_value, "%04X has a value", index);
    ck_assert(eds_find(&eds, 0x1005, 0)->has_value);
    ck_assert_uint_eq(eds_find(&eds, 0x1005, 0)->value, UINT64_MAX);
    ck_assert_uint_eq(eds_find(&eds, 0x1006, 0)->value, 8 + 4);
    ck_assert_str_eq(error_of("[1000]\nDataType=+7\n"),
                     ":2: DataType '+7' is not a number such as 0x0006");
}
END_TEST

/* A '-' sign before a lone number (the value of a signed type): decimal, hex or octal, in two's
 * complement, down to INT64_MIN; never in a $NODEID sum, never before a blank or a second sign;
 * not in a DataType. The line of the value is kept for messages. */
START_TEST(negative_numbers_alone)
{
    ck_assert_int_eq(load("[1000]\n"
                          "DefaultValue=-1234\n"
                          "[1001]\n"
                          "ParameterValue= -0x10 \n"
                          "[1002]\n"
                          "DefaultValue=-010\n"
                          "[1003]\n"
                          "DefaultValue=-9223372036854775808\n"
                          "[1004]\n"
                          "DefaultValue=-9223372036854775809\n"
                          "[1005]\n"
                          "DefaultValue=-5+$NODEID\n"
                          "[1006]\n"
                          "DefaultValue=$NODEID+-5\n"
                          "[1007]\n"
                          "DefaultValue=- 5\n"
                          "[1008]\n"
                          "DefaultValue=--5\n"
                          "[1009]\n"
                          "DefaultValue=-$NODEID\n"),
                     EDS_OK);
    static const int64_t values[] = {-1234, -16, -8, INT64_MIN};
    for (uint16_t index = 0x1000; index <= 0x1003; index++) {
        const eds_entry_t *e = eds_find(&eds, index, 0);
        ck_assert_msg(e->has_value && e->negative, "%04X", index);
        ck_assert_int_eq((int64_t)e->value, values[index - 0x1000]);
    }
    ck_assert_uint_eq(eds_find(&eds, 0x1001, 0)->value_line, 4);
    for (uint16_t index = 0x1004; index <= 0x1009; index++)
        ck_assert_msg(!eds_find(&eds, index, 0)->has_value, "%04X has a value", index);
    ck_assert_str_eq(error_of("[1000]\nDataType=-7\n"),
                     ":2: DataType '-7' is not a number such as 0x0006");
}
END_TEST

/* A value that is no number leaves no number behind: not the entry's earlier value, not the one
 * of its sign's number. The fuzz harness read "ParameterValue=-1)" after "DefaultValue=5" as 5,
 * and a canonical rendering of the file, without the 5, differently. */
START_TEST(a_value_that_is_no_number_leaves_none)
{
    ck_assert_int_eq(load("[1000]\n"
                          "DefaultValue=5\n"
                          "ParameterValue=-1)\n"
                          "[1001]\n"
                          "DefaultValue=7\n"
                          "ParameterValue=12x\n"),
                     EDS_OK);
    for (uint16_t index = 0x1000; index <= 0x1001; index++) {
        const eds_entry_t *e = eds_find(&eds, index, 0);
        ck_assert_msg(!e->has_value && e->value == 0 && !e->negative, "%04X: %llu", index,
                      (unsigned long long)e->value);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("eds_reader");
    TCase *tc = tcase_create("syntax");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, comments_only_on_lines_of_their_own);
    tcase_add_test(tc, a_value_that_is_no_number_leaves_none);
    tcase_add_test(tc, blanks_carriage_returns_and_case);
    tcase_add_test(tc, keys_outside_object_sections_ignored);
    tcase_add_test(tc, repeated_keys_and_sections);
    tcase_add_test(tc, device_info_of_any_case);
    tcase_add_test(tc, syntax_errors_name_the_line);
    tcase_add_test(tc, object_sections_named_as_cia306_writes_them);
    tcase_add_test(tc, numbers_as_cia306_writes_them);
    tcase_add_test(tc, negative_numbers_alone);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
