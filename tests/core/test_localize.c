/* Tests for src/core/localize.c (with blur.c and peak.c): recovery in synthetic rooms,
 * empty inputs, heading wrap, extreme coordinates, vote saturation, capacity limits,
 * the odometry prior, the sparse path of large rasters against the plain computation. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/localize.h"
#include "blur.h"
#include "peak.h"
#include "synthroom.h"

typedef struct fixture {
    sr_room_t room;
    hl_vector_t map[1500];
    uint32_t n;
    hl_scan_t scan;
    hl_pose_t truth;
    hl_loc_params_t p;
    hl_localizer_t *loc;
} fixture_t;

/* A 10 m cluttered room with its corner at (x0, y0), a 1500-vector map, and a scan. */
static fixture_t *make_fixture(double x0, double y0, uint64_t seed)
{
    fixture_t *f = calloc(1, sizeof *f);
    sr_room_make(&f->room, x0, y0, 10000, 10000, 25, seed);
    f->n = sr_make_map(&f->room, 1500, 128, 8000, 10, f->map);
    f->truth = sr_free_pose(&f->room, 600);
    sr_sound(&f->room, f->truth, 128, 8000, 10, &f->scan);
    hl_loc_params_default(&f->p);
    f->p.max_cells = 1u << 19;
    f->loc = hl_loc_create(&f->p);
    assert_non_null(f->loc);
    return f;
}

static void free_fixture(fixture_t *f)
{
    hl_loc_destroy(f->loc);
    free(f);
}

static void assert_within(int64_t got, int64_t want, int64_t tol)
{
    if (got < want - tol || got > want + tol)
        fail_msg("got %lld, want %lld +- %lld", (long long)got, (long long)want, (long long)tol);
}

static hl_loc_query_t local_query(hl_pose_t truth)
{
    hl_pose_t pred = { truth.x_mm + 150, truth.y_mm - 100,
                       (hl_bam_t)(truth.theta + hl_bam_from_deg(3.0)) };
    return (hl_loc_query_t){ .predicted = pred, .window_mm = 1000, .search_theta = true };
}

static void test_empty_map_and_scan(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 1);
    hl_loc_query_t q = local_query(f->truth);
    hl_loc_result_t r;
    assert_int_equal(hl_loc_run(f->loc, f->map, 0, &f->scan, &q, &r), HL_ERR_EMPTY);
    assert_int_equal(r.votes, 0);

    hl_scan_t *empty = calloc(1, sizeof *empty);
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, empty, &q, &r), HL_ERR_EMPTY);
    free(empty);

    hl_scan_t *invalid = calloc(1, sizeof *invalid);
    *invalid = f->scan;
    for (uint32_t i = 0; i < invalid->count; i++)
        invalid->readings[i].valid = false;
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, invalid, &q, &r), HL_ERR_EMPTY);
    free(invalid);

    assert_int_equal(hl_loc_run(NULL, f->map, f->n, &f->scan, &q, &r), HL_ERR_ARG);
    assert_int_equal(hl_loc_run(f->loc, NULL, 5, &f->scan, &q, &r), HL_ERR_ARG);
    free_fixture(f);
}

static void test_global_xy_recovers_true_pose(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        fixture_t *f = make_fixture(0, 0, seed);
        hl_loc_query_t q = { .predicted = f->truth, .window_mm = 0, .search_theta = false };
        hl_loc_result_t r;
        assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_OK);
        assert_within(r.pose.x_mm, f->truth.x_mm, f->p.cell_mm);
        assert_within(r.pose.y_mm, f->truth.y_mm, f->p.cell_mm);
        assert_int_equal(r.pose.theta, f->truth.theta);
        assert_true(r.peak > r.second);
        assert_true(r.votes > 1000 && r.pairs >= r.votes);
        free_fixture(f);
    }
}

static void test_local_xyt_recovers_true_pose(void **state)
{
    (void)state;
    for (uint64_t seed = 11; seed <= 14; seed++) {
        fixture_t *f = make_fixture(0, 0, seed);
        hl_loc_query_t q = local_query(f->truth);
        hl_loc_result_t r;
        assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_OK);
        assert_within(r.pose.x_mm, f->truth.x_mm, f->p.cell_mm);
        assert_within(r.pose.y_mm, f->truth.y_mm, f->p.cell_mm);
        assert_within(hl_bam_diff(r.pose.theta, f->truth.theta), 0, f->p.theta_step);
        assert_true(hl_loc_confidence(&r) > 0.2);
        free_fixture(f);
    }
}

static void test_heading_wraps_through_180(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 22);
    /* the slice of +-8.8 degrees around each prediction straddles +-180 */
    const double headings[] = { 174.0, 179.0, 180.0, 181.5, 186.0 };
    for (size_t i = 0; i < sizeof headings / sizeof headings[0]; i++) {
        f->truth.theta = hl_bam_from_deg(headings[i]);
        sr_sound(&f->room, f->truth, 128, 8000, 10, &f->scan);
        hl_loc_query_t q = local_query(f->truth);
        hl_loc_result_t r;
        assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_OK);
        assert_within(hl_bam_diff(r.pose.theta, f->truth.theta), 0, f->p.theta_step);
        assert_within(r.pose.x_mm, f->truth.x_mm, f->p.cell_mm);
        assert_within(r.pose.y_mm, f->truth.y_mm, f->p.cell_mm);
    }
    free_fixture(f);
}

static void test_extreme_coordinates(void **state)
{
    (void)state;
    /* A room in the far corner of the coordinate range. */
    fixture_t *f = make_fixture(HL_COORD_MAX_MM - 10001, -HL_COORD_MAX_MM + 1, 31);
    hl_loc_query_t q = local_query(f->truth);
    hl_loc_result_t r;
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_OK);
    assert_within(r.pose.x_mm, f->truth.x_mm, f->p.cell_mm);
    assert_within(r.pose.y_mm, f->truth.y_mm, f->p.cell_mm);
    q.predicted.x_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_ERR_RANGE);
    free_fixture(f);
}

/* 16384 identical map vectors and 1024 identical readings: 16.7 million votes into one
 * cell, which must saturate at 65535 rather than wrap, and blur without overflow. */
static void test_vote_saturation(void **state)
{
    (void)state;
    hl_loc_params_t p;
    hl_loc_params_default(&p);
    p.max_cells = 1u << 16;
    hl_localizer_t *loc = hl_loc_create(&p);
    hl_vector_t *map = calloc(16384, sizeof *map);
    for (int i = 0; i < 16384; i++)
        map[i] = (hl_vector_t){ 5000, 0, 32768, 5000 };
    hl_scan_t *scan = calloc(1, sizeof *scan);
    for (int i = 0; i < HL_SCAN_MAX_READINGS; i++)
        hl_scan_add(scan, 0, 5000, 0, true);
    hl_loc_query_t q = { .predicted = { 0, 0, 0 }, .window_mm = 500, .search_theta = false };
    hl_loc_result_t r;
    assert_int_equal(hl_loc_run(loc, map, 16384, scan, &q, &r), HL_OK);
    assert_int_equal(r.votes, 16384u * 1024u);
    hl_loc_surface_t s;
    hl_loc_get_surface(loc, &s);
    assert_int_equal(s.votes[r.iy * s.nx + r.ix], HL_VOTE_MAX);
    /* the blur spreads the saturated cell: peak below 65535 x 256, nothing wrapped */
    assert_true(r.peak > 0 && r.peak < 65535u * 256u);
    assert_within(r.pose.x_mm, 0, p.cell_mm);
    assert_within(r.pose.y_mm, 0, p.cell_mm);
    free(map);
    free(scan);
    hl_loc_destroy(loc);
}

/* Run with group_mm = 0 (every vector alone, the default) and with 48 mm groups. */
static void run_both(const hl_vector_t *map, uint32_t n, const hl_scan_t *scan,
                     const hl_loc_query_t *q, hl_loc_result_t *alone, hl_loc_result_t *grouped,
                     uint16_t *alone_votes, uint16_t *grouped_votes, size_t max_cells)
{
    hl_loc_params_t p;
    hl_loc_params_default(&p);
    p.max_cells = (uint32_t)max_cells;
    hl_loc_surface_t s;
    for (int g = 0; g < 2; g++) {
        p.group_mm = g ? 48 : 0;
        hl_localizer_t *loc = hl_loc_create(&p);
        assert_non_null(loc);
        assert_int_equal(hl_loc_run(loc, map, n, scan, q, g ? grouped : alone), HL_OK);
        hl_loc_get_surface(loc, &s);
        memcpy(g ? grouped_votes : alone_votes, s.votes,
               (size_t)s.nx * s.ny * s.nt * sizeof *s.votes);
        hl_loc_destroy(loc);
    }
}

/* Vectors at one point vote together exactly: a map holding each vector three times
 * gives, grouped, the raster of the plain method, vote for vote. */
static void test_groups_of_one_point_are_exact(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 43);
    hl_vector_t *map = malloc(3 * f->n * sizeof *map);
    hl_loc_query_t q = local_query(f->truth);
    size_t cells = hl_loc_cells_for_window(&f->p, q.window_mm, true);
    uint16_t *a = malloc(cells * sizeof *a), *b = malloc(cells * sizeof *b);
    hl_loc_result_t ra, rb;
    /* squares of 48 mm hold several distinct points too: keep one point per square */
    uint32_t n = 0;
    for (uint32_t i = 0; i < f->n; i++) {
        bool alone = true;
        for (uint32_t j = 0; j < n && alone; j++)
            alone = !(map[j].x_mm / 48 == f->map[i].x_mm / 48 &&
                      map[j].y_mm / 48 == f->map[i].y_mm / 48);
        if (alone && f->map[i].x_mm > 0 && f->map[i].y_mm > 0)
            map[n++] = f->map[i];
    }
    for (uint32_t i = n; i < 3 * n; i++)
        map[i] = map[i % n];
    run_both(map, 3 * n, &f->scan, &q, &ra, &rb, a, b, cells);
    assert_true(ra.votes > 1000);
    assert_int_equal(ra.votes, rb.votes);
    assert_int_equal(ra.pairs, rb.pairs);
    assert_memory_equal(a, b, cells * sizeof *a);
    assert_int_equal(ra.pose.x_mm, rb.pose.x_mm);
    assert_int_equal(ra.pose.y_mm, rb.pose.y_mm);
    assert_int_equal(ra.pose.theta, rb.pose.theta);
    free(a);
    free(b);
    free(map);
    free_fixture(f);
}

/* A map ten times as dense as the fixture's: grouped, the scan's true pose is found as
 * well as by the plain method, with the same number of votes up to the few groups at
 * the window's edge, from far fewer writes. */
static void test_groups_of_a_dense_map(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 44);
    uint32_t big = 15000;
    hl_vector_t *map = malloc(big * sizeof *map);
    uint32_t n = sr_make_map(&f->room, big, 128, 8000, 10, map);
    hl_loc_query_t q = local_query(f->truth);
    size_t cells = hl_loc_cells_for_window(&f->p, q.window_mm, true);
    uint16_t *a = malloc(cells * sizeof *a), *b = malloc(cells * sizeof *b);
    hl_loc_result_t ra, rb;
    run_both(map, n, &f->scan, &q, &ra, &rb, a, b, cells);
    assert_within(labs((long)ra.votes - (long)rb.votes), 0, ra.votes / 50);
    assert_within(rb.pose.x_mm, f->truth.x_mm, 30);
    assert_within(rb.pose.y_mm, f->truth.y_mm, 30);
    assert_within(hl_bam_diff(rb.pose.theta, f->truth.theta), 0, hl_bam_from_deg(1.1));
    assert_within(rb.pose.x_mm, ra.pose.x_mm, 24);
    assert_within(rb.pose.y_mm, ra.pose.y_mm, 24);
    free(a);
    free(b);
    free(map);
    free_fixture(f);
}

/* vote_once: a reading votes at most once into a cell, so a map holding every vector five
 * times votes exactly as the map itself (the paper's pair votes would count each pair
 * five times), and the peak is still the truth. */
static void test_vote_once_counts_readings_not_pairs(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 45);
    hl_vector_t *five = malloc(5 * f->n * sizeof *five);
    for (uint32_t k = 0; k < 5; k++)
        memcpy(five + k * f->n, f->map, f->n * sizeof *five);
    hl_loc_params_t p = f->p;
    p.vote_once = true;
    p.max_map_vectors = 5 * f->n;
    hl_localizer_t *once = hl_loc_create(&p), *pairs = hl_loc_create(&f->p);
    assert_non_null(once);
    /* the stamps: a cell each, over the same localizer without them (merging the map,
     * so that neither takes the lone vectors' loop and its lists) */
    hl_loc_params_t pm = p;
    pm.group_mm = 8;
    hl_localizer_t *once_m = hl_loc_create(&pm);
    pm.vote_once = false;
    hl_localizer_t *plain_m = hl_loc_create(&pm);
    assert_non_null(once_m);
    assert_non_null(plain_m);
    assert_int_equal(hl_loc_mem_bytes(once_m) - hl_loc_mem_bytes(plain_m),
                     (size_t)p.max_cells * sizeof(uint16_t));
    hl_loc_destroy(once_m);
    hl_loc_destroy(plain_m);
    hl_loc_query_t q = local_query(f->truth);
    hl_loc_result_t one, many, plain;
    assert_int_equal(hl_loc_run(once, f->map, f->n, &f->scan, &q, &one), HL_OK);
    assert_int_equal(hl_loc_run(once, five, 5 * f->n, &f->scan, &q, &many), HL_OK);
    assert_int_equal(hl_loc_run(pairs, f->map, f->n, &f->scan, &q, &plain), HL_OK);
    assert_int_equal(many.votes, one.votes);
    assert_int_equal(many.peak, one.peak);
    assert_int_equal(many.pose.x_mm, one.pose.x_mm);
    assert_int_equal(many.pose.theta, one.pose.theta);
    assert_true(one.votes <= plain.votes);
    assert_true(one.pairs == plain.pairs);
    assert_within(one.pose.x_mm, f->truth.x_mm, 30);
    assert_within(one.pose.y_mm, f->truth.y_mm, 30);
    assert_within(hl_bam_diff(one.pose.theta, f->truth.theta), 0, hl_bam_from_deg(1.1));
    hl_loc_destroy(once);
    hl_loc_destroy(pairs);
    free(five);
    free_fixture(f);
}

/* reading_stride k: readings 0, k, 2k, ... vote, exactly as a scan holding only those. */
static void test_reading_stride(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 45);
    hl_scan_t *even = malloc(sizeof *even);
    *even = f->scan;
    for (uint32_t i = 1; i < even->count; i += 2)
        even->readings[i].valid = false;
    hl_loc_query_t q = local_query(f->truth);
    hl_loc_params_t p = f->p;
    p.reading_stride = 2;
    hl_localizer_t *strided = hl_loc_create(&p);
    assert_non_null(strided);
    hl_loc_result_t a, b, all;
    assert_int_equal(hl_loc_run(strided, f->map, f->n, &f->scan, &q, &a), HL_OK);
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, even, &q, &b), HL_OK);
    assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &all), HL_OK);
    assert_int_equal(a.votes, b.votes);
    assert_int_equal(a.peak, b.peak);
    assert_memory_equal(&a.pose, &b.pose, sizeof a.pose);
    assert_in_range(a.votes, all.votes / 3, all.votes * 2 / 3);
    assert_within(a.pose.x_mm, f->truth.x_mm, 40);
    assert_within(a.pose.y_mm, f->truth.y_mm, 40);
    p.reading_stride = 0;
    assert_string_equal(hl_loc_params_error(&p), "reading_stride must be in 1..64");
    hl_loc_destroy(strided);
    free(even);
    free_fixture(f);
}

static void test_capacity_limits(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 41);
    hl_loc_params_t p = f->p;
    p.max_map_vectors = 100;
    p.max_cells = 1000;
    hl_localizer_t *small = hl_loc_create(&p);
    hl_loc_query_t q = local_query(f->truth);
    hl_loc_result_t r;
    assert_int_equal(hl_loc_run(small, f->map, f->n, &f->scan, &q, &r), HL_ERR_CAPACITY);
    assert_int_equal(hl_loc_run(small, f->map, 100, &f->scan, &q, &r), HL_ERR_CAPACITY);
    q.window_mm = 300;  /* 25 x 25 x 17 cells > 1000 */
    assert_int_equal(hl_loc_run(small, f->map, 100, &f->scan, &q, &r), HL_ERR_CAPACITY);
    q.search_theta = false;     /* 625 cells fit */
    assert_int_equal(hl_loc_run(small, f->map, 100, &f->scan, &q, &r), HL_OK);
    hl_loc_destroy(small);
    free_fixture(f);
}

static void test_params_validated(void **state)
{
    (void)state;
    hl_loc_params_t p;
    hl_loc_params_default(&p);
    assert_null(hl_loc_params_error(&p));
    p.cell_mm = 0;
    assert_string_equal(hl_loc_params_error(&p), "cell_mm must be in 1..1000");
    assert_null(hl_loc_create(&p));
    hl_loc_params_default(&p);
    p.theta_half_steps = 300;
    assert_non_null(hl_loc_params_error(&p));
    hl_loc_params_default(&p);
    p.theta_step = hl_bam_from_deg(20);
    assert_string_equal(hl_loc_params_error(&p),
                        "the heading slice must span less than half a turn");
    hl_loc_params_default(&p);
    p.group_mm = 7;
    assert_string_equal(hl_loc_params_error(&p), "group_mm must be 0 or in 8..1000");
    p.group_mm = 1001;
    assert_non_null(hl_loc_params_error(&p));
    p.group_mm = 0;
    assert_null(hl_loc_params_error(&p));
    assert_non_null(hl_loc_params_error(NULL));
    hl_loc_destroy(NULL);
}

/* Two copies of the same room side by side: without a prior the copies tie and the
 * first in raster order wins; with the prior centred near the second copy, it wins. */
static void test_prior_breaks_ambiguity(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 51);
    const int32_t shift = 12000;
    hl_vector_t *twin = calloc(3000, sizeof *twin);
    memcpy(twin, f->map, f->n * sizeof *twin);
    for (uint32_t i = 0; i < f->n; i++) {
        twin[f->n + i] = f->map[i];
        twin[f->n + i].x_mm += shift;
    }
    hl_loc_params_t p = f->p;
    p.max_cells = 1u << 20;
    hl_localizer_t *loc = hl_loc_create(&p);
    hl_pose_t pred = { f->truth.x_mm + shift + 200, f->truth.y_mm - 100, f->truth.theta };
    hl_loc_query_t q = { .predicted = pred, .window_mm = 0 };
    hl_loc_result_t r;
    assert_int_equal(hl_loc_run(loc, twin, 2 * f->n, &f->scan, &q, &r), HL_OK);
    assert_within(r.pose.x_mm, f->truth.x_mm, p.cell_mm);
    assert_true(r.second * 10 >= r.peak * 9);   /* the twin peak is as high */
    /* without a prior, both pairs are the same */
    assert_int_equal(r.score, r.peak);
    assert_int_equal(r.second_score, r.second);
    q.use_prior = true;
    assert_int_equal(hl_loc_run(loc, twin, 2 * f->n, &f->scan, &q, &r), HL_OK);
    assert_within(r.pose.x_mm, f->truth.x_mm + shift, p.cell_mm);
    assert_within(r.pose.y_mm, f->truth.y_mm, p.cell_mm);
    /* after the prior the first copy is suppressed, and the pose is distinct ... */
    assert_true(r.second_score * 2 < r.score);
    assert_true(hl_loc_confidence(&r) > 0.5);
    /* ... but before it, the first copy matches as well as the second (localize.h) */
    assert_true(r.second * 10 >= r.peak * 9);
    hl_loc_destroy(loc);
    free(twin);
    free_fixture(f);
}

/* peak is the blurred cell the search chose, unweighted; score the same cell weighted
 * by the prior, so lower the farther the prediction is; the second place before the
 * prior is the best unweighted cell at least peak_separation_mm away, found here by a
 * plain scan of the surface. */
static void test_peak_is_before_the_prior(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(0, 0, 61);
    for (int off = 0; off <= 400; off += 400) {
        hl_pose_t pred = f->truth;
        pred.x_mm += off;
        pred.y_mm -= off / 3;
        hl_loc_query_t q = { .predicted = pred, .window_mm = 1000, .search_theta = true,
                             .use_prior = true };
        hl_loc_result_t r;
        assert_int_equal(hl_loc_run(f->loc, f->map, f->n, &f->scan, &q, &r), HL_OK);
        assert_within(r.pose.x_mm, f->truth.x_mm, off == 0 ? f->p.cell_mm : 150);
        assert_within(r.pose.y_mm, f->truth.y_mm, off == 0 ? f->p.cell_mm : 150);
        hl_loc_surface_t sf;
        hl_loc_get_surface(f->loc, &sf);
        assert_int_equal(r.peak, sf.cells[((size_t)r.it * sf.ny + r.iy) * sf.nx + r.ix]);
        uint32_t want_second = 0;
        int64_t sep2 = (int64_t)f->p.peak_separation_mm * f->p.peak_separation_mm;
        for (int32_t it = 0; it < sf.nt; it++)
            for (int32_t iy = 0; iy < sf.ny; iy++)
                for (int32_t ix = 0; ix < sf.nx; ix++) {
                    int64_t dx = (int64_t)(ix - r.ix) * sf.cell_mm;
                    int64_t dy = (int64_t)(iy - r.iy) * sf.cell_mm;
                    uint32_t c = sf.cells[((size_t)it * sf.ny + iy) * sf.nx + ix];
                    if (dx * dx + dy * dy >= sep2 && c > want_second)
                        want_second = c;
                }
        assert_int_equal(r.second, want_second);
        assert_true(r.score <= r.peak && r.second_score <= r.second);
        /* the prior weighs the chosen cell by its distance from the prediction: at the
         * prediction, hardly; 400 mm away (1.3 sigma), to well under its height, which a
         * peak-ratio test on score would take for a worse match */
        if (off == 0)
            assert_true(r.score * 10 >= r.peak * 9);
        else
            assert_true(r.score * 10 < r.peak * 7);
    }
    free_fixture(f);
}

/* The blurred cell (ix, iy, it) of a raster laid out as hl_blur3's, 0 outside. */
static uint32_t cell_of(const uint32_t *c, int32_t nx, int32_t ny, int32_t ix, int32_t iy,
                        int32_t it)
{
    return c[((size_t)it * ny + iy) * nx + ix];
}

/* One axis's interpolated offset as localize.c takes it, from a whole raster. */
static int32_t plain_offset(const uint32_t *c, const hl_loc_surface_t *s, const hl_peak_t *pk,
                            int axis, int32_t step)
{
    int32_t i[3] = { pk->ix, pk->iy, pk->it }, n[3] = { s->nx, s->ny, s->nt };
    if (step == 0 || i[axis] == 0 || i[axis] == n[axis] - 1)
        return 0;
    int32_t lo[3] = { i[0], i[1], i[2] }, hi[3] = { i[0], i[1], i[2] };
    lo[axis]--;
    hi[axis]++;
    return hl_peak_offset(cell_of(c, s->nx, s->ny, lo[0], lo[1], lo[2]), pk->score,
                          cell_of(c, s->nx, s->ny, hi[0], hi[1], hi[2]), step);
}

/* Whole-map searches without a prior over rasters of millions of cells take the sparse
 * path (tiles.h); windows with a prior, and small rasters, the plain one. One localizer
 * through a mix of both gives, every run, the votes of a fresh localizer, and the
 * surface, peak, second peak and interpolated pose of the plain computation (hl_blur3
 * and hl_peak_find) over those votes. */
static void test_sparse_path_is_the_plain_one(void **state)
{
    (void)state;
    for (uint64_t seed = 21; seed <= 23; seed++) {
        fixture_t *f = make_fixture(-3000, 2000, seed);
        hl_loc_params_t p = f->p;
        p.max_cells = 1u << 23;
        p.vote_once = seed == 23;
        hl_localizer_t *loc = hl_loc_create(&p);
        assert_non_null(loc);
        hl_kernel_t kx, kt;
        hl_kernel_gaussian(&kx, (double)p.blur_sigma_mm / p.cell_mm);
        hl_kernel_gaussian(&kt, (double)p.blur_sigma_theta / p.theta_step);
        size_t max = p.max_cells;
        uint32_t *a = malloc(max * sizeof *a), *b = malloc(max * sizeof *b);
        uint32_t *rows = malloc(max * sizeof *rows);
        uint16_t *votes = malloc(max * sizeof *votes);
        hl_pose_t off = { f->truth.x_mm + 2000, f->truth.y_mm - 1000,
                          (hl_bam_t)(f->truth.theta + hl_bam_from_deg(40)) };
        const hl_loc_query_t queries[] = {
            { .predicted = f->truth, .window_mm = 0, .search_theta = true },
            local_query(f->truth),
            { .predicted = off, .window_mm = 0, .search_theta = true },
            { .predicted = f->truth, .window_mm = 0, .search_theta = false },
            { .predicted = f->truth, .window_mm = 0, .search_theta = true },
            { .predicted = off, .window_mm = 4000, .search_theta = true },
            { .predicted = f->truth, .window_mm = 1000, .search_theta = true,
              .use_prior = true },
            { .predicted = off, .window_mm = 0, .search_theta = true },
        };
        int sparse = 0;
        for (size_t k = 0; k < sizeof queries / sizeof queries[0]; k++) {
            const hl_loc_query_t *q = &queries[k];
            hl_loc_result_t r, fresh_r;
            assert_int_equal(hl_loc_run(loc, f->map, f->n, &f->scan, q, &r), HL_OK);
            hl_loc_surface_t s, fresh_s;
            hl_loc_get_surface(loc, &s);
            size_t cells = (size_t)s.nx * s.ny * s.nt;
            sparse += !q->use_prior && cells >= 1u << 18;
            memcpy(votes, s.votes, cells * sizeof *votes);
            hl_localizer_t *fresh = hl_loc_create(&p);
            assert_int_equal(hl_loc_run(fresh, f->map, f->n, &f->scan, q, &fresh_r), HL_OK);
            hl_loc_get_surface(fresh, &fresh_s);
            assert_memory_equal(votes, fresh_s.votes, cells * sizeof *votes);
            hl_loc_destroy(fresh);
            assert_int_equal(r.votes, fresh_r.votes);
            if (q->use_prior)
                continue;   /* the prior's cells: test_peak_is_before_the_prior */

            const uint32_t *c = hl_blur3(votes, s.nx, s.ny, s.nt, &kx, &kx, &kt, a, b);
            assert_memory_equal(s.cells, c, cells * sizeof *c);
            hl_grid_t g = { .cells = c, .nx = s.nx, .ny = s.ny, .nt = s.nt, .row_max = rows };
            hl_peak_t pk;
            assert_int_equal(hl_peak_find(&g, s.cell_mm, p.peak_separation_mm, &pk), 1);
            assert_int_equal(r.ix, pk.ix);
            assert_int_equal(r.iy, pk.iy);
            assert_int_equal(r.it, pk.it);
            assert_int_equal(r.score, pk.score);
            assert_int_equal(r.second_score, pk.second);
            assert_int_equal(r.pose.x_mm, r.cell_pose.x_mm + plain_offset(c, &s, &pk, 0, s.cell_mm));
            assert_int_equal(r.pose.y_mm, r.cell_pose.y_mm + plain_offset(c, &s, &pk, 1, s.cell_mm));
            assert_int_equal(r.pose.theta, (hl_bam_t)(r.cell_pose.theta +
                                                      plain_offset(c, &s, &pk, 2, s.theta_step)));
        }
        assert_int_equal(sparse, 5);
        free(a);
        free(b);
        free(rows);
        free(votes);
        hl_loc_destroy(loc);
        free_fixture(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_empty_map_and_scan),
        cmocka_unit_test(test_global_xy_recovers_true_pose),
        cmocka_unit_test(test_local_xyt_recovers_true_pose),
        cmocka_unit_test(test_heading_wraps_through_180),
        cmocka_unit_test(test_extreme_coordinates),
        cmocka_unit_test(test_vote_saturation),
        cmocka_unit_test(test_capacity_limits),
        cmocka_unit_test(test_groups_of_one_point_are_exact),
        cmocka_unit_test(test_groups_of_a_dense_map),
        cmocka_unit_test(test_reading_stride),
        cmocka_unit_test(test_vote_once_counts_readings_not_pairs),
        cmocka_unit_test(test_params_validated),
        cmocka_unit_test(test_prior_breaks_ambiguity),
        cmocka_unit_test(test_peak_is_before_the_prior),
        cmocka_unit_test(test_sparse_path_is_the_plain_one),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
