/* Tests for src/core/slam.c: the online cycle on a random walk through a synthetic
 * room with noisy odometry, in guarded and paper modes; the heading gain; wild-error
 * rejection and the recent-peak average; a long drive with the odometry's heading off;
 * parameters and inputs checked. Saved state,
 * restore, set_pose and failed updates: test_slam_state.c; entering unmapped space and
 * the map's bound: test_slam_growth.c. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/slam_search.h"
#include "houghloc/slam.h"
#include "synthroom.h"

#include "slam_walk.h"

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
    uint64_t version = hl_map_version(hl_slam_map(s));
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
        uint64_t version = hl_map_version(hl_slam_map(s));
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

/* Long drives (slam.long_drive_mm): the walk mapped with exact odometry, then a drive
 * back to the walk's stop farthest from its end, which the odometry reports turned by 11
 * degrees about where it started: the prediction is off by a metre or more across the
 * drive and 11 degrees in heading, beyond the tracker's heading search. The drive tried
 * turned by -12 degrees lies within a degree of the truth, and the judge takes it. */
static hl_slam_step_t drive_back(const hl_slam_params_t *p, hl_pose_t *truth)
{
    walk_t *w = make_walk(5);   /* afresh: the room's generator also draws the noise */
    hl_slam_t *s = hl_slam_create(p);
    assert_non_null(s);
    hl_slam_reset(s, w->truth[0]);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_step_t out;
    int far = 0;
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->truth[i], &out), HL_OK);
        assert_false(out.turned);   /* 400 mm steps: never a long drive */
        if (dist(w->truth[i], w->truth[STEPS - 1]) > dist(w->truth[far], w->truth[STEPS - 1]))
            far = i;
    }
    hl_pose_t last = w->truth[STEPS - 1], turned = last;
    turned.theta = (hl_bam_t)(turned.theta + hl_bam_from_deg(11.0));
    *truth = w->truth[far];
    hl_pose_t odom = hl_pose_compose(turned, hl_pose_between(last, *truth));
    assert_true(dist(odom, *truth) > 600.0);
    sr_sound(&w->room, *truth, 128, 8000, 15, scan);
    assert_int_equal(hl_slam_update(s, scan, odom, &out), HL_OK);
    free(scan);
    free(w);
    hl_slam_destroy(s);
    return out;
}

static void test_long_drive_turned_back(void **state)
{
    (void)state;
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    hl_pose_t truth;
    hl_slam_step_t plain = drive_back(&p, &truth);
    assert_false(plain.turned);
    assert_true(dist(plain.pose, truth) > 400.0);
    p.long_drive_mm = 2000;
    hl_slam_step_t turned = drive_back(&p, &truth);
    assert_true(turned.turned);
    assert_int_equal(turned.status, HL_SLAM_ACCEPTED);
    assert_true(dist(turned.pose, truth) < 150.0);
    int32_t dh = hl_bam_diff(turned.pose.theta, truth.theta);
    assert_true(abs(dh) < hl_bam_from_deg(2.0));
    /* a drive shorter than long_drive_mm is tracked as before */
    p.long_drive_mm = 1000000;
    hl_slam_step_t short_drive = drive_back(&p, &truth);
    assert_false(short_drive.turned);
    assert_pose_equal(short_drive.pose, plain.pose);
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
    p.crowd_square_mm = 300;        /* the crowding cull's, which is off */
    assert_string_equal(hl_slam_params_error(&p),
                        "crowd_square_mm is the crowding cull's: it needs cull_crowded");
    p.map_per_place = 2;
    p.cull_choices = 8;
    p.cull_crowded = true;
    assert_null(hl_slam_params_error(&p));
    p.crowd_square_mm = 5;
    assert_string_equal(hl_slam_params_error(&p), "crowd_square_mm must be 0 or in 10..1000");
    hl_slam_params_default(&p);
    p.long_drive_turns = 0;         /* long drives are off: not checked */
    assert_null(hl_slam_params_error(&p));
    p.long_drive_mm = 2000;
    assert_non_null(hl_slam_params_error(&p));
    p.long_drive_turns = HL_SLAM_MAX_DRIVE_TURNS + 1;
    assert_non_null(hl_slam_params_error(&p));
    p.long_drive_turns = HL_SLAM_MAX_DRIVE_TURNS;
    assert_null(hl_slam_params_error(&p));
    p.long_drive_turn = hl_bam_from_deg(30.0);  /* 4 x 30 degrees: more than a quarter turn */
    assert_non_null(hl_slam_params_error(&p));
    p.long_drive_turn = 0;
    assert_non_null(hl_slam_params_error(&p));
    p.long_drive_turn = hl_bam_from_deg(6.0);
    p.long_drive_mm = -1;
    assert_string_equal(hl_slam_params_error(&p), "long_drive_mm must be in 0..1000000");

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
        cmocka_unit_test(test_heading_gain_blends_the_correction),
        cmocka_unit_test(test_paper_mode_accepts_everything),
        cmocka_unit_test(test_wild_jump_is_rejected),
        cmocka_unit_test(test_localize_changes_nothing),
        cmocka_unit_test(test_long_drive_turned_back),
        cmocka_unit_test(test_params_and_inputs_validated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
