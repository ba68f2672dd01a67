/*
 * wire.h - private to src/bus: the LCM wire format, written and read by hand.
 *
 * LCM encodes a message as its 8-byte fingerprint hash, then every field in declaration
 * order, big-endian, with no padding: integers in their declared width, float as its
 * IEEE-754 bits in 4 bytes, boolean as one byte (0 or 1), a fixed array as its elements
 * inline, a variable array as its elements after the count field that sizes it, a nested
 * struct as its fields (no hash of its own), and a string as an int32 length that counts
 * the terminating NUL, the bytes, and the NUL.
 *
 * hl_wire_out_t and hl_wire_in_t are cursors over a caller's buffer. Every put and get
 * checks the bounds; the first one that does not fit clears `ok` and every later call is
 * a no-op (a get then yields 0), so a codec checks `ok` once at the end.
 *
 * Error reporting: codecs fail through hl_wire_fail, which writes one line
 * "<message>: <what>" into the caller's `why` (HL_BUS_WHY_LEN bytes, may be NULL).
 * HL_ERR_PARSE is for the framing (length, fingerprint, a string's length field and NUL
 * terminator); HL_ERR_RANGE for a value outside its documented range.
 */
#ifndef HOUGHLOC_BUS_WIRE_H
#define HOUGHLOC_BUS_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/status.h"

typedef struct hl_wire_out {
    uint8_t *p;
    size_t cap;
    size_t pos;
    bool ok;
} hl_wire_out_t;

typedef struct hl_wire_in {
    const uint8_t *p;
    size_t len;
    size_t pos;
    bool ok;
} hl_wire_in_t;

static inline hl_wire_out_t hl_wire_out(void *buf, size_t cap)
{
    hl_wire_out_t w = { buf, cap, 0, buf != NULL };
    return w;
}

static inline void hl_wire_put_be(hl_wire_out_t *w, uint64_t v, size_t n)
{
    if (!w->ok || w->cap - w->pos < n) {
        w->ok = false;
        return;
    }
    for (size_t i = 0; i < n; i++)
        w->p[w->pos + i] = (uint8_t)(v >> (8 * (n - 1 - i)));
    w->pos += n;
}

static inline void hl_wire_put_i8(hl_wire_out_t *w, int8_t v)
{
    hl_wire_put_be(w, (uint8_t)v, 1);
}
static inline void hl_wire_put_i16(hl_wire_out_t *w, int16_t v)
{
    hl_wire_put_be(w, (uint16_t)v, 2);
}
static inline void hl_wire_put_i32(hl_wire_out_t *w, int32_t v)
{
    hl_wire_put_be(w, (uint32_t)v, 4);
}
static inline void hl_wire_put_i64(hl_wire_out_t *w, int64_t v)
{
    hl_wire_put_be(w, (uint64_t)v, 8);
}
static inline void hl_wire_put_bool(hl_wire_out_t *w, bool v)
{
    hl_wire_put_be(w, v ? 1u : 0u, 1);
}

static inline void hl_wire_put_f32(hl_wire_out_t *w, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    hl_wire_put_be(w, bits, 4);
}

static inline void hl_wire_put_bytes(hl_wire_out_t *w, const uint8_t *src, size_t n)
{
    if (!w->ok || w->cap - w->pos < n) {
        w->ok = false;
        return;
    }
    memcpy(w->p + w->pos, src, n);
    w->pos += n;
}

/** The encoded length, or -1 when something did not fit. */
static inline int hl_wire_out_len(const hl_wire_out_t *w)
{
    return w->ok && w->pos <= (size_t)INT32_MAX ? (int)w->pos : -1;
}

static inline uint64_t hl_wire_get_be(hl_wire_in_t *r, size_t n)
{
    if (!r->ok || r->len - r->pos < n) {
        r->ok = false;
        return 0;
    }
    uint64_t v = 0;
    for (size_t i = 0; i < n; i++)
        v = (v << 8) | r->p[r->pos + i];
    r->pos += n;
    return v;
}

static inline int8_t hl_wire_get_i8(hl_wire_in_t *r)
{
    return (int8_t)(uint8_t)hl_wire_get_be(r, 1);
}
static inline uint8_t hl_wire_get_u8(hl_wire_in_t *r)
{
    return (uint8_t)hl_wire_get_be(r, 1);
}
static inline int16_t hl_wire_get_i16(hl_wire_in_t *r)
{
    return (int16_t)(uint16_t)hl_wire_get_be(r, 2);
}
static inline int32_t hl_wire_get_i32(hl_wire_in_t *r)
{
    return (int32_t)(uint32_t)hl_wire_get_be(r, 4);
}
static inline int64_t hl_wire_get_i64(hl_wire_in_t *r)
{
    return (int64_t)hl_wire_get_be(r, 8);
}

static inline float hl_wire_get_f32(hl_wire_in_t *r)
{
    uint32_t bits = (uint32_t)hl_wire_get_be(r, 4);
    float v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

static inline void hl_wire_get_bytes(hl_wire_in_t *r, uint8_t *dst, size_t n)
{
    if (!r->ok || r->len - r->pos < n) {
        r->ok = false;
        return;
    }
    memcpy(dst, r->p + r->pos, n);
    r->pos += n;
}

/** Writes "<msg>: <formatted text>" into @p why (may be NULL). @return @p st. */
hl_status_t hl_wire_fail(char *why, hl_status_t st, const char *msg, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/**
 * Starts decoding: checks the pointers, that @p len holds at least @p fixed bytes
 * (exactly @p fixed when @p exact), and the fingerprint.
 * @return HL_OK with @p r positioned after the hash; HL_ERR_ARG, HL_ERR_PARSE.
 */
hl_status_t hl_wire_begin(hl_wire_in_t *r, const void *data, size_t len, const void *out,
                          uint64_t hash, size_t fixed, bool exact, const char *msg,
                          char *why);

/** Reads a boolean byte into @p v: HL_ERR_RANGE unless it is 0 or 1. */
hl_status_t hl_wire_get_bool(hl_wire_in_t *r, bool *v, const char *msg, const char *field,
                             char *why);

/**
 * Reads an LCM string into @p out (HL_BUS_TEXT_MAX bytes): a length of 1..HL_BUS_TEXT_MAX
 * that fits the rest of the buffer, a NUL at its end and nowhere else (HL_ERR_PARSE), no
 * control character (HL_ERR_RANGE; see hl_wire_text_ok).
 */
hl_status_t hl_wire_get_text(hl_wire_in_t *r, char *out, const char *msg, const char *field,
                             char *why);

/** Fails with HL_ERR_PARSE unless every byte of the buffer has been read. */
hl_status_t hl_wire_end(const hl_wire_in_t *r, const char *msg, char *why);

/**
 * Whether @p s (HL_BUS_TEXT_MAX bytes of storage) is a valid one-line text: a NUL
 * within the storage and no byte below 0x20 or equal to 0x7f before it. Bytes from 0x80
 * up pass (UTF-8 is not checked further). @p bad receives the first offending byte's
 * index, or HL_BUS_TEXT_MAX - 1 when the NUL is missing; may be NULL.
 */
bool hl_wire_text_ok(const char *s, size_t *bad);

/** Writes @p s as an LCM string; clears w->ok unless hl_wire_text_ok(s). */
void hl_wire_put_text(hl_wire_out_t *w, const char *s);

/** |v| <= HL_COORD_MAX_MM. */
static inline bool hl_wire_coord_ok(int32_t v)
{
    return v >= -HL_COORD_MAX_MM && v <= HL_COORD_MAX_MM;
}

#endif
