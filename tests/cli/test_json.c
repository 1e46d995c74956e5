/* SPDX-License-Identifier: Apache-2.0 */
/* The JSON writer (src/cli/json.h): the commas it places, its strings' escapes, and a document
 * that does not fit or is not closed never given as whole. */
#include "check_main.h"
#include "cli/json.h"

#include <check.h>
#include <string.h>

START_TEST(members_elements_and_commas)
{
    char buf[256];
    cli_json_t json;
    cli_json_init(&json, buf, sizeof buf);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", true);
    cli_json_begin_array(&json, "list");
    cli_json_int(&json, NULL, -2);
    cli_json_uint(&json, NULL, 18446744073709551615ull);
    cli_json_null(&json, NULL);
    cli_json_begin_object(&json, NULL);
    cli_json_end_object(&json);
    cli_json_end_array(&json);
    cli_json_number(&json, "rate", "%.1f", 8.25);
    cli_json_str(&json, "name", "a \"b\" c\\d\te\x01\x7f");
    cli_json_end_object(&json);
    const char *expected = "{\"ok\":true,\"list\":[-2,18446744073709551615,null,{}],"
                           "\"rate\":8.2,\"name\":\"a \\\"b\\\" c\\\\d\\u0009e\\u0001\x7f\"}";
    ck_assert_str_eq(buf, expected);
    ck_assert_uint_eq(cli_json_finish(&json), strlen(expected));
}
END_TEST

START_TEST(a_document_that_does_not_fit_is_empty)
{
    char buf[8];
    cli_json_t json;
    cli_json_init(&json, buf, sizeof buf);
    cli_json_begin_object(&json, NULL);
    cli_json_str(&json, "key", "value");
    cli_json_end_object(&json);
    ck_assert(json.overflow);
    ck_assert_uint_eq(cli_json_finish(&json), 0);
    ck_assert_str_eq(buf, "");

    cli_json_init(&json, buf, sizeof buf);
    cli_json_begin_array(&json, NULL);
    ck_assert_uint_eq(cli_json_finish(&json), 0);
    ck_assert_str_eq(buf, "");
}
END_TEST

START_TEST(quote_into_a_buffer)
{
    char out[16];
    ck_assert(cli_json_quote("say \"hi\"", out, sizeof out));
    ck_assert_str_eq(out, "\"say \\\"hi\\\"\"");
    ck_assert(!cli_json_quote("longer than sixteen", out, sizeof out));
    ck_assert_str_eq(out, "");
}
END_TEST

/* CLI_JSON_QUOTED_MAX(n) is the room of the worst text of n bytes, every byte escaped, and no
 * more than that room. */
START_TEST(quoted_max_holds_the_worst_text)
{
    char text[8], out[CLI_JSON_QUOTED_MAX(sizeof text - 1)];
    memset(text, 0x01, sizeof text - 1);
    text[sizeof text - 1] = '\0';
    ck_assert(cli_json_quote(text, out, sizeof out));
    ck_assert_uint_eq(strlen(out), sizeof out - 1);
    ck_assert_str_eq(out, "\"\\u0001\\u0001\\u0001\\u0001\\u0001\\u0001\\u0001\"");
    ck_assert(!cli_json_quote(text, out, sizeof out - 1));
}
END_TEST

static Suite *json_suite(void)
{
    Suite *s = suite_create("json");
    TCase *tc = tcase_create("json");
    tcase_add_test(tc, members_elements_and_commas);
    tcase_add_test(tc, a_document_that_does_not_fit_is_empty);
    tcase_add_test(tc, quote_into_a_buffer);
    tcase_add_test(tc, quoted_max_holds_the_worst_text);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(json_suite());
}
