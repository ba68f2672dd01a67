/* wire.c - the shared parts of the hand-written LCM codecs (see wire.h). */
#include "wire.h"

#include <stdarg.h>
#include <stdio.h>

hl_status_t hl_wire_fail(char *why, hl_status_t st, const char *msg, const char *fmt, ...)
{
    if (!why)
        return st;
    int n = snprintf(why, HL_BUS_WHY_LEN, "%s: ", msg);
    if (n < 0 || n >= HL_BUS_WHY_LEN)
        return st;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why + n, HL_BUS_WHY_LEN - (size_t)n, fmt, ap);
    va_end(ap);
    return st;
}

hl_status_t hl_wire_begin(hl_wire_in_t *r, const void *data, size_t len, const void *out,
                          uint64_t hash, size_t fixed, bool exact, const char *msg,
                          char *why)
{
    if (!data || !out)
        return hl_wire_fail(why, HL_ERR_ARG, msg, "no %s", data ? "output" : "message");
    if (len < fixed)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "truncated: %zu bytes, %s %zu", len,
                            exact ? "expected" : "at least", fixed);
    if (exact && len > fixed)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "%zu trailing bytes after %zu",
                            len - fixed, fixed);
    *r = (hl_wire_in_t){ data, len, 0, true };
    uint64_t got = hl_wire_get_be(r, 8);
    if (got != hash)
        return hl_wire_fail(why, HL_ERR_PARSE, msg,
                            "fingerprint %016llx is not houghloc.%s_t's %016llx",
                            (unsigned long long)got, msg, (unsigned long long)hash);
    return HL_OK;
}

hl_status_t hl_wire_get_bool(hl_wire_in_t *r, bool *v, const char *msg, const char *field,
                             char *why)
{
    uint8_t b = hl_wire_get_u8(r);
    if (b > 1)
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "%s byte %u is not 0 or 1", field, b);
    *v = b == 1;
    return HL_OK;
}

bool hl_wire_text_ok(const char *s, size_t *bad)
{
    for (size_t i = 0; i < HL_BUS_TEXT_MAX; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == 0)
            return true;
        if (c < 0x20 || c == 0x7f) {
            if (bad)
                *bad = i;
            return false;
        }
    }
    if (bad)
        *bad = HL_BUS_TEXT_MAX - 1;
    return false;
}

hl_status_t hl_wire_get_text(hl_wire_in_t *r, char *out, const char *msg, const char *field,
                             char *why)
{
    int32_t n = hl_wire_get_i32(r);
    if (!r->ok)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "truncated in the length of %s", field);
    if (n < 1)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "%s length %d is below 1 (the NUL counts)",
                            field, (int)n);
    if (n > HL_BUS_TEXT_MAX)
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "%s of %d bytes is longer than %d", field,
                            (int)n, HL_BUS_TEXT_MAX);
    if (r->len - r->pos < (size_t)n)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "truncated in %s: %zu of %d bytes", field,
                            r->len - r->pos, (int)n);
    const char *s = (const char *)r->p + r->pos;
    if (s[n - 1] != '\0')
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "%s is not NUL-terminated", field);
    const char *nul = memchr(s, '\0', (size_t)n);
    if (nul != s + n - 1)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "%s holds a NUL at byte %td of %d", field,
                            nul - s, (int)n);
    memcpy(out, s, (size_t)n);
    r->pos += (size_t)n;
    size_t bad;
    if (!hl_wire_text_ok(out, &bad))
        return hl_wire_fail(why, HL_ERR_RANGE, msg,
                            "%s holds control character 0x%02x at byte %zu", field,
                            (unsigned char)out[bad], bad);
    return HL_OK;
}

hl_status_t hl_wire_end(const hl_wire_in_t *r, const char *msg, char *why)
{
    if (!r->ok)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "truncated: %zu bytes", r->len);
    if (r->pos != r->len)
        return hl_wire_fail(why, HL_ERR_PARSE, msg, "%zu trailing bytes after %zu",
                            r->len - r->pos, r->pos);
    return HL_OK;
}

void hl_wire_put_text(hl_wire_out_t *w, const char *s)
{
    if (!s || !hl_wire_text_ok(s, NULL)) {
        w->ok = false;
        return;
    }
    size_t n = strlen(s) + 1;
    hl_wire_put_i32(w, (int32_t)n);
    hl_wire_put_bytes(w, (const uint8_t *)s, n);
}
