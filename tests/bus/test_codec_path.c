/* Tests for src/bus/codec_path.c: PATH against the lcm-gen code, both ways, byte for byte;
 * truncation, fingerprint, a hostile point count, out-of-range points; noise. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_path_t.h"

static hl_status_t dec_path(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_path(d, n, o, why);
}
static int enc_path(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_path(in, buf, cap);
}

static hl_bus_path_t random_path(hl_rng_t *rng, int32_t n)
{
    hl_bus_path_t m = { .utime = tk_range(rng, 0, INT64_MAX),
                        .destination_seq = n ? tk_range(rng, 1, INT64_MAX) : -1,
                        .npoints = n };
    for (int32_t i = 0; i < n; i++) {
        m.x_mm[i] = (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
        m.y_mm[i] = (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
    }
    return m;
}

static void test_path_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_PATH_MAX_BYTES], b[HL_BUS_PATH_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 61);
    for (int it = 0; it < 300; it++) {
        int32_t n = it == 0 ? 0 : it == 1 ? HL_BUS_PATH_MAX_POINTS
                                          : (int32_t)tk_range(&rng, 0, HL_BUS_PATH_MAX_POINTS);
        hl_bus_path_t m = random_path(&rng, n), back;
        int len = hl_bus_encode_path(&m, a, sizeof a);
        assert_int_equal(len, 8 + 8 + 8 + 4 + 8 * n);
        houghloc_path_t g;
        assert_int_equal(houghloc_path_t_decode(a, 0, len, &g), len);
        assert_int_equal(g.utime, m.utime);
        assert_int_equal(g.destination_seq, m.destination_seq);
        assert_int_equal(g.npoints, n);
        for (int32_t i = 0; i < n; i++) {
            assert_int_equal(g.x_mm[i], m.x_mm[i]);
            assert_int_equal(g.y_mm[i], m.y_mm[i]);
        }
        assert_int_equal(houghloc_path_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, (size_t)len);
        assert_int_equal(hl_bus_decode_path(b, (size_t)len, &back, NULL), HL_OK);
        assert_int_equal(back.npoints, n);
        assert_memory_equal(back.x_mm, m.x_mm, (size_t)n * sizeof m.x_mm[0]);
        assert_memory_equal(back.y_mm, m.y_mm, (size_t)n * sizeof m.y_mm[0]);
        houghloc_path_t_decode_cleanup(&g);
    }
}

static void test_path_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_PATH_MAX_BYTES], b[HL_BUS_PATH_MAX_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 62);
    hl_bus_path_t m = random_path(&rng, 3), out;
    tk_codec_t c = { "path", dec_path, enc_path, NULL, &out };
    size_t len = (size_t)hl_bus_encode_path(&m, a, sizeof a);
    assert_int_equal(len, 28 + 24);
    tk_check_truncations(&c, a, len);
    tk_check_bad_hash(&c, a, len);
    tk_check_small_buffers(&c, &m, len);
    /* offsets: 8 utime 16 destination_seq 24 npoints 28 x[3] 40 y[3] */
    struct { size_t off; uint64_t v; size_t n; hl_status_t st; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, HL_ERR_RANGE, "utime" },
        { 16, 0, 8, HL_ERR_RANGE, "destination_seq" },
        { 16, (uint64_t)-2, 8, HL_ERR_RANGE, "destination_seq" },
        { 24, (uint32_t)-1, 4, HL_ERR_RANGE, "npoints" },
        { 24, HL_BUS_PATH_MAX_POINTS + 1, 4, HL_ERR_RANGE, "npoints" },
        { 24, 0x7fffffff, 4, HL_ERR_RANGE, "npoints" },
        { 24, 2, 4, HL_ERR_PARSE, "npoints" },      /* fewer than the bytes hold */
        { 24, 4, 4, HL_ERR_PARSE, "npoints" },      /* more */
        { 32, HL_COORD_MAX_MM + 1, 4, HL_ERR_RANGE, "point" },
        { 40, (uint32_t)-HL_COORD_MAX_MM - 1, 4, HL_ERR_RANGE, "point" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, len);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, len, bad[k].st, bad[k].field);
    }
    hl_bus_path_t q = m;
    q.npoints = HL_BUS_PATH_MAX_POINTS + 1;
    assert_int_equal(hl_bus_encode_path(&q, b, sizeof b), -1);
    q = m;
    q.destination_seq = 0;
    assert_int_equal(hl_bus_encode_path(&q, b, sizeof b), -1);
    q = m;
    q.y_mm[2] = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_path(&q, b, sizeof b), -1);
    assert_in_range(tk_fuzz(&c, a, len, 5000, 63), 1, 4999);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_path_matches_generated_code),
        cmocka_unit_test(test_path_hostile_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
