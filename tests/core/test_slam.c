/* Tests for src/core/slam.c: the online cycle on a random walk through a synthetic
 * room with noisy odometry, in guarded and paper modes; wild-error rejection. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

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

/* The odometry claims a 2.5 m jump that did not happen: the scan cannot match inside
 * the +-1 m window around the prediction, so the guarded cycle rejects it and leaves
 * the map alone. */
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
    for (int i = 0; i < 6; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->truth[i], &out), HL_OK);
    }
    uint32_t version = hl_map_version(hl_slam_map(s));
    hl_pose_t lie = w->truth[5];
    lie.x_mm += 2500;
    sr_sound(&w->room, w->truth[5], 128, 8000, 15, scan);
    assert_int_equal(hl_slam_update(s, scan, lie, &out), HL_OK);
    assert_int_equal(out.status, HL_SLAM_REJECTED_WILD);
    assert_int_equal(out.added, 0);
    assert_int_equal(hl_map_version(hl_slam_map(s)), version);
    /* falls back to the prediction: the last estimate moved by the odometry */
    assert_true(dist(out.pose, out.predicted) == 0.0);
    assert_true(dist(out.pose, lie) < 50.0);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_guarded_walk_beats_odometry),
        cmocka_unit_test(test_paper_mode_accepts_everything),
        cmocka_unit_test(test_wild_jump_is_rejected),
        cmocka_unit_test(test_localize_changes_nothing),
        cmocka_unit_test(test_params_and_inputs_validated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
