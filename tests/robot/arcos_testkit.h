/* arcos_testkit.h - what the ARCOS codec's tests share: feeding a parser and collecting
 * the packets that come out. */
#ifndef HOUGHLOC_TESTS_ARCOS_TESTKIT_H
#define HOUGHLOC_TESTS_ARCOS_TESTKIT_H

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "houghloc/arcos.h"
#include "houghloc/rng.h"

#define MAX_GOT 64
#define STREAM_MAX 8192

typedef struct got {
    hl_arcos_packet_t pk[MAX_GOT];
    size_t n;
} got_t;


/* Feeds @p n bytes (n > 0) and appends every packet that comes out to @p g. */
static inline void feed(hl_arcos_parser_t *p, const uint8_t *in, size_t n, got_t *g)
{
    size_t off = 0, used = 0;
    hl_arcos_packet_t pk;
    for (;;) {
        hl_status_t st = hl_arcos_parse(p, in + off, n - off, &used, &pk);
        assert_true(used <= n - off);
        off += used;
        if (st != HL_OK) {
            assert_int_equal(st, HL_ERR_EMPTY);
            assert_int_equal(off, n);
            return;
        }
        assert_true(g->n < MAX_GOT);
        g->pk[g->n++] = pk;
    }
}

static inline void assert_bytes(const uint8_t *got, size_t got_len, const uint8_t *want, size_t len)
{
    assert_int_equal(got_len, len);
    assert_memory_equal(got, want, len);
}

/* Payload of framed packet @p f equal to @p pk. */
static inline int same_packet(const hl_arcos_packet_t *pk, const uint8_t *f)
{
    return pk->len == f[2] - 2 && memcmp(pk->data, f + 3, pk->len) == 0;
}

static inline void random_sip(hl_rng_t *r, hl_arcos_sip_t *s, uint8_t count)
{
    memset(s, 0, sizeof *s);
    s->type = hl_rng_below(r, 2) ? HL_ARCOS_SIP_MOVING : HL_ARCOS_SIP_STOPPED;
    s->x = (uint16_t)hl_rng_next(r);
    s->y = (uint16_t)hl_rng_next(r);
    s->th = (int16_t)hl_rng_next(r);
    s->vel_left = (int16_t)hl_rng_next(r);
    s->vel_right = (int16_t)hl_rng_next(r);
    s->battery = (uint8_t)hl_rng_next(r);
    s->stall_bumpers = (uint16_t)hl_rng_next(r);
    s->control = (int16_t)hl_rng_next(r);
    s->flags = (uint16_t)hl_rng_next(r);
    s->compass = (uint8_t)hl_rng_next(r);
    s->sonar_count = count;
    for (uint8_t i = 0; i < count; i++) {
        s->sonar[i].transducer = (uint8_t)hl_rng_below(r, HL_ARCOS_SONAR_MAX);
        s->sonar[i].range = (uint16_t)hl_rng_next(r);
    }
    s->extra_len = (uint8_t)hl_rng_below(r, HL_ARCOS_PAYLOAD_MAX - HL_ARCOS_SIP_FIXED - 3u * count + 1);
}

#endif
