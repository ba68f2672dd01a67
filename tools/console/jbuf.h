/*
 * jbuf.h - a growable text buffer for building JSON and Server-Sent Event frames
 * (private to tools/console).
 *
 * Appends never fail silently: the first allocation failure or a buffer grown past its
 * bound sets `failed`, after which appends do nothing, so a caller checks once at the
 * end instead of after every append. A buffer always holds a NUL after its text.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_JBUF_H
#define HOUGHLOC_TOOLS_CONSOLE_JBUF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct jbuf {
    char *data;         /* NULL until the first append */
    size_t len;         /* bytes of text, without the NUL */
    size_t cap;         /* bytes allocated */
    size_t max;         /* the bound on len; 0: none */
    bool failed;        /* out of memory or over the bound: the text is incomplete */
} jbuf_t;

/** An empty buffer bounded to @p max bytes of text (0: unbounded). */
void jbuf_init(jbuf_t *b, size_t max);
/** Frees the text; the buffer is then empty and usable again. Accepts NULL. */
void jbuf_free(jbuf_t *b);
/** Empties the text but keeps the allocation and the bound; clears `failed`. */
void jbuf_reset(jbuf_t *b);
/** Removes the first @p n bytes (all of them when n >= len). */
void jbuf_consume(jbuf_t *b, size_t n);

/** Appends @p n bytes of @p s. */
void jbuf_put(jbuf_t *b, const char *s, size_t n);
/** Appends the NUL-terminated @p s. */
void jbuf_puts(jbuf_t *b, const char *s);
/** Appends one character. */
void jbuf_putc(jbuf_t *b, char c);
/** Appends a decimal integer. */
void jbuf_int(jbuf_t *b, int64_t v);
/** Appends a finite number with at most @p decimals decimals (NaN or infinite: 0). */
void jbuf_num(jbuf_t *b, double v, int decimals);
/**
 * Appends @p s (NUL-terminated) as a quoted JSON string: '"' and '\' escaped, control
 * characters and every byte above 0x7e as \u00XX (a byte read as Latin-1), so that the
 * result is plain ASCII JSON whatever the bytes were.
 */
void jbuf_str(jbuf_t *b, const char *s);

#endif
