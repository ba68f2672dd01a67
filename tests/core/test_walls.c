/* Tests for src/core/walls.c and the tracker's square walls (slam.wall_gain): the walls'
 * axis of a scan and of a map's vectors, folded four times round, with its R; the mean
 * offset of a scan's normals from an axis over those within a window; and an accepted
 * scan's heading turned by the walls where the odometry left it off. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/walls.h"
#include "synthroom.h"

#include "slam_walk.h"

#define DEG (3.14159265358979323846 / 180)

/* A scan with no readings (free it). */
static hl_scan_t *empty_scan(void)
{
    hl_scan_t *s = malloc(sizeof *s);
    hl_scan_clear(s);
    return s;
}

/* A reading at @p bearing_deg whose surface normal points along @p normal_deg in the
 * robot's frame (its tilt: the normal's turn from the beam's reverse). */
static void add_normal(hl_scan_t *s, double bearing_deg, double normal_deg)
{
    assert_int_equal(hl_scan_add(s, hl_bam_from_deg(bearing_deg), 2000, 0, true), HL_OK);
    hl_reading_t *r = &s->readings[s->count - 1];
    r->tilt = (int16_t)hl_bam_diff(hl_bam_from_deg(normal_deg),
                                   (hl_bam_t)(r->bearing + HL_BAM_HALF_TURN));
    assert_true(fabs(hl_bam_to_sdeg(hl_reading_normal(r, 0)) - remainder(normal_deg, 360)) <
                0.01);
}

/* Four walls of a room turned 10 degrees: every normal on the axis (R 1), which the
 * quarter turns between them do not change; a reading not valid counts for nothing. */
static void test_scan_axis_of_a_turned_room(void **state)
{
    (void)state;
    hl_scan_t *s = empty_scan();
    for (int k = 0; k < 12; k++)
        add_normal(s, 30 * k, 10 + 90 * (k % 4));
    assert_int_equal(hl_scan_add(s, 0, 500, 0, false), HL_OK);
    hl_walls_t w = hl_walls_of_scan(s);
    assert_int_equal(w.n, 12);
    assert_true(fabs(w.axis - 10 * DEG) < 0.01 * DEG);
    assert_true(fabs(w.r - 1) < 1e-9);
    /* ... and turned 50 degrees, the same walls lie at -40 = 50 - 90 */
    hl_scan_clear(s);
    for (int k = 0; k < 12; k++)
        add_normal(s, 30 * k, 50 + 90 * (k % 4));
    w = hl_walls_of_scan(s);
    assert_true(fabs(w.axis - -40 * DEG) < 0.01 * DEG);
    free(s);
}

/* Normals spread evenly round the turn say nothing: R near 0; walls among them still
 * give the axis, with an R between. */
static void test_clutter_lowers_r(void **state)
{
    (void)state;
    hl_scan_t *s = empty_scan();
    for (int k = 0; k < 36; k++)
        add_normal(s, 10 * k, 10 * k + 3);
    hl_walls_t w = hl_walls_of_scan(s);
    assert_true(w.r < 0.01);
    for (int k = 0; k < 36; k++)
        add_normal(s, 10 * k + 5, -20 + 90 * (k % 4));
    w = hl_walls_of_scan(s);
    assert_true(w.r > 0.4 && w.r < 0.6);
    assert_true(fabs(w.axis - -20 * DEG) < 0.5 * DEG);
    free(s);
}

/* A map's axis from its vectors' normals (counted in bins of 0.09 degrees of the axis):
 * a square room turned 25 degrees; no vectors, no axis. */
static void test_map_axis(void **state)
{
    (void)state;
    enum { N = 400 };
    hl_vector_t v[N];
    for (int i = 0; i < N; i++)
        v[i] = (hl_vector_t){ .x_mm = i, .y_mm = 0,
                              .normal = hl_bam_from_deg(25 + 90 * (i % 4) + (i % 7 - 3) * 0.5),
                              .range_mm = 1000 };
    hl_walls_t w = hl_walls_of_vectors(v, N);
    assert_int_equal(w.n, N);
    assert_true(fabs(w.axis - 25 * DEG) < 0.1 * DEG);
    assert_true(w.r > 0.99);
    w = hl_walls_of_vectors(v, 0);
    assert_int_equal(w.n, 0);
    assert_true(w.r == 0);
}

/* The offset from an axis: walls 3 degrees off it at heading 0, a surface 30 degrees off
 * left out by a 10-degree window; at heading -3 degrees the walls lie on it. */
static void test_offset_within_the_window(void **state)
{
    (void)state;
    hl_scan_t *s = empty_scan();
    for (int k = 0; k < 8; k++)
        add_normal(s, 45 * k, 3 + 90 * (k % 4));
    for (int k = 0; k < 4; k++)
        add_normal(s, 45 * k + 20, 30 + 90 * k);
    uint32_t in;
    double off = hl_walls_offset(s, 0, 0, 10 * DEG, &in);
    assert_int_equal(in, 8);
    assert_true(fabs(off - 3 * DEG) < 0.01 * DEG);
    off = hl_walls_offset(s, -3 * DEG, 0, 10 * DEG, &in);
    assert_int_equal(in, 8);
    assert_true(fabs(off) < 0.01 * DEG);
    off = hl_walls_offset(s, 0, 45 * DEG, 10 * DEG, &in);  /* nothing near that axis */
    assert_int_equal(in, 0);
    assert_true(off == 0);
    free(s);
}

/* The tracker: the second scan arrives with the odometry 3 degrees off and the heading
 * left with the odometry (heading_gain 0), normals fitted to the room's walls. Without
 * square walls the heading stays 3 degrees off; with wall_gain 1 the room's walls (its
 * boxes half of them turned) bring it back to within a degree; with 0.5, half way. */
static void test_tracker_heading_turned_by_the_walls(void **state)
{
    (void)state;
    walk_t *w = make_walk(8);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_pose_t second_odom = w->truth[1];
    second_odom.theta = (hl_bam_t)(second_odom.theta + hl_bam_from_deg(3.0));
    const double gains[3] = { 0.0, 1.0, 0.5 };
    int32_t off[3];
    for (int g = 0; g < 3; g++) {
        hl_slam_params_t p;
        ray_sensor_defaults(&p);
        p.fit_normals = true;
        p.heading_gain = 0;
        p.wall_gain = gains[g];
        hl_slam_t *s = hl_slam_create_with(&p);
        assert_non_null(s);
        hl_slam_reset(s, w->truth[0]);
        hl_slam_step_t out;
        sr_sound(&w->room, w->truth[0], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->truth[0], &out), HL_OK);
        sr_sound(&w->room, w->truth[1], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, second_odom, &out), HL_OK);
        assert_int_equal(out.status, HL_SLAM_ACCEPTED);
        off[g] = hl_bam_diff(out.pose.theta, w->truth[1].theta);
        hl_slam_destroy(s);
    }
    assert_true(abs(off[0] - hl_bam_from_deg(3.0)) <= hl_bam_from_deg(0.1));
    assert_true(abs(off[1]) < hl_bam_from_deg(1.0));
    assert_true(abs(off[2] - (off[0] + off[1]) / 2) <= hl_bam_from_deg(0.5));
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.wall_gain = -0.1;
    assert_string_equal(hl_slam_params_error(&p), "wall_gain must be in 0..1");
    free(scan);
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan_axis_of_a_turned_room),
        cmocka_unit_test(test_clutter_lowers_r),
        cmocka_unit_test(test_map_axis),
        cmocka_unit_test(test_offset_within_the_window),
        cmocka_unit_test(test_tracker_heading_turned_by_the_walls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
