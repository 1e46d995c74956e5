/* SPDX-License-Identifier: Apache-2.0 */
/* The INI line reader on its own: what each callback is handed (section, key, value, line
 * number), a key before any header in the section "", and the reading stopped by a callback's
 * false, its error kept. The dialects of its two users are tested through them
 * (test_eds_reader.c, tests/comaster/test_network.c). */
#include "check_main.h"
#include "eds/ini_reader.h"

#include <stdio.h>
#include <string.h>

typedef struct seen {
    char lines[8][64];
    size_t count;
    size_t stop_at; /* the callback refuses this line (1-based count), 0: none */
} seen_t;

static bool record(void *ctx, const ini_line_t *line, char *err, size_t err_len)
{
    seen_t *seen = ctx;
    ck_assert_uint_lt(seen->count, 8);
    snprintf(seen->lines[seen->count++], sizeof seen->lines[0], "%u [%s] %s=%s", line->number,
             line->section, line->key ? line->key : "(header)", line->value ? line->value : "");
    if (seen->count != seen->stop_at)
        return true;
    snprintf(err, err_len, "%s:%u: refused", line->path, line->number);
    return false;
}

static bool read_text(const char *text, const ini_reader_t *reader, seen_t *seen, char *err,
                      size_t err_len)
{
    FILE *f = fmemopen((void *)text, strlen(text), "r");
    ck_assert_ptr_nonnull(f);
    bool ok = ini_read(f, "test.ini", reader, seen, err, err_len);
    fclose(f);
    return ok;
}

START_TEST(callbacks_get_section_key_value_and_line)
{
    const ini_reader_t reader = {.key_line = "key=value", .on_section = record, .on_key = record};
    seen_t seen = {0};
    char err[128] = "";
    ck_assert(read_text("first = 1\n; comment\n\n[ One ]\n a = b = c \n[Two]\nempty=\n", &reader,
                        &seen, err, sizeof err));
    ck_assert_uint_eq(seen.count, 5);
    ck_assert_str_eq(seen.lines[0], "1 [] first=1");
    ck_assert_str_eq(seen.lines[1], "4 [One] (header)=");
    ck_assert_str_eq(seen.lines[2], "5 [One] a=b = c");
    ck_assert_str_eq(seen.lines[3], "6 [Two] (header)=");
    ck_assert_str_eq(seen.lines[4], "7 [Two] empty=");
    ck_assert_str_eq(err, "");
}
END_TEST

START_TEST(headers_without_callback_only_name_the_section)
{
    const ini_reader_t reader = {
        .trailing_comments = true, .key_line = "key = value", .on_key = record};
    seen_t seen = {0};
    char err[128] = "";
    ck_assert(read_text("[A] ; a\nk = v ; c\n", &reader, &seen, err, sizeof err));
    ck_assert_uint_eq(seen.count, 1);
    ck_assert_str_eq(seen.lines[0], "2 [A] k=v");
}
END_TEST

START_TEST(a_refusing_callback_stops_the_reading)
{
    const ini_reader_t reader = {.key_line = "key=value", .on_section = record, .on_key = record};
    seen_t seen = {.stop_at = 2};
    char err[128] = "";
    ck_assert(!read_text("[A]\nk=v\nnot read\n", &reader, &seen, err, sizeof err));
    ck_assert_uint_eq(seen.count, 2);
    ck_assert_str_eq(err, "test.ini:2: refused");
}
END_TEST

/* A file of a section [1000] and a line of `length` characters: "ParameterName=", x's and
 * "[1001]" at its end. */
static void long_line_file(char *text, size_t length)
{
    const char *head = "[1000]\nParameterName=";
    size_t name = strlen("ParameterName=");
    strcpy(text, head);
    memset(text + strlen(head), 'x', length - name - strlen("[1001]"));
    strcpy(text + strlen(head) + length - name - strlen("[1001]"), "[1001]\n");
}

/* A line longer than the reader's buffer was read in pieces, each taken for a line of its own:
 * "[1001]" at the end of a long name became a section of the file. */
START_TEST(a_line_too_long_is_refused_with_its_number)
{
    const ini_reader_t reader = {.key_line = "key=value", .on_section = record, .on_key = record};
    static char text[2 * INI_LINE_MAX];
    seen_t seen = {0};
    char err[128] = "";
    long_line_file(text, INI_LINE_MAX - 2); /* with its newline, the buffer full */
    ck_assert_msg(read_text(text, &reader, &seen, err, sizeof err), "%s", err);
    ck_assert_uint_eq(seen.count, 2);

    /* One character more: refused at line 2, nothing of it read. */
    long_line_file(text, INI_LINE_MAX - 1);
    seen = (seen_t){0};
    ck_assert(!read_text(text, &reader, &seen, err, sizeof err));
    ck_assert_uint_eq(seen.count, 1);
    ck_assert_str_eq(err, "test.ini:2: line longer than 1022 characters");
}
END_TEST

/* A NUL byte is no character of a text file; read as the end of the line, it cut a long line in
 * two without notice, its tail read as a line of its own. */
START_TEST(a_nul_byte_is_refused_with_its_line)
{
    const ini_reader_t reader = {.key_line = "key=value", .on_section = record, .on_key = record};
    static const char text[] = "[1000]\nParameterName=x\0x[1001]\n";
    seen_t seen = {0};
    char err[128] = "";
    FILE *f = fmemopen((void *)text, sizeof text - 1, "r");
    ck_assert_ptr_nonnull(f);
    ck_assert(!ini_read(f, "test.ini", &reader, &seen, err, sizeof err));
    fclose(f);
    ck_assert_uint_eq(seen.count, 1);
    ck_assert_str_eq(err, "test.ini:2: a NUL byte in the line");
}
END_TEST

/* The last line, without its newline, has the same limit: 1022 characters, not one more. */
START_TEST(a_last_line_without_newline_has_the_same_limit)
{
    const ini_reader_t reader = {.key_line = "key=value", .on_section = record, .on_key = record};
    static char text[2 * INI_LINE_MAX];
    strcpy(text, "[A]\nk=");
    memset(text + strlen(text), 'v', INI_LINE_MAX - 2 - strlen("k=")); /* no newline at the end */
    seen_t seen = {0};
    char err[128] = "";
    ck_assert_msg(read_text(text, &reader, &seen, err, sizeof err), "%s", err);
    ck_assert_uint_eq(seen.count, 2);
    strcat(text, "v");
    seen = (seen_t){0};
    ck_assert(!read_text(text, &reader, &seen, err, sizeof err));
    ck_assert_str_eq(err, "test.ini:2: line longer than 1022 characters");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("ini_reader");
    TCase *tc = tcase_create("lines");
    tcase_add_test(tc, callbacks_get_section_key_value_and_line);
    tcase_add_test(tc, headers_without_callback_only_name_the_section);
    tcase_add_test(tc, a_refusing_callback_stops_the_reading);
    tcase_add_test(tc, a_line_too_long_is_refused_with_its_number);
    tcase_add_test(tc, a_last_line_without_newline_has_the_same_limit);
    tcase_add_test(tc, a_nul_byte_is_refused_with_its_line);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
