/* SPDX-License-Identifier: Apache-2.0 */
#include "co_linux/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* One logger per process: the runtime is the process, unlike the core. */
static const char *log_ident = "co";
static co_log_level_t log_level = CO_LOG_INFO;
static bool to_journal;

static const char *const level_names[] = {"error", "warn", "info", "debug"};
/* The syslog priority of each level (LOG_ERR, LOG_WARNING, LOG_INFO, LOG_DEBUG), which journald
 * reads from a "<N>" at the start of a line (systemd.exec, SyslogLevelPrefix=, on by default). */
static const char *const journal_prefixes[] = {"<3>", "<4>", "<6>", "<7>"};

/* systemd sets $JOURNAL_STREAM to "DEVICE:INODE" of the stream it connected stderr to. Children
 * inherit it, so it counts only while stderr is still that stream (not after a `2>file`). */
static bool stderr_is_journal(void)
{
    const char *stream = getenv("JOURNAL_STREAM");
    unsigned long long dev, ino;
    char rest;
    struct stat st;
    if (!stream || sscanf(stream, "%llu:%llu%c", &dev, &ino, &rest) != 2)
        return false;
    return fstat(STDERR_FILENO, &st) == 0 && (unsigned long long)st.st_dev == dev &&
           (unsigned long long)st.st_ino == ino;
}

void co_log_setup(const char *ident, co_log_level_t level)
{
    log_ident = ident;
    log_level = level;
    to_journal = stderr_is_journal();
}

const char *co_log_ident(void)
{
    return log_ident;
}

bool co_log_enabled(co_log_level_t level)
{
    return level <= log_level;
}

const char *co_log_level_name(co_log_level_t level)
{
    return level_names[level];
}

bool co_log_level_parse(const char *name, co_log_level_t *level)
{
    for (size_t i = 0; i < sizeof level_names / sizeof level_names[0]; i++) {
        if (strcmp(name, level_names[i]) == 0) {
            *level = (co_log_level_t)i;
            return true;
        }
    }
    return false;
}

void co_log(co_log_level_t level, const char *format, ...)
{
    if (!co_log_enabled(level))
        return;
    char line[1024];
    int n = snprintf(line, sizeof line, "%s%s: %s: ", to_journal ? journal_prefixes[level] : "",
                     log_ident, level_names[level]);
    va_list args;
    va_start(args, format);
    int m = vsnprintf(line + n, sizeof line - (size_t)n - 1, format, args);
    va_end(args);
    size_t len = (size_t)n + (m < 0 ? 0 : (size_t)m);
    if (len > sizeof line - 2)
        len = sizeof line - 2; /* truncated message: keep the newline */
    line[len++] = '\n';
    /* A failed write to stderr has nowhere to be reported. */
    ssize_t written = write(STDERR_FILENO, line, len);
    (void)written;
}
