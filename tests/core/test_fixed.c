/* Tests for src/core/fixed.c: the trig table, polar conversion at the range extremes,
 * angle wrap-around and conversions. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/fixed.h"

static const double PI = 3.14159265358979323846;

static void test_trig_exact_points(void **state)
{
    (void)state;
    assert_int_equal(hl_sin(0), 0);
    assert_int_equal(hl_sin(16384), 16384);
    assert_int_equal(hl_sin(32768), 0);
    assert_int_equal(hl_sin(49152), -16384);
    assert_int_equal(hl_cos(0), 16384);
    assert_int_equal(hl_cos(32768), -16384);
    assert_int_equal(hl_cos(16384), 0);
}

static void test_trig_matches_libm_everywhere(void **state)
{
    (void)state;
    for (uint32_t a = 0; a < 65536; a++) {
        double r = a * 2 * PI / 65536.0;
        assert_true(fabs(hl_sin((hl_bam_t)a) - 16384.0 * sin(r)) <= 0.5 + 1e-9);
        assert_true(fabs(hl_cos((hl_bam_t)a) - 16384.0 * cos(r)) <= 0.5 + 1e-9);
    }
}

/* The extremes of the documented range: 32 m readings in every direction must land
 * within 1.5 mm of the exact point (fixed.h's bound), with no overflow. */
static void test_polar_extreme_range(void **state)
{
    (void)state;
    for (uint32_t a = 0; a < 65536; a += 7) {
        int32_t x, y;
        hl_polar_to_xy(HL_RANGE_MAX_MM, (hl_bam_t)a, &x, &y);
        double r = a * 2 * PI / 65536.0;
        assert_true(fabs(x - HL_RANGE_MAX_MM * cos(r)) <= 1.5);
        assert_true(fabs(y - HL_RANGE_MAX_MM * sin(r)) <= 1.5);
    }
    int32_t x, y;
    hl_polar_to_xy(HL_RANGE_MAX_MM, 0, &x, &y);
    assert_int_equal(x, 32767);
    assert_int_equal(y, 0);
    hl_polar_to_xy(HL_RANGE_MAX_MM, 32768, &x, &y);
    assert_int_equal(x, -32767);
    assert_int_equal(y, 0);
}

static void test_polar_clamps_out_of_range(void **state)
{
    (void)state;
    int32_t x, y;
    hl_polar_to_xy(1000000, 0, &x, &y);
    assert_int_equal(x, HL_RANGE_MAX_MM);
    hl_polar_to_xy(-5, 16384, &x, &y);
    assert_int_equal(x, 0);
    assert_int_equal(y, 0);
}

static void test_polar_symmetric_rounding(void **state)
{
    (void)state;
    /* Opposite directions give exactly opposite vectors. */
    for (uint32_t a = 0; a < 32768; a += 13) {
        int32_t x1, y1, x2, y2;
        hl_polar_to_xy(12345, (hl_bam_t)a, &x1, &y1);
        hl_polar_to_xy(12345, (hl_bam_t)(a + 32768), &x2, &y2);
        assert_int_equal(x1, -x2);
        assert_int_equal(y1, -y2);
    }
}

static void test_bam_wrap(void **state)
{
    (void)state;
    assert_int_equal(hl_bam_diff(10, 65530), 16);
    assert_int_equal(hl_bam_diff(65530, 10), -16);
    assert_int_equal(hl_bam_diff(0, 32768), -32768);
    assert_int_equal(hl_bam_from_deg(180.0), 32768);
    assert_int_equal(hl_bam_from_deg(-180.0), 32768);
    assert_int_equal(hl_bam_from_deg(360.0), 0);
    assert_int_equal(hl_bam_from_deg(-90.0), 49152);
    assert_int_equal(hl_bam_from_deg(1.1), 200);
    assert_true(fabs(hl_bam_to_sdeg(hl_bam_from_deg(-179.0)) + 179.0) < 0.003);
    assert_true(fabs(hl_bam_to_deg(hl_bam_from_rad(PI / 2)) - 90.0) < 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trig_exact_points),
        cmocka_unit_test(test_trig_matches_libm_everywhere),
        cmocka_unit_test(test_polar_extreme_range),
        cmocka_unit_test(test_polar_clamps_out_of_range),
        cmocka_unit_test(test_polar_symmetric_rounding),
        cmocka_unit_test(test_bam_wrap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
