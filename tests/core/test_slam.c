/* Tests for src/core/slam.c: the online cycle on a random walk through a synthetic
 * room with noisy odometry, in guarded and paper modes; wild-error rejection and the
 * recent-peak average; entering unmapped space (a corridor behind a door; a scan with
 * nothing to vote against); map capacity as the one bound on the map; saved state and
 * restore; set_pose; an update that fails changes nothing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/slam.h"
#include "../../tools/testkit/synthroom.h"

#define STEPS 40

typedef struct walk {
    sr_room_t room;
    hl_pose_t truth[STEPS];
    hl_pose_t odom[STEPS];
} walk_t;

/* A walk of 400 mm steps; odometry accumulates 5 % of distance and 2 deg per metre of
 * Gaussian error per step. The map starts at the first true pose. */
static walk_t *make_walk(uint64_t seed)
{
    walk_t *w = calloc(1, sizeof *w);
    sr_room_make(&w->room, 0, 0, 10000, 8000, 18, seed);
    w->truth[0] = sr_free_pose(&w->room, 800);
    w->odom[0] = w->truth[0];
    for (int i = 1; i < STEPS; i++) {
        w->truth[i] = sr_walk(&w->room, w->truth[i - 1], 400, 500);
        hl_pose_t rel = hl_pose_between(w->truth[i - 1], w->truth[i]);
        double d = hypot(rel.x_mm, rel.y_mm);
        rel.x_mm += (hl_mm_t)lround(0.05 * d * sr_gauss(&w->room));
        rel.y_mm += (hl_mm_t)lround(0.05 * d * sr_gauss(&w->room));
        rel.theta = (hl_bam_t)(rel.theta + hl_bam_from_deg(2.0 * d / 1000.0 * sr_gauss(&w->room)));
        w->odom[i] = hl_pose_compose(w->odom[i - 1], rel);
    }
    return w;
}

/* The defaults, for the synthetic room's sensor: a thin ray, not a sonar cone, so its
 * readings already lie where they echoed and echo-bearing estimation stays off. */
static void ray_sensor_defaults(hl_slam_params_t *p)
{
    hl_slam_params_default(p);
    p->echo_bearings = false;
}

static double dist(hl_pose_t a, hl_pose_t b)
{
    return hypot((double)a.x_mm - b.x_mm, (double)a.y_mm - b.y_mm);
}

/* Runs the walk; returns the largest position error and counts statuses. */
static double run_walk(const hl_slam_params_t *p, walk_t *w, int *accepted, int *rejected)
{
    hl_slam_t *s = hl_slam_create(p);
    assert_non_null(s);
    hl_slam_reset(s, w->truth[0]);
    hl_scan_t *scan = malloc(sizeof *scan);
    double worst = 0;
    *accepted = *rejected = 0;
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        hl_slam_step_t out;
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &out), HL_OK);
        if (i == 0)
            assert_int_equal(out.status, HL_SLAM_ODOMETRY_ONLY);
        *accepted += out.status == HL_SLAM_ACCEPTED;
        *rejected += out.status == HL_SLAM_REJECTED_WILD;
        double e = dist(out.pose, w->truth[i]);
        worst = e > worst ? e : worst;
    }
    assert_true(hl_map_count(hl_slam_map(s)) <= p->map_capacity);
    free(scan);
    hl_slam_destroy(s);
    return worst;
}

static void test_guarded_walk_beats_odometry(void **state)
{
    (void)state;
    walk_t *w = make_walk(5);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    int acc, rej;
    double worst = run_walk(&p, w, &acc, &rej);
    double odom_final = dist(w->odom[STEPS - 1], w->truth[STEPS - 1]);
    assert_true(acc >= STEPS - 5);
    assert_true(worst < 100.0);
    assert_true(odom_final > 3 * worst);
    free(w);
}

/* heading_gain g: an accepted localization's heading is the prediction's plus g of the
 * correction (0: the odometry's heading, 1: the localizer's), the position is the
 * localizer's either way. Two scans: the first builds the map at the true pose, the
 * second arrives with the odometry 3 degrees off. */
static void test_heading_gain_blends_the_correction(void **state)
{
    (void)state;
    walk_t *w = make_walk(8);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_pose_t second_odom = w->truth[1];
    second_odom.theta = (hl_bam_t)(second_odom.theta + hl_bam_from_deg(3.0));
    hl_slam_step_t out[3];
    const double gains[3] = { 1.0, 0.5, 0.0 };
    for (int g = 0; g < 3; g++) {
        hl_slam_params_t p;
        ray_sensor_defaults(&p);
        p.heading_gain = gains[g];
        hl_slam_t *s = hl_slam_create(&p);
        assert_non_null(s);
        hl_slam_reset(s, w->truth[0]);
        sr_sound(&w->room, w->truth[0], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->truth[0], &out[g]), HL_OK);
        sr_sound(&w->room, w->truth[1], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, second_odom, &out[g]), HL_OK);
        assert_int_equal(out[g].status, HL_SLAM_ACCEPTED);
        assert_int_equal(hl_slam_pose(s).theta, out[g].pose.theta);
        hl_slam_destroy(s);
    }
    /* the full correction brings the heading back to within a degree of the truth */
    assert_true(abs(hl_bam_diff(out[0].pose.theta, w->truth[1].theta)) < hl_bam_from_deg(1.0));
    int32_t correction = hl_bam_diff(out[0].pose.theta, out[0].predicted.theta);
    assert_true(abs(correction) > hl_bam_from_deg(2.0));
    assert_int_equal(out[2].pose.theta, out[2].predicted.theta);
    int32_t half = hl_bam_diff(out[1].pose.theta, out[1].predicted.theta);
    assert_true(abs(half - correction / 2) <= hl_bam_from_deg(0.5));
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.heading_gain = 1.5;
    assert_string_equal(hl_slam_params_error(&p), "heading_gain must be in 0..1");
    free(scan);
    free(w);
}

static void test_paper_mode_accepts_everything(void **state)
{
    (void)state;
    walk_t *w = make_walk(6);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.guarded = false;
    p.use_prior = false;
    p.interpolate = false;
    int acc, rej;
    run_walk(&p, w, &acc, &rej);
    assert_int_equal(acc, STEPS - 1);
    assert_int_equal(rej, 0);
    free(w);
}

/* The recent-peak average after a step (slam.h): a quarter of the way to an accepted
 * peak, the geometric mean with a rejected one (floor of the square root). */
static uint32_t expected_average(uint32_t avg, const hl_slam_step_t *out)
{
    if (out->status == HL_SLAM_ODOMETRY_ONLY)
        return avg;
    if (avg == 0)
        return out->loc.peak;
    if (out->status == HL_SLAM_ACCEPTED)
        return (uint32_t)((int64_t)avg + ((int64_t)out->loc.peak - avg) / 4);
    uint64_t p = (uint64_t)avg * out->loc.peak, r = (uint64_t)sqrt((double)p);
    while (r * r > p)
        r--;
    while ((r + 1) * (r + 1) <= p)
        r++;
    return (uint32_t)r;
}

/* The odometry claims a 2.5 m jump that did not happen: the scan cannot match inside
 * the +-1 m window around the prediction, so the guarded cycle rejects it and leaves
 * the map alone. The peak average follows its rule at every step, and the rejected
 * peak (before the prior) pulls it to the geometric mean. */
static void test_wild_jump_is_rejected(void **state)
{
    (void)state;
    walk_t *w = make_walk(7);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    hl_slam_t *s = hl_slam_create(&p);
    hl_slam_reset(s, w->truth[0]);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_step_t out;
    hl_slam_state_t before, after;
    for (int i = 0; i < 6; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        hl_slam_get_state(s, &before);
        assert_int_equal(hl_slam_update(s, scan, w->truth[i], &out), HL_OK);
        hl_slam_get_state(s, &after);
        assert_int_equal(out.status, i == 0 ? HL_SLAM_ODOMETRY_ONLY : HL_SLAM_ACCEPTED);
        assert_int_equal(after.peak_avg, expected_average(before.peak_avg, &out));
    }
    assert_true(after.peak_avg > 1000);
    uint32_t version = hl_map_version(hl_slam_map(s));
    hl_pose_t lie = w->truth[5];
    lie.x_mm -= 2500;
    sr_sound(&w->room, w->truth[5], 128, 8000, 15, scan);
    hl_slam_get_state(s, &before);
    assert_int_equal(hl_slam_update(s, scan, lie, &out), HL_OK);
    assert_int_equal(out.status, HL_SLAM_REJECTED_WILD);
    assert_int_equal(out.added, 0);
    assert_int_equal(hl_map_version(hl_slam_map(s)), version);
    /* falls back to the prediction: the last estimate moved by the odometry */
    assert_true(dist(out.pose, out.predicted) == 0.0);
    assert_true(dist(out.pose, lie) < 50.0);
    hl_slam_get_state(s, &after);
    assert_true(out.loc.peak * 4 < before.peak_avg);   /* rejected for its low peak */
    assert_int_equal(after.peak_avg, expected_average(before.peak_avg, &out));
    assert_true(after.peak_avg < before.peak_avg / 2);
    free(scan);
    hl_slam_destroy(s);
    free(w);
}

/* hl_slam_localize answers near the truth, twice the same, and changes nothing: the
 * map's version stays, and the cycle then proceeds normally. With and without
 * refinement. */
static void test_localize_changes_nothing(void **state)
{
    (void)state;
    walk_t *w = make_walk(8);
    for (int refine = 0; refine <= 1; refine++) {
        hl_slam_params_t p;
        ray_sensor_defaults(&p);
        p.refine = refine;
        hl_slam_t *s = hl_slam_create(&p);
        hl_slam_reset(s, w->truth[0]);
        hl_scan_t *scan = malloc(sizeof *scan);
        hl_slam_step_t out;
        for (int i = 0; i < 5; i++) {
            sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
            assert_int_equal(hl_slam_update(s, scan, w->truth[i], &out), HL_OK);
        }
        uint32_t version = hl_map_version(hl_slam_map(s));
        sr_sound(&w->room, w->truth[5], 128, 8000, 15, scan);
        hl_pose_t guess = w->truth[5];
        guess.x_mm += 120;
        hl_loc_result_t r;
        hl_pose_t found, again;
        assert_int_equal(hl_slam_localize(s, scan, guess, &r, &found), HL_OK);
        assert_int_equal(hl_slam_localize(s, scan, guess, &r, &again), HL_OK);
        assert_memory_equal(&found, &again, sizeof found);
        assert_true(dist(found, w->truth[5]) < 60.0);
        assert_int_equal(hl_map_version(hl_slam_map(s)), version);
        /* the cycle itself then proceeds as if nothing had been asked */
        assert_int_equal(hl_slam_update(s, scan, w->truth[5], &out), HL_OK);
        assert_int_equal(out.status, HL_SLAM_ACCEPTED);
        assert_true(dist(out.pose, w->truth[5]) < 60.0);
        assert_int_equal(hl_slam_localize(NULL, scan, guess, &r, &found), HL_ERR_ARG);
        hl_pose_t outside = { HL_COORD_MAX_MM + 1, 0, 0 };
        assert_int_equal(hl_slam_localize(s, scan, outside, &r, &found), HL_ERR_RANGE);
        free(scan);
        hl_slam_destroy(s);
    }
    free(w);
}

static void test_params_and_inputs_validated(void **state)
{
    (void)state;
    hl_slam_params_t p;
    hl_slam_params_default(&p);
    assert_null(hl_slam_params_error(&p));
    p.map_capacity = 0;
    assert_non_null(hl_slam_params_error(&p));
    assert_null(hl_slam_create(&p));
    p.map_capacity = HL_MAP_MAX_CAPACITY + 1;
    assert_string_equal(hl_slam_params_error(&p), "map_capacity must be in 1..1048576");
    /* map_capacity alone bounds the map: the localizer's own bound is not read */
    p.map_capacity = 20000;
    assert_null(hl_slam_params_error(&p));
    p.loc.max_map_vectors = 0;
    assert_null(hl_slam_params_error(&p));
    hl_slam_params_default(&p);
    p.loc.max_cells = 1000;
    assert_string_equal(hl_slam_params_error(&p),
                        "the search window needs more raster cells than max_cells");
    hl_slam_params_default(&p);
    p.min_confidence = 2;
    assert_non_null(hl_slam_params_error(&p));
    hl_slam_params_default(&p);
    p.echo.half_beam = 0;
    assert_non_null(hl_slam_params_error(&p));
    p.echo_bearings = false;    /* not used, not checked */
    assert_null(hl_slam_params_error(&p));
    hl_slam_params_default(&p);
    p.refine_params.match_mm = 0;
    assert_non_null(hl_slam_params_error(&p));
    assert_null(hl_slam_create(&p));

    hl_slam_params_default(&p);
    hl_slam_t *s = hl_slam_create(&p);
    hl_scan_t *scan = calloc(1, sizeof *scan);
    hl_slam_step_t out;
    hl_pose_t far = { HL_COORD_MAX_MM + 5, 0, 0 };
    assert_int_equal(hl_slam_update(s, scan, far, &out), HL_ERR_RANGE);
    scan->count = HL_SCAN_MAX_READINGS + 1;
    hl_pose_t origin = { 0, 0, 0 };
    assert_int_equal(hl_slam_update(s, scan, origin, &out), HL_ERR_RANGE);
    assert_int_equal(hl_slam_update(NULL, scan, origin, &out), HL_ERR_ARG);
    /* an empty scan on an empty map: odometry only, nothing added */
    scan->count = 0;
    assert_int_equal(hl_slam_update(s, scan, origin, &out), HL_OK);
    assert_int_equal(out.status, HL_SLAM_ODOMETRY_ONLY);
    assert_int_equal(out.added, 0);
    free(scan);
    hl_slam_destroy(s);
    hl_slam_destroy(NULL);
}

/* Every field of two steps, one by one (struct padding is not compared). */
static void assert_pose_equal(hl_pose_t a, hl_pose_t b)
{
    assert_int_equal(a.x_mm, b.x_mm);
    assert_int_equal(a.y_mm, b.y_mm);
    assert_int_equal(a.theta, b.theta);
}

static void assert_step_equal(const hl_slam_step_t *a, const hl_slam_step_t *b)
{
    assert_pose_equal(a->pose, b->pose);
    assert_pose_equal(a->predicted, b->predicted);
    assert_int_equal(a->status, b->status);
    assert_int_equal(a->added, b->added);
    assert_pose_equal(a->loc.pose, b->loc.pose);
    assert_pose_equal(a->loc.cell_pose, b->loc.cell_pose);
    assert_int_equal(a->loc.ix, b->loc.ix);
    assert_int_equal(a->loc.iy, b->loc.iy);
    assert_int_equal(a->loc.it, b->loc.it);
    assert_int_equal(a->loc.peak, b->loc.peak);
    assert_int_equal(a->loc.second, b->loc.second);
    assert_int_equal(a->loc.score, b->loc.score);
    assert_int_equal(a->loc.second_score, b->loc.second_score);
    assert_int_equal(a->loc.votes, b->loc.votes);
    assert_int_equal(a->loc.pairs, b->loc.pairs);
}

static void assert_state_equal(const hl_slam_state_t *a, const hl_slam_state_t *b)
{
    assert_int_equal(a->started, b->started);
    assert_pose_equal(a->pose, b->pose);
    assert_pose_equal(a->odom, b->odom);
    assert_int_equal(a->peak_avg, b->peak_avg);
    assert_int_equal(a->map_version, b->map_version);
    assert_true(a->cull_rng.state == b->cull_rng.state);
    assert_true(a->cull_rng.inc == b->cull_rng.inc);
}

/* The map's vectors of two slams are the same, count and bytes. */
static void assert_maps_equal(hl_slam_t *a, hl_slam_t *b)
{
    hl_map_t *ma = hl_slam_map(a), *mb = hl_slam_map(b);
    assert_int_equal(hl_map_count(ma), hl_map_count(mb));
    assert_memory_equal(hl_map_vectors(ma), hl_map_vectors(mb),
                        hl_map_count(ma) * sizeof(hl_vector_t));
}

/* A snapshot of everything observable: the state and a copy of the vectors. */
typedef struct snapshot {
    hl_slam_state_t state;
    uint32_t count;
    hl_vector_t *vectors;
} snapshot_t;

static void take_snapshot(hl_slam_t *s, snapshot_t *snap)
{
    hl_map_t *m = hl_slam_map(s);
    hl_slam_get_state(s, &snap->state);
    snap->count = hl_map_count(m);
    snap->vectors = malloc((snap->count + 1) * sizeof(hl_vector_t));
    memcpy(snap->vectors, hl_map_vectors(m), snap->count * sizeof(hl_vector_t));
}

static void assert_unchanged(hl_slam_t *s, snapshot_t *snap)
{
    hl_slam_state_t now;
    hl_slam_get_state(s, &now);
    assert_state_equal(&now, &snap->state);
    hl_map_t *m = hl_slam_map(s);
    assert_int_equal(hl_map_count(m), snap->count);
    assert_memory_equal(hl_map_vectors(m), snap->vectors,
                        snap->count * sizeof(hl_vector_t));
    free(snap->vectors);
    snap->vectors = NULL;
}

/* Saved after K scans (state + vectors) and restored into a fresh slam whose seed
 * differs (so the culling generator must come from the state), the copy then takes the
 * same steps as the original, scan after scan, and keeps the same map. The capacity is
 * small so that culling runs from the fourth scan on. Guarded and paper modes. */
static void test_restore_continues_identically(void **state)
{
    (void)state;
    enum { K = 15 };
    walk_t *w = make_walk(9);
    hl_scan_t *scan = malloc(sizeof *scan);
    for (int guarded = 0; guarded <= 1; guarded++) {
        hl_slam_params_t p;
        ray_sensor_defaults(&p);
        p.guarded = guarded;
        p.map_capacity = 400;
        hl_slam_t *a = hl_slam_create(&p);
        p.seed = 12345;
        hl_slam_t *b = hl_slam_create(&p);
        assert_non_null(a);
        assert_non_null(b);
        hl_slam_reset(a, w->truth[0]);
        hl_slam_step_t sa, sb;
        int accepted = 0;
        for (int i = 0; i < K; i++) {
            sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
            assert_int_equal(hl_slam_update(a, scan, w->odom[i], &sa), HL_OK);
        }
        assert_int_equal(hl_map_count(hl_slam_map(a)), 400);   /* culling is active */

        snapshot_t snap;
        take_snapshot(a, &snap);
        assert_true(snap.state.started);
        assert_int_equal(snap.state.pose.x_mm, hl_slam_pose(a).x_mm);
        assert_int_equal(snap.state.odom.x_mm, w->odom[K - 1].x_mm);
        assert_int_equal(snap.state.map_version, hl_map_version(hl_slam_map(a)));
        assert_int_equal(hl_slam_restore(b, &snap.state, snap.vectors, snap.count), HL_OK);
        free(snap.vectors);
        hl_slam_state_t ga, gb;
        hl_slam_get_state(a, &ga);
        hl_slam_get_state(b, &gb);
        assert_state_equal(&ga, &gb);
        assert_memory_equal(&ga, &gb, sizeof ga);   /* get_state zeroes the padding */
        assert_maps_equal(a, b);

        for (int i = K; i < STEPS; i++) {
            sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
            assert_int_equal(hl_slam_update(a, scan, w->odom[i], &sa), HL_OK);
            assert_int_equal(hl_slam_update(b, scan, w->odom[i], &sb), HL_OK);
            assert_step_equal(&sa, &sb);
            assert_maps_equal(a, b);
            hl_slam_get_state(a, &ga);
            hl_slam_get_state(b, &gb);
            assert_state_equal(&ga, &gb);
            accepted += sa.status == HL_SLAM_ACCEPTED;
        }
        assert_true(accepted >= STEPS - K - 5);  /* real localizations were compared */
        hl_slam_destroy(a);
        hl_slam_destroy(b);
    }
    free(scan);
    free(w);
}

/* A restore with too many vectors, an out-of-range vector or pose changes nothing. */
static void test_restore_refuses_bad_input(void **state)
{
    (void)state;
    walk_t *w = make_walk(10);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.map_capacity = 300;
    hl_slam_t *s = hl_slam_create(&p);
    hl_slam_reset(s, w->truth[0]);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_step_t out;
    for (int i = 0; i < 3; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &out), HL_OK);
    }
    hl_vector_t *in = calloc(301, sizeof *in);
    for (int i = 0; i < 301; i++)
        in[i] = (hl_vector_t){ 100 * i, -50 * i, (hl_bam_t)(i * 200), 1000 };
    hl_slam_state_t good = { .started = true, .pose = { 10, 20, 30 },
                             .odom = { 40, 50, 60 }, .peak_avg = 77, .map_version = 3,
                             .cull_rng = { 5, 7 } };
    snapshot_t snap;
    take_snapshot(s, &snap);
    assert_int_equal(hl_slam_restore(s, &good, in, 301), HL_ERR_CAPACITY);
    in[299].x_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_slam_restore(s, &good, in, 300), HL_ERR_RANGE);
    in[299].x_mm = 0;
    in[0].range_mm = HL_RANGE_MAX_MM + 1;
    assert_int_equal(hl_slam_restore(s, &good, in, 300), HL_ERR_RANGE);
    in[0].range_mm = 1000;
    hl_slam_state_t bad = good;
    bad.pose.y_mm = -HL_COORD_MAX_MM - 1;
    assert_int_equal(hl_slam_restore(s, &bad, in, 300), HL_ERR_RANGE);
    bad = good;
    bad.odom.x_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_slam_restore(s, &bad, in, 300), HL_ERR_RANGE);
    assert_int_equal(hl_slam_restore(s, NULL, in, 300), HL_ERR_ARG);
    assert_int_equal(hl_slam_restore(s, &good, NULL, 1), HL_ERR_ARG);
    assert_unchanged(s, &snap);
    /* and the good one is taken whole */
    assert_int_equal(hl_slam_restore(s, &good, in, 300), HL_OK);
    hl_slam_state_t now;
    hl_slam_get_state(s, &now);
    assert_state_equal(&now, &good);
    assert_memory_equal(hl_map_vectors(hl_slam_map(s)), in, 300 * sizeof *in);
    free(in);
    free(scan);
    hl_slam_destroy(s);
    free(w);
}

/* Before the first scan set_pose sets the start (the first scan's odometry is the
 * reference); after it, it moves the estimate, keeps the map, and the next prediction
 * is the new pose moved by the odometry difference. */
static void test_set_pose(void **state)
{
    (void)state;
    walk_t *w = make_walk(11);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    hl_slam_t *s = hl_slam_create(&p);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_step_t out;
    hl_pose_t odd = { 777, -888, 999 };
    assert_int_equal(hl_slam_set_pose(s, w->truth[0], odd), HL_OK);
    assert_pose_equal(hl_slam_pose(s), w->truth[0]);
    hl_slam_state_t st;
    hl_slam_get_state(s, &st);
    assert_false(st.started);
    sr_sound(&w->room, w->truth[0], 128, 8000, 15, scan);
    assert_int_equal(hl_slam_update(s, scan, w->odom[0], &out), HL_OK);
    assert_pose_equal(out.predicted, w->truth[0]);  /* not moved by odom[0] - odd */
    assert_pose_equal(out.pose, w->truth[0]);
    assert_true(out.added > 0);
    for (int i = 1; i < 4; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &out), HL_OK);
    }
    hl_map_t *m = hl_slam_map(s);
    uint32_t count = hl_map_count(m), version = hl_map_version(m);

    /* out of range: nothing changes */
    hl_pose_t before = hl_slam_pose(s);
    hl_pose_t outside = { 0, HL_COORD_MAX_MM + 1, 0 };
    assert_int_equal(hl_slam_set_pose(s, outside, w->odom[3]), HL_ERR_RANGE);
    assert_int_equal(hl_slam_set_pose(s, w->truth[3], outside), HL_ERR_RANGE);
    assert_int_equal(hl_slam_set_pose(NULL, w->truth[3], w->odom[3]), HL_ERR_ARG);
    assert_pose_equal(hl_slam_pose(s), before);

    /* the operator places the robot 300 mm off, at odometry odom[3] */
    hl_pose_t placed = w->truth[3];
    placed.x_mm += 300;
    placed.theta = (hl_bam_t)(placed.theta + 1000);
    assert_int_equal(hl_slam_set_pose(s, placed, w->odom[3]), HL_OK);
    assert_pose_equal(hl_slam_pose(s), placed);
    assert_int_equal(hl_map_count(m), count);
    assert_int_equal(hl_map_version(m), version);
    hl_slam_get_state(s, &st);
    assert_true(st.started);
    assert_pose_equal(st.pose, placed);
    assert_pose_equal(st.odom, w->odom[3]);
    sr_sound(&w->room, w->truth[4], 128, 8000, 15, scan);
    assert_int_equal(hl_slam_update(s, scan, w->odom[4], &out), HL_OK);
    assert_pose_equal(out.predicted,
                      hl_pose_compose(placed, hl_pose_between(w->odom[3], w->odom[4])));
    free(scan);
    hl_slam_destroy(s);
    free(w);
}

/* A localizer error in the middle of the cycle (a global search over a map whose
 * bounding box needs more raster than max_cells): hl_slam_update returns it and the
 * state and map are as before, started or not. */
static void test_failed_update_changes_nothing(void **state)
{
    (void)state;
    walk_t *w = make_walk(12);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.window_mm = 0;    /* global: the raster covers the map's bounding box */
    hl_slam_t *s = hl_slam_create(&p);
    hl_scan_t *scan = malloc(sizeof *scan);
    sr_sound(&w->room, w->truth[0], 128, 8000, 15, scan);
    hl_vector_t far[3] = { { 0, 0, 0, 1000 }, { 200000, 200000, 16384, 1000 },
                           { 5000, 4000, 32768, 2000 } };
    for (int started = 0; started <= 1; started++) {
        hl_slam_state_t st = { .started = started, .pose = { 1000, 1000, 0 },
                               .odom = { 0, 0, 0 }, .peak_avg = 1234, .map_version = 9,
                               .cull_rng = { 11, 13 } };
        assert_int_equal(hl_slam_restore(s, &st, far, 3), HL_OK);
        snapshot_t snap;
        take_snapshot(s, &snap);
        hl_pose_t moved = { 100, 0, 50 };
        hl_slam_step_t out = { .added = 4242 };
        assert_int_equal(hl_slam_update(s, scan, moved, &out), HL_ERR_CAPACITY);
        assert_int_equal(out.added, 4242);  /* the step is not written either */
        assert_unchanged(s, &snap);
        assert_int_equal(hl_map_version(hl_slam_map(s)), 9);
    }
    free(scan);
    hl_slam_destroy(s);
    free(w);
}

/* The peak of a local window at the edge of the coordinate range lies outside it (the
 * robot's scan says it stands beyond HL_COORD_MAX_MM): the paper-mode cycle would
 * accept the pose and extend the map there; it returns HL_ERR_RANGE and changes
 * nothing. */
static void test_update_beyond_the_edge_changes_nothing(void **state)
{
    (void)state;
    sr_room_t *room = malloc(sizeof *room);
    /* walls from E - 4000 to E + 1000 in x, -2000..2000 in y */
    const double e = HL_COORD_MAX_MM;
    sr_room_make(room, e - 4000, -2000, 5000, 4000, 4, 3);
    hl_pose_t truth = { HL_COORD_MAX_MM + 300, 0, 0 };
    assert_true(sr_clearance(room, truth.x_mm, truth.y_mm) > 300);
    hl_vector_t *pool = malloc(1500 * sizeof *pool);
    uint32_t n = sr_make_map(room, 1500, 128, 8000, 5, pool), kept = 0;
    for (uint32_t i = 0; i < n; i++)    /* the part of the room inside the range */
        if (hl_vector_in_range(&pool[i]))
            pool[kept++] = pool[i];
    assert_true(kept > 500);

    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.guarded = false;
    p.use_prior = false;
    hl_slam_t *s = hl_slam_create(&p);
    hl_slam_state_t st = { .started = true, .pose = { HL_COORD_MAX_MM - 100, 0, 0 },
                           .odom = { 0, 0, 0 }, .map_version = 21, .cull_rng = { 1, 1 } };
    assert_int_equal(hl_slam_restore(s, &st, pool, kept), HL_OK);
    hl_scan_t *scan = malloc(sizeof *scan);
    sr_sound(room, truth, 128, 8000, 5, scan);
    /* what the cycle would find: beyond the edge */
    hl_loc_result_t r;
    hl_pose_t found;
    assert_int_equal(hl_slam_localize(s, scan, st.pose, &r, &found), HL_OK);
    assert_true(found.x_mm > HL_COORD_MAX_MM);
    assert_true(dist(found, truth) < 100.0);

    snapshot_t snap;
    take_snapshot(s, &snap);
    hl_slam_step_t out;
    hl_pose_t same = { 0, 0, 0 };
    assert_int_equal(hl_slam_update(s, scan, same, &out), HL_ERR_RANGE);
    assert_unchanged(s, &snap);
    free(scan);
    free(pool);
    free(room);
    hl_slam_destroy(s);
}

/* ---- entering unmapped space ------------------------------------------------------- */

static void add_segment(sr_room_t *r, double x1, double y1, double x2, double y2)
{
    assert_true(r->nseg < SR_MAX_SEGMENTS);
    r->seg[r->nseg++] = (sr_segment_t){ x1, y1, x2, y2 };
}

static void add_box(sr_room_t *r, double x0, double y0, double x1, double y1)
{
    add_segment(r, x0, y0, x1, y0);
    add_segment(r, x1, y0, x1, y1);
    add_segment(r, x1, y1, x0, y1);
    add_segment(r, x0, y1, x0, y0);
}

#define CORRIDOR_MAX_STOPS 48

/*
 * A 6 m x 5 m room with four boxes, and behind a 1 m door in its east wall a corridor
 * 3 m wide and 12 m long (pillars on alternate walls every 1.5 m) that the room's
 * soundings barely see: the robot circles the room (16 stops), then drives east through
 * the door and down the corridor in 500 mm steps. The truth, and odometry with the
 * walk's noise; returns the number of stops, the first in the corridor in *first.
 */
static int corridor_tour(sr_room_t *room, hl_pose_t *truth, hl_pose_t *odom, int *first)
{
    const double pi = 3.14159265358979323846;
    sr_room_make(room, 0, 0, 6000, 5000, 0, 1);
    room->seg[1] = (sr_segment_t){ 6000, 0, 6000, 2000 };  /* east wall, door at 2..3 m */
    add_segment(room, 6000, 3000, 6000, 5000);
    add_box(room, 1200, 900, 1800, 1300);
    add_box(room, 900, 3600, 1400, 4100);
    add_box(room, 3300, 4200, 4100, 4500);
    add_box(room, 4000, 600, 4400, 1300);
    add_segment(room, 6000, 1000, 18000, 1000);
    add_segment(room, 6000, 4000, 18000, 4000);
    add_segment(room, 18000, 1000, 18000, 4000);
    for (int k = 0; k < 7; k++) {
        double x = 7000 + 1500 * k;
        if (k % 2)
            add_box(room, x, 1000, x + 300, 1300);
        else
            add_box(room, x, 3700, x + 300, 4000);
    }
    int n = 0;
    for (int i = 0; i < 16; i++) {
        double a = 2 * pi * i / 16;
        truth[n++] = (hl_pose_t){ (hl_mm_t)lround(3000 + 1100 * cos(a)),
                                  (hl_mm_t)lround(2500 + 1100 * sin(a)),
                                  hl_bam_from_rad(a + pi / 2) };
    }
    *first = -1;
    for (int x = 4500; x <= 16000 && n < CORRIDOR_MAX_STOPS; x += 500) {
        if (x > 6000 && *first < 0)
            *first = n;
        truth[n++] = (hl_pose_t){ x, 2500, 0 };
    }
    odom[0] = truth[0];
    for (int i = 1; i < n; i++) {
        hl_pose_t rel = hl_pose_between(truth[i - 1], truth[i]);
        double d = hypot(rel.x_mm, rel.y_mm);
        rel.x_mm += (hl_mm_t)lround(0.05 * d * sr_gauss(room));
        rel.y_mm += (hl_mm_t)lround(0.05 * d * sr_gauss(room));
        rel.theta = (hl_bam_t)(rel.theta + hl_bam_from_deg(2.0 * d / 1000.0 * sr_gauss(room)));
        odom[i] = hl_pose_compose(odom[i - 1], rel);
    }
    return n;
}

/* The robot leaves the mapped room for the corridor. Its peak falls by more than ten
 * times within a few scans, so the guard rejects those; then the average has come down
 * (or a scan finds nothing to vote against and goes into the map at the prediction),
 * and the map grows down the corridor with the robot: every later scan there is
 * accepted and close to the truth. (Before, no scan after the door was accepted, the
 * map never got past the door and the robot ran on odometry to the end.) */
static void test_map_follows_robot_into_unmapped_corridor(void **state)
{
    (void)state;
    sr_room_t *room = malloc(sizeof *room);
    hl_pose_t truth[CORRIDOR_MAX_STOPS], odom[CORRIDOR_MAX_STOPS];
    int first;
    int n = corridor_tour(room, truth, odom, &first);
    assert_int_equal(n, 40);
    assert_int_equal(first, 20);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    hl_slam_t *s = hl_slam_create(&p);
    hl_slam_reset(s, truth[0]);
    hl_scan_t *scan = malloc(sizeof *scan);
    int in_row = 0, longest = 0, rejected = 0, accepted_late = 0, unvotable = 0;
    for (int i = 0; i < n; i++) {
        sr_sound(room, truth[i], 128, 4000, 15, scan);
        hl_slam_step_t out;
        assert_int_equal(hl_slam_update(s, scan, odom[i], &out), HL_OK);
        if (i < first - 1)  /* the room: mapped as the robot goes round */
            assert_int_equal(out.status, i == 0 ? HL_SLAM_ODOMETRY_ONLY : HL_SLAM_ACCEPTED);
        in_row = out.status == HL_SLAM_ACCEPTED ? 0 : in_row + 1;
        longest = in_row > longest ? in_row : longest;
        rejected += out.status == HL_SLAM_REJECTED_WILD;
        if (i > 0 && out.status == HL_SLAM_ODOMETRY_ONLY) {
            /* nothing to vote against: the scan goes into the map where odometry says */
            unvotable++;
            assert_pose_equal(out.pose, out.predicted);
            assert_int_equal(out.added, hl_scan_valid_count(scan));
        }
        if (truth[i].x_mm >= 10000) {
            accepted_late += out.status == HL_SLAM_ACCEPTED;
            assert_true(dist(out.pose, truth[i]) < 400.0);
        }
    }
    assert_true(rejected >= 3);             /* the door: the guard did see the fall */
    assert_true(longest <= 8);              /* ... for a few scans, not for good */
    assert_true(unvotable <= 2);
    assert_int_equal(accepted_late, 13);    /* every scan from x = 10 m on */
    uint32_t deep = 0;      /* vectors of the far half of the corridor */
    const hl_vector_t *v = hl_map_vectors(hl_slam_map(s));
    for (uint32_t k = 0; k < hl_map_count(hl_slam_map(s)); k++)
        deep += v[k].x_mm > 12000;
    assert_true(deep > 300);
    free(scan);
    free(room);
    hl_slam_destroy(s);
}

/* A scan whose readings have nothing near the prediction to vote against (the map lies
 * 100 m away) is not localized, and goes into the map at the prediction, reading by
 * reading, in guarded mode as in paper mode. */
static void test_unvotable_scan_extends_map_at_prediction(void **state)
{
    (void)state;
    walk_t *w = make_walk(13);
    for (int guarded = 0; guarded <= 1; guarded++) {
        hl_slam_params_t p;
        ray_sensor_defaults(&p);
        p.guarded = guarded;
        hl_slam_t *s = hl_slam_create(&p);
        hl_vector_t far[2] = { { 100000, 100000, 0, 1000 }, { 100000, 101000, 16384, 1000 } };
        hl_slam_state_t st = { .started = true, .pose = w->truth[2], .odom = w->odom[2],
                               .peak_avg = 5000, .map_version = 4, .cull_rng = { 3, 5 } };
        assert_int_equal(hl_slam_restore(s, &st, far, 2), HL_OK);
        hl_scan_t *scan = malloc(sizeof *scan);
        sr_sound(&w->room, w->truth[3], 128, 8000, 15, scan);
        hl_slam_step_t out;
        assert_int_equal(hl_slam_update(s, scan, w->odom[3], &out), HL_OK);
        assert_int_equal(out.status, HL_SLAM_ODOMETRY_ONLY);
        assert_pose_equal(out.pose, out.predicted);
        assert_pose_equal(out.predicted,
                          hl_pose_compose(w->truth[2], hl_pose_between(w->odom[2], w->odom[3])));
        uint32_t valid = hl_scan_valid_count(scan);
        assert_true(valid > 100);
        assert_int_equal(out.added, valid);
        hl_map_t *m = hl_slam_map(s);
        assert_int_equal(hl_map_count(m), 2 + valid);
        const hl_vector_t *v = hl_map_vectors(m);
        uint32_t k = 2;
        for (uint32_t i = 0; i < scan->count; i++) {
            hl_vector_t want;
            if (!hl_vector_from_reading(out.predicted, &scan->readings[i], &want))
                continue;
            assert_int_equal(v[k].x_mm, want.x_mm);
            assert_int_equal(v[k].y_mm, want.y_mm);
            assert_int_equal(v[k].normal, want.normal);
            k++;
        }
        hl_slam_get_state(s, &st);
        assert_int_equal(st.peak_avg, 5000);    /* no localization, no new peak */
        free(scan);
        hl_slam_destroy(s);
    }
    free(w);
}

/* slam.map_capacity is the one bound on the map's size: a slam made for 20,000 vectors,
 * more than the localizer's default of 16,384, with those defaults, takes a map that
 * full and localizes against it. */
static void test_map_capacity_is_the_one_bound(void **state)
{
    (void)state;
    enum { N = 20000 };
    sr_room_t *room = malloc(sizeof *room);
    sr_room_make(room, 0, 0, 10000, 8000, 18, 21);
    hl_vector_t *vectors = malloc(N * sizeof *vectors);
    assert_int_equal(sr_make_map(room, N, 128, 8000, 10, vectors), N);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.map_capacity = N;
    assert_true(p.loc.max_map_vectors < N);
    hl_slam_t *s = hl_slam_create(&p);
    assert_non_null(s);
    hl_pose_t truth = sr_free_pose(room, 800);
    hl_pose_t start = truth;
    start.x_mm += 120;
    start.y_mm -= 80;
    hl_slam_state_t st = { .started = true, .pose = start, .odom = { 0, 0, 0 },
                           .map_version = 1, .cull_rng = { 1, 1 } };
    assert_int_equal(hl_slam_restore(s, &st, vectors, N), HL_OK);
    hl_scan_t *scan = malloc(sizeof *scan);
    sr_sound(room, truth, 128, 8000, 10, scan);
    hl_slam_step_t out;
    hl_pose_t still = { 0, 0, 0 };
    assert_int_equal(hl_slam_update(s, scan, still, &out), HL_OK);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);
    assert_true(dist(out.pose, truth) < 60.0);
    assert_int_equal(hl_map_count(hl_slam_map(s)), N);  /* full: culled as it grew */
    free(scan);
    free(vectors);
    free(room);
    hl_slam_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_guarded_walk_beats_odometry),
        cmocka_unit_test(test_heading_gain_blends_the_correction),
        cmocka_unit_test(test_paper_mode_accepts_everything),
        cmocka_unit_test(test_wild_jump_is_rejected),
        cmocka_unit_test(test_localize_changes_nothing),
        cmocka_unit_test(test_params_and_inputs_validated),
        cmocka_unit_test(test_restore_continues_identically),
        cmocka_unit_test(test_restore_refuses_bad_input),
        cmocka_unit_test(test_set_pose),
        cmocka_unit_test(test_failed_update_changes_nothing),
        cmocka_unit_test(test_update_beyond_the_edge_changes_nothing),
        cmocka_unit_test(test_map_follows_robot_into_unmapped_corridor),
        cmocka_unit_test(test_unvotable_scan_extends_map_at_prediction),
        cmocka_unit_test(test_map_capacity_is_the_one_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
