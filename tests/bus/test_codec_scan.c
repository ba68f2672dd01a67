/* Tests for src/bus/codec_scan.c: SONAR and ODOMETRY against the lcm-gen code, both
 * ways, byte for byte; truncation, fingerprints, every out-of-range field; noise. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_odometry_t.h"
#include "houghloc_scan_t.h"

static hl_status_t dec_scan(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_scan(d, n, o, why);
}
static int enc_scan(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_scan(in, buf, cap);
}
static hl_status_t dec_odo(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_odometry(d, n, o, why);
}
static int enc_odo(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_odometry(in, buf, cap);
}

/* Offsets in an encoded scan (after the 8-byte hash). */
#define OFF_ODO_UTIME 20
#define OFF_VELOCITY 38
#define OFF_STOPPED 40
#define OFF_COUNT 41
#define OFF_READINGS 43

/* What hl_bus_encode_scan writes around the odometry pose: the scan's utime, velocity
 * 0, stopped true. */
static void normalize_scan(uint8_t *b, size_t len)
{
    (void)len;
    memcpy(b + OFF_ODO_UTIME, b + 8, 8);
    tk_put_be(b, OFF_VELOCITY, 0, 2);
    b[OFF_STOPPED] = 1;
}

static hl_bus_scan_t *new_scan(void)
{
    hl_bus_scan_t *s = calloc(1, sizeof *s);
    assert_non_null(s);
    return s;
}

static void random_scan(hl_rng_t *rng, hl_bus_scan_t *s, int n)
{
    s->utime = tk_range(rng, 0, INT64_MAX);
    s->seq = (int32_t)tk_range(rng, 0, INT32_MAX);
    s->odometry.x_mm = (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
    s->odometry.y_mm = (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
    s->odometry.theta = (hl_bam_t)hl_rng_next(rng);
    s->scan.count = (uint32_t)n;
    for (int i = 0; i < n; i++) {
        hl_reading_t *r = &s->scan.readings[i];
        r->range_mm = (int32_t)tk_range(rng, 0, HL_RANGE_MAX_MM);
        r->bearing = (hl_bam_t)hl_rng_next(rng);
        r->transducer = (int8_t)tk_range(rng, -1, 127);
        r->valid = hl_rng_below(rng, 2);
    }
}

static void assert_scan_matches(const hl_bus_scan_t *s, const houghloc_scan_t *g)
{
    assert_int_equal(g->utime, s->utime);
    assert_int_equal(g->seq, s->seq);
    assert_int_equal(g->odometry.x_mm, s->odometry.x_mm);
    assert_int_equal(g->odometry.y_mm, s->odometry.y_mm);
    assert_int_equal((hl_bam_t)g->odometry.heading_bam, s->odometry.theta);
    assert_int_equal(g->nreadings, (int)s->scan.count);
    for (int i = 0; i < g->nreadings; i++) {
        const hl_reading_t *r = &s->scan.readings[i];
        assert_int_equal(g->transducer[i], r->transducer);
        assert_int_equal((hl_bam_t)g->bearing_bam[i], r->bearing);
        assert_int_equal(g->range_mm[i], r->range_mm);
        assert_int_equal(g->valid[i], r->valid);
    }
}

/* (a) ours -> generated decode, same fields, and the generated encoder writes the same
 * bytes; generated encode -> ours, same fields, and we write the same bytes. Not for zero
 * readings: the generated decoder gives an empty array a NULL pointer and hands it to
 * memcpy, which UBSan refuses even for zero bytes (test_codec_empty.c covers them). */
static void test_scan_matches_generated_code(void **state)
{
    (void)state;
    static uint8_t a[HL_BUS_SCAN_MAX_BYTES], b[HL_BUS_SCAN_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 11);
    hl_bus_scan_t *s = new_scan(), *t = new_scan();
    const int counts[] = { 1, 2, 16, 128, 1023, HL_SCAN_MAX_READINGS };
    for (int it = 0; it < 60; it++) {
        int n = it < 6 ? counts[it] : (int)tk_range(&rng, 1, HL_SCAN_MAX_READINGS);
        random_scan(&rng, s, n);
        int len = hl_bus_encode_scan(s, a, sizeof a);
        assert_int_equal(len, 43 + 8 * n);
        houghloc_scan_t g;
        assert_int_equal(houghloc_scan_t_decode(a, 0, len, &g), len);
        assert_scan_matches(s, &g);
        assert_int_equal(g.odometry.utime, s->utime);
        assert_int_equal(g.odometry.velocity_mm_s, 0);
        assert_int_equal(g.odometry.stopped, 1);
        assert_int_equal(houghloc_scan_t_encoded_size(&g), len);
        assert_int_equal(houghloc_scan_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, (size_t)len);

        /* the other way: a message made by the generated encoder */
        g.seq = (int32_t)tk_range(&rng, 0, INT32_MAX);
        for (int i = 0; i < g.nreadings; i++)
            g.range_mm[i] = (int32_t)tk_range(&rng, 0, HL_RANGE_MAX_MM);
        assert_int_equal(houghloc_scan_t_encode(b, 0, sizeof b, &g), len);
        assert_int_equal(hl_bus_decode_scan(b, (size_t)len, t, NULL), HL_OK);
        assert_scan_matches(t, &g);
        assert_int_equal(hl_bus_encode_scan(t, a, sizeof a), len);
        assert_memory_equal(a, b, (size_t)len);
        houghloc_scan_t_decode_cleanup(&g);
    }
    free(s);
    free(t);
}

/* Another sender's velocity, stopped flag and odometry time are accepted and dropped. */
static void test_scan_odometry_extras_are_dropped(void **state)
{
    (void)state;
    static uint8_t a[HL_BUS_SCAN_MAX_BYTES];
    int8_t tr[2] = { 3, -1 }, valid[2] = { 1, 0 };
    int16_t bearing[2] = { 100, -100 };
    int32_t range[2] = { 2500, 0 };
    houghloc_scan_t g = {
        .utime = 5000, .seq = 7,
        .odometry = { .utime = 4000, .x_mm = -12, .y_mm = 34, .heading_bam = -2,
                      .velocity_mm_s = -250, .stopped = 0 },
        .nreadings = 2, .transducer = tr, .bearing_bam = bearing, .range_mm = range,
        .valid = valid,
    };
    int len = houghloc_scan_t_encode(a, 0, sizeof a, &g);
    assert_int_equal(len, 59);
    hl_bus_scan_t *s = new_scan();
    assert_int_equal(hl_bus_decode_scan(a, (size_t)len, s, NULL), HL_OK);
    assert_int_equal(s->utime, 5000);
    assert_int_equal(s->odometry.x_mm, -12);
    assert_int_equal(s->odometry.y_mm, 34);
    assert_int_equal(s->odometry.theta, 65534);
    assert_int_equal(s->scan.count, 2);
    assert_int_equal(s->scan.readings[1].transducer, -1);
    assert_int_equal(s->scan.readings[1].bearing, 65436);
    assert_false(s->scan.readings[1].valid);
    free(s);
}

static void test_scan_hostile_bytes(void **state)
{
    (void)state;
    static uint8_t a[HL_BUS_SCAN_MAX_BYTES], b[HL_BUS_SCAN_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 12);
    hl_bus_scan_t *s = new_scan(), *out = new_scan();
    tk_codec_t c = { "scan", dec_scan, enc_scan, normalize_scan, out };
    random_scan(&rng, s, 12);
    size_t len = (size_t)hl_bus_encode_scan(s, a, sizeof a);
    tk_check_truncations(&c, a, len);
    tk_check_bad_hash(&c, a, len);

    /* counts: negative, too many, and one that does not match the length */
    const int16_t counts[] = { -1, -32768, 1025, 32767, 11, 13 };
    const hl_status_t want[] = { HL_ERR_RANGE, HL_ERR_RANGE, HL_ERR_RANGE, HL_ERR_RANGE,
                                 HL_ERR_PARSE, HL_ERR_PARSE };
    for (int k = 0; k < 6; k++) {
        memcpy(b, a, len);
        tk_put_be(b, OFF_COUNT, (uint16_t)counts[k], 2);
        tk_refused(&c, b, len, want[k], "nreadings");
    }
    /* one field at a time, each just outside its range */
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, "utime" },
        { 16, (uint32_t)-1, 4, "seq" },
        { OFF_ODO_UTIME, (uint64_t)INT64_MIN, 8, "odometry.utime" },
        { 28, HL_COORD_MAX_MM + 1, 4, "odometry position" },
        { 32, (uint32_t)-HL_COORD_MAX_MM - 1, 4, "odometry position" },
        { OFF_STOPPED, 2, 1, "odometry.stopped" },
        { OFF_READINGS + 5, (uint8_t)-2, 1, "transducer[5]" },
        { OFF_READINGS + 36 + 4 * 3, HL_RANGE_MAX_MM + 1, 4, "range_mm[3]" },
        { OFF_READINGS + 36 + 4 * 0, (uint32_t)-1, 4, "range_mm[0]" },
        { OFF_READINGS + 84 + 11, 2, 1, "valid[11]" },
        { OFF_READINGS + 84 + 0, 0xff, 1, "valid[0]" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, len);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, len, HL_ERR_RANGE, bad[k].field);
    }
    free(s);
    free(out);
}

static void test_scan_encode_refuses_bad_input(void **state)
{
    (void)state;
    static uint8_t a[HL_BUS_SCAN_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 13);
    hl_bus_scan_t *s = new_scan();
    tk_codec_t c = { "scan", dec_scan, enc_scan, NULL, NULL };
    random_scan(&rng, s, 128);
    tk_check_small_buffers(&c, s, 43 + 8 * 128);
    hl_bus_scan_t saved = *s;
    s->scan.count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->scan.readings[7].range_mm = HL_RANGE_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    s->scan.readings[7].range_mm = -1;
    s->scan.readings[7].valid = false;     /* invalid readings are checked too */
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->scan.readings[0].transducer = -2;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->odometry.y_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->seq = -1;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->utime = -1;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), -1);
    *s = saved;
    s->odometry.x_mm = -HL_COORD_MAX_MM;   /* the limits themselves pass */
    s->odometry.y_mm = HL_COORD_MAX_MM;
    assert_int_equal(hl_bus_encode_scan(s, a, sizeof a), 43 + 8 * 128);
    free(s);
}

static void test_scan_noise(void **state)
{
    (void)state;
    static uint8_t a[HL_BUS_SCAN_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 14);
    hl_bus_scan_t *s = new_scan(), *out = new_scan();
    tk_codec_t c = { "scan", dec_scan, enc_scan, normalize_scan, out };
    random_scan(&rng, s, 6);
    size_t len = (size_t)hl_bus_encode_scan(s, a, sizeof a);
    int accepted = tk_fuzz(&c, a, len, 5000, 15);
    assert_in_range(accepted, 1, 4999);     /* some mutations are still valid scans */
    free(s);
    free(out);
}

/* ---- ODOMETRY ---------------------------------------------------------------------- */

static void test_odometry_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_ODOMETRY_BYTES + 8], b[HL_BUS_ODOMETRY_BYTES + 8];
    hl_rng_t rng;
    hl_rng_seed(&rng, 21);
    for (int it = 0; it < 500; it++) {
        hl_bus_odometry_t o = {
            .utime = tk_range(&rng, 0, INT64_MAX),
            .pose = { (int32_t)tk_range(&rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM),
                      (int32_t)tk_range(&rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM),
                      (hl_bam_t)hl_rng_next(&rng) },
            .velocity_mm_s = (int16_t)hl_rng_next(&rng),
            .stopped = hl_rng_below(&rng, 2),
        }, back;
        int len = hl_bus_encode_odometry(&o, a, sizeof a);
        assert_int_equal(len, HL_BUS_ODOMETRY_BYTES);
        houghloc_odometry_t g;
        assert_int_equal(houghloc_odometry_t_decode(a, 0, len, &g), len);
        assert_int_equal(g.utime, o.utime);
        assert_int_equal(g.x_mm, o.pose.x_mm);
        assert_int_equal(g.y_mm, o.pose.y_mm);
        assert_int_equal((hl_bam_t)g.heading_bam, o.pose.theta);
        assert_int_equal(g.velocity_mm_s, o.velocity_mm_s);
        assert_int_equal(g.stopped, o.stopped);
        assert_int_equal(houghloc_odometry_t_encoded_size(&g), len);
        assert_int_equal(houghloc_odometry_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, (size_t)len);
        assert_int_equal(hl_bus_decode_odometry(b, (size_t)len, &back, NULL), HL_OK);
        assert_int_equal(back.pose.x_mm, o.pose.x_mm);
        assert_int_equal(back.pose.y_mm, o.pose.y_mm);
        assert_int_equal(back.pose.theta, o.pose.theta);
        assert_int_equal(back.utime, o.utime);
        assert_int_equal(back.velocity_mm_s, o.velocity_mm_s);
        assert_int_equal(back.stopped, o.stopped);
    }
}

static void test_odometry_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_ODOMETRY_BYTES], b[HL_BUS_ODOMETRY_BYTES];
    hl_bus_odometry_t o = { 77, { 1000, -2000, 3 }, -40, false }, out;
    tk_codec_t c = { "odometry", dec_odo, enc_odo, NULL, &out };
    assert_int_equal(hl_bus_encode_odometry(&o, a, sizeof a), HL_BUS_ODOMETRY_BYTES);
    tk_check_truncations(&c, a, sizeof a);
    tk_check_bad_hash(&c, a, sizeof a);
    tk_check_small_buffers(&c, &o, sizeof a);
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)-5, 8, "utime" },
        { 16, HL_COORD_MAX_MM + 1, 4, "position" },
        { 20, 0x80000000u, 4, "position" },
        { 28, 7, 1, "stopped" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, sizeof a);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, sizeof b, HL_ERR_RANGE, bad[k].field);
    }
    o.pose.x_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_odometry(&o, a, sizeof a), -1);
    o.pose.x_mm = 0;
    o.utime = -1;
    assert_int_equal(hl_bus_encode_odometry(&o, a, sizeof a), -1);
    o.utime = 0;
    assert_int_equal(hl_bus_encode_odometry(&o, a, sizeof a), HL_BUS_ODOMETRY_BYTES);
    assert_in_range(tk_fuzz(&c, a, sizeof a, 5000, 22), 1, 4999);
}

static void test_null_arguments(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_ODOMETRY_BYTES] = { 0 };
    hl_bus_odometry_t o;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_odometry(NULL, sizeof a, &o, why), HL_ERR_ARG);
    tk_assert_why(why, "odometry");
    assert_int_equal(hl_bus_decode_odometry(a, sizeof a, NULL, NULL), HL_ERR_ARG);
    assert_int_equal(hl_bus_decode_scan(a, sizeof a, NULL, why), HL_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan_matches_generated_code),
        cmocka_unit_test(test_scan_odometry_extras_are_dropped),
        cmocka_unit_test(test_scan_hostile_bytes),
        cmocka_unit_test(test_scan_encode_refuses_bad_input),
        cmocka_unit_test(test_scan_noise),
        cmocka_unit_test(test_odometry_matches_generated_code),
        cmocka_unit_test(test_odometry_hostile_bytes),
        cmocka_unit_test(test_null_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
