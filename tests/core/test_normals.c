/* Tests for src/core/normals.c: a laser's readings of a wall seen obliquely get the
 * wall's normal; a corner's reading and a lone return have no line and are dropped; a
 * surface at grazing incidence is dropped; the normal is what the map and the localizer
 * use (hl_vector_from_reading); hostile scans and parameter checks. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "houghloc-internal/map.h"
#include "houghloc-internal/normals.h"

#define PI 3.14159265358979323846

/* Range along bearing b (deg) to the line x cos(n) + y sin(n) = d (normal n deg away
 * from the robot), or -1 when the beam runs away from it. */
static int32_t line_range(double b_deg, double n_deg, double d_mm)
{
    double c = cos((b_deg - n_deg) * PI / 180.0);
    return c > 1e-6 ? (int32_t)lround(d_mm / c) : -1;
}

/* A 180-beam laser, one degree apart from -90 to +89, seeing one wall whose normal
 * (away from the robot) is at @p n_deg, @p d_mm away; beams that miss it return nothing. */
static void wall_scan(hl_scan_t *s, double n_deg, double d_mm)
{
    hl_scan_clear(s);
    for (int i = 0; i < 180; i++) {
        double b = -90.0 + i;
        int32_t r = line_range(b, n_deg, d_mm);
        bool ok = r > 0 && r <= HL_RANGE_MAX_MM;
        assert_true(hl_scan_add(s, hl_bam_from_deg(b), ok ? r : 0, -1, ok) == HL_OK ||
                    !ok);
    }
}

/* The fitted normal of every kept reading is the wall's (facing the robot: n + 180) to
 * 0.5 degree, whatever the beam; readings seen within 45 degrees of square are all kept
 * (farther off, the points spread along the wall beyond reach_mm and some are not). */
static void test_oblique_wall_gets_its_normal(void **state)
{
    (void)state;
    static hl_scan_t in, out;
    hl_normals_params_t p;
    hl_normals_params_default(&p);
    const double n_deg = 30.0, max_tilt = hl_bam_to_deg(p.max_tilt);
    wall_scan(&in, n_deg, 3000.0);
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    assert_int_equal(out.count, in.count);
    int kept = 0, square_enough = 0;
    for (uint32_t i = 0; i < out.count; i++) {
        const hl_reading_t *a = &in.readings[i], *b = &out.readings[i];
        assert_int_equal(a->bearing, b->bearing);
        assert_int_equal(a->range_mm, b->range_mm);
        double incidence = fabs(remainder(hl_bam_to_sdeg(a->bearing) - n_deg, 360.0));
        if (a->valid && incidence < 45.0) {
            square_enough++;
            assert_true(b->valid);
        }
        if (!b->valid)
            continue;
        kept++;
        double normal = hl_bam_to_sdeg(hl_reading_normal(b, 0));
        assert_true(fabs(remainder(normal - (n_deg + 180.0), 360.0)) < 0.5);
        assert_true(incidence <= max_tilt + 0.5);
    }
    assert_true(square_enough >= 89);
    assert_true(kept > square_enough);
}

/* The map stores the fitted normal: a vector made from an oblique reading faces the wall's
 * way, not back along the beam (which is 40 degrees off here). */
static void test_map_vector_takes_the_fitted_normal(void **state)
{
    (void)state;
    static hl_scan_t in, out;
    hl_normals_params_t p;
    hl_normals_params_default(&p);
    wall_scan(&in, 0.0, 2000.0);
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    uint32_t i = 90 + 40;       /* bearing +40 */
    assert_true(out.readings[i].valid);
    hl_vector_t v;
    hl_pose_t pose = { 1000, -500, hl_bam_from_deg(90.0) };
    assert_true(hl_vector_from_reading(pose, &out.readings[i], &v));
    assert_true(fabs(remainder(hl_bam_to_sdeg(v.normal) - 270.0, 360.0)) < 0.5);
    assert_true(hl_vector_from_reading(pose, &in.readings[i], &v));
    assert_true(fabs(remainder(hl_bam_to_sdeg(v.normal) - 310.0, 360.0)) < 0.5);
}

/* A right-angled corner: the reading at its apex lies on no line (its neighbours bend
 * 90 degrees) and is dropped; readings a few beams away along either wall are kept. A
 * lone return among no-returns has too few points. With keep_unfitted both stay, at
 * tilt 0. */
static void test_corner_and_lone_return_are_dropped(void **state)
{
    (void)state;
    static hl_scan_t in, out;
    hl_normals_params_t p;
    hl_normals_params_default(&p);
    hl_scan_clear(&in);
    /* walls x = 2000 (normal 0) and y = 2000 (normal 90): the corner at bearing 45 */
    uint32_t apex = 0;
    for (int i = 0; i <= 90; i++) {
        double b = i;
        int32_t r1 = line_range(b, 0.0, 2000.0), r2 = line_range(b, 90.0, 2000.0);
        int32_t r = r1 < 0 ? r2 : r2 < 0 ? r1 : (r1 < r2 ? r1 : r2);
        if (i == 45)
            apex = in.count;
        assert_int_equal(hl_scan_add(&in, hl_bam_from_deg(b), r, -1, true), HL_OK);
    }
    for (int i = 0; i < 20; i++)    /* one return in the middle of twenty */
        assert_int_equal(hl_scan_add(&in, hl_bam_from_deg(120.0 + i), i == 10 ? 1500 : 0,
                                     -1, i == 10),
                         HL_OK);
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    assert_false(out.readings[apex].valid);
    assert_true(out.readings[apex - 6].valid);
    assert_true(out.readings[apex + 6].valid);
    assert_false(out.readings[91 + 10].valid);
    assert_int_equal(hl_scan_check(&out), HL_OK);
    /* keep_unfitted: the same readings stay, square to their beams (the paper's tangent) */
    p.keep_unfitted = true;
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    assert_true(out.readings[apex].valid);
    assert_int_equal(out.readings[apex].tilt, 0);
    assert_true(out.readings[91 + 10].valid);
    assert_int_equal(out.readings[91 + 10].tilt, 0);
    assert_int_equal(hl_scan_valid_count(&out), hl_scan_valid_count(&in));
}

/* A grazing wall, y = 200 mm, seen by beams 6 to 8 degrees from it: its normal is 82 to 84
 * degrees off the beams' reverse, beyond the default max_tilt of 75, and every reading is
 * dropped; at max_tilt 89 the same readings are kept. */
static void test_grazing_surface_is_dropped(void **state)
{
    (void)state;
    static hl_scan_t in, out;
    hl_normals_params_t p;
    hl_normals_params_default(&p);
    hl_scan_clear(&in);
    for (int i = 0; i < 9; i++) {
        double b = 6.0 + 0.25 * i;
        assert_int_equal(hl_scan_add(&in, hl_bam_from_deg(b), line_range(b, 90.0, 200.0), -1,
                                     true),
                         HL_OK);
    }
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    for (uint32_t i = 0; i < out.count; i++)
        assert_false(out.readings[i].valid);
    p.max_tilt = hl_bam_from_deg(89.0);
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    assert_true(hl_scan_valid_count(&out) >= 7);
}

static void test_bad_input(void **state)
{
    (void)state;
    static hl_scan_t in, out;
    hl_normals_params_t p;
    hl_normals_params_default(&p);
    wall_scan(&in, 0.0, 2000.0);
    assert_null(hl_normals_params_error(&p));
    assert_int_equal(hl_normals_fit(NULL, &in, &out), HL_ERR_ARG);
    assert_int_equal(hl_normals_fit(&p, NULL, &out), HL_ERR_ARG);
    assert_int_equal(hl_normals_fit(&p, &in, NULL), HL_ERR_ARG);
    assert_int_equal(hl_normals_fit(&p, &in, &in), HL_ERR_ARG);     /* overlap */
    hl_normals_params_t bad = p;
    bad.half_window = 0;
    assert_non_null(hl_normals_params_error(&bad));
    assert_int_equal(hl_normals_fit(&bad, &in, &out), HL_ERR_ARG);
    bad = p;
    bad.min_points = 2;
    assert_non_null(hl_normals_params_error(&bad));
    bad = p;
    bad.min_points = (uint16_t)(2 * p.half_window + 2);
    assert_non_null(hl_normals_params_error(&bad));
    bad = p;
    bad.max_tilt = HL_BAM_QUARTER_TURN;
    assert_non_null(hl_normals_params_error(&bad));
    bad = p;
    bad.reach_mm = 0;
    assert_non_null(hl_normals_params_error(&bad));
    assert_true(in.readings[90].valid);
    in.readings[90].range_mm = -5;                  /* a scan hl_scan_check refuses */
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_ERR_RANGE);
    in.readings[90].range_mm = 2000;
    in.readings[90].tilt = HL_BAM_QUARTER_TURN;     /* a normal facing away */
    assert_int_equal(hl_scan_check(&in), HL_ERR_RANGE);
    in.count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_ERR_RANGE);
    in.count = 0;                                   /* empty: fine, nothing to fit */
    assert_int_equal(hl_normals_fit(&p, &in, &out), HL_OK);
    assert_int_equal(out.count, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_oblique_wall_gets_its_normal),
        cmocka_unit_test(test_map_vector_takes_the_fitted_normal),
        cmocka_unit_test(test_corner_and_lone_return_are_dropped),
        cmocka_unit_test(test_grazing_surface_is_dropped),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
