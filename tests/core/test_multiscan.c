/* Tests for src/core/multiscan.c: readings of an earlier view moved into the newest
 * scan's frame with their surfaces' normals, surfaces that face away left out, scans
 * leaving the window by travel, by turning and when it is full, and the tracker that
 * draws a scan into its map only once it has left the window. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/multiscan.h"
#include "houghloc-internal/slam_params.h"
#include "synthroom.h"

#include "slam_walk.h"

static hl_scan_t *one_reading(double bearing_deg, int32_t range_mm)
{
    hl_scan_t *s = malloc(sizeof *s);
    hl_scan_clear(s);
    assert_int_equal(hl_scan_add(s, hl_bam_from_deg(bearing_deg), range_mm, 0, true), HL_OK);
    return s;
}

/* A wall 2 m to the left of where the earlier view stood, seen square (a sonar's tangent);
 * the newest view 1 m further on: the reading lies at (-1000, 2000) in its frame, and its
 * surface still faces -y, so its tilt is the turn from the new beam's reverse to -y. */
static void test_assemble_moves_readings_with_their_normals(void **state)
{
    (void)state;
    hl_multiscan_t *m = hl_multiscan_create(8, 5000, hl_bam_from_deg(90));
    assert_non_null(m);
    hl_scan_t *earlier = one_reading(90, 2000), *newest = one_reading(0, 3000);
    hl_scan_t *out = malloc(sizeof *out);
    hl_pose_t at0 = { 0, 0, 0 }, at1 = { 1000, 0, 0 };
    hl_multiscan_push(m, earlier, at0, at0, true);
    assert_int_equal(hl_multiscan_assemble(m, newest, at1, out), 1);
    assert_int_equal(out->count, 2);
    assert_int_equal(out->readings[0].range_mm, 3000);     /* the newest first, as it was */
    const hl_reading_t *r = &out->readings[1];
    assert_int_equal(r->range_mm, 2236);                    /* hypot(1000, 2000) */
    assert_true(fabs(hl_bam_to_sdeg(r->bearing) - 116.565) < 0.05);
    assert_true(fabs(hl_bam_to_sdeg(hl_reading_normal(r, 0)) - -90.0) < 0.05);
    assert_int_equal(hl_scan_check(out), HL_OK);
    hl_multiscan_destroy(m);
    free(earlier);
    free(newest);
    free(out);
}

/* A wall 0.5 m ahead of the earlier view, the newest view past it (through a door): the
 * surface faces away from the newest pose and is left out. From in front of it, 1 m to
 * the right and turned a quarter turn, it is seen at (1000, -500), its normal along +x of
 * the world, 90 degrees in that frame. */
static void test_assemble_leaves_out_surfaces_facing_away(void **state)
{
    (void)state;
    hl_multiscan_t *m = hl_multiscan_create(8, 5000, hl_bam_from_deg(180));
    hl_scan_t *earlier = one_reading(0, 500), *newest = one_reading(0, 3000);
    hl_scan_t *out = malloc(sizeof *out);
    hl_pose_t at0 = { 0, 0, 0 }, past = { 1000, 0, 0 }, before = { 0, -1000, 0 };
    hl_multiscan_push(m, earlier, at0, at0, true);
    assert_int_equal(hl_multiscan_assemble(m, newest, past, out), 1);
    assert_int_equal(out->count, 1);
    before.theta = hl_bam_from_deg(90);
    assert_int_equal(hl_multiscan_assemble(m, newest, before, out), 1);
    assert_int_equal(out->count, 2);
    assert_true(fabs(hl_bam_to_sdeg(out->readings[1].bearing) - -26.565) < 0.05);
    assert_true(fabs(hl_bam_to_sdeg(hl_reading_normal(&out->readings[1], 0)) - 90.0) < 0.05);
    hl_multiscan_destroy(m);
    free(earlier);
    free(newest);
    free(out);
}

/* Scans 300 mm apart in a 1000 mm window: at 1200 mm the first is due and the second
 * not; a turn of 40 degrees in a 30-degree window makes the next due; a full window
 * gives up its oldest even without travel. */
static void test_scans_leave_by_travel_turn_and_fullness(void **state)
{
    (void)state;
    hl_multiscan_t *m = hl_multiscan_create(4, 1000, hl_bam_from_deg(30));
    hl_scan_t *scan = one_reading(0, 1000);
    for (int k = 0; k < 4; k++) {
        hl_pose_t at = { 300 * k, 0, 0 }, pose = { 300 * k, 7, 0 };
        hl_multiscan_push(m, scan, at, pose, k != 1);
    }
    const hl_scan_t *old;
    hl_pose_t odo, pose;
    bool draw;
    hl_pose_t here = { 1200, 0, 0 };
    /* full (4 of 4): the oldest goes whatever the travel */
    assert_true(hl_multiscan_pop_due(m, here, &old, &odo, &pose, &draw));
    assert_int_equal(odo.x_mm, 0);
    assert_int_equal(pose.y_mm, 7);
    assert_true(draw);
    assert_false(hl_multiscan_pop_due(m, here, &old, &odo, &pose, &draw));    /* 900 mm */
    here.theta = hl_bam_from_deg(40);
    assert_true(hl_multiscan_pop_due(m, here, &old, &odo, &pose, &draw));     /* turned */
    assert_int_equal(odo.x_mm, 300);
    assert_false(draw);
    assert_int_equal(hl_multiscan_count(m), 2);
    hl_multiscan_clear(m);
    assert_int_equal(hl_multiscan_count(m), 0);
    assert_false(hl_multiscan_pop_due(m, here, &old, &odo, &pose, &draw));
    hl_multiscan_destroy(m);
    free(scan);
}

static void test_create_refuses_bad_arguments(void **state)
{
    (void)state;
    assert_null(hl_multiscan_create(0, 1000, 0));
    assert_null(hl_multiscan_create(HL_MULTISCAN_MAX_SCANS + 1, 1000, 0));
    assert_null(hl_multiscan_create(4, -1, 0));
    hl_multiscan_destroy(NULL);
}

/* The tracker with a 1 m window on the synthetic walk (400 mm steps): after the first
 * scan the map holds only it until the drive has taken a scan out of the window, and the
 * walk is still tracked. */
static void test_tracker_draws_scans_once_they_leave(void **state)
{
    (void)state;
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.multiscan_mm = 1000;
    walk_run_t r = walk_run_start(5, &p);
    uint32_t first = 0;
    double worst = 0;
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&r.w->room, r.w->truth[i], 128, 8000, 15, r.scan);
        hl_slam_step_t out;
        assert_int_equal(hl_slam_update(r.s, r.scan, r.w->odom[i], &out), HL_OK);
        uint32_t count = hl_map_count(hl_slam_map(r.s));
        if (i == 0)
            first = count;
        if (i == 1 || i == 2)   /* 400 and 800 mm: nothing has left the window */
            assert_int_equal(count, first);
        double e = dist(out.pose, r.w->truth[i]);
        worst = e > worst ? e : worst;
    }
    assert_true(first > 0);
    assert_true(hl_map_count(hl_slam_map(r.s)) > first);
    assert_true(worst < 150.0);
    walk_run_finish(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_assemble_moves_readings_with_their_normals),
        cmocka_unit_test(test_assemble_leaves_out_surfaces_facing_away),
        cmocka_unit_test(test_scans_leave_by_travel_turn_and_fullness),
        cmocka_unit_test(test_create_refuses_bad_arguments),
        cmocka_unit_test(test_tracker_draws_scans_once_they_leave),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
