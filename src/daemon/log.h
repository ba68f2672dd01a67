/*
 * log.h - the daemon's log: one event per line on stderr, prefixed with its syslog level
 * in the form journald reads ("<3>houghlocd: ..."), gated by a minimum level.
 */
#ifndef HOUGHLOC_DAEMON_LOG_H
#define HOUGHLOC_DAEMON_LOG_H

#include <stdbool.h>

enum hl_log_level {
    HL_LOG_ERR = 3,
    HL_LOG_WARNING = 4,
    HL_LOG_NOTICE = 5,
    HL_LOG_INFO = 6,
    HL_LOG_DEBUG = 7,
};

/** Lines above @p level are dropped. Default HL_LOG_INFO. */
void hl_log_set_level(int level);
/** Parses "error", "warning", "notice", "info", "debug". @return -1 if none of them. */
int hl_log_parse_level(const char *name);
const char *hl_log_level_name(int level);
/** Whether a line at @p level would be written (to skip formatting work). */
bool hl_log_enabled(int level);

/** Writes one line; newlines and control characters in the text become '?'. */
void hl_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
