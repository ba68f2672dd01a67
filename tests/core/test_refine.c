/* Tests for src/core/refine.c: polishing an offset pose in a synthetic room (position
 * only and with heading), refusals (empty map, no readings, too far, too few matches),
 * capacity, hostile maps, a crowded map against the plain one, and parameter checks. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/refine.h"
#include "synthroom.h"

typedef struct fixture {
    sr_room_t room;
    hl_vector_t map[1500];
    uint32_t n;
    hl_scan_t scan;
    hl_pose_t truth;
    hl_refiner_t *r;
} fixture_t;

static fixture_t *make_fixture(uint64_t seed)
{
    fixture_t *f = calloc(1, sizeof *f);
    sr_room_make(&f->room, -3000, 2000, 9000, 8000, 20, seed);
    f->n = sr_make_map(&f->room, 1500, 128, 8000, 10, f->map);
    f->truth = sr_free_pose(&f->room, 700);
    sr_sound(&f->room, f->truth, 128, 8000, 10, &f->scan);
    hl_refine_params_t p;
    hl_refine_params_default(&p);
    f->r = hl_refine_create(&p, 1500);
    assert_non_null(f->r);
    return f;
}

static void free_fixture(fixture_t *f)
{
    hl_refine_destroy(f->r);
    free(f);
}

static double dist(hl_pose_t a, hl_pose_t b)
{
    return hypot((double)a.x_mm - b.x_mm, (double)a.y_mm - b.y_mm);
}

static hl_pose_t offset(hl_pose_t p, int dx, int dy, double dtheta_deg)
{
    p.x_mm += dx;
    p.y_mm += dy;
    p.theta = (hl_bam_t)(p.theta + hl_bam_from_deg(dtheta_deg));
    return p;
}

/* From 100 mm off, in five rooms: back to within 15 mm, heading untouched. */
static void test_recovers_position(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        fixture_t *f = make_fixture(seed);
        hl_pose_t start = offset(f->truth, 80, -60, 0.0), out;
        assert_int_equal(hl_refine_run(f->r, f->map, f->n, &f->scan, start, false, &out), HL_OK);
        if (dist(out, f->truth) > 15.0)
            fail_msg("seed %llu: %.1f mm from the truth", (unsigned long long)seed,
                     dist(out, f->truth));
        assert_int_equal(out.theta, start.theta);
        free_fixture(f);
    }
}

/* From 100 mm and 2 degrees off: back to within 15 mm and 0.3 degrees. */
static void test_recovers_heading(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        fixture_t *f = make_fixture(seed + 10);
        hl_pose_t start = offset(f->truth, -60, 80, 2.0), out;
        assert_int_equal(hl_refine_run(f->r, f->map, f->n, &f->scan, start, true, &out), HL_OK);
        double dth = fabs(hl_bam_to_sdeg((hl_bam_t)(out.theta - f->truth.theta)));
        if (dist(out, f->truth) > 15.0 || dth > 0.3)
            fail_msg("seed %llu: %.1f mm and %.2f deg from the truth",
                     (unsigned long long)seed, dist(out, f->truth), dth);
        free_fixture(f);
    }
}

static void test_refusals_keep_the_start(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(21);
    hl_pose_t start = offset(f->truth, 50, 0, 0.0), out;
    /* empty map */
    assert_int_equal(hl_refine_run(f->r, f->map, 0, &f->scan, start, false, &out), HL_ERR_EMPTY);
    assert_memory_equal(&out, &start, sizeof out);
    /* no valid reading */
    hl_scan_t *blind = malloc(sizeof *blind);
    *blind = f->scan;
    for (uint32_t i = 0; i < blind->count; i++)
        blind->readings[i].valid = false;
    assert_int_equal(hl_refine_run(f->r, f->map, f->n, blind, start, false, &out), HL_ERR_EMPTY);
    assert_memory_equal(&out, &start, sizeof out);
    /* a map that lies elsewhere: nothing within the match distance */
    hl_vector_t far[64];
    for (int i = 0; i < 64; i++)
        far[i] = (hl_vector_t){ .x_mm = 2000000 + 10 * i, .y_mm = -2000000, .normal = 0,
                                .range_mm = 1000 };
    assert_int_equal(hl_refine_run(f->r, far, 64, &f->scan, start, false, &out), HL_ERR_EMPTY);
    assert_memory_equal(&out, &start, sizeof out);
    /* a start so far off that the answer would move more than max_shift_mm */
    hl_refine_params_t p;
    hl_refine_params_default(&p);
    p.max_shift_mm = 20;
    hl_refiner_t *tight = hl_refine_create(&p, 1500);
    hl_pose_t off = offset(f->truth, 90, 90, 0.0);
    assert_int_equal(hl_refine_run(tight, f->map, f->n, &f->scan, off, false, &out),
                     HL_ERR_EMPTY);
    assert_memory_equal(&out, &off, sizeof out);
    hl_refine_destroy(tight);
    free(blind);
    free_fixture(f);
}

/* Degenerate and extreme maps: every vector on one point, vectors at the coordinate
 * limits, a pose at the limit. No crash; an answer or a refusal. */
static void test_hostile_maps(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(31);
    hl_vector_t *m = calloc(1500, sizeof *m);
    for (int i = 0; i < 1500; i++)
        m[i] = (hl_vector_t){ .x_mm = f->truth.x_mm + 1000, .y_mm = f->truth.y_mm,
                              .normal = 32768, .range_mm = 1000 };
    hl_pose_t out;
    hl_status_t st = hl_refine_run(f->r, m, 1500, &f->scan, f->truth, true, &out);
    assert_true(st == HL_OK || st == HL_ERR_EMPTY);
    for (int i = 0; i < 1500; i++)
        m[i] = (hl_vector_t){ .x_mm = (i % 2 ? 1 : -1) * HL_COORD_MAX_MM,
                              .y_mm = (i % 3 ? 1 : -1) * HL_COORD_MAX_MM,
                              .normal = (hl_bam_t)(i * 977), .range_mm = HL_RANGE_MAX_MM };
    hl_pose_t edge = { HL_COORD_MAX_MM, -HL_COORD_MAX_MM, 12345 };
    st = hl_refine_run(f->r, m, 1500, &f->scan, edge, true, &out);
    assert_true(st == HL_OK || st == HL_ERR_EMPTY);
    assert_true(hl_pose_in_range(out));
    free(m);
    free_fixture(f);
}

/* Does vector i of map m have at least three neighbours (itself included) within the
 * normal radius facing its way, so that its normal is its neighbours' line? */
static bool shaped(const hl_vector_t *m, uint32_t n, uint32_t i)
{
    const double r2 = (double)HL_REFINE_NORMAL_RADIUS_MM * HL_REFINE_NORMAL_RADIUS_MM;
    uint32_t near = 0;
    for (uint32_t j = 0; j < n; j++) {
        double dx = (double)m[j].x_mm - m[i].x_mm, dy = (double)m[j].y_mm - m[i].y_mm;
        near += dx * dx + dy * dy <= r2 && abs(hl_bam_diff(m[i].normal, m[j].normal)) <= 10923;
    }
    return near >= 3;
}

/* A map crowded a hundredfold (every vector of a room's map 100 times over, so that
 * each reading has hundreds of vectors around it, more than a list holds, and is matched
 * from the cells as they lie) polishes to the very same pose as the map itself (matched
 * from the lists): the same neighbours' lines (sums a hundred times larger, the same
 * quotients), the same nearest points. Vectors with too few neighbours to shape a line
 * are left out of both, as a hundred copies of one would shape one. */
static void test_crowded_map_polishes_as_the_plain_one(void **state)
{
    (void)state;
    enum { COPIES = 100 };
    for (uint64_t seed = 1; seed <= 3; seed++) {
        fixture_t *f = make_fixture(seed + 50);
        uint32_t n = f->n;
        for (bool dropped = true; dropped;) {
            dropped = false;
            for (uint32_t i = 0; i < n; i++)
                if (!shaped(f->map, n, i)) {
                    f->map[i--] = f->map[--n];
                    dropped = true;
                }
        }
        assert_true(n > 500);
        hl_vector_t *crowd = malloc((size_t)n * COPIES * sizeof *crowd);
        for (uint32_t i = 0; i < n * COPIES; i++)
            crowd[i] = f->map[i / COPIES];
        hl_refine_params_t p;
        hl_refine_params_default(&p);
        hl_refiner_t *big = hl_refine_create(&p, n * COPIES);
        assert_non_null(big);
        hl_pose_t starts[2] = { offset(f->truth, 80, -60, 0.0), offset(f->truth, -60, 80, 2.0) };
        for (int k = 0; k < 2; k++) {
            hl_pose_t plain, crowded;
            hl_status_t a = hl_refine_run(f->r, f->map, n, &f->scan, starts[k], k == 1, &plain);
            hl_status_t b = hl_refine_run(big, crowd, n * COPIES, &f->scan, starts[k], k == 1,
                                          &crowded);
            assert_int_equal(a, HL_OK);
            assert_int_equal(b, a);
            assert_memory_equal(&crowded, &plain, sizeof plain);
        }
        hl_refine_destroy(big);
        free(crowd);
        free_fixture(f);
    }
}

static void test_params_and_inputs_validated(void **state)
{
    (void)state;
    hl_refine_params_t p;
    hl_refine_params_default(&p);
    assert_null(hl_refine_params_error(&p));
    assert_non_null(hl_refine_params_error(NULL));
    assert_null(hl_refine_create(&p, 0));
    p.match_mm = 0;
    assert_non_null(hl_refine_params_error(&p));
    assert_null(hl_refine_create(&p, 10));
    hl_refine_params_default(&p);
    p.iterations = 0;
    assert_non_null(hl_refine_params_error(&p));
    hl_refine_params_default(&p);
    p.huber_mm = 0;
    assert_non_null(hl_refine_params_error(&p));
    hl_refine_destroy(NULL);

    fixture_t *f = make_fixture(41);
    hl_pose_t out;
    assert_int_equal(hl_refine_run(NULL, f->map, f->n, &f->scan, f->truth, false, &out),
                     HL_ERR_ARG);
    assert_int_equal(hl_refine_run(f->r, NULL, f->n, &f->scan, f->truth, false, &out),
                     HL_ERR_ARG);
    assert_int_equal(hl_refine_run(f->r, f->map, f->n, NULL, f->truth, false, &out), HL_ERR_ARG);
    assert_int_equal(hl_refine_run(f->r, f->map, f->n, &f->scan, f->truth, false, NULL),
                     HL_ERR_ARG);
    assert_int_equal(hl_refine_run(f->r, f->map, 1501, &f->scan, f->truth, false, &out),
                     HL_ERR_CAPACITY);
    hl_pose_t outside = { HL_COORD_MAX_MM + 1, 0, 0 };
    assert_int_equal(hl_refine_run(f->r, f->map, f->n, &f->scan, outside, false, &out),
                     HL_ERR_RANGE);
    f->scan.count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_refine_run(f->r, f->map, f->n, &f->scan, f->truth, false, &out),
                     HL_ERR_RANGE);
    assert_true(hl_refine_mem_bytes(f->r) > 1500 * sizeof(double));
    free_fixture(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recovers_position),
        cmocka_unit_test(test_recovers_heading),
        cmocka_unit_test(test_refusals_keep_the_start),
        cmocka_unit_test(test_hostile_maps),
        cmocka_unit_test(test_crowded_map_polishes_as_the_plain_one),
        cmocka_unit_test(test_params_and_inputs_validated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
