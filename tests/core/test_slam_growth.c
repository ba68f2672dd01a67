/* Tests for src/core/slam.c, entering unmapped space (a corridor behind a door; a scan
 * with nothing to vote against) and map capacity as the one bound on the map. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slam_walk.h"

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
    hl_slam_t *s = hl_slam_create_with(&p);
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
        hl_slam_t *s = hl_slam_create_with(&p);
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
    hl_slam_t *s = hl_slam_create_with(&p);
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
        cmocka_unit_test(test_map_follows_robot_into_unmapped_corridor),
        cmocka_unit_test(test_unvotable_scan_extends_map_at_prediction),
        cmocka_unit_test(test_map_capacity_is_the_one_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
