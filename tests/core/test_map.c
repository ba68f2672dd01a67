/* Tests for src/core/map.c and src/core/scan.c: tangent vectors, capacity and random
 * culling, extreme coordinates, pose algebra, saving and restoring a map. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/map.h"

static hl_vector_t vec(int32_t x, int32_t y)
{
    hl_vector_t v = { x, y, 0, 1000 };
    return v;
}

static void test_create_rejects_bad_capacity(void **state)
{
    (void)state;
    assert_null(hl_map_create(0, 1));
    assert_null(hl_map_create(HL_MAP_MAX_CAPACITY + 1, 1));
    hl_map_destroy(NULL);
}

static void test_vector_points_back_at_sensor(void **state)
{
    (void)state;
    hl_pose_t pose = { 1000, -2000, hl_bam_from_deg(30) };
    hl_reading_t r = { .range_mm = 2500, .bearing = hl_bam_from_deg(45), .valid = true };
    hl_vector_t v;
    assert_true(hl_vector_from_reading(pose, &r, &v));
    /* surface at 75 degrees, 2.5 m away */
    assert_in_range(v.x_mm, 1000 + 647 - 1, 1000 + 647 + 1);
    assert_in_range(v.y_mm, -2000 + 2415 - 1, -2000 + 2415 + 1);
    assert_int_equal(v.normal, (hl_bam_t)(hl_bam_from_deg(75) + 32768));
    int32_t ox, oy;
    hl_vector_origin(&v, &ox, &oy);
    assert_in_range(ox, 998, 1002);
    assert_in_range(oy, -2002, -1998);
    r.valid = false;
    assert_false(hl_vector_from_reading(pose, &r, &v));
}

static void test_extreme_coordinates(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(10, 1);
    hl_vector_t v = vec(HL_COORD_MAX_MM, -HL_COORD_MAX_MM);
    assert_int_equal(hl_map_add(m, &v), HL_OK);
    v = vec(HL_COORD_MAX_MM + 1, 0);
    assert_int_equal(hl_map_add(m, &v), HL_ERR_RANGE);
    v = vec(0, -HL_COORD_MAX_MM - 1);
    assert_int_equal(hl_map_add(m, &v), HL_ERR_RANGE);
    assert_int_equal(hl_map_count(m), 1);

    /* A 32 m reading from a pose at the edge leaves the range: skipped, not wrapped. */
    hl_scan_t *scan = calloc(1, sizeof *scan);
    hl_scan_add(scan, 0, HL_RANGE_MAX_MM, 0, true);
    hl_scan_add(scan, 32768, HL_RANGE_MAX_MM, 1, true);
    hl_pose_t edge = { HL_COORD_MAX_MM - 100, 0, 0 };
    uint32_t added = 99;
    assert_int_equal(hl_map_add_scan(m, scan, edge, &added), HL_OK);
    assert_int_equal(added, 1);
    assert_int_equal(hl_map_vectors(m)[1].x_mm, HL_COORD_MAX_MM - 100 - 32767);
    hl_pose_t outside = { HL_COORD_MAX_MM + 1, 0, 0 };
    assert_int_equal(hl_map_add_scan(m, scan, outside, &added), HL_ERR_RANGE);
    free(scan);
    hl_map_destroy(m);
}

static void test_capacity_and_culling(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(100, 7);
    for (int i = 0; i < 100; i++) {
        hl_vector_t v = vec(i, 0);
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 100);
    uint64_t v0 = hl_map_version(m);
    /* 1000 more: the map stays at capacity. Each arrival drops one of 101 at random,
     * so a vector survives k later arrivals with probability (100/101)^k: the first
     * hundred are all but surely gone (survival 5e-5 each) and about 63 of the
     * newest hundred remain. The seed is fixed, so the counts are too. */
    for (int i = 0; i < 1000; i++) {
        hl_vector_t v = vec(1000 + i, 0);
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 100);
    assert_true(hl_map_version(m) > v0);
    int old = 0, late = 0;
    for (uint32_t i = 0; i < 100; i++) {
        old += hl_map_vectors(m)[i].x_mm < 1000;
        late += hl_map_vectors(m)[i].x_mm >= 1900;
    }
    assert_int_equal(old, 0);
    assert_in_range(late, 50, 76);
    hl_map_destroy(m);
}

static void test_culling_is_deterministic_by_seed(void **state)
{
    (void)state;
    hl_map_t *a = hl_map_create(50, 3), *b = hl_map_create(50, 3), *c = hl_map_create(50, 4);
    for (int i = 0; i < 500; i++) {
        hl_vector_t v = vec(i, i);
        hl_map_add(a, &v);
        hl_map_add(b, &v);
        hl_map_add(c, &v);
    }
    int same_ab = 1, same_ac = 1;
    for (int i = 0; i < 50; i++) {
        same_ab &= hl_map_vectors(a)[i].x_mm == hl_map_vectors(b)[i].x_mm;
        same_ac &= hl_map_vectors(a)[i].x_mm == hl_map_vectors(c)[i].x_mm;
    }
    assert_true(same_ab);
    assert_false(same_ac);
    hl_map_destroy(a);
    hl_map_destroy(b);
    hl_map_destroy(c);
}

static void test_scan_add_and_check(void **state)
{
    (void)state;
    hl_scan_t *s = calloc(1, sizeof *s);
    for (int i = 0; i < HL_SCAN_MAX_READINGS; i++)
        assert_int_equal(hl_scan_add(s, 0, 100, 0, true), HL_OK);
    assert_int_equal(hl_scan_add(s, 0, 100, 0, true), HL_ERR_CAPACITY);
    assert_int_equal(hl_scan_add(s, 0, 40000, 0, true), HL_ERR_CAPACITY);
    hl_scan_clear(s);
    /* a range the format cannot hold: appended as an invalid reading, and said so */
    assert_int_equal(hl_scan_add(s, 0, -1, 0, true), HL_ERR_RANGE);
    assert_int_equal(hl_scan_add(s, 100, HL_RANGE_MAX_MM + 1, 1, true), HL_ERR_RANGE);
    assert_int_equal(hl_scan_add(s, 200, 45000, 2, false), HL_OK);  /* nothing lost */
    assert_int_equal(hl_scan_add(s, 300, HL_RANGE_MAX_MM, 3, true), HL_OK);
    assert_int_equal(hl_scan_add(s, 400, 5, 4, true), HL_OK);
    assert_int_equal(s->count, 5);
    assert_false(s->readings[1].valid);
    assert_int_equal(s->readings[1].range_mm, 0);
    assert_int_equal(s->readings[1].bearing, 100);
    assert_int_equal(s->readings[1].transducer, 1);
    assert_false(s->readings[2].valid);
    assert_int_equal(s->readings[2].range_mm, 0);
    assert_true(s->readings[3].valid);
    assert_int_equal(s->readings[3].range_mm, HL_RANGE_MAX_MM);
    assert_int_equal(hl_scan_valid_count(s), 2);
    assert_int_equal(hl_scan_check(s), HL_OK);
    s->readings[0].valid = true;
    s->readings[0].range_mm = 40000;
    assert_int_equal(hl_scan_check(s), HL_ERR_RANGE);
    s->count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_scan_check(s), HL_ERR_RANGE);
    assert_int_equal(hl_scan_add(NULL, 0, 0, 0, true), HL_ERR_ARG);
    free(s);
}

static void test_pose_algebra_round_trip(void **state)
{
    (void)state;
    hl_pose_t a = { 1234567, -7654321 / 4, hl_bam_from_deg(170) };
    hl_pose_t b = { 1236000, -1913000, hl_bam_from_deg(-175) };
    hl_pose_t rel = hl_pose_between(a, b);
    assert_int_equal(rel.theta, (hl_bam_t)(b.theta - a.theta));   /* wraps through 180 */
    hl_pose_t back = hl_pose_compose(a, rel);
    assert_in_range(back.x_mm, b.x_mm - 1, b.x_mm + 1);
    assert_in_range(back.y_mm, b.y_mm - 1, b.y_mm + 1);
    assert_int_equal(back.theta, b.theta);
    hl_pose_t far = { HL_COORD_MAX_MM, 0, 0 };
    assert_true(hl_pose_in_range(far));
    far.x_mm++;
    assert_false(hl_pose_in_range(far));
}

static void test_vector_in_range_bounds(void **state)
{
    (void)state;
    hl_vector_t v = { HL_COORD_MAX_MM, -HL_COORD_MAX_MM, 65535, HL_RANGE_MAX_MM };
    assert_true(hl_vector_in_range(&v));
    v.range_mm = HL_RANGE_MAX_MM + 1;
    assert_false(hl_vector_in_range(&v));
    v = vec(-HL_COORD_MAX_MM - 1, 0);
    assert_false(hl_vector_in_range(&v));
    v = vec(0, HL_COORD_MAX_MM + 1);
    assert_false(hl_vector_in_range(&v));
    v = vec(0, INT32_MIN);
    assert_false(hl_vector_in_range(&v));
}

/* The version counts on past 32 bits, and stops at HL_COUNT_MAX (count.h) rather than
 * wrap; a version above it is refused by a restore, which leaves the map as it was. */
static void test_version_is_64_bit(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(40, 11), *b = hl_map_create(40, 12);
    hl_vector_t v = vec(1, 2);
    assert_int_equal(hl_map_restore(m, NULL, 0, UINT32_MAX - 1, hl_map_rng(m)), HL_OK);
    for (int i = 0; i < 3; i++)
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    assert_true(hl_map_version(m) == (uint64_t)UINT32_MAX + 2);
    assert_int_equal(hl_map_restore(m, NULL, 0, (uint64_t)HL_COUNT_MAX - 1, hl_map_rng(m)),
                     HL_OK);
    assert_int_equal(hl_map_add(m, &v), HL_OK);
    assert_int_equal(hl_map_add(m, &v), HL_OK);
    hl_map_clear(m);
    assert_true(hl_map_version(m) == (uint64_t)HL_COUNT_MAX);
    hl_map_swap(m, b);
    assert_true(hl_map_version(m) == (uint64_t)HL_COUNT_MAX);
    assert_int_equal(hl_map_restore(m, NULL, 0, (uint64_t)HL_COUNT_MAX + 1, hl_map_rng(m)),
                     HL_ERR_RANGE);
    assert_true(hl_map_version(m) == (uint64_t)HL_COUNT_MAX);
    hl_map_destroy(m);
    hl_map_destroy(b);
}

/* A map restored from another's vectors, version and culling state culls exactly as
 * the original from then on; a fresh map with the same seed would not (its generator
 * has not advanced). */
static void test_restore_continues_culling(void **state)
{
    (void)state;
    hl_map_t *a = hl_map_create(40, 11), *b = hl_map_create(40, 99);
    hl_map_t *c = hl_map_create(40, 11);
    for (int i = 0; i < 300; i++) {
        hl_vector_t v = vec(i, -i);
        assert_int_equal(hl_map_add(a, &v), HL_OK);
    }
    hl_vector_t saved[40];
    memcpy(saved, hl_map_vectors(a), sizeof saved);
    hl_rng_t rng = hl_map_rng(a);
    assert_int_equal(hl_map_restore(b, saved, 40, hl_map_version(a), rng), HL_OK);
    assert_int_equal(hl_map_restore(c, saved, 40, hl_map_version(a), rng), HL_OK);
    hl_rng_seed(&rng, 11);
    assert_int_equal(hl_map_restore(c, saved, 40, 7, rng), HL_OK);  /* a fresh generator */
    assert_int_equal(hl_map_count(b), 40);
    assert_int_equal(hl_map_version(b), hl_map_version(a));
    assert_int_equal(hl_map_version(c), 7);
    assert_memory_equal(hl_map_vectors(b), saved, sizeof saved);
    for (int i = 0; i < 200; i++) {
        hl_vector_t v = vec(1000 + i, i);
        hl_map_add(a, &v);
        hl_map_add(b, &v);
        hl_map_add(c, &v);
    }
    assert_memory_equal(hl_map_vectors(a), hl_map_vectors(b), 40 * sizeof(hl_vector_t));
    assert_int_equal(hl_map_version(a), hl_map_version(b));
    hl_rng_t ra = hl_map_rng(a), rb = hl_map_rng(b);
    assert_true(ra.state == rb.state && ra.inc == rb.inc);
    assert_memory_not_equal(hl_map_vectors(a), hl_map_vectors(c), 40 * sizeof(hl_vector_t));
    /* fewer than the capacity, zero, and the map's own vectors handed back */
    assert_int_equal(hl_map_restore(b, saved, 3, 5, ra), HL_OK);
    assert_int_equal(hl_map_count(b), 3);
    assert_int_equal(hl_map_restore(b, hl_map_vectors(b) + 1, 2, 6, ra), HL_OK);
    assert_int_equal(hl_map_vectors(b)[0].x_mm, saved[1].x_mm);
    assert_int_equal(hl_map_vectors(b)[1].x_mm, saved[2].x_mm);
    assert_int_equal(hl_map_restore(b, NULL, 0, 8, ra), HL_OK);
    assert_int_equal(hl_map_count(b), 0);
    assert_int_equal(hl_map_version(b), 8);
    hl_map_destroy(a);
    hl_map_destroy(b);
    hl_map_destroy(c);
}

/* How many of the map's vectors lie in the 50 mm square at (sx, sy) with normals in
 * the eighth of a turn holding `normal`. */
static uint32_t in_place(const hl_map_t *m, int32_t sx, int32_t sy, hl_bam_t normal)
{
    uint32_t n = 0;
    const hl_vector_t *v = hl_map_vectors(m);
    for (uint32_t i = 0; i < hl_map_count(m); i++)
        n += v[i].x_mm / 50 == sx && v[i].y_mm / 50 == sy && v[i].normal >> 13 == normal >> 13;
    return n;
}

/* A map of @p capacity vectors seeded with @p seed, bounded to @p per_place vectors a
 * @p square_mm square (0: no bound) and culling by @p cull (below). */
enum cull { UNIFORM, EVIDENCE, CROWDING };
/* The params of a map of @p capacity vectors seeded with @p seed, bounded to @p per_place
 * vectors a place of a @p square_mm square (0: no bound), round or square. */
static hl_map_params_t bounded(uint32_t capacity, uint64_t seed, int32_t square_mm,
                               uint32_t per_place, bool round)
{
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.capacity = capacity;
    p.seed = seed;
    p.per_place = per_place;
    p.square_mm = square_mm;
    p.round_places = round;
    return p;
}

static hl_map_t *made(const hl_map_params_t *p)
{
    assert_null(hl_map_params_error(p));
    hl_map_t *m = hl_map_create_with(p);
    assert_non_null(m);
    return m;
}

static hl_map_t *map_with(uint32_t capacity, uint64_t seed, int32_t square_mm,
                          uint32_t per_place, enum cull cull, uint32_t choices, int32_t mm)
{
    hl_map_params_t p = bounded(capacity, seed, square_mm, per_place, false);
    if (cull != UNIFORM)
        p.cull_choices = choices;
    if (cull == EVIDENCE)
        p.confirm_mm = mm;
    p.cull_crowded = cull == CROWDING;
    if (cull == CROWDING)
        p.crowd_square_mm = mm;
    return made(&p);
}

/* floor(v / square_mm), the squares the density bound is meant to have. */
static int64_t square_index(int64_t v, int64_t side)
{
    return v >= 0 ? v / side : -((-v + side - 1) / side);
}

/* The density bound's squares split exactly where floor(v / square_mm) does (its index
 * divides by a multiply): two vectors one millimetre apart share a place exactly when
 * they share a square, at every square's edges tried, on both sides of zero and at the
 * limits of the coordinates, for square sizes across the allowed range. */
static void test_density_squares_split_at_edges(void **state)
{
    (void)state;
    const int32_t sides[] = { HL_MAP_MIN_SQUARE_MM, 11, 48, 50, 64, 333, 999,
                              HL_MAP_MAX_SQUARE_MM };
    const int64_t max = HL_COORD_MAX_MM;
    for (size_t k = 0; k < sizeof sides / sizeof *sides; k++) {
        int64_t d = sides[k];
        const int64_t edges[] = { 0, d, -d, 7 * d, -7 * d, (max / d) * d, -(max / d) * d,
                                  max, -max + 1 };
        for (size_t e = 0; e < sizeof edges / sizeof *edges; e++) {
            int64_t a = edges[e] - 1, b = edges[e];
            if (a < -max)
                continue;   /* -max itself is an edge: nothing below it */
            for (int axis = 0; axis < 2; axis++) {
                hl_map_t *m = map_with(10, 1, (int32_t)d, 1, UNIFORM, 1, 0);
                hl_vector_t va = axis ? vec(5, (int32_t)a) : vec((int32_t)a, 5);
                hl_vector_t vb = axis ? vec(5, (int32_t)b) : vec((int32_t)b, 5);
                /* both seen from the side whose sensor lies within the coordinates */
                va.normal = vb.normal = axis == 0 && b > 0 ? 32768 : 0;
                assert_int_equal(hl_map_add(m, &va), HL_OK);
                assert_int_equal(hl_map_add(m, &vb), HL_OK);
                uint32_t places = square_index(a, d) == square_index(b, d) ? 1 : 2;
                assert_int_equal(hl_map_count(m), places);
                hl_map_destroy(m);
            }
        }
    }
}

/* The density bound: a place keeps at most per_place vectors however often it is seen,
 * other places and the other side of the same place are unaffected, the newest vector
 * gets in at the rate the paper's culling gives (per_place / (per_place + 1) of the
 * time in a full place), and the map still fills to capacity elsewhere. */
static void test_density_bound(void **state)
{
    (void)state;
    hl_map_t *m = map_with(1000, 5, 50, 3, UNIFORM, 1, 0);
    uint32_t newest_kept = 0;
    for (int i = 0; i < 400; i++) {
        hl_vector_t v = { 1000 + i % 40, 2010 + i % 30, (hl_bam_t)(1000 + i), 3000 };
        assert_int_equal(hl_map_add(m, &v), HL_OK);
        const hl_vector_t *w = hl_map_vectors(m);
        for (uint32_t k = 0; k < hl_map_count(m); k++)
            newest_kept += memcmp(&w[k], &v, sizeof v) == 0;
    }
    assert_int_equal(in_place(m, 20, 40, 1000), 3);
    assert_int_equal(hl_map_count(m), 3);
    assert_in_range(newest_kept, 260, 340);     /* 3/4 of 400, give or take */
    /* the other side of the same square, and the next square */
    hl_vector_t back = { 1000, 2010, 40000, 3000 }, next = { 1050, 2010, 1000, 3000 };
    assert_int_equal(hl_map_add(m, &back), HL_OK);
    assert_int_equal(hl_map_add(m, &next), HL_OK);
    assert_int_equal(hl_map_count(m), 5);
    /* distinct places fill the map to its capacity, then the global culling takes over */
    for (int i = 0; i < 3000; i++) {
        hl_vector_t v = vec(-20000 + 60 * i, 100);
        hl_map_add(m, &v);
    }
    assert_int_equal(hl_map_count(m), 1000);
    assert_in_range(in_place(m, 20, 40, 1000), 0, 3);
    hl_map_destroy(m);
    /* bad settings are refused, each with its reason */
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.per_place = 3;
    p.square_mm = 5;
    assert_non_null(hl_map_params_error(&p));
    assert_null(hl_map_create_with(&p));
    p.square_mm = 50;
    p.per_place = HL_MAP_MAX_PER_PLACE + 1;
    assert_non_null(hl_map_params_error(&p));
    assert_null(hl_map_create_with(&p));
    assert_non_null(hl_map_params_error(NULL));
    assert_null(hl_map_create_with(NULL));
    p.per_place = 0;
    p.square_mm = 5;    /* no bound: its square is not read */
    assert_null(hl_map_params_error(&p));
}

/* A bounded map saved and restored chooses exactly as the one that kept running: the
 * places' chains are rebuilt in slot order, the order they are always kept in. */
static void test_density_bound_restores_exactly(void **state)
{
    (void)state;
    hl_map_t *a = map_with(300, 21, 40, 2, UNIFORM, 1, 0);
    hl_map_t *b = map_with(300, 77, 40, 2, UNIFORM, 1, 0);
    hl_rng_t r;
    hl_rng_seed(&r, 3);
    for (int i = 0; i < 2000; i++) {
        hl_vector_t v = { (hl_mm_t)hl_rng_below(&r, 2000), (hl_mm_t)hl_rng_below(&r, 2000),
                          (hl_bam_t)hl_rng_below(&r, 65536), 1000 };
        hl_map_add(a, &v);
        if (i == 999)
            assert_int_equal(hl_map_restore(b, hl_map_vectors(a), hl_map_count(a),
                                            hl_map_version(a), hl_map_rng(a)), HL_OK);
        if (i >= 1000)
            hl_map_add(b, &v);
    }
    assert_int_equal(hl_map_count(a), hl_map_count(b));
    assert_memory_equal(hl_map_vectors(a), hl_map_vectors(b),
                        hl_map_count(a) * sizeof(hl_vector_t));
    /* and the bound held: no 40 mm square holds more than 2 of one side */
    const hl_vector_t *v = hl_map_vectors(a);
    for (uint32_t i = 0; i < hl_map_count(a); i++) {
        uint32_t same = 0;
        for (uint32_t j = 0; j < hl_map_count(a); j++)
            same += v[j].x_mm / 40 == v[i].x_mm / 40 && v[j].y_mm / 40 == v[i].y_mm / 40 &&
                    v[j].normal >> 13 == v[i].normal >> 13;
        assert_in_range(same, 1, 2);
    }
    hl_map_destroy(a);
    hl_map_destroy(b);
}

/* A map bounded to @p per_place vectors a round place of a @p square_mm square's area. */
static hl_map_t *round_map(uint32_t capacity, uint64_t seed, int32_t square_mm,
                           uint32_t per_place)
{
    hl_map_params_t p = bounded(capacity, seed, square_mm, per_place, true);
    return made(&p);
}

/* A round place is the disc of the square's area about the new vector (28 mm for 50 mm
 * squares), normals within 22.5 degrees: one vector a place, a second 27 mm away is
 * refused across a square's edge, 29 mm away or facing 23 degrees apart it is not. */
static void test_round_places_count_by_distance_and_facing(void **state)
{
    (void)state;
    hl_map_t *m = round_map(10, 1, 50, 1);
    hl_vector_t a = { 40, 10, 0, 1000 };
    hl_vector_t near = { 67, 10, hl_bam_from_deg(20.0), 1000 };     /* 27 mm, next square */
    hl_vector_t apart = { 40, 39, 0, 1000 };                        /* 29 mm */
    hl_vector_t turned = { 40, 20, hl_bam_from_deg(23.0), 1000 };   /* 10 mm, 23 degrees */
    for (int k = 0; k < 8; k++)     /* a full place keeps one of the two at random */
        assert_int_equal(hl_map_add(m, k == 0 ? &a : &near), HL_OK);
    assert_int_equal(hl_map_count(m), 1);
    assert_int_equal(hl_map_add(m, &apart), HL_OK);
    assert_int_equal(hl_map_add(m, &turned), HL_OK);
    assert_int_equal(hl_map_count(m), 3);
    hl_map_destroy(m);
}

/* Round places bound the same vectors in any frame: the same vectors turned a quarter
 * turn (exactly, in whole millimetres) leave the same slots filled with them, and a map
 * restored midway continues exactly. 3,000 vectors in a 300 mm square, about ten to a
 * round place: the bound keeps a fraction of them. */
static void test_round_places_turn_with_the_frame_and_restore_exactly(void **state)
{
    (void)state;
    hl_map_t *a = round_map(4000, 21, 50, 2), *b = round_map(4000, 21, 50, 2);
    hl_map_t *c = round_map(4000, 77, 50, 2);
    hl_rng_t r;
    hl_rng_seed(&r, 3);
    for (int i = 0; i < 3000; i++) {
        hl_vector_t v = { (hl_mm_t)hl_rng_below(&r, 300), (hl_mm_t)hl_rng_below(&r, 300),
                          (hl_bam_t)hl_rng_below(&r, 65536), 1000 };
        hl_vector_t turned = { -v.y_mm, v.x_mm, (hl_bam_t)(v.normal + HL_BAM_QUARTER_TURN),
                               v.range_mm };
        hl_map_add(a, &v);
        hl_map_add(b, &turned);
        if (i == 1499)
            assert_int_equal(hl_map_restore(c, hl_map_vectors(a), hl_map_count(a),
                                            hl_map_version(a), hl_map_rng(a)), HL_OK);
        if (i >= 1500)
            hl_map_add(c, &v);
    }
    uint32_t n = hl_map_count(a);
    assert_in_range(n, 300, 1500);     /* of 3,000: the bound held */
    assert_int_equal(hl_map_count(b), n);
    const hl_vector_t *va = hl_map_vectors(a), *vb = hl_map_vectors(b);
    for (uint32_t i = 0; i < n; i++) {
        assert_int_equal(vb[i].x_mm, -va[i].y_mm);
        assert_int_equal(vb[i].y_mm, va[i].x_mm);
    }
    assert_int_equal(hl_map_count(c), n);
    assert_memory_equal(va, hl_map_vectors(c), n * sizeof(hl_vector_t));
    hl_map_destroy(a);
    hl_map_destroy(b);
    hl_map_destroy(c);
}

/* The density bound with round places as map.h defines it, by a search of every vector
 * (the map's index finds them by squares): the lowest slots (at most HL_MAP_NEAR_MAX)
 * within @p radius of @p x, normals within a sixteenth of a turn, drop one of them or x
 * at random; else x joins the map, or the paper's random cull makes room for it. */
static void add_by_search(hl_vector_t *v, uint32_t *n, uint32_t capacity, hl_rng_t *rng,
                          const hl_vector_t *x, int32_t radius, uint32_t per_place)
{
    uint32_t near[HL_MAP_NEAR_MAX], c = 0;
    for (uint32_t s = 0; s < *n && c < HL_MAP_NEAR_MAX; s++) {
        int64_t dx = v[s].x_mm - x->x_mm, dy = v[s].y_mm - x->y_mm;
        int32_t dn = hl_bam_diff(v[s].normal, x->normal);
        if (dx * dx + dy * dy <= (int64_t)radius * radius && abs(dn) <= HL_BAM_PER_TURN / 16)
            near[c++] = s;
    }
    uint32_t victim;
    if (c >= per_place) {
        if ((victim = hl_rng_below(rng, c + 1)) < c)
            v[near[victim]] = *x;
    } else if (*n < capacity) {
        v[(*n)++] = *x;
    } else if ((victim = hl_rng_below(rng, capacity + 1)) < capacity) {
        v[victim] = *x;
    }
}

/* The map's round places choose exactly as that search: 20,000 vectors on a 2 m floor,
 * facing four ways give or take 30 degrees, into 400 slots (chains of unlike squares
 * share a bucket, places fill, the full map culls), compared every 500. */
static void test_round_places_choose_as_a_search_of_every_vector(void **state)
{
    (void)state;
    enum { CAPACITY = 400, PER_PLACE = 2 };
    hl_map_t *m = round_map(CAPACITY, 9, 50, PER_PLACE);
    hl_vector_t want[CAPACITY];
    uint32_t n = 0;
    hl_rng_t culls, draws;
    hl_rng_seed(&culls, 9);     /* as the map seeds its own */
    hl_rng_seed(&draws, 4);
    for (int i = 0; i < 20000; i++) {
        hl_bam_t facing = (hl_bam_t)(hl_rng_below(&draws, 4) * HL_BAM_QUARTER_TURN +
                                     hl_rng_below(&draws, 10923) - 5461);
        hl_vector_t x = { (hl_mm_t)hl_rng_below(&draws, 2000) - 1000,
                          (hl_mm_t)hl_rng_below(&draws, 2000) - 1000, facing, 1000 };
        assert_int_equal(hl_map_add(m, &x), HL_OK);
        add_by_search(want, &n, CAPACITY, &culls, &x, 28, PER_PLACE);
        if (i % 500 == 499) {
            assert_int_equal(hl_map_count(m), n);
            assert_memory_equal(hl_map_vectors(m), want, n * sizeof want[0]);
        }
    }
    assert_int_equal(n, CAPACITY);
    hl_map_destroy(m);
}

/* Too many vectors, or one out of range anywhere in the list: refused, nothing changes
 * (vectors, count, version, culling state). */
static void test_restore_refuses_and_changes_nothing(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(8, 5);
    for (int i = 0; i < 20; i++) {
        hl_vector_t v = vec(i, i);
        hl_map_add(m, &v);
    }
    hl_vector_t before[8];
    memcpy(before, hl_map_vectors(m), sizeof before);
    uint64_t version = hl_map_version(m);
    hl_rng_t rng = hl_map_rng(m), other = { 1, 3 };
    hl_vector_t in[9];
    for (int i = 0; i < 9; i++)
        in[i] = vec(-5000 - i, 5000 + i);
    assert_int_equal(hl_map_restore(m, in, 9, 1, other), HL_ERR_CAPACITY);
    in[7].y_mm = HL_COORD_MAX_MM + 1;   /* the last one, after seven good ones */
    assert_int_equal(hl_map_restore(m, in, 8, 1, other), HL_ERR_RANGE);
    in[7] = vec(0, 0);
    in[0].range_mm = HL_RANGE_MAX_MM + 1;
    assert_int_equal(hl_map_restore(m, in, 8, 1, other), HL_ERR_RANGE);
    assert_int_equal(hl_map_restore(m, NULL, 1, 1, other), HL_ERR_ARG);
    assert_int_equal(hl_map_restore(NULL, in, 1, 1, other), HL_ERR_ARG);
    assert_int_equal(hl_map_count(m), 8);
    assert_int_equal(hl_map_version(m), version);
    assert_memory_equal(hl_map_vectors(m), before, sizeof before);
    hl_rng_t now = hl_map_rng(m);
    assert_true(now.state == rng.state && now.inc == rng.inc);
    hl_map_destroy(m);
}

/* Share of the map's vectors on a wall that every scan sees again, after 60 scans of 20
 * wall readings and 20 spurious echoes (each seen once) through a 200-vector map. */
static double wall_share(uint32_t choices)
{
    hl_map_t *m = map_with(200, 7, 50, 0, choices > 1 ? EVIDENCE : UNIFORM, choices, 100);
    hl_scan_t *s = calloc(1, sizeof *s);
    uint32_t lcg = 12345;
    for (int k = 0; k < 60; k++) {
        hl_scan_clear(s);
        for (int i = 0; i < 20; i++) {      /* the wall: 2 m ahead, +-19 degrees */
            hl_bam_t b = hl_bam_from_deg(-19.0 + 2.0 * i);
            assert_int_equal(hl_scan_add(s, b, 2000, 0, true), HL_OK);
            lcg = lcg * 1103515245u + 12345u;
            assert_int_equal(hl_scan_add(s, (hl_bam_t)(lcg >> 16), 500 + (int32_t)(lcg % 3000),
                                         1, true), HL_OK);
        }
        assert_int_equal(hl_map_add_scan(m, s, (hl_pose_t){ 0, 0, 0 }, NULL), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 200);
    const hl_vector_t *v = hl_map_vectors(m);
    int wall = 0;
    for (uint32_t i = 0; i < 200; i++) {
        int64_t r2 = (int64_t)v[i].x_mm * v[i].x_mm + (int64_t)v[i].y_mm * v[i].y_mm;
        wall += r2 > 1990LL * 1990 && r2 < 2010LL * 2010 && v[i].x_mm > 1800;
    }
    free(s);
    hl_map_destroy(m);
    return wall / 200.0;
}

static void test_evidence_cull_keeps_surfaces(void **state)
{
    (void)state;
    double uniform = wall_share(1), evidence = wall_share(16);
    /* uniform culling keeps the two kinds as they came (half and half, give or take);
     * the evidence cull drops the echoes seen once */
    assert_true(uniform > 0.35 && uniform < 0.65);
    assert_true(evidence > 0.9);
}

static void test_evidence_cull_arguments(void **state)
{
    (void)state;
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.capacity = 10;
    p.cull_choices = 0;
    assert_non_null(hl_map_params_error(&p));
    p.cull_choices = HL_MAP_MAX_CHOICES + 1;
    assert_non_null(hl_map_params_error(&p));
    p.cull_choices = 2;
    p.confirm_mm = 0;
    assert_non_null(hl_map_params_error(&p));
    assert_null(hl_map_create_with(&p));
    p.confirm_mm = HL_MAP_MAX_SQUARE_MM + 1;
    assert_non_null(hl_map_params_error(&p));
    p.cull_choices = 1;
    p.confirm_mm = 0;   /* off: no radius needed */
    assert_null(hl_map_params_error(&p));
    hl_map_t *uniform = hl_map_create_with(&p);
    hl_map_t *evidence = map_with(10, 1, 50, 0, EVIDENCE, 4, 100);
    assert_non_null(uniform);
    assert_true(hl_map_mem_bytes(uniform) < hl_map_mem_bytes(evidence));
    hl_map_destroy(uniform);
    hl_map_destroy(evidence);
}

/* Share of a 300-vector map (density bound: 2 per 50 mm square) left on a wall seen by
 * the first scan only, after 100 more scans of a wall elsewhere seen from many places
 * (each scan's readings along 4 m of it, shifted so they land in fresh squares). */
static double first_wall_share(bool crowded, int32_t crowd_square_mm)
{
    hl_map_t *m = map_with(300, 9, 50, 2, crowded ? CROWDING : UNIFORM, 8, crowd_square_mm);
    hl_scan_t *s = calloc(1, sizeof *s);
    for (int k = 0; k <= 100; k++) {
        hl_scan_clear(s);
        for (int i = 0; i < 40; i++)    /* 40 readings, 2 m ahead, +-39 degrees */
            assert_int_equal(hl_scan_add(s, hl_bam_from_deg(-39.0 + 2.0 * i), 2000, -1, true),
                             HL_OK);
        /* scan 0 sees the first wall from (0, 0); the others a second one, 20 m away,
         * from positions 7 mm apart */
        hl_pose_t at = k == 0 ? (hl_pose_t){ 0, 0, 0 } : (hl_pose_t){ 20000 + 7 * k, 0, 0 };
        assert_int_equal(hl_map_add_scan(m, s, at, NULL), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 300);
    const hl_vector_t *v = hl_map_vectors(m);
    int first = 0;
    for (uint32_t i = 0; i < 300; i++)
        first += v[i].x_mm < 10000;
    free(s);
    hl_map_destroy(m);
    return first / 40.0;
}

/* The crowding cull keeps a surface seen once where the uniform cull forgets it: the map
 * sheds the much-seen wall's crowded squares first. */
static void test_crowding_cull_keeps_what_was_seen_once(void **state)
{
    (void)state;
    double uniform = first_wall_share(false, 0), crowded = first_wall_share(true, 0);
    assert_true(uniform < 0.2);     /* 0.03 here */
    assert_true(crowded > 0.6);     /* 0.78 here */
    /* counted in 300 mm squares the sparse wall is plainly the less crowded: more stays */
    double squares = first_wall_share(true, 300);
    assert_true(squares > crowded && squares > 0.9);    /* 0.975 here */
}

/* The squares' index follows the map through restores and culls: a map restored from
 * another's vectors and generator culls by crowding exactly as the original. */
static void test_crowding_squares_restore(void **state)
{
    (void)state;
    hl_map_t *a = map_with(60, 3, 50, 2, CROWDING, 8, 300);
    hl_map_t *b = map_with(60, 77, 50, 2, CROWDING, 8, 300);
    for (int i = 0; i < 400; i++) {     /* a dense row and a sparse one */
        hl_vector_t v = i % 4 ? vec((i * 7) % 3000, 0) : vec(i * 97, 5000);
        assert_int_equal(hl_map_add(a, &v), HL_OK);
    }
    assert_int_equal(hl_map_restore(b, hl_map_vectors(a), hl_map_count(a), hl_map_version(a),
                                    hl_map_rng(a)), HL_OK);
    for (int i = 0; i < 400; i++) {
        hl_vector_t v = i % 3 ? vec((i * 13) % 3000, 40) : vec(i * 89, 9000);
        hl_map_add(a, &v);
        hl_map_add(b, &v);
    }
    assert_int_equal(hl_map_count(b), 60);
    assert_memory_equal(hl_map_vectors(a), hl_map_vectors(b), 60 * sizeof(hl_vector_t));
    hl_map_destroy(a);
    hl_map_destroy(b);
}

static void test_crowding_cull_arguments(void **state)
{
    (void)state;
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.capacity = 10;
    p.cull_crowded = true;
    p.cull_choices = 4;
    assert_non_null(hl_map_params_error(&p));      /* no density bound */
    p.per_place = 2;
    p.cull_choices = 1;
    assert_non_null(hl_map_params_error(&p));
    p.cull_choices = HL_MAP_MAX_CHOICES + 1;
    assert_non_null(hl_map_params_error(&p));
    p.cull_choices = 4;
    p.crowd_square_mm = HL_MAP_MIN_SQUARE_MM - 1;
    assert_non_null(hl_map_params_error(&p));
    p.crowd_square_mm = HL_MAP_MAX_SQUARE_MM + 1;
    assert_non_null(hl_map_params_error(&p));
    assert_null(hl_map_create_with(&p));
    p.crowd_square_mm = 300;
    assert_null(hl_map_params_error(&p));
    p.crowd_square_mm = 0;
    assert_null(hl_map_params_error(&p));
    hl_map_t *m = hl_map_create_with(&p);
    assert_non_null(m);
    for (int i = 0; i < 30; i++) {
        hl_vector_t v = vec(i * 100, 0);
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 10);
    hl_map_destroy(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_rejects_bad_capacity),
        cmocka_unit_test(test_vector_points_back_at_sensor),
        cmocka_unit_test(test_extreme_coordinates),
        cmocka_unit_test(test_capacity_and_culling),
        cmocka_unit_test(test_culling_is_deterministic_by_seed),
        cmocka_unit_test(test_scan_add_and_check),
        cmocka_unit_test(test_pose_algebra_round_trip),
        cmocka_unit_test(test_vector_in_range_bounds),
        cmocka_unit_test(test_version_is_64_bit),
        cmocka_unit_test(test_restore_continues_culling),
        cmocka_unit_test(test_restore_refuses_and_changes_nothing),
        cmocka_unit_test(test_density_bound),
        cmocka_unit_test(test_density_bound_restores_exactly),
        cmocka_unit_test(test_evidence_cull_keeps_surfaces),
        cmocka_unit_test(test_evidence_cull_arguments),
        cmocka_unit_test(test_crowding_cull_keeps_what_was_seen_once),
        cmocka_unit_test(test_crowding_squares_restore),
        cmocka_unit_test(test_crowding_cull_arguments),
        cmocka_unit_test(test_density_squares_split_at_edges),
        cmocka_unit_test(test_round_places_count_by_distance_and_facing),
        cmocka_unit_test(test_round_places_turn_with_the_frame_and_restore_exactly),
        cmocka_unit_test(test_round_places_choose_as_a_search_of_every_vector),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
