/* Tests for tools/eval/truth_frame.c: the simulator's true poses moved into houghlocd's map
 * frame, which the console, houghloc-map and hl-eval draw and score the truth in. The
 * first true pose lands on the daemon's start pose; the rest follow rigidly (a robot that
 * set off at 14 degrees in the world sets off along the map's +x axis). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/fixed.h"
#include "truth_frame.h"

#define DEG (3.14159265358979323846 / 180.0)

static hl_pose_t pose(double x_m, double y_m, double deg)
{
    return (hl_pose_t){ (hl_mm_t)lround(x_m * 1000), (hl_mm_t)lround(y_m * 1000),
                        hl_bam_from_deg(deg) };
}

/* Within a millimetre and a hundredth of a degree of (x_m, y_m, deg). */
static void assert_pose(hl_pose_t p, double x_m, double y_m, double deg)
{
    assert_true(labs((long)p.x_mm - lround(x_m * 1000)) <= 1);
    assert_true(labs((long)p.y_mm - lround(y_m * 1000)) <= 1);
    double d = fabs(hl_bam_to_sdeg((hl_bam_t)(p.theta - hl_bam_from_deg(deg))));
    assert_true(d < 0.01);
}

static void test_first_pose_lands_on_the_origin(void **state)
{
    (void)state;
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, pose(0, 0, 0));
    hl_pose_t out;
    /* the robot set down at (5.4, 1.5) facing 14 degrees: the daemon's origin */
    assert_true(hl_truth_frame_map(&f, pose(5.4, 1.5, 14), &out));
    assert_pose(out, 0, 0, 0);
    /* one metre ahead, then one metre to its left, turned 90 degrees */
    assert_true(hl_truth_frame_map(&f, pose(5.4 + cos(14 * DEG), 1.5 + sin(14 * DEG), 14), &out));
    assert_pose(out, 1, 0, 0);
    assert_true(hl_truth_frame_map(&f, pose(5.4 + cos(14 * DEG) - sin(14 * DEG),
                                            1.5 + sin(14 * DEG) + cos(14 * DEG), 104), &out));
    assert_pose(out, 1, 1, 90);
}

static void test_a_configured_start_pose(void **state)
{
    (void)state;
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, pose(2, -1, 90));
    hl_pose_t out;
    assert_true(hl_truth_frame_map(&f, pose(-3, 4, 180), &out));
    assert_pose(out, 2, -1, 90);
    /* ahead of the first pose is -x in the world, +y in this map */
    assert_true(hl_truth_frame_map(&f, pose(-5, 4, 180), &out));
    assert_pose(out, 2, 1, 90);
    /* headings wrap: 170 degrees in the world is 80 in the map */
    assert_true(hl_truth_frame_map(&f, pose(-3, 4, -190), &out));
    assert_pose(out, 2, -1, 80);
}

static void test_distances_are_kept(void **state)
{
    (void)state;
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, pose(-1.25, 0.5, -33));
    hl_pose_t prev_in = pose(7.1, -2.2, 200), prev_out;
    assert_true(hl_truth_frame_map(&f, prev_in, &prev_out));
    for (int i = 1; i < 50; i++) {
        hl_pose_t in = pose(7.1 + 0.3 * i * cos(i), -2.2 + 0.2 * i * sin(1.7 * i), 11.0 * i), out;
        assert_true(hl_truth_frame_map(&f, in, &out));
        double din = hypot(in.x_mm - prev_in.x_mm, in.y_mm - prev_in.y_mm);
        double dout = hypot(out.x_mm - prev_out.x_mm, out.y_mm - prev_out.y_mm);
        assert_true(fabs(din - dout) <= 2.0);
        prev_in = in;
        prev_out = out;
    }
}

static void test_anchor_once(void **state)
{
    (void)state;
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, pose(0, 0, 0));
    assert_false(f.anchored);
    hl_truth_frame_anchor(&f, pose(1, 1, 0));
    hl_truth_frame_anchor(&f, pose(9, 9, 45));     /* ignored: anchored already */
    hl_pose_t out;
    assert_true(hl_truth_frame_map(&f, pose(2, 1, 0), &out));
    assert_pose(out, 1, 0, 0);
}

static void test_beyond_the_range(void **state)
{
    (void)state;
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, pose(4000, 0, 0));
    hl_pose_t out = pose(7, 7, 7);
    assert_true(hl_truth_frame_map(&f, pose(0, 0, 0), &out));
    assert_pose(out, 4000, 0, 0);
    out = pose(7, 7, 7);
    assert_false(hl_truth_frame_map(&f, pose(200, 0, 0), &out));   /* 4200 m */
    assert_pose(out, 7, 7, 7);
}

static void test_parse(void **state)
{
    (void)state;
    hl_pose_t p;
    char why[HL_TRUTH_FRAME_WHY_LEN];
    assert_true(hl_truth_frame_parse_pose("5.4,1.5,0", &p, why));
    assert_pose(p, 5.4, 1.5, 0);
    assert_true(hl_truth_frame_parse_pose("-1,2.25,-90", &p, why));
    assert_pose(p, -1, 2.25, -90);
    assert_true(hl_truth_frame_parse_pose("0,0,370", &p, why));
    assert_pose(p, 0, 0, 10);
    static const char *const bad[] = { "1,2", "1,2,3,4", "a,b,c", " 1,2,3", "1,,2", "1,2,nan",
                                       "1,2,", "", "1;2;3", "0x10,0,0" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        why[0] = '\0';
        assert_false(hl_truth_frame_parse_pose(bad[i], &p, why));
        assert_non_null(strstr(why, "is not X,Y,DEG"));
    }
    assert_false(hl_truth_frame_parse_pose("4194.305,0,0", &p, why));
    assert_non_null(strstr(why, "outside +-4194.304 m"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_pose_lands_on_the_origin),
        cmocka_unit_test(test_a_configured_start_pose),
        cmocka_unit_test(test_distances_are_kept),
        cmocka_unit_test(test_anchor_once),
        cmocka_unit_test(test_beyond_the_range),
        cmocka_unit_test(test_parse),
    };
    return cmocka_run_group_tests_name("truth_frame", tests, NULL, NULL);
}
