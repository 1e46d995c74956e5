/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 58's EMCY code table (atv58_emcy_table, its card manual's) as an EMCY consumer
 * reads it: each code's text, the standard meaning where the manual lists nothing, and every
 * fault the model sends (atv58_faults) explained by the table under the fault's own code. */
#include "atv58/atv58.h"
#include "check_main.h"

#include <ctype.h>
#include <string.h>

START_TEST(texts_of_the_manual)
{
    const co_emcy_code_table_t *t = &atv58_emcy_table;
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x2310), "OCF: overcurrent fault (ATV58)");
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x8130),
                     "communication error (life guard time out) (ATV58)");
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x7520),
                     "ILF/CNF: fast communication link or network fault (ATV58)");
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x0000), "NOF: no fault");
    /* Codes the manual does not list, or lists less precisely, keep their standard meaning. */
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x8110), "CAN overrun (objects lost)");
    ck_assert_str_eq(co_emcy_code_text_in(t, 0x3220), "DC link under-voltage");
}
END_TEST

/* The text names the fault's mnemonic, compared without case ("ObF" is "OBF" in the table), or,
 * for the communication-loss fault, its meaning. */
static bool text_names(const char *text, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = text; *p; p++) {
        size_t i = 0;
        while (i < n && p[i] && tolower((unsigned char)p[i]) == tolower((unsigned char)word[i]))
            i++;
        if (i == n)
            return true;
    }
    return false;
}

START_TEST(every_fault_has_its_meaning)
{
    for (size_t i = 0; i < atv58_faults.count; i++) {
        const drive_fault_def_t *f = &atv58_faults.faults[i];
        const char *text = co_emcy_code_text_in(&atv58_emcy_table, f->emcy_code);
        ck_assert_msg(text_names(text, f->code) || text_names(text, f->meaning),
                      "fault %s (EMCY %04X): the table says '%s'", f->code, f->emcy_code, text);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv58_emcy");
    TCase *tc = tcase_create("atv58_emcy");
    tcase_add_test(tc, texts_of_the_manual);
    tcase_add_test(tc, every_fault_has_its_meaning);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
