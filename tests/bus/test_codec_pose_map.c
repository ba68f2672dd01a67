/* Tests for src/bus/codec_pose.c and codec_map.c: POSE and MAP against the lcm-gen code,
 * both ways, byte for byte; truncation, fingerprints, out-of-range fields; noise. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_map_t.h"
#include "houghloc_pose_t.h"

static hl_status_t dec_pose(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_pose(d, n, o, why);
}
static int enc_pose(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_pose(in, buf, cap);
}
static hl_status_t dec_map(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_map(d, n, o, why);
}
static int enc_map(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_map(in, buf, cap);
}

static int32_t coord(hl_rng_t *rng)
{
    return (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
}

/* ---- POSE -------------------------------------------------------------------------- */

static hl_bus_pose_t random_pose(hl_rng_t *rng)
{
    hl_bus_pose_t p = {
        .utime = tk_range(rng, 0, INT64_MAX),
        .scan_seq = (int32_t)tk_range(rng, 0, INT32_MAX),
        .pose = { coord(rng), coord(rng), (hl_bam_t)hl_rng_next(rng) },
        .status = (int8_t)tk_range(rng, 0, 4),
        .confidence = (float)hl_rng_next(rng) / 4294967296.0f,
        .peak = (int32_t)tk_range(rng, 0, INT32_MAX),
        .second_peak = (int32_t)tk_range(rng, 0, INT32_MAX),
        .votes = (int32_t)tk_range(rng, 0, INT32_MAX),
        .search_score = (float)hl_rng_next(rng) / 4294967296.0f,
        .runner_up = { coord(rng), coord(rng), (hl_bam_t)hl_rng_next(rng) },
        .runner_up_score = (float)hl_rng_next(rng) / 4294967296.0f,
    };
    return p;
}

static void assert_pose_matches(const hl_bus_pose_t *p, const houghloc_pose_t *g)
{
    assert_int_equal(g->utime, p->utime);
    assert_int_equal(g->scan_seq, p->scan_seq);
    assert_int_equal(g->x_mm, p->pose.x_mm);
    assert_int_equal(g->y_mm, p->pose.y_mm);
    assert_int_equal((hl_bam_t)g->heading_bam, p->pose.theta);
    assert_int_equal(g->status, p->status);
    assert_memory_equal(&g->confidence, &p->confidence, sizeof(float));
    assert_int_equal(g->peak, p->peak);
    assert_int_equal(g->second_peak, p->second_peak);
    assert_int_equal(g->votes, p->votes);
    assert_memory_equal(&g->search_score, &p->search_score, sizeof(float));
    assert_int_equal(g->runner_up_x_mm, p->runner_up.x_mm);
    assert_int_equal(g->runner_up_y_mm, p->runner_up.y_mm);
    assert_int_equal((hl_bam_t)g->runner_up_heading_bam, p->runner_up.theta);
    assert_memory_equal(&g->runner_up_score, &p->runner_up_score, sizeof(float));
}

static void test_pose_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_POSE_BYTES], b[HL_BUS_POSE_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 31);
    for (int it = 0; it < 500; it++) {
        hl_bus_pose_t p = random_pose(&rng), back;
        if (it == 0)
            p.confidence = 1.0f;
        int len = hl_bus_encode_pose(&p, a, sizeof a);
        assert_int_equal(len, HL_BUS_POSE_BYTES);
        houghloc_pose_t g;
        assert_int_equal(houghloc_pose_t_decode(a, 0, len, &g), len);
        assert_pose_matches(&p, &g);
        assert_int_equal(houghloc_pose_t_encoded_size(&g), len);
        assert_int_equal(houghloc_pose_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, sizeof a);

        g.status = (int8_t)tk_range(&rng, 0, 4);
        g.votes = (int32_t)tk_range(&rng, 0, INT32_MAX);
        assert_int_equal(houghloc_pose_t_encode(b, 0, sizeof b, &g), len);
        assert_int_equal(hl_bus_decode_pose(b, sizeof b, &back, NULL), HL_OK);
        assert_pose_matches(&back, &g);
        assert_int_equal(hl_bus_encode_pose(&back, a, sizeof a), len);
        assert_memory_equal(a, b, sizeof a);
    }
}

static void test_pose_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_POSE_BYTES], b[HL_BUS_POSE_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 32);
    hl_bus_pose_t p = random_pose(&rng), out;
    tk_codec_t c = { "pose", dec_pose, enc_pose, NULL, &out };
    assert_int_equal(hl_bus_encode_pose(&p, a, sizeof a), HL_BUS_POSE_BYTES);
    tk_check_truncations(&c, a, sizeof a);
    tk_check_bad_hash(&c, a, sizeof a);
    tk_check_small_buffers(&c, &p, sizeof a);
    /* offsets: 8 utime 16 scan_seq 20 x 24 y 28 heading 30 status 31 confidence 35 peak
     * 39 second_peak 43 votes 47 search_score 51 runner-up x 55 y 59 heading
     * 61 runner_up_score */
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, "utime" },
        { 16, 0x80000000u, 4, "scan_seq" },
        { 20, HL_COORD_MAX_MM + 1, 4, "position" },
        { 24, (uint32_t)-HL_COORD_MAX_MM - 1, 4, "position" },
        { 30, 5, 1, "status" },
        { 30, 0xff, 1, "status" },
        { 31, 0x7fc00000u, 4, "confidence" },      /* NaN */
        { 31, 0x7f800000u, 4, "confidence" },      /* +inf */
        { 31, 0xff800000u, 4, "confidence" },      /* -inf */
        { 31, 0x3f800001u, 4, "confidence" },      /* just above 1 */
        { 31, 0xbf800000u, 4, "confidence" },      /* -1 */
        { 35, (uint32_t)-1, 4, "peak" },
        { 39, 0x80000000u, 4, "second_peak" },
        { 43, (uint32_t)-7, 4, "votes" },
        { 47, 0x7fc00000u, 4, "search_score" },    /* NaN */
        { 47, 0x3f800001u, 4, "search_score" },
        { 51, HL_COORD_MAX_MM + 1, 4, "runner-up position" },
        { 55, (uint32_t)-HL_COORD_MAX_MM - 1, 4, "runner-up position" },
        { 61, 0xbf800000u, 4, "runner_up_score" }, /* -1 */
        { 61, 0x7f800000u, 4, "runner_up_score" }, /* +inf */
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, sizeof a);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, sizeof b, HL_ERR_RANGE, bad[k].field);
    }
    const float bad_conf[] = { NAN, INFINITY, -INFINITY, 1.0001f, -0.5f };
    for (size_t k = 0; k < sizeof bad_conf / sizeof bad_conf[0]; k++) {
        hl_bus_pose_t q = p;
        q.confidence = bad_conf[k];
        assert_int_equal(hl_bus_encode_pose(&q, a, sizeof a), -1);
    }
    hl_bus_pose_t q = p;
    q.status = 5;
    assert_int_equal(hl_bus_encode_pose(&q, a, sizeof a), -1);
    q = p;
    q.peak = -1;
    assert_int_equal(hl_bus_encode_pose(&q, a, sizeof a), -1);
    q = p;
    q.pose.y_mm = -HL_COORD_MAX_MM - 1;
    assert_int_equal(hl_bus_encode_pose(&q, a, sizeof a), -1);
    assert_int_equal(hl_bus_encode_pose(&p, a, sizeof a), HL_BUS_POSE_BYTES);
    assert_in_range(tk_fuzz(&c, a, sizeof a, 5000, 33), 1, 4999);
}

/* POSE of logs made before the global search's fields (houghloc 0.x): the older layout,
 * under its own fingerprint, still decodes, the new fields zero; re-encoding writes the
 * current layout with the same leading fields. Its fingerprint at the current size, or
 * the current fingerprint at its size, is refused. */
static void test_pose_older_layout(void **state)
{
    (void)state;
    hl_rng_t rng;
    hl_rng_seed(&rng, 34);
    hl_bus_pose_t p = random_pose(&rng), out;
    uint8_t cur[HL_BUS_POSE_BYTES], old[HL_BUS_POSE_BYTES - 18];
    assert_int_equal(hl_bus_encode_pose(&p, cur, sizeof cur), HL_BUS_POSE_BYTES);
    memcpy(old, cur, sizeof old);
    tk_put_be(old, 0, 0xd976510111d909d3ull, 8);
    assert_int_equal(hl_bus_decode_pose(old, sizeof old, &out, NULL), HL_OK);
    assert_int_equal(out.utime, p.utime);
    assert_int_equal(out.pose.x_mm, p.pose.x_mm);
    assert_int_equal(out.votes, p.votes);
    assert_true(out.search_score == 0.0f && out.runner_up_score == 0.0f);
    assert_int_equal(out.runner_up.x_mm, 0);
    uint8_t again[HL_BUS_POSE_BYTES];
    assert_int_equal(hl_bus_encode_pose(&out, again, sizeof again), HL_BUS_POSE_BYTES);
    assert_memory_equal(again + 8, old + 8, sizeof old - 8);
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_pose(old, sizeof old - 1, &out, why), HL_ERR_PARSE);
    tk_put_be(cur, 0, 0xd976510111d909d3ull, 8);
    assert_int_equal(hl_bus_decode_pose(cur, sizeof cur, &out, why), HL_ERR_PARSE);
    assert_non_null(strstr(why, "fingerprint"));
    assert_int_equal(hl_bus_encode_pose(&p, cur, sizeof cur), HL_BUS_POSE_BYTES);
    memcpy(old, cur, sizeof old);
    assert_int_equal(hl_bus_decode_pose(old, sizeof old, &out, why), HL_ERR_PARSE);
}

/* ---- MAP --------------------------------------------------------------------------- */

#define MAP_STORAGE 700

static void random_map(hl_rng_t *rng, hl_bus_map_t *m, hl_vector_t *v, uint32_t n)
{
    m->utime = tk_range(rng, 0, INT64_MAX);
    m->version = tk_range(rng, 0, INT64_MAX);
    m->capacity = (int32_t)tk_range(rng, n ? n : 1, HL_MAP_MAX_CAPACITY);
    m->count = n;
    m->vectors = v;
    for (uint32_t i = 0; i < n; i++)
        v[i] = (hl_vector_t){ coord(rng), coord(rng), (hl_bam_t)hl_rng_next(rng),
                              (uint16_t)tk_range(rng, 0, HL_RANGE_MAX_MM) };
}

static void assert_map_matches(const hl_bus_map_t *m, const houghloc_map_t *g)
{
    assert_int_equal(g->utime, m->utime);
    assert_int_equal(g->version, m->version);
    assert_int_equal(g->capacity, m->capacity);
    assert_int_equal(g->nvectors, (int32_t)m->count);
    for (int i = 0; i < g->nvectors; i++) {
        assert_int_equal(g->x_mm[i], m->vectors[i].x_mm);
        assert_int_equal(g->y_mm[i], m->vectors[i].y_mm);
        assert_int_equal((hl_bam_t)g->normal_bam[i], m->vectors[i].normal);
        assert_int_equal(g->range_mm[i], m->vectors[i].range_mm);
    }
}

static void test_map_matches_generated_code(void **state)
{
    (void)state;
    size_t cap = hl_bus_map_bytes(MAP_STORAGE);
    uint8_t *a = malloc(cap), *b = malloc(cap);
    hl_vector_t *v = calloc(MAP_STORAGE, sizeof *v), *w = calloc(MAP_STORAGE, sizeof *w);
    hl_rng_t rng;
    hl_rng_seed(&rng, 41);
    assert_int_equal(hl_bus_map_bytes(0), 32);
    assert_int_equal(hl_bus_map_bytes(1500), 32 + 12 * 1500);
    for (int it = 0; it < 60; it++) {
        uint32_t n = it < 3 ? (uint32_t)it : (uint32_t)tk_range(&rng, 0, MAP_STORAGE);
        hl_bus_map_t m, back = { .vectors = w, .max_vectors = MAP_STORAGE };
        random_map(&rng, &m, v, n);
        int len = hl_bus_encode_map(&m, a, cap);
        assert_int_equal(len, (int)hl_bus_map_bytes(n));
        houghloc_map_t g;
        assert_int_equal(houghloc_map_t_decode(a, 0, len, &g), len);
        assert_map_matches(&m, &g);
        assert_int_equal(houghloc_map_t_encoded_size(&g), len);
        assert_int_equal(houghloc_map_t_encode(b, 0, (int)cap, &g), len);
        assert_memory_equal(a, b, (size_t)len);

        g.version = tk_range(&rng, 0, INT64_MAX);
        for (int i = 0; i < g.nvectors; i++)
            g.range_mm[i] = (int16_t)tk_range(&rng, 0, HL_RANGE_MAX_MM);
        assert_int_equal(houghloc_map_t_encode(b, 0, (int)cap, &g), len);
        assert_int_equal(hl_bus_decode_map(b, (size_t)len, &back, NULL), HL_OK);
        assert_map_matches(&back, &g);
        assert_int_equal(back.max_vectors, MAP_STORAGE);
        assert_int_equal(hl_bus_encode_map(&back, a, cap), len);
        assert_memory_equal(a, b, (size_t)len);
        houghloc_map_t_decode_cleanup(&g);
    }
    free(a);
    free(b);
    free(v);
    free(w);
}

static void test_map_hostile_bytes(void **state)
{
    (void)state;
    enum { N = 9 };
    uint8_t a[32 + 12 * N], b[32 + 12 * N];
    hl_vector_t v[N], w[N];
    hl_rng_t rng;
    hl_rng_seed(&rng, 42);
    hl_bus_map_t m, out = { .vectors = w, .max_vectors = N };
    random_map(&rng, &m, v, N);
    m.capacity = 20;
    tk_codec_t c = { "map", dec_map, enc_map, NULL, &out };
    assert_int_equal(hl_bus_encode_map(&m, a, sizeof a), (int)sizeof a);
    tk_check_truncations(&c, a, sizeof a);
    tk_check_bad_hash(&c, a, sizeof a);
    tk_check_small_buffers(&c, &m, sizeof a);
    /* offsets: 8 utime 16 version 24 capacity 28 nvectors 32 x[] 68 y[] 104 normal[]
     * 122 range[] */
    struct { size_t off; uint64_t v; size_t n; hl_status_t st; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, HL_ERR_RANGE, "utime" },
        { 16, (uint64_t)-1, 8, HL_ERR_RANGE, "version" },
        { 16, UINT64_C(1) << 63, 8, HL_ERR_RANGE, "version" },
        { 24, 0, 4, HL_ERR_RANGE, "capacity" },
        { 24, (uint32_t)-1, 4, HL_ERR_RANGE, "capacity" },
        { 24, HL_MAP_MAX_CAPACITY + 1, 4, HL_ERR_RANGE, "capacity" },
        { 24, 8, 4, HL_ERR_RANGE, "nvectors" },                 /* count above capacity */
        { 28, (uint32_t)-1, 4, HL_ERR_RANGE, "nvectors" },
        { 28, 0x7fffffffu, 4, HL_ERR_RANGE, "nvectors" },
        { 28, N + 1, 4, HL_ERR_RANGE, "nvectors" },              /* above max_vectors */
        { 28, N - 1, 4, HL_ERR_PARSE, "nvectors" },              /* length mismatch */
        { 28, 0, 4, HL_ERR_PARSE, "nvectors" },
        { 32 + 4 * 2, HL_COORD_MAX_MM + 1, 4, HL_ERR_RANGE, "vector 2" },
        { 68 + 4 * 8, 0x80000000u, 4, HL_ERR_RANGE, "vector 8" },
        { 122 + 2 * 4, 0x8000, 2, HL_ERR_RANGE, "range_mm[4]" },
        { 122 + 2 * 0, 0xffff, 2, HL_ERR_RANGE, "range_mm[0]" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, sizeof a);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, sizeof b, bad[k].st, bad[k].field);
    }
    /* no storage for a non-empty map is the caller's bug */
    hl_bus_map_t none = { .vectors = NULL, .max_vectors = N };
    assert_int_equal(hl_bus_decode_map(a, sizeof a, &none, NULL), HL_ERR_ARG);

    hl_bus_map_t q = m;
    q.count = 21;                   /* above capacity */
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    q = m;
    q.capacity = 0;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    q.capacity = (int32_t)HL_MAP_MAX_CAPACITY + 1;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    q = m;
    q.vectors = NULL;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    q = m;
    v[3].range_mm = HL_RANGE_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    v[3].range_mm = 0;
    v[5].x_mm = -HL_COORD_MAX_MM - 1;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    v[5].x_mm = -HL_COORD_MAX_MM;
    q.version = -1;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), -1);
    /* a version past 32 bits, up to 2^63 - 1, goes out and comes back whole */
    q.version = INT64_MAX;
    assert_int_equal(hl_bus_encode_map(&q, b, sizeof b), (int)sizeof b);
    assert_int_equal(hl_bus_decode_map(b, sizeof b, &out, NULL), HL_OK);
    assert_int_equal(out.version, INT64_MAX);
    q.version = 0;
    assert_int_equal(hl_bus_encode_map(&q, a, sizeof a), (int)sizeof a);
    assert_in_range(tk_fuzz(&c, a, sizeof a, 5000, 43), 1, 4999);
}

static void test_empty_map(void **state)
{
    (void)state;
    uint8_t a[32];
    hl_bus_map_t m = { .utime = 1, .version = 0, .capacity = 1, .count = 0, .vectors = NULL };
    hl_bus_map_t out = { .vectors = NULL, .max_vectors = 0 };
    assert_int_equal(hl_bus_encode_map(&m, a, sizeof a), 32);
    assert_int_equal(hl_bus_decode_map(a, sizeof a, &out, NULL), HL_OK);
    assert_int_equal(out.count, 0);
    assert_int_equal(out.capacity, 1);
    assert_int_equal(out.utime, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pose_matches_generated_code),
        cmocka_unit_test(test_pose_hostile_bytes),
        cmocka_unit_test(test_pose_older_layout),
        cmocka_unit_test(test_map_matches_generated_code),
        cmocka_unit_test(test_map_hostile_bytes),
        cmocka_unit_test(test_empty_map),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
