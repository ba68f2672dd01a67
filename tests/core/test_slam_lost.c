/* Tests for src/core/slam_lost.c: the tracker's recovery through hl_slam_update alone, as a
 * program embedding the library meets it. A robot told it is lost is found where it is;
 * a robot carried to another mapped place is noticed by the periodic global search, or
 * after a run of doubtful scans, relocalized and confirmed by the next scan; a pose set by
 * hand or hl_slam_stop_searching ends the lost state; the lost scans the search takes
 * together are kept apart; the parameters are checked. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/slam_params.h"
#include "slam_walk.h"

/* Steps of the walk that make the map before anything happens. */
#define MAPPED 30

typedef walk_run_t run_t;

static run_t start(uint64_t seed, int32_t lost_after, int32_t search_every)
{
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.lost_after = lost_after;
    p.search_every = search_every;
    return walk_run_start(seed, &p);
}

static void finish(run_t *r)
{
    walk_run_finish(r);
}

/* One scan sounded at @p truth, the base's odometry saying @p odometry. */
static hl_slam_step_t sound(run_t *r, hl_pose_t truth, hl_pose_t odometry)
{
    sr_sound(&r->w->room, truth, 128, 8000, 15, r->scan);
    hl_slam_step_t out;
    assert_int_equal(hl_slam_update(r->s, r->scan, odometry, &out), HL_OK);
    return out;
}

static void map_the_walk(run_t *r)
{
    for (int i = 0; i < MAPPED; i++)
        sound(r, r->w->truth[i], r->w->odom[i]);
    assert_false(hl_slam_lost(r->s));
}

/* Where a kidnapper sets the robot down after MAPPED steps. */
static int far_step(const run_t *r)
{
    return walk_far_step(r->w, MAPPED);
}

/* Told it is lost where it stands: the next scan searches, finds the robot where
 * tracking puts it too, and tracking goes on. */
static void test_lost_by_command_found_in_place(void **state)
{
    (void)state;
    run_t r = start(21, 0, 0);
    map_the_walk(&r);
    hl_slam_lose(r.s);
    assert_true(hl_slam_lost(r.s));
    assert_int_equal(hl_slam_lost_epoch(r.s), 1);
    hl_slam_step_t out = sound(&r, r.w->truth[MAPPED], r.w->odom[MAPPED]);
    assert_true(out.searched_lost);
    assert_int_equal(out.search_status, HL_OK);
    assert_int_equal(out.found_how, HL_SLAM_FOUND_AGREES);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);
    assert_false(hl_slam_lost(r.s));
    assert_true(dist(out.pose, r.w->truth[MAPPED]) < 150);
    finish(&r);
}

/* Carried from the end of the walk to a far step with the wheels still: the periodic
 * search puts the scan there (RELOCALIZED, lost), and the next scan, a step further,
 * confirms it. */
static void test_carried_away_noticed_by_the_search(void **state)
{
    (void)state;
    run_t r = start(22, 0, 1);
    map_the_walk(&r);
    int k = far_step(&r);
    hl_pose_t still = r.w->odom[MAPPED - 1];
    hl_slam_step_t out = sound(&r, r.w->truth[k], still);
    assert_int_equal(out.status, HL_SLAM_RELOCALIZED);
    assert_int_equal(out.lost_why, HL_SLAM_LOST_ELSEWHERE);
    assert_true(out.search.found);
    assert_true(out.search.score > out.tracked_score);
    assert_true(dist(out.pose, r.w->truth[k]) < 300);
    assert_true(hl_slam_lost(r.s));

    /* the next step of the walk, the odometry moved by it */
    hl_pose_t moved = hl_pose_compose(still, hl_pose_between(r.w->truth[k], r.w->truth[k + 1]));
    out = sound(&r, r.w->truth[k + 1], moved);
    assert_int_equal(out.found_how, HL_SLAM_FOUND_CONFIRMED);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);
    assert_false(hl_slam_lost(r.s));
    assert_true(dist(out.pose, r.w->truth[k + 1]) < 300);
    finish(&r);
}

/* The same kidnap without the periodic search: tracking rejects the scans (wild), and
 * after lost_after of them in a row the tracker is lost and searches on that scan. */
static void test_doubtful_run_makes_it_lost(void **state)
{
    (void)state;
    run_t r = start(22, 2, 0);
    map_the_walk(&r);
    int k = far_step(&r);
    hl_pose_t still = r.w->odom[MAPPED - 1];
    hl_slam_step_t out = sound(&r, r.w->truth[k], still);
    assert_int_equal(out.status, HL_SLAM_REJECTED_WILD);
    assert_false(hl_slam_lost(r.s));
    out = sound(&r, r.w->truth[k], still);
    assert_int_equal(out.lost_why, HL_SLAM_LOST_DOUBTFUL);
    assert_int_equal(out.doubtful_run, 2);
    assert_true(out.searched_lost);
    assert_int_equal(out.status, HL_SLAM_RELOCALIZED);
    assert_true(dist(out.pose, r.w->truth[k]) < 300);
    assert_int_equal(hl_slam_lost_epoch(r.s), 1);
    finish(&r);
}

/* A pose set by hand ends the lost state, as does giving up the search; each entry
 * counts in the epoch. */
static void test_set_pose_and_stop_searching_end_it(void **state)
{
    (void)state;
    run_t r = start(23, 0, 0);
    map_the_walk(&r);
    hl_slam_lose(r.s);
    assert_int_equal(hl_slam_set_pose(r.s, r.w->truth[MAPPED - 1], r.w->odom[MAPPED - 1]),
                     HL_OK);
    assert_false(hl_slam_lost(r.s));
    hl_slam_lose(r.s);
    hl_slam_stop_searching(r.s);
    assert_false(hl_slam_lost(r.s));
    hl_slam_stop_searching(r.s);    /* not lost: nothing happens */
    assert_int_equal(hl_slam_lost_epoch(r.s), 2);
    /* and tracking goes on from the estimate */
    hl_slam_step_t out = sound(&r, r.w->truth[MAPPED], r.w->odom[MAPPED]);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);
    assert_int_equal(out.found_how, HL_SLAM_FOUND_NOT);
    assert_false(out.searched_lost);
    finish(&r);
}

/* While lost the search takes the scans kept 0.5 m or 30 degrees apart (reloc.scans of
 * them): a scan nearer the newest kept one replaces it. The search here never answers
 * found (a bar no pose clears), so the tracker stays lost and reports each search. */
static void test_lost_scans_kept_apart(void **state)
{
    (void)state;
    run_t r = { .w = make_walk(5), .scan = malloc(sizeof *r.scan) };
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.lost_after = 50;          /* tracking alone does not end it within this test */
    p.reloc.min_explained_pct = 100.0;
    p.reloc.max_ratio = 0.01;
    assert_int_equal(p.reloc.scans, 3);
    r.s = hl_slam_create_with(&p);
    assert_non_null(r.s);
    hl_slam_reset(r.s, r.w->truth[0]);
    map_the_walk(&r);
    hl_slam_lose(r.s);
    /* the robot stands still; its odometry says where it went */
    hl_pose_t at = r.w->truth[MAPPED - 1], odo = r.w->odom[MAPPED - 1];
    struct { int32_t forward_mm; double turn_deg; uint16_t scans; } moves[] = {
        { 0, 0, 1 },        /* the first lost scan */
        { 100, 0, 1 },      /* 0.1 m on: replaces it */
        { 500, 0, 2 },      /* 0.6 m from the kept one */
        { 0, 35, 3 },       /* turned 35 degrees */
        { 200, 0, 3 },      /* near: replaces the newest */
        { 600, 0, 3 },      /* apart: the oldest goes */
    };
    for (size_t i = 0; i < sizeof moves / sizeof moves[0]; i++) {
        odo = hl_pose_compose(odo, (hl_pose_t){ moves[i].forward_mm, 0,
                                                hl_bam_from_deg(moves[i].turn_deg) });
        hl_slam_step_t out = sound(&r, at, odo);
        assert_true(hl_slam_lost(r.s));
        assert_int_equal(out.status, HL_SLAM_LOST);
        assert_true(out.searched_lost);
        assert_int_equal(out.search.scans, moves[i].scans);
    }
    finish(&r);
}

static void test_params_checked(void **state)
{
    (void)state;
    hl_slam_params_t p;
    hl_slam_params_default(&p);
    assert_null(hl_slam_params_error(&p));
    assert_int_equal(p.lost_after, 2);      /* on: the search answers wrong on <= 1 % */
    assert_int_equal(p.search_every, 10);   /* and on every scan in doubt */
    p.lost_after = -1;
    assert_non_null(hl_slam_params_error(&p));
    hl_slam_params_default(&p);
    p.search_every = 1000001;
    assert_non_null(hl_slam_params_error(&p));
    assert_null(hl_slam_create_with(&p));
    /* NULL is safe */
    assert_false(hl_slam_lost(NULL));
    assert_int_equal(hl_slam_lost_epoch(NULL), 0);
    hl_slam_lose(NULL);
    hl_slam_stop_searching(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lost_by_command_found_in_place),
        cmocka_unit_test(test_carried_away_noticed_by_the_search),
        cmocka_unit_test(test_doubtful_run_makes_it_lost),
        cmocka_unit_test(test_set_pose_and_stop_searching_end_it),
        cmocka_unit_test(test_lost_scans_kept_apart),
        cmocka_unit_test(test_params_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
