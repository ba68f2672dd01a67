/* Tests for src/core/map.c and src/core/scan.c: tangent vectors, capacity and random
 * culling, extreme coordinates, pose algebra. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>

#include "houghloc/map.h"

static hl_vector_t vec(int32_t x, int32_t y)
{
    hl_vector_t v = { x, y, 0, 1000 };
    return v;
}

static void test_create_rejects_bad_capacity(void **state)
{
    (void)state;
    assert_null(hl_map_create(0, 1));
    assert_null(hl_map_create(HL_MAP_MAX_CAPACITY + 1, 1));
    hl_map_destroy(NULL);
}

static void test_vector_points_back_at_sensor(void **state)
{
    (void)state;
    hl_pose_t pose = { 1000, -2000, hl_bam_from_deg(30) };
    hl_reading_t r = { .range_mm = 2500, .bearing = hl_bam_from_deg(45), .valid = true };
    hl_vector_t v;
    assert_true(hl_vector_from_reading(pose, &r, &v));
    /* surface at 75 degrees, 2.5 m away */
    assert_in_range(v.x_mm, 1000 + 647 - 1, 1000 + 647 + 1);
    assert_in_range(v.y_mm, -2000 + 2415 - 1, -2000 + 2415 + 1);
    assert_int_equal(v.normal, (hl_bam_t)(hl_bam_from_deg(75) + 32768));
    int32_t ox, oy;
    hl_vector_origin(&v, &ox, &oy);
    assert_in_range(ox, 998, 1002);
    assert_in_range(oy, -2002, -1998);
    r.valid = false;
    assert_false(hl_vector_from_reading(pose, &r, &v));
}

static void test_extreme_coordinates(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(10, 1);
    hl_vector_t v = vec(HL_COORD_MAX_MM, -HL_COORD_MAX_MM);
    assert_int_equal(hl_map_add(m, &v), HL_OK);
    v = vec(HL_COORD_MAX_MM + 1, 0);
    assert_int_equal(hl_map_add(m, &v), HL_ERR_RANGE);
    v = vec(0, -HL_COORD_MAX_MM - 1);
    assert_int_equal(hl_map_add(m, &v), HL_ERR_RANGE);
    assert_int_equal(hl_map_count(m), 1);

    /* A 32 m reading from a pose at the edge leaves the range: skipped, not wrapped. */
    hl_scan_t *scan = calloc(1, sizeof *scan);
    hl_scan_add(scan, 0, HL_RANGE_MAX_MM, 0, true);
    hl_scan_add(scan, 32768, HL_RANGE_MAX_MM, 1, true);
    hl_pose_t edge = { HL_COORD_MAX_MM - 100, 0, 0 };
    uint32_t added = 99;
    assert_int_equal(hl_map_add_scan(m, scan, edge, &added), HL_OK);
    assert_int_equal(added, 1);
    assert_int_equal(hl_map_vectors(m)[1].x_mm, HL_COORD_MAX_MM - 100 - 32767);
    hl_pose_t outside = { HL_COORD_MAX_MM + 1, 0, 0 };
    assert_int_equal(hl_map_add_scan(m, scan, outside, &added), HL_ERR_RANGE);
    free(scan);
    hl_map_destroy(m);
}

static void test_capacity_and_culling(void **state)
{
    (void)state;
    hl_map_t *m = hl_map_create(100, 7);
    for (int i = 0; i < 100; i++) {
        hl_vector_t v = vec(i, 0);
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 100);
    uint32_t v0 = hl_map_version(m);
    /* 1000 more: the map stays at capacity. Each arrival drops one of 101 at random,
     * so a vector survives k later arrivals with probability (100/101)^k: the first
     * hundred are all but surely gone (survival 5e-5 each) and about 63 of the
     * newest hundred remain. The seed is fixed, so the counts are too. */
    for (int i = 0; i < 1000; i++) {
        hl_vector_t v = vec(1000 + i, 0);
        assert_int_equal(hl_map_add(m, &v), HL_OK);
    }
    assert_int_equal(hl_map_count(m), 100);
    assert_true(hl_map_version(m) > v0);
    int old = 0, late = 0;
    for (uint32_t i = 0; i < 100; i++) {
        old += hl_map_vectors(m)[i].x_mm < 1000;
        late += hl_map_vectors(m)[i].x_mm >= 1900;
    }
    assert_int_equal(old, 0);
    assert_in_range(late, 50, 76);
    hl_map_destroy(m);
}

static void test_culling_is_deterministic_by_seed(void **state)
{
    (void)state;
    hl_map_t *a = hl_map_create(50, 3), *b = hl_map_create(50, 3), *c = hl_map_create(50, 4);
    for (int i = 0; i < 500; i++) {
        hl_vector_t v = vec(i, i);
        hl_map_add(a, &v);
        hl_map_add(b, &v);
        hl_map_add(c, &v);
    }
    int same_ab = 1, same_ac = 1;
    for (int i = 0; i < 50; i++) {
        same_ab &= hl_map_vectors(a)[i].x_mm == hl_map_vectors(b)[i].x_mm;
        same_ac &= hl_map_vectors(a)[i].x_mm == hl_map_vectors(c)[i].x_mm;
    }
    assert_true(same_ab);
    assert_false(same_ac);
    hl_map_destroy(a);
    hl_map_destroy(b);
    hl_map_destroy(c);
}

static void test_scan_add_and_check(void **state)
{
    (void)state;
    hl_scan_t *s = calloc(1, sizeof *s);
    for (int i = 0; i < HL_SCAN_MAX_READINGS; i++)
        assert_int_equal(hl_scan_add(s, 0, 100, 0, true), HL_OK);
    assert_int_equal(hl_scan_add(s, 0, 100, 0, true), HL_ERR_CAPACITY);
    hl_scan_clear(s);
    hl_scan_add(s, 0, -1, 0, true);
    hl_scan_add(s, 0, HL_RANGE_MAX_MM + 1, 0, true);
    hl_scan_add(s, 0, 5, 0, true);
    assert_int_equal(hl_scan_valid_count(s), 1);
    assert_int_equal(hl_scan_check(s), HL_OK);
    s->readings[0].valid = true;
    s->readings[0].range_mm = 40000;
    assert_int_equal(hl_scan_check(s), HL_ERR_RANGE);
    s->count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_scan_check(s), HL_ERR_RANGE);
    assert_int_equal(hl_scan_add(NULL, 0, 0, 0, true), HL_ERR_ARG);
    free(s);
}

static void test_pose_algebra_round_trip(void **state)
{
    (void)state;
    hl_pose_t a = { 1234567, -7654321 / 4, hl_bam_from_deg(170) };
    hl_pose_t b = { 1236000, -1913000, hl_bam_from_deg(-175) };
    hl_pose_t rel = hl_pose_between(a, b);
    assert_int_equal(rel.theta, (hl_bam_t)(b.theta - a.theta));   /* wraps through 180 */
    hl_pose_t back = hl_pose_compose(a, rel);
    assert_in_range(back.x_mm, b.x_mm - 1, b.x_mm + 1);
    assert_in_range(back.y_mm, b.y_mm - 1, b.y_mm + 1);
    assert_int_equal(back.theta, b.theta);
    hl_pose_t far = { HL_COORD_MAX_MM, 0, 0 };
    assert_true(hl_pose_in_range(far));
    far.x_mm++;
    assert_false(hl_pose_in_range(far));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_rejects_bad_capacity),
        cmocka_unit_test(test_vector_points_back_at_sensor),
        cmocka_unit_test(test_extreme_coordinates),
        cmocka_unit_test(test_capacity_and_culling),
        cmocka_unit_test(test_culling_is_deterministic_by_seed),
        cmocka_unit_test(test_scan_add_and_check),
        cmocka_unit_test(test_pose_algebra_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
