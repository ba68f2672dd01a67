/* Tests for src/robot/safety.c: which sonar readings are in the way ahead. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "houghloc/safety.h"

#define DEG(d) ((hl_bam_t)((d) * 65536 / 360))

static const hl_safety_params_t P = { .radius_mm = 250, .half_beam = DEG(15) };

static void test_straight_ahead_is_in_the_way(void **state)
{
    (void)state;
    hl_bam_t b[] = { DEG(0) };
    int32_t r[] = { 900 };
    int32_t which = 7;
    assert_int_equal(hl_safety_ahead_mm(&P, b, r, 1, &which), 900);
    assert_int_equal(which, 0);
}

static void test_abeam_and_behind_are_not(void **state)
{
    (void)state;
    /* a wall 300 mm to the left seen square (90 deg), one behind, one at 135 deg */
    hl_bam_t b[] = { DEG(90), DEG(180), DEG(135), (hl_bam_t)(65536 - DEG(90)) };
    int32_t r[] = { 300, 200, 280, 310 };
    int32_t which = 7;
    assert_int_equal(hl_safety_ahead_mm(&P, b, r, 4, &which), -1);
    assert_int_equal(which, -1);
}

static void test_the_lobe_edge_decides_to_the_side(void **state)
{
    (void)state;
    /* transducer at 45 deg: the lobe reaches 30 deg; sin(30) * r <= 250 for r <= 500 */
    hl_bam_t b[] = { DEG(45) };
    int32_t near[] = { 490 }, far[] = { 520 };
    assert_int_equal(hl_safety_ahead_mm(&P, b, near, 1, NULL), 490);
    assert_int_equal(hl_safety_ahead_mm(&P, b, far, 1, NULL), -1);
    /* the same on the right (negative bearings wrap to the top of the circle) */
    hl_bam_t right[] = { (hl_bam_t)(65536 - DEG(45)) };
    assert_int_equal(hl_safety_ahead_mm(&P, right, near, 1, NULL), 490);
}

static void test_the_nearest_in_the_way_wins(void **state)
{
    (void)state;
    hl_bam_t b[] = { DEG(0), DEG(22.5), DEG(90), DEG(-22.5) };
    int32_t r[] = { 1200, 700, 300, 650 };
    int32_t which = -1;
    assert_int_equal(hl_safety_ahead_mm(&P, b, r, 4, &which), 650);
    assert_int_equal(which, 3);
}

static void test_no_echo_and_bad_arguments(void **state)
{
    (void)state;
    hl_bam_t b[] = { DEG(0), DEG(0) };
    int32_t r[] = { 0, -5 };
    assert_int_equal(hl_safety_ahead_mm(&P, b, r, 2, NULL), -1);
    assert_int_equal(hl_safety_ahead_mm(NULL, b, r, 2, NULL), -1);
    assert_int_equal(hl_safety_ahead_mm(&P, NULL, r, 2, NULL), -1);
    assert_int_equal(hl_safety_ahead_mm(&P, b, r, -1, NULL), -1);
    hl_safety_params_t bad = { .radius_mm = 0, .half_beam = DEG(15) };
    int32_t ok[] = { 500, 500 };
    assert_int_equal(hl_safety_ahead_mm(&bad, b, ok, 2, NULL), -1);
    assert_int_equal(hl_safety_ahead_mm(&P, b, ok, 0, NULL), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_straight_ahead_is_in_the_way),
        cmocka_unit_test(test_abeam_and_behind_are_not),
        cmocka_unit_test(test_the_lobe_edge_decides_to_the_side),
        cmocka_unit_test(test_the_nearest_in_the_way_wins),
        cmocka_unit_test(test_no_echo_and_bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
