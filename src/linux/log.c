#include "co_linux/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* One logger per process: the runtime is the process, unlike the core. */
static const char *log_ident = "co";
static co_log_level_t log_level = CO_LOG_INFO;

static const char *const level_names[] = {"error", "warn", "info", "debug"};

void co_log_setup(const char *ident, co_log_level_t level)
{
    log_ident = ident;
    log_level = level;
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
    int n = snprintf(line, sizeof line, "%s: %s: ", log_ident, level_names[level]);
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
