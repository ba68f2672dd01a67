/* slam_walk.h - what tests/core/test_slam.c and test_slam_growth.c share: a random walk
 * through a synthetic room with noisy odometry, the defaults for its thin-ray sensor,
 * and pose comparisons. Header-only (static inline): each test program is one file. */
#ifndef HOUGHLOC_TESTS_SLAM_WALK_H
#define HOUGHLOC_TESTS_SLAM_WALK_H

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/slam_params.h"
#include "synthroom.h"

#define STEPS 40

typedef struct walk {
    sr_room_t room;
    hl_pose_t truth[STEPS];
    hl_pose_t odom[STEPS];
} walk_t;

/* A walk of 400 mm steps; odometry accumulates 5 % of distance and 2 deg per metre of
 * Gaussian error per step. The map starts at the first true pose. */
static inline walk_t *make_walk(uint64_t seed)
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
 * readings already lie where they echoed and echo-bearing estimation stays off; and the
 * tracker alone, without the LOST state (whose tests turn it on). */
static inline void ray_sensor_defaults(hl_slam_params_t *p)
{
    hl_slam_params_default(p);
    p->echo_bearings = false;
    p->lost_after = 0;
    p->search_every = 0;
}

/* A tracker on a walk: the walk, the slam (reset at the walk's first true pose) and a
 * scan to sound into. */
typedef struct walk_run {
    walk_t *w;
    hl_slam_t *s;
    hl_scan_t *scan;
} walk_run_t;

static inline walk_run_t walk_run_start(uint64_t seed, const hl_slam_params_t *p)
{
    walk_run_t r = { .w = make_walk(seed), .scan = malloc(sizeof *r.scan) };
    r.s = hl_slam_create_with(p);
    assert_non_null(r.s);
    hl_slam_reset(r.s, r.w->truth[0]);
    return r;
}

static inline void walk_run_finish(walk_run_t *r)
{
    hl_slam_destroy(r->s);
    free(r->scan);
    free(r->w);
}

static inline double dist(hl_pose_t a, hl_pose_t b)
{
    return hypot((double)a.x_mm - b.x_mm, (double)a.y_mm - b.y_mm);
}

/* The step before @p upto - 5 farthest from step @p upto - 1, where the walk stands after
 * @p upto steps: where a kidnapper sets the robot down, in the part of the room the map
 * of those steps knows (more than 1.5 m away). */
static inline int walk_far_step(const walk_t *w, int upto)
{
    int best = 0;
    for (int i = 0; i < upto - 5; i++)
        if (dist(w->truth[i], w->truth[upto - 1]) > dist(w->truth[best], w->truth[upto - 1]))
            best = i;
    assert_true(dist(w->truth[best], w->truth[upto - 1]) > 1500);
    return best;
}

static inline void assert_pose_equal(hl_pose_t a, hl_pose_t b)
{
    assert_int_equal(a.x_mm, b.x_mm);
    assert_int_equal(a.y_mm, b.y_mm);
    assert_int_equal(a.theta, b.theta);
}

#endif
