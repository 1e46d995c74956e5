/* SPDX-License-Identifier: Apache-2.0 */
/* A small leveled logger for the Linux runtime and the daemon: one line per message on stderr,
 * "<ident>: <level>: <message>", written with a single write so lines of concurrent processes
 * never interleave. When stderr is the systemd journal ($JOURNAL_STREAM) each line starts with
 * its syslog priority, "<3>" error, "<4>" warn, "<6>" info, "<7>" debug, which journald keeps as
 * the entry's priority and strips from the text. */
#ifndef CO_LINUX_LOG_H
#define CO_LINUX_LOG_H

#include <stdbool.h>

typedef enum co_log_level { CO_LOG_ERROR, CO_LOG_WARN, CO_LOG_INFO, CO_LOG_DEBUG } co_log_level_t;

/* Sets the program name printed first on every line and the most verbose level printed, and
 * looks whether stderr is the journal. */
void co_log_setup(const char *ident, co_log_level_t level);

/* The program name co_log_setup set ("co" before it was called). */
const char *co_log_ident(void);

/* True when messages of this level are printed (to skip formatting work otherwise). */
bool co_log_enabled(co_log_level_t level);

void co_log(co_log_level_t level, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* "error", "warn", "info", "debug". */
const char *co_log_level_name(co_log_level_t level);

/* Parses a level name; returns false for anything else. */
bool co_log_level_parse(const char *name, co_log_level_t *level);

#endif
