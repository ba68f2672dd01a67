/*
 * logcheck.c - walks an LCM event log's headers before liblcm is trusted with it
 * (see houghloc/logcheck.h).
 *
 * An event is, big-endian: int32 sync 0xEDA1DA01 | int64 event number | int64 timestamp
 * (utime) | int32 channel length | int32 data length | channel bytes | data bytes.
 * The file is read through stdio one header at a time; the channel and data are
 * skipped, with fseeko on a regular file (glibc stays inside its buffer for short hops,
 * and a multi-gigabyte log costs one lseek per large event) and by reading into a small
 * buffer otherwise (a pipe). A regular file's size is known up front, so a length field
 * that runs past the end is reported at its own header, before any skipping.
 */
#include "houghloc/logcheck.h"

#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#define HEADER_BYTES 28

typedef struct walk {
    const char *path;
    char *why;
    FILE *f;
    bool sized;             /* a regular file: size is known and fseeko works */
    uint64_t size;
    uint64_t off;           /* where the current event starts */
} walk_t;

static hl_status_t fail(const walk_t *w, hl_status_t st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* "<path>: byte <off>: <text>", keeping errno for HL_ERR_OS. */
static hl_status_t fail(const walk_t *w, hl_status_t st, const char *fmt, ...)
{
    int saved = errno;
    if (w->why) {
        int n = snprintf(w->why, HL_LOG_WHY_LEN, "%s: byte %llu: ", w->path,
                         (unsigned long long)w->off);
        if (n >= 0 && n < HL_LOG_WHY_LEN) {
            va_list ap;
            va_start(ap, fmt);
            vsnprintf(w->why + n, HL_LOG_WHY_LEN - (size_t)n, fmt, ap);
            va_end(ap);
        }
    }
    errno = saved;
    return st;
}

static uint32_t be32(const uint8_t *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static uint64_t be64(const uint8_t *b)
{
    return (uint64_t)be32(b) << 32 | be32(b + 4);
}

/* Skips @p n bytes of the current event. @return HL_OK, HL_ERR_PARSE at the end of the
 * file (only possible when the size is unknown), HL_ERR_OS. */
static hl_status_t skip(walk_t *w, uint64_t n, const char *what, int32_t len)
{
    if (w->sized) {
        if (n > 0 && fseeko(w->f, (off_t)n, SEEK_CUR) != 0)
            return fail(w, HL_ERR_OS, "cannot seek: %s", strerror(errno));
        return HL_OK;
    }
    uint8_t buf[4096];
    while (n > 0) {
        size_t want = n < sizeof buf ? (size_t)n : sizeof buf;
        size_t got = fread(buf, 1, want, w->f);
        if (got < want) {
            if (ferror(w->f))
                return fail(w, HL_ERR_OS, "cannot read: %s", strerror(errno));
            return fail(w, HL_ERR_PARSE, "%s %ld runs past the end of the file", what,
                        (long)len);
        }
        n -= got;
    }
    return HL_OK;
}

/* Checks one event's header; on HL_OK the file is positioned after the event. */
static hl_status_t check_event(walk_t *w, const uint8_t *h, uint64_t *event_bytes)
{
    uint32_t sync = be32(h);
    if (sync != HL_LOG_SYNC)
        return fail(w, HL_ERR_PARSE, "sync word 0x%08lx is not 0x%08lx (not an LCM log, or "
                    "corrupt)", (unsigned long)sync, (unsigned long)HL_LOG_SYNC);
    int32_t chan = (int32_t)be32(h + 20), data = (int32_t)be32(h + 24);
    if (chan < 1 || chan > HL_LOG_CHANNEL_MAX)
        return fail(w, HL_ERR_PARSE, "event channel length %ld outside 1..%d", (long)chan,
                    HL_LOG_CHANNEL_MAX);
    if (data < 0)
        return fail(w, HL_ERR_PARSE, "event data length %ld is negative", (long)data);
    uint64_t left = UINT64_MAX;
    if (w->sized)   /* the header was read, so it lay within the size (unless it shrank) */
        left = w->size >= w->off + HEADER_BYTES ? w->size - w->off - HEADER_BYTES : 0;
    if ((uint64_t)chan > left)
        return fail(w, HL_ERR_PARSE, "event channel length %ld runs past the end of the file",
                    (long)chan);
    if ((uint64_t)data > left - (uint64_t)chan)
        return fail(w, HL_ERR_PARSE, "event data length %ld runs past the end of the file",
                    (long)data);
    if ((uint32_t)data > HL_LOG_EVENT_MAX_BYTES)
        return fail(w, HL_ERR_PARSE, "event data length %ld above the %lu-byte limit",
                    (long)data, (unsigned long)HL_LOG_EVENT_MAX_BYTES);
    hl_status_t st = skip(w, (uint64_t)chan, "event channel length", chan);
    if (st == HL_OK)
        st = skip(w, (uint64_t)data, "event data length", data);
    *event_bytes = HEADER_BYTES + (uint64_t)chan + (uint64_t)data;
    return st;
}

static hl_status_t walk(walk_t *w, hl_log_info_t *info)
{
    uint8_t h[HEADER_BYTES];
    for (;;) {
        size_t got = fread(h, 1, sizeof h, w->f);
        if (got < sizeof h && ferror(w->f))
            return fail(w, HL_ERR_OS, "cannot read: %s", strerror(errno));
        if (got == 0)
            break;
        if (got < sizeof h)
            return fail(w, HL_ERR_PARSE, "truncated event header: %zu of %d bytes", got,
                        HEADER_BYTES);
        uint64_t n = 0;
        hl_status_t st = check_event(w, h, &n);
        if (st != HL_OK)
            return st;
        int64_t utime = (int64_t)be64(h + 12);
        if (info->events == 0)
            info->first_utime = utime;
        info->last_utime = utime;
        info->events++;
        w->off += n;
        info->bytes = w->off;
    }
    if (info->events == 0)
        return fail(w, HL_ERR_EMPTY, "no event (empty file)");
    return HL_OK;
}

hl_status_t hl_log_check(const char *path, hl_log_info_t *info, char *why)
{
    hl_log_info_t local;
    if (!info)
        info = &local;
    *info = (hl_log_info_t){ 0, 0, 0, 0 };
    if (!path) {
        if (why)
            snprintf(why, HL_LOG_WHY_LEN, "no log path");
        return HL_ERR_ARG;
    }
    walk_t w = { .path = path, .why = why };
    w.f = fopen(path, "rb");
    if (!w.f) {
        int saved = errno;
        if (why)
            snprintf(why, HL_LOG_WHY_LEN, "%s: cannot open: %s", path, strerror(saved));
        errno = saved;
        return HL_ERR_OS;
    }
    struct stat sb;
    if (fstat(fileno(w.f), &sb) == 0 && S_ISREG(sb.st_mode)) {
        w.sized = true;
        w.size = (uint64_t)sb.st_size;
    }
    hl_status_t st = walk(&w, info);
    int saved = errno;
    fclose(w.f);
    errno = saved;
    return st;
}

/* ---- URLs ---------------------------------------------------------------------------- */

/* The last mode=... among liblcm's options ("k=v" separated by '&' or ','; a later key
 * replaces an earlier one, as in liblcm's hash table) is "w" or "a". */
static bool writes(const char *opts)
{
    bool w = false;
    const char *p = opts;
    while (*p) {
        size_t n = strcspn(p, "&,");
        if (n == 6 && strncmp(p, "mode=w", 6) == 0)
            w = true;
        else if (n == 6 && strncmp(p, "mode=a", 6) == 0)
            w = true;
        else if (n >= 4 && strncmp(p, "mode", 4) == 0 && (n == 4 || p[4] == '='))
            w = false;
        p += n;
        if (*p)
            p++;
    }
    return w;
}

int hl_log_url_path(const char *url, char *out, size_t cap)
{
    if (!url)
        return 0;
    const char *rest;
    if (strncmp(url, "file://", 7) == 0)
        rest = url + 7;
    else if (strncmp(url, "file:", 5) == 0)
        rest = url + 5;
    else
        return 0;
    size_t n = strcspn(rest, "?");
    if (n == 0 || (rest[n] == '?' && writes(rest + n + 1)))
        return 0;
    if (!out || n >= cap)
        return -1;
    memcpy(out, rest, n);
    out[n] = '\0';
    return 1;
}
