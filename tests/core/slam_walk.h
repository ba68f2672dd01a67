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

static inline double dist(hl_pose_t a, hl_pose_t b)
{
    return hypot((double)a.x_mm - b.x_mm, (double)a.y_mm - b.y_mm);
}

static inline void assert_pose_equal(hl_pose_t a, hl_pose_t b)
{
    assert_int_equal(a.x_mm, b.x_mm);
    assert_int_equal(a.y_mm, b.y_mm);
    assert_int_equal(a.theta, b.theta);
}

#endif
