/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime's logger (co_linux/log.h): "<ident>: <level>: <message>" on stderr, and when stderr
 * is the journal ($JOURNAL_STREAM names its device and inode, as systemd sets it) each line starts
 * with its syslog priority, <3> error, <4> warning, <6> info, <7> debug, which journald reads as
 * the line's level. stderr is a temporary file here. */
#include "check_main.h"
#include "co_linux/log.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char path[32];
static int saved_stderr = -1;

static void stderr_to_file(void)
{
    strcpy(path, "/tmp/co_test_log.XXXXXX");
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    saved_stderr = dup(STDERR_FILENO);
    ck_assert_int_eq(dup2(fd, STDERR_FILENO), STDERR_FILENO);
    close(fd);
}

static void stderr_back(void)
{
    dup2(saved_stderr, STDERR_FILENO);
    close(saved_stderr);
    unlink(path);
    unsetenv("JOURNAL_STREAM");
}

static const char *logged(void)
{
    static char text[512];
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    return text;
}

static void log_every_level(void)
{
    co_log(CO_LOG_ERROR, "e %d", 1);
    co_log(CO_LOG_WARN, "w");
    co_log(CO_LOG_INFO, "i");
    co_log(CO_LOG_DEBUG, "d");
}

static void journal_is(const char *value)
{
    ck_assert_int_eq(setenv("JOURNAL_STREAM", value, 1), 0);
}

static void journal_is_stderr(void)
{
    struct stat st;
    ck_assert_int_eq(fstat(STDERR_FILENO, &st), 0);
    char value[64];
    snprintf(value, sizeof value, "%llu:%llu", (unsigned long long)st.st_dev,
             (unsigned long long)st.st_ino);
    journal_is(value);
}

START_TEST(plain_lines_without_journal)
{
    unsetenv("JOURNAL_STREAM");
    co_log_setup("atv312d", CO_LOG_DEBUG);
    log_every_level();
    ck_assert_str_eq(logged(), "atv312d: error: e 1\natv312d: warn: w\natv312d: info: i\n"
                               "atv312d: debug: d\n");
}
END_TEST

START_TEST(syslog_priorities_when_stderr_is_the_journal)
{
    journal_is_stderr();
    co_log_setup("atv312d", CO_LOG_DEBUG);
    log_every_level();
    ck_assert_str_eq(logged(), "<3>atv312d: error: e 1\n<4>atv312d: warn: w\n<6>atv312d: info: i\n"
                               "<7>atv312d: debug: d\n");
}
END_TEST

/* systemd's rule: $JOURNAL_STREAM is inherited, so it counts only while stderr is still the
 * stream it names (not after `2>file` in a script the service runs). */
START_TEST(plain_lines_when_stderr_is_another_file)
{
    journal_is("1:1");
    co_log_setup("atv312d", CO_LOG_INFO);
    co_log(CO_LOG_INFO, "i");
    journal_is("garbage");
    co_log_setup("atv312d", CO_LOG_INFO);
    co_log(CO_LOG_WARN, "w");
    ck_assert_str_eq(logged(), "atv312d: info: i\natv312d: warn: w\n");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("log");
    TCase *tc = tcase_create("log");
    tcase_add_checked_fixture(tc, stderr_to_file, stderr_back);
    tcase_add_test(tc, plain_lines_without_journal);
    tcase_add_test(tc, syslog_priorities_when_stderr_is_the_journal);
    tcase_add_test(tc, plain_lines_when_stderr_is_another_file);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
