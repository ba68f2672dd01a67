/* Tests for src/core/slam.c, its state: saved state and restore continue identically,
 * bad restores are refused, set_pose, and an update that fails changes nothing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/slam_search.h"
#include "slam_walk.h"

/* Every field of two steps, one by one (struct padding is not compared). */

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
        hl_slam_t *a = hl_slam_create_with(&p);
        p.seed = 12345;
        hl_slam_t *b = hl_slam_create_with(&p);
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
    hl_slam_t *s = hl_slam_create_with(&p);
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
    hl_slam_t *s = hl_slam_create_with(&p);
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
    uint32_t count = hl_map_count(m);
    uint64_t version = hl_map_version(m);

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
 * bounding box needs more raster than max_cells): hl_slam_update returns it, answers the
 * prediction, and the state and map are as before, started or not. */
static void test_failed_update_changes_nothing(void **state)
{
    (void)state;
    walk_t *w = make_walk(12);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.window_mm = 0;    /* global: the raster covers the map's bounding box */
    hl_slam_t *s = hl_slam_create_with(&p);
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
        /* the step answers the prediction, and nothing went into the map */
        hl_pose_t predicted = started ? hl_pose_compose(st.pose, hl_pose_between(st.odom, moved))
                                      : st.pose;
        assert_int_equal(out.status, HL_SLAM_ODOMETRY_ONLY);
        assert_int_equal(out.added, 0);
        assert_pose_equal(out.pose, predicted);
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
    hl_slam_t *s = hl_slam_create_with(&p);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_restore_continues_identically),
        cmocka_unit_test(test_restore_refuses_bad_input),
        cmocka_unit_test(test_set_pose),
        cmocka_unit_test(test_failed_update_changes_nothing),
        cmocka_unit_test(test_update_beyond_the_edge_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
