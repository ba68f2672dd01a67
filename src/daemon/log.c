/* log.c - one line per event on stderr, with a journald level prefix. */
#include "log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int min_level = HL_LOG_INFO;

static const char *const level_names[8] = {
    [HL_LOG_ERR] = "error", [HL_LOG_WARNING] = "warning", [HL_LOG_NOTICE] = "notice",
    [HL_LOG_INFO] = "info", [HL_LOG_DEBUG] = "debug",
};

void hl_log_set_level(int level)
{
    min_level = level;
}

int hl_log_parse_level(const char *name)
{
    for (int i = 0; i < 8; i++)
        if (level_names[i] && strcmp(level_names[i], name) == 0)
            return i;
    return -1;
}

const char *hl_log_level_name(int level)
{
    return level >= 0 && level < 8 && level_names[level] ? level_names[level] : "?";
}

bool hl_log_enabled(int level)
{
    return level <= min_level;
}

void hl_log(int level, const char *fmt, ...)
{
    if (!hl_log_enabled(level))
        return;
    /* One write per line, so that lines from a restarting daemon never interleave and a
     * message from outside (a rejection reason) cannot forge a second log line. */
    char line[512];
    int n = snprintf(line, sizeof line, "<%d>houghlocd: ", level);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line + n, sizeof line - (size_t)n - 1, fmt, ap);
    va_end(ap);
    size_t len = strlen(line);
    for (size_t i = (size_t)n; i < len; i++)
        if ((unsigned char)line[i] < 0x20 || line[i] == 0x7f)
            line[i] = '?';
    line[len++] = '\n';
    fwrite(line, 1, len, stderr);
}
