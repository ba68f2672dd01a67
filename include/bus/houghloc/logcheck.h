/*
 * logcheck.h - checks an LCM event log's framing before liblcm reads it.
 *
 * liblcm 1.3.1 trusts each event's length fields: a huge data length crashes it (in
 * lcm_create for the first event of a file:// URL, in lcm_handle's read-ahead later, in
 * lcm_eventlog_read_next_event's allocation). Every program of ours that reads a log
 * walks all its event headers with hl_log_check first: the sync word, a channel length
 * of 1..HL_LOG_CHANNEL_MAX, a data length that fits in what is left of the file, and no
 * partial event at the end.
 */
#ifndef HOUGHLOC_LOGCHECK_H
#define HOUGHLOC_LOGCHECK_H

#include <stdint.h>

#include "houghloc/bus.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_LOG_SYNC 0xEDA1DA01u
#define HL_LOG_CHANNEL_MAX 255
#define HL_LOG_EVENT_MAX_BYTES (64u << 20)  /* larger events are refused */

typedef struct hl_log_info {
    uint64_t events;
    uint64_t bytes;
    int64_t first_utime, last_utime;    /* event timestamps; 0 when no event */
} hl_log_info_t;

/**
 * Checks every event header of the log at @p path.
 * @param[out] info  may be NULL.
 * @param[out] why   on failure, one line naming the file, the byte offset and what is
 *                   wrong (e.g. "x.lcmlog: byte 1234: event data length 2147483647
 *                   runs past the end of the file"), HL_LOG_WHY_LEN bytes.
 * @return HL_OK; HL_ERR_OS when the file cannot be opened or read (errno kept; a
 *         folder is one); HL_ERR_PARSE for bad framing or a truncated last event;
 *         HL_ERR_EMPTY for a file with no event; HL_ERR_ARG when @p path is NULL.
 * Reads the headers through stdio, skipping each event's channel and data (fseeko on a
 * regular file, reads through a pipe), so a multi-gigabyte log is never held in memory.
 */
#define HL_LOG_WHY_LEN 512
hl_status_t hl_log_check(const char *path, hl_log_info_t *info, char *why);

/**
 * The file path inside an LCM URL of liblcm's log provider that reads a log
 * ("file://PATH?opts", "file:PATH"; not one whose last mode= option is w or a), written
 * to @p out (@p cap bytes). Options are split on '&' and ',' as liblcm does. liblcm
 * 1.3.1 itself refuses "file:PATH" (it wants "://"); it is recognized here anyway.
 * @return 1 when @p url reads a log and the path fits, 0 when it is not a log-reading
 *         URL (or @p url is NULL, or the path is empty), -1 when the path does not fit
 *         (or @p out is NULL).
 */
int hl_log_url_path(const char *url, char *out, size_t cap);

#ifdef __cplusplus
}
#endif
#endif
