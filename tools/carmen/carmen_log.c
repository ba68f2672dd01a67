/* carmen_log.c - CARMEN log lines: a gzip-or-plain line reader and a strict parser. */
#include "carmen_log.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

struct carmen_reader {
    gzFile f;
    char *buf;
    size_t cap;
    long lineno;
};

carmen_reader_t *carmen_open(const char *path, char *why)
{
    carmen_reader_t *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(why, CARMEN_WHY_LEN, "out of memory");
        return NULL;
    }
    errno = 0;
    r->f = gzopen(path, "rb");
    r->cap = 4096;
    r->buf = malloc(r->cap);
    if (!r->f || !r->buf) {
        snprintf(why, CARMEN_WHY_LEN, "cannot open: %s",
                 errno ? strerror(errno) : "out of memory");
        carmen_close(r);
        return NULL;
    }
    return r;
}

void carmen_close(carmen_reader_t *r)
{
    if (!r)
        return;
    if (r->f)
        gzclose(r->f);
    free(r->buf);
    free(r);
}

/* After gzgets returned NULL: a real error, or just the end? */
static bool gz_failed(gzFile f, char *why)
{
    int err = Z_OK;
    const char *msg = gzerror(f, &err);
    if (err == Z_OK || err == Z_STREAM_END)
        return false;
    /* zlib's message starts with the path, which the caller prints already */
    const char *colon = err == Z_ERRNO ? NULL : strstr(msg, ": ");
    snprintf(why, CARMEN_WHY_LEN, "read error: %s",
             err == Z_ERRNO ? strerror(errno) : colon ? colon + 2 : msg);
    return true;
}

int carmen_next_line(carmen_reader_t *r, char **line, long *lineno, char *why)
{
    size_t len = 0;
    for (;;) {
        /* gzgets reads at most cap - len - 1 bytes and stops after a newline. */
        if (!gzgets(r->f, r->buf + len, (int)(r->cap - len))) {
            if (gz_failed(r->f, why))
                return -1;
            if (len == 0)
                return 0;
            break;      /* a last line without a newline */
        }
        len += strlen(r->buf + len);
        if (len > 0 && r->buf[len - 1] == '\n')
            break;
        if (gzeof(r->f))
            break;
        if (len + 1 < r->cap) {     /* gzgets stopped early: at a NUL byte */
            snprintf(why, CARMEN_WHY_LEN, "line %ld holds a NUL byte", r->lineno + 1);
            return -1;
        }
        if (r->cap > CARMEN_MAX_LINE) {
            snprintf(why, CARMEN_WHY_LEN, "line %ld is longer than %d bytes",
                     r->lineno + 1, CARMEN_MAX_LINE);
            return -1;
        }
        char *bigger = realloc(r->buf, r->cap * 2);
        if (!bigger) {
            snprintf(why, CARMEN_WHY_LEN, "out of memory");
            return -1;
        }
        r->buf = bigger;
        r->cap *= 2;
    }
    while (len > 0 && (r->buf[len - 1] == '\n' || r->buf[len - 1] == '\r'))
        r->buf[--len] = '\0';
    *line = r->buf;
    *lineno = ++r->lineno;
    return 1;
}

bool carmen_parse_number(const char *tok, double *out)
{
    /* Only [+-]digits[.digits][e[+-]digits]: strtod alone would take "0x1p3", "inf",
     * "nan" and "1e5junk" (up to where it stops). */
    const char *p = tok;
    if (*p == '+' || *p == '-')
        p++;
    size_t digits = strspn(p, "0123456789");
    p += digits;
    if (*p == '.') {
        size_t frac = strspn(p + 1, "0123456789");
        digits += frac;
        p += 1 + frac;
    }
    if (digits == 0)
        return false;
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-')
            p++;
        size_t exp = strspn(p, "0123456789");
        if (exp == 0)
            return false;
        p += exp;
    }
    if (*p != '\0')
        return false;
    errno = 0;
    double v = strtod(tok, NULL);
    if (!isfinite(v))
        return false;
    *out = v;
    return true;
}

bool carmen_parse_time_us(const char *tok, int64_t *out)
{
    const char *p = tok[0] == '+' ? tok + 1 : tok;
    size_t whole = strspn(p, "0123456789");
    size_t frac = 0;
    if (p[whole] == '.')
        frac = strspn(p + whole + 1, "0123456789");
    bool plain = (whole > 0 || frac > 0) &&
                 p[whole + (p[whole] == '.' ? 1 + frac : 0)] == '\0';
    if (plain) {
        if (whole > 12)
            return false;
        int64_t us = 0;
        for (size_t i = 0; i < whole; i++)
            us = us * 10 + (p[i] - '0');
        const char *f = p + whole + 1;
        for (size_t i = 0; i < 6; i++)
            us = us * 10 + (i < frac ? f[i] - '0' : 0);
        if (frac > 6 && f[6] >= '5')
            us++;
        *out = us;
        return true;
    }
    double v;
    if (!carmen_parse_number(tok, &v) || v < 0 || v > 1e12)
        return false;
    *out = llround(v * 1e6);
    return true;
}

/* The next whitespace-separated token of *cursor, NUL-terminated in place; NULL at the
 * end of the line. */
static char *next_token(char **cursor)
{
    char *p = *cursor;
    while (*p && isspace((unsigned char)*p))
        p++;
    if (!*p) {
        *cursor = p;
        return NULL;
    }
    char *start = p;
    while (*p && !isspace((unsigned char)*p))
        p++;
    if (*p)
        *p++ = '\0';
    *cursor = p;
    return start;
}

/* What the k-th number after the beam count (0-based) of an n-beam FLASER is. */
static void field_name(int k, int n, char *buf, size_t cap)
{
    static const char *const pose[7] = { "x", "y", "theta", "odom_x", "odom_y",
                                         "odom_theta", "timestamp" };
    if (k < n)
        snprintf(buf, cap, "beam %d", k + 1);
    else
        snprintf(buf, cap, "%s", pose[k - n < 7 ? k - n : 6]);
}

static int parse_flaser(char *cursor, carmen_flaser_t *f, char *why)
{
    char *tok = next_token(&cursor);
    if (!tok)
        return snprintf(why, CARMEN_WHY_LEN, "FLASER without a beam count"), -1;
    size_t nd = strspn(tok, "0123456789");
    long n = nd > 0 && nd < 8 && tok[nd] == '\0' ? strtol(tok, NULL, 10) : -1;
    if (n < 2 || n > CARMEN_MAX_BEAMS)
        return snprintf(why, CARMEN_WHY_LEN, "FLASER beam count '%.40s' is not 2..%d", tok,
                        CARMEN_MAX_BEAMS), -1;
    int need = (int)n + 7;
    double tail[7];
    int k = 0;
    char name[32];
    for (; k < need; k++) {
        tok = next_token(&cursor);
        if (!tok)
            return snprintf(why, CARMEN_WHY_LEN,
                            "FLASER with %ld beams: the line ends after %d numbers "
                            "(%ld ranges, 6 pose values and a timestamp make %d)",
                            n, k, n, need), -1;
        double v;
        if (!carmen_parse_number(tok, &v)) {
            /* a word where numbers should go on: a hostname after too few numbers
             * means the beam count is wrong; anything else is a bad field */
            char *rest = cursor;
            char *after = next_token(&rest);
            double dummy;
            bool tail_like = !after || (carmen_parse_number(after, &dummy) && !next_token(&rest));
            if (tail_like && k >= 7)
                return snprintf(why, CARMEN_WHY_LEN,
                                "FLASER declares %ld beams but holds %d numbers before "
                                "'%.40s' (%ld ranges, 6 pose values and a timestamp make %d)",
                                n, k, tok, n, need), -1;
            field_name(k, (int)n, name, sizeof name);
            return snprintf(why, CARMEN_WHY_LEN, "FLASER with %ld beams: %s '%.40s' is not a number",
                            n, name, tok), -1;
        }
        if (k < n) {
            if (v < 0)
                return snprintf(why, CARMEN_WHY_LEN, "FLASER: beam %d range %.40s is negative",
                                k + 1, tok), -1;
            f->ranges[k] = v;
        } else if (k < need - 1) {
            tail[k - n] = v;
        } else if (!carmen_parse_time_us(tok, &f->time_us)) {
            return snprintf(why, CARMEN_WHY_LEN,
                            "FLASER: timestamp '%.40s' is not a time of 0 to 10^12 s", tok), -1;
        }
    }
    /* after the timestamp: nothing, or a hostname (a word) and a logger timestamp */
    char *host = next_token(&cursor);
    double v;
    if (host && carmen_parse_number(host, &v)) {
        int more = 1;
        while ((host = next_token(&cursor)) != NULL && carmen_parse_number(host, &v))
            more++;
        /* with a hostname, the logger timestamp after it is not one of the n + 7 */
        return snprintf(why, CARMEN_WHY_LEN,
                        "FLASER declares %ld beams but holds %d numbers%s "
                        "(%ld ranges, 6 pose values and a timestamp make %d)",
                        n, need + more, host ? " before the hostname" : "", n, need), -1;
    }
    char *logger = host ? next_token(&cursor) : NULL;
    if (logger && !carmen_parse_number(logger, &v))
        return snprintf(why, CARMEN_WHY_LEN, "FLASER: logger timestamp '%.40s' is not a number",
                        logger), -1;
    char *extra = logger ? next_token(&cursor) : NULL;
    if (extra)
        return snprintf(why, CARMEN_WHY_LEN, "FLASER: '%.40s' after the logger timestamp", extra),
               -1;
    f->nbeams = (int)n;
    f->pose = (carmen_pose_t){ tail[0], tail[1], tail[2] };
    f->odom = (carmen_pose_t){ tail[3], tail[4], tail[5] };
    return 0;
}

int carmen_parse_line(char *line, carmen_line_t *out, char *why)
{
    char *cursor = line;
    char *type = next_token(&cursor);
    out->kind = CARMEN_SKIP;
    if (!type)
        return 0;
    if (strcmp(type, "FLASER") == 0) {
        if (parse_flaser(cursor, &out->flaser, why) != 0)
            return -1;
        out->kind = CARMEN_FLASER;
    } else if (strcmp(type, "PARAM") == 0) {
        out->param.name = next_token(&cursor);
        out->param.value = out->param.name ? next_token(&cursor) : NULL;
        if (!out->param.value)
            return snprintf(why, CARMEN_WHY_LEN, "PARAM without a name and a value"), -1;
        out->kind = CARMEN_PARAM;
    }
    return 0;
}
