/* jbuf.c - the growable text buffer of the console's JSON and event frames (jbuf.h). */
#include "jbuf.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void jbuf_init(jbuf_t *b, size_t max)
{
    *b = (jbuf_t){ .max = max };
}

void jbuf_free(jbuf_t *b)
{
    if (!b)
        return;
    free(b->data);
    jbuf_init(b, b->max);
}

void jbuf_reset(jbuf_t *b)
{
    b->len = 0;
    b->failed = false;
    if (b->data)
        b->data[0] = '\0';
}

void jbuf_consume(jbuf_t *b, size_t n)
{
    if (n >= b->len) {
        b->len = 0;
    } else {
        memmove(b->data, b->data + n, b->len - n);
        b->len -= n;
    }
    if (b->data)
        b->data[b->len] = '\0';
}

/* Makes room for @p n more bytes and the NUL; doubles, so appends are amortized O(1). */
static bool reserve(jbuf_t *b, size_t n)
{
    if (b->failed)
        return false;
    if ((b->max && n > b->max - b->len) || n > SIZE_MAX / 2 - b->len) {
        b->failed = true;
        return false;
    }
    size_t need = b->len + n + 1;
    if (need <= b->cap)
        return true;
    size_t cap = b->cap ? b->cap : 256;
    while (cap < need)
        cap *= 2;
    char *p = realloc(b->data, cap);
    if (!p) {
        b->failed = true;
        return false;
    }
    b->data = p;
    b->cap = cap;
    return true;
}

void jbuf_put(jbuf_t *b, const char *s, size_t n)
{
    if (n == 0 || !reserve(b, n))
        return;
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

void jbuf_puts(jbuf_t *b, const char *s)
{
    jbuf_put(b, s, strlen(s));
}

void jbuf_putc(jbuf_t *b, char c)
{
    jbuf_put(b, &c, 1);
}

void jbuf_int(jbuf_t *b, int64_t v)
{
    char tmp[24];
    int n = snprintf(tmp, sizeof tmp, "%" PRId64, v);
    jbuf_put(b, tmp, (size_t)n);
}

void jbuf_num(jbuf_t *b, double v, int decimals)
{
    if (!isfinite(v))
        v = 0.0;
    char tmp[48];
    int n = snprintf(tmp, sizeof tmp, "%.*f", decimals < 0 ? 0 : decimals > 9 ? 9 : decimals, v);
    if (n < 0 || (size_t)n >= sizeof tmp) {
        jbuf_putc(b, '0'); /* beyond 1e37: nothing the console sends is that large */
        return;
    }
    /* "-0.000" is valid JSON but reads oddly on the page */
    jbuf_puts(b, strtod(tmp, NULL) == 0.0 ? "0" : tmp);
}

void jbuf_str(jbuf_t *b, const char *s)
{
    static const char hex[] = "0123456789abcdef";
    jbuf_putc(b, '"');
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\') {
            char esc[2] = { '\\', (char)*c };
            jbuf_put(b, esc, 2);
        } else if (*c < 0x20 || *c > 0x7e) {
            char esc[6] = { '\\', 'u', '0', '0', hex[*c >> 4], hex[*c & 15] };
            jbuf_put(b, esc, 6);
        } else {
            jbuf_putc(b, (char)*c);
        }
    }
    jbuf_putc(b, '"');
}
