/*
 * codec_testkit.h - checks shared by the codec tests (tests/bus/test_codec_*.c): every
 * truncation and a trailing byte refused, a wrong fingerprint refused, random and mutated
 * bytes never crash and, when they decode, re-encode to the same bytes. Include after
 * <cmocka.h>. Each test program gets its own copy of these static functions.
 */
#ifndef HOUGHLOC_TESTS_CODEC_TESTKIT_H
#define HOUGHLOC_TESTS_CODEC_TESTKIT_H

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/rng.h"

/* The codecs through one signature; each test wraps its type's pair in these. */
typedef hl_status_t (*tk_decode_fn)(const void *data, size_t len, void *out, char *why);
typedef int (*tk_encode_fn)(const void *in, void *buf, size_t cap);
/* Rewrites bytes that decode but do not survive a re-encode (the scan's odometry extras)
 * to what the encoder writes; NULL when every decodable message is canonical. */
typedef void (*tk_normalize_fn)(uint8_t *bytes, size_t len);

typedef struct tk_codec {
    const char *name;           /* the message name every reason starts with */
    tk_decode_fn decode;
    tk_encode_fn encode;
    tk_normalize_fn normalize;
    void *out;                  /* decode target (and encode source on re-encode) */
} tk_codec_t;

static inline int64_t tk_range(hl_rng_t *rng, int64_t lo, int64_t hi)
{
    uint64_t span = (uint64_t)hi - (uint64_t)lo + 1;       /* 0: the whole int64 range */
    uint64_t r = ((uint64_t)hl_rng_next(rng) << 32) | hl_rng_next(rng);
    return (int64_t)((uint64_t)lo + (span == 0 ? r : r % span));
}

/* Random printable text of 0..max characters, with some bytes above 0x7f. */
static inline void tk_text(hl_rng_t *rng, char *s, size_t max)
{
    size_t n = (size_t)tk_range(rng, 0, (int64_t)max);
    for (size_t i = 0; i < n; i++)
        s[i] = (char)(hl_rng_below(rng, 8) == 0 ? tk_range(rng, 0x80, 0xff)
                                                : tk_range(rng, 0x20, 0x7e));
    s[n] = '\0';
}

static inline void tk_put_be(uint8_t *b, size_t off, uint64_t v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        b[off + i] = (uint8_t)(v >> (8 * (n - 1 - i)));
}

/* A reason is one line that starts with "<name>: ". */
static inline void tk_assert_why(const char *why, const char *name)
{
    size_t n = strlen(name);
    assert_int_equal(strncmp(why, name, n), 0);
    assert_int_equal(why[n], ':');
    assert_null(strchr(why, '\n'));
    assert_true(strlen(why) > n + 2);
}

/* Decodes a heap copy of exactly @p len bytes, so that ASan sees any over-read. */
static inline hl_status_t tk_decode(const tk_codec_t *c, const uint8_t *bytes, size_t len,
                                    char *why)
{
    uint8_t *copy = malloc(len ? len : 1);
    assert_non_null(copy);
    if (len)
        memcpy(copy, bytes, len);
    hl_status_t st = c->decode(copy, len, c->out, why);
    free(copy);
    return st;
}

/* Decoding @p bytes fails with @p want and a reason naming the message and @p field. */
static inline void tk_refused(const tk_codec_t *c, const uint8_t *bytes, size_t len,
                              hl_status_t want, const char *field)
{
    char why[HL_BUS_WHY_LEN] = "";
    assert_int_equal(tk_decode(c, bytes, len, why), want);
    tk_assert_why(why, c->name);
    if (field && !strstr(why, field))
        fail_msg("reason \"%s\" does not name \"%s\"", why, field);
}

/* (b) Every proper prefix and the message plus one byte are HL_ERR_PARSE; the message
 * itself decodes. */
static inline void tk_check_truncations(const tk_codec_t *c, const uint8_t *bytes, size_t len)
{
    assert_int_equal(tk_decode(c, bytes, len, NULL), HL_OK);
    for (size_t k = 0; k < len; k++)
        tk_refused(c, bytes, k, HL_ERR_PARSE, NULL);
    uint8_t *longer = malloc(len + 1);
    assert_non_null(longer);
    memcpy(longer, bytes, len);
    longer[len] = 0;
    tk_refused(c, longer, len + 1, HL_ERR_PARSE, NULL);
    free(longer);
}

/* (c) A change to any byte of the fingerprint is HL_ERR_PARSE. */
static inline void tk_check_bad_hash(const tk_codec_t *c, const uint8_t *bytes, size_t len)
{
    uint8_t *copy = malloc(len);
    assert_non_null(copy);
    for (size_t i = 0; i < 8; i++) {
        memcpy(copy, bytes, len);
        copy[i] ^= 0x10;
        tk_refused(c, copy, len, HL_ERR_PARSE, "fingerprint");
    }
    free(copy);
}

/* The encoder refuses every buffer shorter than the message and writes nothing past
 * the end of the one it gets (a heap block of exactly @p cap bytes, for ASan). */
static inline void tk_check_small_buffers(const tk_codec_t *c, const void *in, size_t len)
{
    for (size_t cap = 0; cap < len; cap++) {
        uint8_t *buf = malloc(cap ? cap : 1);
        assert_non_null(buf);
        assert_int_equal(c->encode(in, buf, cap), -1);
        free(buf);
    }
    uint8_t *buf = malloc(len);
    assert_non_null(buf);
    assert_int_equal(c->encode(in, buf, len), (int)len);
    assert_int_equal(c->encode(in, NULL, len), -1);
    assert_int_equal(c->encode(NULL, buf, len), -1);
    free(buf);
}

/* (d) @p iterations random buffers (half of them starting with the right fingerprint)
 * and random mutations of @p valid: the decoder returns OK, PARSE or RANGE and never
 * crashes; whatever it accepts re-encodes to the same bytes (after normalize). */
static inline int tk_fuzz(const tk_codec_t *c, const uint8_t *valid, size_t len,
                          int iterations, uint64_t seed)
{
    hl_rng_t rng;
    hl_rng_seed(&rng, seed);
    size_t cap = len + 64;
    uint8_t *buf = malloc(cap), *again = malloc(cap);
    assert_non_null(buf);
    assert_non_null(again);
    int accepted = 0;
    for (int it = 0; it < iterations; it++) {
        size_t n;
        if (it % 2 == 0) {
            n = (size_t)tk_range(&rng, 0, (int64_t)cap);
            for (size_t i = 0; i < n; i++)
                buf[i] = (uint8_t)hl_rng_next(&rng);
            if (hl_rng_below(&rng, 2) && n >= 8)
                memcpy(buf, valid, 8);
        } else {
            memcpy(buf, valid, len);
            n = len;
            int flips = (int)tk_range(&rng, 1, 4);
            for (int f = 0; f < flips; f++)
                buf[8 + hl_rng_below(&rng, (uint32_t)(len - 8))] = (uint8_t)hl_rng_next(&rng);
            if (hl_rng_below(&rng, 8) == 0)
                n = (size_t)tk_range(&rng, 0, (int64_t)cap);
            for (size_t i = len; i < n; i++)
                buf[i] = (uint8_t)hl_rng_next(&rng);
        }
        char why[HL_BUS_WHY_LEN] = "";
        hl_status_t st = tk_decode(c, buf, n, why);
        if (st == HL_OK) {
            accepted++;
            if (c->normalize)
                c->normalize(buf, n);
            int m = c->encode(c->out, again, cap);
            assert_int_equal(m, (int)n);
            assert_memory_equal(again, buf, n);
        } else {
            assert_true(st == HL_ERR_PARSE || st == HL_ERR_RANGE);
            tk_assert_why(why, c->name);
        }
    }
    free(buf);
    free(again);
    return accepted;
}

#endif
