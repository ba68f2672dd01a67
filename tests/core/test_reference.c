/* The fixed-point localizer against the floating-point reference (tests/support):
 * on randomized scenes the peak cell is the same and the interpolated poses agree
 * within half a cell (and half a heading step).
 *
 * "The same" allows one thing: a tie at the fixed-point resolution. When the fixed
 * surface has the reference's peak cell within 2/256 of a vote of its own peak, the
 * two cells are equal to the precision the blurred raster keeps (fixed.h), and either
 * is a correct answer. At most one scene in eight may be such a tie (measured: 4 of
 * 400 scenes).
 *
 * With group_mm > 0 nearby map vectors vote together (localize.h): those runs are held
 * to a pose within a cell of the reference's instead. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "houghloc/localize.h"
#include "ref_localize.h"
#include "synthroom.h"

#define SCENES 24

typedef struct scene {
    sr_room_t room;
    hl_vector_t map[1500];
    uint32_t n;
    hl_scan_t scan;
    hl_pose_t truth;
} scene_t;

static void make_scene(scene_t *s, uint64_t seed)
{
    /* size, clutter and noise vary with the seed */
    double w = 6000 + 1000 * (double)(seed % 5), h = 6000 + 1000 * (double)(seed % 3);
    sr_room_make(&s->room, -3000.0 * (double)(seed % 4), 1000.0 * (double)(seed % 7), w, h,
                 10 + (int)(seed % 20), 1000 + seed);
    s->n = sr_make_map(&s->room, 600 + 150 * (uint32_t)(seed % 7), 128, 8000, 5 + (double)(seed % 15), s->map);
    s->truth = sr_free_pose(&s->room, 600);
    sr_sound(&s->room, s->truth, 128, 8000, 10, &s->scan);
}

/* A global search with the heading known, or a local one from a prediction off by a
 * typical odometry error. */
static hl_loc_query_t scene_query(const scene_t *s, bool local)
{
    hl_loc_query_t q = { .predicted = s->truth, .window_mm = 0, .search_theta = false };
    if (local) {
        q.predicted.x_mm += 130;
        q.predicted.y_mm -= 170;
        q.predicted.theta = (hl_bam_t)(q.predicted.theta + hl_bam_from_deg(2.5));
        q.window_mm = 800;
        q.search_theta = true;
    }
    return q;
}

/* Grouped voting (group_mm > 0, localize.h) moves each vote by less than a group's
 * half-diagonal: against the reference the pose stays within `tol_mm` and a heading
 * step, and the votes within 3 %. With group_mm = 0 the checks above are exact. */
static void compare_grouped(const hl_loc_params_t *p, bool local, double tol_mm)
{
    hl_localizer_t *loc = hl_loc_create(p);
    ref_localizer_t *ref = ref_create(p);
    scene_t *s = malloc(sizeof *s);
    assert_non_null(loc);
    assert_non_null(ref);
    double worst = 0;
    for (uint64_t seed = 1; seed <= SCENES; seed++) {
        make_scene(s, seed + (local ? 100 : 0));
        hl_loc_query_t q = scene_query(s, local);
        hl_loc_result_t r;
        ref_result_t rr;
        assert_int_equal(hl_loc_run(loc, s->map, s->n, &s->scan, &q, &r), HL_OK);
        assert_int_equal(ref_run(ref, s->map, s->n, &s->scan, &q, &rr), 0);
        double d = hypot(r.pose.x_mm - rr.x_mm, r.pose.y_mm - rr.y_mm);
        worst = d > worst ? d : worst;
        if (d > tol_mm)
            fail_msg("scene %llu: grouped pose %.1f mm from the reference's", (unsigned long long)seed, d);
        double dt = hl_bam_diff(r.pose.theta, (hl_bam_t)(int64_t)lround(rr.theta_bam));
        assert_true(fabs(dt) <= p->theta_step + 1);
        assert_true(labs((long)r.votes - rr.votes) <= rr.votes * 3 / 100 + 5);
    }
    print_message("grouped by %d mm: worst %.1f mm from the reference\n", p->group_mm, worst);
    free(s);
    ref_destroy(ref);
    hl_loc_destroy(loc);
}

static void compare(const hl_loc_params_t *p, bool local)
{
    hl_localizer_t *loc = hl_loc_create(p);
    ref_localizer_t *ref = ref_create(p);
    scene_t *s = malloc(sizeof *s);
    assert_non_null(loc);
    assert_non_null(ref);
    int ties = 0;
    for (uint64_t seed = 1; seed <= SCENES; seed++) {
        make_scene(s, seed + (local ? 100 : 0));
        hl_loc_query_t q = scene_query(s, local);
        hl_loc_result_t r;
        ref_result_t rr;
        assert_int_equal(hl_loc_run(loc, s->map, s->n, &s->scan, &q, &r), HL_OK);
        assert_int_equal(ref_run(ref, s->map, s->n, &s->scan, &q, &rr), 0);
        if (r.ix != rr.ix || r.iy != rr.iy || r.it != rr.it) {
            hl_loc_surface_t sf;
            hl_loc_get_surface(loc, &sf);
            uint32_t at_ref = sf.cells[((size_t)rr.it * sf.ny + rr.iy) * sf.nx + rr.ix];
            if (r.peak - at_ref <= 2 && ++ties <= SCENES / 8)
                continue;
            fail_msg("scene %llu: fixed cell (%d %d %d) peak %u, reference (%d %d %d) peak %.0f",
                     (unsigned long long)seed, r.ix, r.iy, r.it, r.peak, rr.ix, rr.iy, rr.it,
                     rr.peak);
        }
        assert_true(fabs(r.pose.x_mm - rr.x_mm) <= p->cell_mm / 2.0);
        assert_true(fabs(r.pose.y_mm - rr.y_mm) <= p->cell_mm / 2.0);
        double dt = hl_bam_diff(r.pose.theta, (hl_bam_t)(int64_t)lround(rr.theta_bam));
        assert_true(fabs(dt) <= p->theta_step / 2.0 + 1);
        /* same votes up to trig rounding at cell borders: within 2 % */
        assert_true(labs((long)r.votes - rr.votes) <= rr.votes / 50 + 5);
        /* blurred peak heights agree within 10 % */
        assert_true(fabs(r.peak - rr.peak) <= 0.1 * rr.peak);
    }
    free(s);
    ref_destroy(ref);
    hl_loc_destroy(loc);
}

/* The exact method: every vector votes alone (the default). */
static void exact_params(hl_loc_params_t *p)
{
    hl_loc_params_default(p);
    p->group_mm = 0;
    p->max_cells = 1u << 19;
}

static void test_global_xy_matches_reference(void **state)
{
    (void)state;
    hl_loc_params_t p;
    exact_params(&p);
    compare(&p, false);
}

static void test_local_xyt_matches_reference(void **state)
{
    (void)state;
    hl_loc_params_t p;
    exact_params(&p);
    compare(&p, true);
}

static void test_grouped_global_near_reference(void **state)
{
    (void)state;
    hl_loc_params_t p;
    exact_params(&p);
    p.group_mm = 48;
    compare_grouped(&p, false, 24);
}

static void test_grouped_local_near_reference(void **state)
{
    (void)state;
    hl_loc_params_t p;
    exact_params(&p);
    p.group_mm = 48;
    compare_grouped(&p, true, 24);
}

static void test_coarse_raster_matches_reference(void **state)
{
    (void)state;
    hl_loc_params_t p;
    exact_params(&p);
    p.cell_mm = 47;
    p.blur_sigma_mm = 60;
    p.max_cells = 1u << 19;
    compare(&p, true);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_global_xy_matches_reference),
        cmocka_unit_test(test_local_xyt_matches_reference),
        cmocka_unit_test(test_coarse_raster_matches_reference),
        cmocka_unit_test(test_grouped_global_near_reference),
        cmocka_unit_test(test_grouped_local_near_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
