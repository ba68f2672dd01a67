/* Tests for src/core/corrmatch.c: the correlative search finds a scan's pose in a map of
 * the room drawn from elsewhere, from anywhere in its window; the best pose equals the
 * exhaustive search's over the same poses; a corridor's length is told apart from one
 * place by the runner-up; and bad arguments are refused. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/corrmatch.h"
#include "synthroom.h"

#define PI 3.14159265358979323846
#define READINGS 360

typedef struct world {
    sr_room_t room;
    hl_scan_t scan;
    hl_corr_point_t map[HL_CORR_MAX_POINTS], query[HL_CORR_MAX_POINTS];
    uint32_t n_map, n_query;
} world_t;

/* The map: soundings to @p range_mm from @p n_views poses at the truth; the query: a
 * sounding at @p at in the robot's frame. */
static void sound_to(world_t *w, const hl_pose_t *views, int n_views, hl_pose_t at,
                     double range_mm)
{
    w->n_map = 0;
    for (int i = 0; i < n_views; i++) {
        sr_sound(&w->room, views[i], READINGS, range_mm, 5, &w->scan);
        w->n_map = hl_corr_points(&w->scan, hl_pg_from_pose(views[i]), w->map, w->n_map,
                                  HL_CORR_MAX_POINTS);
    }
    sr_sound(&w->room, at, READINGS, range_mm, 5, &w->scan);
    w->n_query = hl_corr_points(&w->scan, (hl_pg_pose_t){ 0, 0, 0 }, w->query, 0,
                                HL_CORR_MAX_POINTS);
}

static void sound(world_t *w, const hl_pose_t *views, int n_views, hl_pose_t at)
{
    sound_to(w, views, n_views, at, 12000);
}

/* A region of +-@p mm and +-@p deg, any best pose an answer, the runner-up sought down
 * down to 0.8 of it. */
static hl_corr_params_t region(double mm, double deg)
{
    return (hl_corr_params_t){ mm, deg * PI / 180, 0, 0.8, 250, 5 * PI / 180 };
}

static double turn_deg(double a, double b)
{
    return fabs(remainder(a - b, 2 * PI)) * 180 / PI;
}

static void test_finds_the_pose_from_anywhere_in_its_window(void **state)
{
    (void)state;
    world_t *w = calloc(1, sizeof *w);
    hl_corr_t *c = hl_corr_create();
    assert_non_null(c);
    sr_room_make(&w->room, 0, 0, 10000, 8000, 10, 3);
    hl_pose_t views[2] = { { 3000, 3000, 0 }, { 6500, 4500, hl_bam_from_deg(120) } };
    hl_pose_t truth = { 5000, 3500, hl_bam_from_deg(40) };
    sound(w, views, 2, truth);
    static const double off[][3] = { { 0, 0, 0 }, { 700, -500, 6 }, { -900, 850, -9 },
                                      { 40, 20, 0.5 } };
    for (size_t k = 0; k < sizeof off / sizeof off[0]; k++) {
        hl_pg_pose_t t = hl_pg_from_pose(truth);
        hl_pg_pose_t center = { t.x + off[k][0], t.y + off[k][1], t.theta + off[k][2] * PI / 180 };
        hl_corr_result_t r;
        hl_corr_params_t p = region(1000, 10);
        assert_true(hl_corr_search(c, w->map, w->n_map, w->query, w->n_query, center, &p, &r));
        assert_true(r.matched);     /* a cluttered room: one place, no runner-up */
        assert_true(hypot(r.pose.x - t.x, r.pose.y - t.y) < 20);
        assert_true(turn_deg(r.pose.theta, t.theta) < 0.3);
        assert_true(r.score > 0.6);
        assert_true(r.runner_up == 0);
    }
    /* Outside the window it is not found there. */
    hl_pg_pose_t t = hl_pg_from_pose(truth);
    hl_corr_result_t r;
    hl_corr_params_t near = region(500, 3);
    assert_true(hl_corr_search(c, w->map, w->n_map, w->query, w->n_query,
                               (hl_pg_pose_t){ t.x + 1500, t.y, t.theta }, &near, &r));
    assert_true(hypot(r.pose.x - t.x, r.pose.y - t.y) > 900);
    /* ... and with a floor above what it finds there, nothing is. */
    near.min_score = 0.9;
    assert_true(hl_corr_search(c, w->map, w->n_map, w->query, w->n_query,
                               (hl_pg_pose_t){ t.x + 1500, t.y, t.theta }, &near, &r));
    assert_false(r.matched);
    assert_true(r.score == 0);
    hl_corr_destroy(c);
    free(w);
}

/* The mean field value of the query at a pose, as the search scores a leaf, but read from
 * a brute-force field (every map point's Gaussian, the nearest kept). */
static double brute_score(const world_t *w, hl_pg_pose_t p)
{
    double sum = 0, cs = cos(p.theta), sn = sin(p.theta);
    for (uint32_t k = 0; k < w->n_query; k++) {
        double x = p.x + cs * w->query[k].x - sn * w->query[k].y;
        double y = p.y + sn * w->query[k].x + cs * w->query[k].y;
        double best = 0;
        for (uint32_t j = 0; j < w->n_map; j++) {
            double d2 = pow(x - w->map[j].x, 2) + pow(y - w->map[j].y, 2);
            best = fmax(best, exp(-d2 / (2 * HL_CORR_SIGMA_MM * HL_CORR_SIGMA_MM)));
        }
        sum += best;
    }
    return sum / w->n_query;
}

/* The branch and bound prunes nothing it should not: its answer scores (by a field made
 * without the search's grid) at least as well as the best of a coarse exhaustive sweep. */
static void test_as_good_as_an_exhaustive_sweep(void **state)
{
    (void)state;
    world_t *w = calloc(1, sizeof *w);
    hl_corr_t *c = hl_corr_create();
    sr_room_make(&w->room, 0, 0, 9000, 7000, 14, 11);
    hl_pose_t views[1] = { { 4000, 3000, 0 } };
    hl_pose_t truth = { 4400, 3300, hl_bam_from_deg(-25) };
    sound(w, views, 1, truth);
    w->n_query = 90;    /* a few points: the brute-force field is slow */
    hl_pg_pose_t center = { 4200, 3500, hl_bam_to_rad(hl_bam_from_deg(-22)) };
    hl_corr_result_t r;
    hl_corr_params_t p = region(400, 4);
    p.runner_share = 1;
    assert_true(hl_corr_search(c, w->map, w->n_map, w->query, w->n_query, center, &p, &r));
    assert_true(r.matched);
    double found = brute_score(w, r.pose), sweep = 0;
    for (double dx = -400; dx <= 400; dx += 50)
        for (double dy = -400; dy <= 400; dy += 50)
            for (double da = -4; da <= 4; da += 1)
                sweep = fmax(sweep, brute_score(w, (hl_pg_pose_t){ center.x + dx, center.y + dy,
                                                                  center.theta + da * PI / 180 }));
    assert_true(found >= sweep - 0.01);
    assert_true(fabs(found - r.score) < 0.05);  /* the search's field is the same field */
    hl_corr_destroy(c);
    free(w);
}

/* Two long walls and nothing else: every place along them looks alike, so the runner-up
 * a metre along scores as well as the best. */
static void test_a_corridor_has_a_runner_up(void **state)
{
    (void)state;
    world_t *w = calloc(1, sizeof *w);
    hl_corr_t *c = hl_corr_create();
    sr_room_make(&w->room, 0, 0, 30000, 2000, 0, 1);
    hl_pose_t views[2] = { { 9000, 1000, 0 }, { 15000, 1000, 0 } };
    hl_pose_t truth = { 12000, 1000, 0 };
    sound_to(w, views, 2, truth, 5000);    /* short range: the corridor's ends out of sight */
    hl_corr_result_t r;
    hl_corr_params_t p = region(1500, 3);
    p.runner_share = 0.9;
    assert_true(hl_corr_search(c, w->map, w->n_map, w->query, w->n_query,
                               hl_pg_from_pose(truth), &p, &r));
    assert_false(r.matched);
    assert_true(r.score > 0.6);
    assert_true(r.runner_up >= 0.9 * r.score);
    hl_corr_destroy(c);
    free(w);
}

static void test_bad_arguments_refused(void **state)
{
    (void)state;
    hl_corr_t *c = hl_corr_create();
    hl_corr_point_t p[2] = { { 1000, 0 }, { 0, 1000 } };
    hl_corr_result_t r;
    hl_pg_pose_t o = { 0, 0, 0 };
    hl_corr_params_t ok = region(100, 5), bad;
    assert_false(hl_corr_search(c, p, 0, p, 2, o, &ok, &r));
    assert_false(hl_corr_search(c, p, 2, p, 0, o, &ok, &r));
    assert_false(hl_corr_search(c, p, HL_CORR_MAX_POINTS + 1, p, 2, o, &ok, &r));
    bad = ok, bad.window_mm = NAN;
    assert_false(hl_corr_search(c, p, 2, p, 2, o, &bad, &r));
    bad = ok, bad.window_rad = -1;
    assert_false(hl_corr_search(c, p, 2, p, 2, o, &bad, &r));
    bad = ok, bad.min_score = 1.5;
    assert_false(hl_corr_search(c, p, 2, p, 2, o, &bad, &r));
    bad = ok, bad.runner_share = NAN;
    assert_false(hl_corr_search(c, p, 2, p, 2, o, &bad, &r));
    bad = ok, bad.window_mm = HL_CORR_MAX_WINDOW_MM + 1;     /* a region too large */
    assert_false(hl_corr_search(c, p, 2, p, 2, o, &bad, &r));
    hl_corr_point_t long_p[2] = { { 20000, 0 }, { 0, 20000 } };
    bad = ok, bad.window_rad = 7;      /* too many turns */
    assert_false(hl_corr_search(c, long_p, 2, long_p, 2, o, &bad, &r));
    /* Points far apart: no field between the query's reach and the map. */
    hl_corr_point_t far[1] = { { 3e7f, 3e7f } };
    assert_true(hl_corr_search(c, p, 2, p, 2, o, &ok, &r));
    assert_false(hl_corr_search(c, far, 1, p, 2, o, &ok, &r));
    hl_corr_destroy(c);
    hl_corr_destroy(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_finds_the_pose_from_anywhere_in_its_window),
        cmocka_unit_test(test_as_good_as_an_exhaustive_sweep),
        cmocka_unit_test(test_a_corridor_has_a_runner_up),
        cmocka_unit_test(test_bad_arguments_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
