/* seqfile.c - the request state file (seqfile.h). */
#include "houghloc/seqfile.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "fileio.h"

#define MAGIC "hlseq"

/* "PATH: text" in @p why (may be NULL), control characters made '?'; keeps errno. */
static hl_status_t __attribute__((format(printf, 4, 5)))
fail(hl_status_t st, char *why, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hl_fileio_why(why, HL_SEQFILE_WHY_LEN, path, fmt, ap);
    va_end(ap);
    return st;
}

static uint32_t crc_of(const char *text, size_t len)
{
    return (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)text, (uInt)len);
}

int hl_seqfile_format(int64_t seq, char *buf, size_t cap)
{
    char body[40];
    if (seq < 0 || !buf)
        return -1;
    int n = snprintf(body, sizeof body, MAGIC " %d %" PRId64, HL_SEQFILE_VERSION, seq);
    int len = snprintf(buf, cap, "%s %08" PRIx32 "\n", body, crc_of(body, (size_t)n));
    return len < 0 || (size_t)len >= cap ? -1 : len;
}

/* A decimal 0..INT64_MAX of exactly @p len digits, no leading zero. */
static bool parse_seq(const char *s, size_t len, int64_t *out)
{
    if (len == 0 || len > 19 || (s[0] == '0' && len > 1))
        return false;
    uint64_t v = 0;
    for (size_t i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9')
            return false;
        v = v * 10 + (uint64_t)(s[i] - '0');
    }
    if (v > (uint64_t)INT64_MAX)
        return false;
    *out = (int64_t)v;
    return true;
}

static bool parse_crc(const char *s, size_t len, uint32_t *out)
{
    if (len != 8)
        return false;
    uint32_t v = 0;
    for (size_t i = 0; i < 8; i++) {
        char c = s[i];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (d < 0)
            return false;
        v = v << 4 | (uint32_t)d;
    }
    *out = v;
    return true;
}

hl_status_t hl_seqfile_parse(const char *text, size_t len, int64_t *seq, char *why)
{
    if (!text || !seq)
        return fail(HL_ERR_ARG, why, NULL, "no text");
    if (len == 0)
        return fail(HL_ERR_PARSE, why, NULL, "empty");
    if (len > HL_SEQFILE_MAX_BYTES)
        return fail(HL_ERR_PARSE, why, NULL, "%zu bytes, more than the %d of a request state "
                    "file", len, HL_SEQFILE_MAX_BYTES);
    if (len < sizeof MAGIC || memcmp(text, MAGIC " ", sizeof MAGIC) != 0)
        return fail(HL_ERR_PARSE, why, NULL, "not a request state file (no '" MAGIC "')");
    if (text[len - 1] != '\n')
        return fail(HL_ERR_PARSE, why, NULL, "cut short (no newline at its end)");
    if (memchr(text, '\n', len - 1) || memchr(text, '\0', len))
        return fail(HL_ERR_PARSE, why, NULL, "more than one line");
    /* "hlseq V SEQ CRC\n": three spaces after the magic's, the line's end */
    const char *v = text + sizeof MAGIC, *end = text + len - 1;
    const char *sp1 = memchr(v, ' ', (size_t)(end - v));
    const char *sp2 = sp1 ? memchr(sp1 + 1, ' ', (size_t)(end - sp1 - 1)) : NULL;
    if (!sp2 || memchr(sp2 + 1, ' ', (size_t)(end - sp2 - 1)))
        return fail(HL_ERR_PARSE, why, NULL, "malformed (not 'hlseq VERSION SEQ CRC')");
    if ((size_t)(sp1 - v) != 1 || *v != '0' + HL_SEQFILE_VERSION)
        return fail(HL_ERR_PARSE, why, NULL, "format version '%.*s'; this program reads "
                    "version %d", (int)(sp1 - v), v, HL_SEQFILE_VERSION);
    int64_t s;
    uint32_t crc;
    if (!parse_seq(sp1 + 1, (size_t)(sp2 - sp1 - 1), &s))
        return fail(HL_ERR_PARSE, why, NULL, "the request number is not a decimal 0 to "
                    "%" PRId64, INT64_MAX);
    if (!parse_crc(sp2 + 1, (size_t)(end - sp2 - 1), &crc))
        return fail(HL_ERR_PARSE, why, NULL, "the checksum is not 8 hexadecimal digits");
    uint32_t want = crc_of(text, (size_t)(sp2 - text));
    if (crc != want)
        return fail(HL_ERR_PARSE, why, NULL, "checksum mismatch (stored %08" PRIx32
                    ", computed %08" PRIx32 ")", crc, want);
    *seq = s;
    if (why)
        why[0] = '\0';
    return HL_OK;
}

hl_status_t hl_seqfile_load(const char *path, int64_t *seq, char *why)
{
    if (!path || !seq)
        return fail(HL_ERR_ARG, why, path, "load: no path");
    int fd;
    /* O_NONBLOCK: a FIFO at PATH must not hang the start */
    HL_FILEIO_RETRY(fd, open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (fd < 0)
        return fail(HL_ERR_OS, why, path, "cannot open: %s", strerror(errno));
    struct stat sb;
    char text[HL_SEQFILE_MAX_BYTES + 1];
    hl_status_t st = HL_OK;
    ssize_t got = 0;
    if (fstat(fd, &sb) != 0)
        st = fail(HL_ERR_OS, why, path, "cannot stat: %s", strerror(errno));
    else if (!S_ISREG(sb.st_mode))
        st = fail(HL_ERR_PARSE, why, path, "not a regular file");
    else if ((got = hl_fileio_read_full(fd, (uint8_t *)text, sizeof text)) < 0)
        st = fail(HL_ERR_OS, why, path, "read failed: %s", strerror(errno));
    hl_fileio_close_quietly(fd);
    if (st != HL_OK)
        return st;
    char reason[HL_SEQFILE_WHY_LEN];
    st = hl_seqfile_parse(text, (size_t)got, seq, reason);
    if (st != HL_OK)
        return fail(st, why, path, "%s", reason);
    return HL_OK;
}

/* The file's one line (NUL-terminated: hl_seqfile_format wrote it). */
static bool write_text_cb(int fd, const void *text)
{
    return hl_fileio_write_all(fd, text, strlen(text));
}

hl_status_t hl_seqfile_save(const char *path, int64_t seq, char *why)
{
    char text[HL_SEQFILE_MAX_BYTES + 1];
    int len = hl_seqfile_format(seq, text, sizeof text);
    if (!path || len < 0)
        return fail(HL_ERR_ARG, why, path, "save: no path or a negative request number");
    char reason[HL_SEQFILE_WHY_LEN];
    if (!hl_fileio_replace(path, write_text_cb, text, reason, sizeof reason))
        return fail(HL_ERR_OS, why, path, "%s", reason);
    if (why)
        why[0] = '\0';
    return HL_OK;
}

bool hl_seqfile_default_path(const char *map_path, char *out, size_t cap)
{
    if (!map_path || !out)
        return false;
    const char *slash = strrchr(map_path, '/');
    int n = slash ? snprintf(out, cap, "%.*s/" HL_SEQFILE_NAME, (int)(slash - map_path),
                             map_path)
                  : snprintf(out, cap, HL_SEQFILE_NAME);
    return n >= 0 && (size_t)n < cap;
}
