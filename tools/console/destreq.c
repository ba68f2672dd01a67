/* destreq.c - the strict parser of POST /destination bodies (destreq.h). */
#include "destreq.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/fixed.h"

typedef struct cursor {
    const char *p, *end;
    char *why;
} cursor_t;

static hl_status_t fail(cursor_t *c, hl_status_t st, const char *what)
{
    if (c->why)
        snprintf(c->why, DESTREQ_WHY_LEN, "%s", what);
    return st;
}

static void skip_ws(cursor_t *c)
{
    while (c->p < c->end && (*c->p == ' ' || *c->p == '\t' || *c->p == '\n' || *c->p == '\r'))
        c->p++;
}

static bool eat(cursor_t *c, char ch)
{
    skip_ws(c);
    if (c->p < c->end && *c->p == ch) {
        c->p++;
        return true;
    }
    return false;
}

static bool is_digit(const cursor_t *c)
{
    return c->p < c->end && *c->p >= '0' && *c->p <= '9';
}

/* One run of digits; @return how many. */
static size_t digits(cursor_t *c)
{
    size_t n = 0;
    while (is_digit(c)) {
        c->p++;
        n++;
    }
    return n;
}

/* A JSON number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)? read with strtod once
 * the grammar has been checked, so strtod's extras (hex, inf, nan, spaces) never apply. */
static hl_status_t number(cursor_t *c, double *out)
{
    const char *start = c->p;
    if (c->p < c->end && *c->p == '-')
        c->p++;
    if (c->p < c->end && *c->p == '0')
        c->p++;
    else if (digits(c) == 0)
        return fail(c, HL_ERR_PARSE, "a value is not a number");
    if (c->p < c->end && *c->p == '.') {
        c->p++;
        if (digits(c) == 0)
            return fail(c, HL_ERR_PARSE, "a number has no digit after its '.'");
    }
    if (c->p < c->end && (*c->p == 'e' || *c->p == 'E')) {
        c->p++;
        if (c->p < c->end && (*c->p == '+' || *c->p == '-'))
            c->p++;
        if (digits(c) == 0)
            return fail(c, HL_ERR_PARSE, "a number has no digit in its exponent");
    }
    char tmp[64];
    size_t n = (size_t)(c->p - start);
    if (n >= sizeof tmp)
        return fail(c, HL_ERR_PARSE, "a number is longer than 63 characters");
    memcpy(tmp, start, n);
    tmp[n] = '\0';
    double v = strtod(tmp, NULL);
    if (!isfinite(v))
        return fail(c, HL_ERR_RANGE, "a number is not finite");
    *out = v;
    return HL_OK;
}

/* A member name: plain printable ASCII without escapes (no name we take needs one). */
static hl_status_t name(cursor_t *c, char *out, size_t cap)
{
    if (!eat(c, '"'))
        return fail(c, HL_ERR_PARSE, "expected a member name in double quotes");
    size_t n = 0;
    while (c->p < c->end && *c->p != '"') {
        unsigned char ch = (unsigned char)*c->p++;
        if (ch < 0x20 || ch > 0x7e || ch == '\\' || n + 1 >= cap)
            return fail(c, HL_ERR_PARSE, "unknown member (expected x_m, y_m, heading_deg)");
        out[n++] = (char)ch;
    }
    if (c->p >= c->end)
        return fail(c, HL_ERR_PARSE, "a member name is not closed");
    c->p++;
    out[n] = '\0';
    return HL_OK;
}

static bool literal(cursor_t *c, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(c->end - c->p) < n || memcmp(c->p, word, n) != 0)
        return false;
    c->p += n;
    return true;
}

static hl_status_t member(cursor_t *c, destreq_t *r, unsigned *seen)
{
    char key[16];
    hl_status_t st = name(c, key, sizeof key);
    if (st != HL_OK)
        return st;
    static const char *const keys[] = { "x_m", "y_m", "heading_deg" };
    int k = -1;
    for (int i = 0; i < 3; i++)
        if (strcmp(key, keys[i]) == 0)
            k = i;
    if (k < 0)
        return fail(c, HL_ERR_PARSE, "unknown member (expected x_m, y_m, heading_deg)");
    if (*seen & (1u << k))
        return fail(c, HL_ERR_PARSE, "a member appears twice");
    *seen |= 1u << k;
    if (!eat(c, ':'))
        return fail(c, HL_ERR_PARSE, "expected ':' after a member name");
    skip_ws(c);
    if (k == 2 && literal(c, "null")) {
        r->has_heading = false;
        return HL_OK;
    }
    double v;
    st = number(c, &v);
    if (st != HL_OK)
        return st;
    if (k < 2 && fabs(round(v * 1000.0)) > HL_COORD_MAX_MM)
        return fail(c, HL_ERR_RANGE, k == 0 ? "x_m is outside +-4194.304 m"
                                            : "y_m is outside +-4194.304 m");
    if (k == 0)
        r->x_m = v;
    else if (k == 1)
        r->y_m = v;
    else {
        r->has_heading = true;
        r->heading_deg = v;
    }
    return HL_OK;
}

hl_status_t destreq_parse(const char *body, size_t len, destreq_t *out, char *why)
{
    cursor_t c = { .p = body, .end = body ? body + len : NULL, .why = why };
    if (!body || !out || len > DESTREQ_MAX_BYTES)
        return fail(&c, HL_ERR_ARG, "no body, or a body above 1024 bytes");
    destreq_t r = { 0 };
    unsigned seen = 0;
    if (!eat(&c, '{'))
        return fail(&c, HL_ERR_PARSE, "the body is not a JSON object");
    if (!eat(&c, '}')) {
        do {
            hl_status_t st = member(&c, &r, &seen);
            if (st != HL_OK)
                return st;
        } while (eat(&c, ','));
        if (!eat(&c, '}'))
            return fail(&c, HL_ERR_PARSE, "expected ',' or '}' after a member");
    }
    skip_ws(&c);
    if (c.p != c.end)
        return fail(&c, HL_ERR_PARSE, "bytes after the object");
    if ((seen & 3u) != 3u)
        return fail(&c, HL_ERR_PARSE, "x_m and y_m are required");
    *out = r;
    return HL_OK;
}

hl_bus_destination_t destreq_message(const destreq_t *r)
{
    return (hl_bus_destination_t){
        .x_mm = (int32_t)lround(r->x_m * 1000.0),
        .y_mm = (int32_t)lround(r->y_m * 1000.0),
        .has_heading = r->has_heading,
        .heading = r->has_heading ? hl_bam_from_deg(fmod(r->heading_deg, 360.0)) : 0,
    };
}
