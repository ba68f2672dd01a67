/* Tests for src/bus/codec_status.c and the REPLY half of codec_request.c: the two
 * messages that carry a string, against the lcm-gen code both ways; truncation,
 * fingerprints, out-of-range fields, the string's framing and content; noise. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_reply_t.h"
#include "houghloc_status_t.h"

static hl_status_t dec_status(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_status(d, n, o, why);
}
static int enc_status(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_status(in, buf, cap);
}
static hl_status_t dec_reply(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_reply(d, n, o, why);
}
static int enc_reply(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_reply(in, buf, cap);
}

#define STATUS_TEXT_OFF 139     /* the string's length field in an encoded status */
#define REPLY_TEXT_OFF 25

/* A 64-bit counter: any value it may hold, most of them past 32 bits. */
static int64_t counter(hl_rng_t *rng)
{
    return tk_range(rng, 0, INT64_MAX);
}

/* A 32-bit field that is not a counter (compute times). */
static int32_t nonneg32(hl_rng_t *rng)
{
    return (int32_t)tk_range(rng, 0, INT32_MAX);
}

static hl_bus_status_t random_status(hl_rng_t *rng)
{
    hl_bus_status_t s = {
        .utime = tk_range(rng, 0, INT64_MAX),
        .state = (int8_t)tk_range(rng, 0, 7),
        .destination_seq = hl_rng_below(rng, 4) ? tk_range(rng, 1, INT64_MAX) : -1,
        .scans = counter(rng), .accepted = counter(rng), .rejected_wild = counter(rng),
        .odometry_only = counter(rng), .relocalized = counter(rng), .lost = counter(rng),
        .bad_packets = counter(rng),
        .bad_messages = counter(rng), .rejected_requests = counter(rng),
        .map_vectors = (int32_t)tk_range(rng, 0, HL_MAP_MAX_CAPACITY),
        .map_version = counter(rng), .saves = counter(rng),
        .pose = { (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM),
                  (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM),
                  (hl_bam_t)hl_rng_next(rng) },
        .compute_median_us = nonneg32(rng), .compute_p99_us = nonneg32(rng),
        .compute_samples = nonneg32(rng),
    };
    tk_text(rng, s.last_error, HL_BUS_TEXT_MAX - 1);
    return s;
}

static void assert_status_matches(const hl_bus_status_t *s, const houghloc_status_t *g)
{
    assert_int_equal(g->utime, s->utime);
    assert_int_equal(g->state, s->state);
    assert_int_equal(g->destination_seq, s->destination_seq);
    assert_int_equal(g->scans, s->scans);
    assert_int_equal(g->accepted, s->accepted);
    assert_int_equal(g->rejected_wild, s->rejected_wild);
    assert_int_equal(g->odometry_only, s->odometry_only);
    assert_int_equal(g->relocalized, s->relocalized);
    assert_int_equal(g->lost, s->lost);
    assert_int_equal(g->bad_packets, s->bad_packets);
    assert_int_equal(g->bad_messages, s->bad_messages);
    assert_int_equal(g->rejected_requests, s->rejected_requests);
    assert_int_equal(g->map_vectors, s->map_vectors);
    assert_int_equal(g->map_version, s->map_version);
    assert_int_equal(g->saves, s->saves);
    assert_int_equal(g->x_mm, s->pose.x_mm);
    assert_int_equal(g->y_mm, s->pose.y_mm);
    assert_int_equal((hl_bam_t)g->heading_bam, s->pose.theta);
    assert_int_equal(g->compute_median_us, s->compute_median_us);
    assert_int_equal(g->compute_p99_us, s->compute_p99_us);
    assert_int_equal(g->compute_samples, s->compute_samples);
    assert_string_equal(g->last_error, s->last_error);
}

static void test_status_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_STATUS_MAX_BYTES], b[HL_BUS_STATUS_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 51);
    for (int it = 0; it < 500; it++) {
        hl_bus_status_t s = random_status(&rng), back;
        if (it == 0)
            memset(s.last_error, 'x', HL_BUS_TEXT_MAX - 1);    /* the longest */
        if (it == 1)
            s.last_error[0] = '\0';
        int len = hl_bus_encode_status(&s, a, sizeof a);
        assert_int_equal(len, STATUS_TEXT_OFF + 4 + (int)strlen(s.last_error) + 1);
        houghloc_status_t g;
        assert_int_equal(houghloc_status_t_decode(a, 0, len, &g), len);
        assert_status_matches(&s, &g);
        assert_int_equal(houghloc_status_t_encoded_size(&g), len);
        assert_int_equal(houghloc_status_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, (size_t)len);

        g.scans = counter(&rng);
        assert_int_equal(houghloc_status_t_encode(b, 0, sizeof b, &g), len);
        assert_int_equal(hl_bus_decode_status(b, (size_t)len, &back, NULL), HL_OK);
        assert_status_matches(&back, &g);
        assert_int_equal(hl_bus_encode_status(&back, a, sizeof a), len);
        assert_memory_equal(a, b, (size_t)len);
        houghloc_status_t_decode_cleanup(&g);
    }
}

/* The string's framing and content, at @p off in a message of @p len bytes whose text
 * is "abc": the length field, the terminator, embedded NULs, control characters. */
static void check_text_field(const tk_codec_t *c, const uint8_t *a, size_t len, size_t off,
                             size_t after, const char *field)
{
    uint8_t b[512];
    assert_int_equal(len, off + 4 + 4 + after);
    struct { uint32_t n; size_t at; uint8_t byte; hl_status_t st; } bad[] = {
        { 0, 0, 0, HL_ERR_PARSE },                   /* length 0: no room for the NUL */
        { (uint32_t)-1, 0, 0, HL_ERR_PARSE },
        { 0x7fffffff, 0, 0, HL_ERR_RANGE },
        { HL_BUS_TEXT_MAX + 1, 0, 0, HL_ERR_RANGE },
        { 5, 0, 0, HL_ERR_PARSE },                   /* runs past the end */
        { 3, 0, 0, HL_ERR_PARSE },                   /* ends at the 'c': no NUL */
        { 4, 3, 'd', HL_ERR_PARSE },                 /* no NUL at the end */
        { 4, 1, 0, HL_ERR_PARSE },                   /* a NUL inside */
        { 4, 1, '\n', HL_ERR_RANGE },
        { 4, 0, '\r', HL_ERR_RANGE },
        { 4, 2, 0x1b, HL_ERR_RANGE },
        { 4, 2, 0x7f, HL_ERR_RANGE },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, len);
        tk_put_be(b, off, bad[k].n, 4);
        if (bad[k].at || bad[k].byte)
            b[off + 4 + bad[k].at] = bad[k].byte;
        tk_refused(c, b, len, bad[k].st, field);
    }
    memcpy(b, a, len);
    b[off + 4 + 1] = 0xc3;                            /* bytes above 0x7f pass */
    assert_int_equal(tk_decode(c, b, len, NULL), HL_OK);
}

static void test_status_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_STATUS_MAX_BYTES], b[HL_BUS_STATUS_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 52);
    hl_bus_status_t s = random_status(&rng), out;
    strcpy(s.last_error, "abc");
    tk_codec_t c = { "status", dec_status, enc_status, NULL, &out };
    size_t len = (size_t)hl_bus_encode_status(&s, a, sizeof a);
    tk_check_truncations(&c, a, len);
    tk_check_bad_hash(&c, a, len);
    tk_check_small_buffers(&c, &s, len);
    check_text_field(&c, a, len, STATUS_TEXT_OFF, 0, "last_error");
    /* offsets: 8 utime 16 state 17 destination_seq 25 counters (9 x 8: scans ..
     * rejected_requests) 97 map_vectors 101 map_version 109 saves 117 x 121 y 125 heading
     * 127 compute_median_us 131 p99 135 samples 139 last_error */
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, "utime" },
        { 16, 8, 1, "state" },
        { 16, 0xff, 1, "state" },
        { 17, 0, 8, "destination_seq" },
        { 17, (uint64_t)-2, 8, "destination_seq" },
        { 25, (uint64_t)-1, 8, "scans" },
        { 25 + 8 * 4, (uint64_t)-1, 8, "relocalized" },
        { 25 + 8 * 5, (uint64_t)-1, 8, "lost" },
        { 25 + 8 * 7, UINT64_C(1) << 63, 8, "bad_messages" },
        { 25 + 8 * 8, UINT64_C(1) << 63, 8, "rejected_requests" },
        { 97, HL_MAP_MAX_CAPACITY + 1, 4, "map_vectors" },
        { 97, (uint32_t)-1, 4, "map_vectors" },
        { 101, (uint64_t)-1, 8, "map_version" },
        { 109, (uint64_t)-1, 8, "saves" },
        { 117, HL_COORD_MAX_MM + 1, 4, "position" },
        { 121, (uint32_t)-HL_COORD_MAX_MM - 1, 4, "position" },
        { 127, (uint32_t)-1, 4, "compute" },
        { 135, (uint32_t)-1, 4, "compute" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, len);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, len, HL_ERR_RANGE, bad[k].field);
    }
    hl_bus_status_t q = s;
    strcpy(q.last_error, "two\nlines");
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), -1);
    memset(q.last_error, 'x', sizeof q.last_error);         /* no NUL */
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), -1);
    q = s;
    q.state = 8;
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), -1);
    q = s;
    q.destination_seq = 0;
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), -1);
    q = s;
    q.bad_messages = -1;
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), -1);
    /* the counters' whole range goes out, past 32 bits up to 2^63 - 1 */
    q = s;
    q.bad_messages = (INT64_C(1) << 31) + 1;
    q.map_version = INT64_MAX;
    q.scans = (INT64_C(1) << 32) + 7;
    assert_int_equal(hl_bus_encode_status(&q, b, sizeof b), (int)len);
    assert_int_equal(hl_bus_decode_status(b, len, &out, NULL), HL_OK);
    assert_int_equal(out.bad_messages, (INT64_C(1) << 31) + 1);
    assert_int_equal(out.map_version, INT64_MAX);
    assert_int_equal(out.scans, (INT64_C(1) << 32) + 7);
    assert_in_range(tk_fuzz(&c, a, len, 5000, 53), 1, 4999);
}

/* ---- REPLY ------------------------------------------------------------------------- */

static void test_reply_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_REPLY_MAX_BYTES], b[HL_BUS_REPLY_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 61);
    for (int it = 0; it < 500; it++) {
        hl_bus_reply_t r = {
            .utime = tk_range(&rng, 0, INT64_MAX),
            .seq = tk_range(&rng, INT64_MIN, INT64_MAX),    /* echoed as it came */
            .result = (int8_t)tk_range(&rng, 0, 7),
        }, back;
        tk_text(&rng, r.message, HL_BUS_TEXT_MAX - 1);
        for (int i = 0; i < HL_BUS_MAC_BYTES; i++)
            r.mac[i] = (uint8_t)hl_rng_next(&rng);
        int len = hl_bus_encode_reply(&r, a, sizeof a);
        assert_int_equal(len, REPLY_TEXT_OFF + 4 + (int)strlen(r.message) + 1 + HL_BUS_MAC_BYTES);
        houghloc_reply_t g;
        assert_int_equal(houghloc_reply_t_decode(a, 0, len, &g), len);
        assert_int_equal(g.utime, r.utime);
        assert_int_equal(g.seq, r.seq);
        assert_int_equal(g.result, r.result);
        assert_string_equal(g.message, r.message);
        assert_memory_equal(g.mac, r.mac, HL_BUS_MAC_BYTES);
        assert_int_equal(houghloc_reply_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, (size_t)len);
        assert_int_equal(hl_bus_decode_reply(b, (size_t)len, &back, NULL), HL_OK);
        assert_int_equal(back.seq, g.seq);
        assert_int_equal(back.result, g.result);
        assert_string_equal(back.message, g.message);
        assert_memory_equal(back.mac, r.mac, HL_BUS_MAC_BYTES);
        assert_int_equal(hl_bus_encode_reply(&back, a, sizeof a), len);
        assert_memory_equal(a, b, (size_t)len);
        houghloc_reply_t_decode_cleanup(&g);
    }
}

static void test_reply_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_REPLY_MAX_BYTES], b[HL_BUS_REPLY_MAX_BYTES];
    hl_bus_reply_t r = { 10, -3, HL_BUS_REPLY_REJECTED_INVALID, "abc", { 0 } }, out;
    tk_codec_t c = { "reply", dec_reply, enc_reply, NULL, &out };
    size_t len = (size_t)hl_bus_encode_reply(&r, a, sizeof a);
    tk_check_truncations(&c, a, len);
    tk_check_bad_hash(&c, a, len);
    tk_check_small_buffers(&c, &r, len);
    check_text_field(&c, a, len, REPLY_TEXT_OFF, HL_BUS_MAC_BYTES, "message");
    memcpy(b, a, len);
    b[24] = 8;
    tk_refused(&c, b, len, HL_ERR_RANGE, "result");
    b[24] = 0x80;
    tk_refused(&c, b, len, HL_ERR_RANGE, "result");
    tk_put_be(b, 8, (uint64_t)-1, 8);
    b[24] = 0;
    tk_refused(&c, b, len, HL_ERR_RANGE, "utime");
    hl_bus_reply_t q = r;
    q.result = 8;
    assert_int_equal(hl_bus_encode_reply(&q, b, sizeof b), -1);
    q.result = -1;
    assert_int_equal(hl_bus_encode_reply(&q, b, sizeof b), -1);
    q = r;
    strcpy(q.message, "tab\there");
    assert_int_equal(hl_bus_encode_reply(&q, b, sizeof b), -1);
    assert_in_range(tk_fuzz(&c, a, len, 5000, 62), 1, 4999);
}

static void test_reply_names(void **state)
{
    (void)state;
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_ACCEPTED), "ACCEPTED");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_ARRIVED), "ARRIVED");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_REJECTED_FENCE), "REJECTED_FENCE");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_REJECTED_AUTH), "REJECTED_AUTH");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_REJECTED_REPLAY), "REJECTED_REPLAY");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_NO_ROBOT), "NO_ROBOT");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_FAILED), "FAILED");
    assert_string_equal(hl_bus_reply_name(HL_BUS_REPLY_REJECTED_INVALID), "REJECTED_INVALID");
    assert_string_equal(hl_bus_reply_name(8), "?");
    assert_string_equal(hl_bus_reply_name(-1), "?");
    assert_string_equal(hl_bus_reply_name(INT8_MIN), "?");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_status_matches_generated_code),
        cmocka_unit_test(test_status_hostile_bytes),
        cmocka_unit_test(test_reply_matches_generated_code),
        cmocka_unit_test(test_reply_hostile_bytes),
        cmocka_unit_test(test_reply_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
