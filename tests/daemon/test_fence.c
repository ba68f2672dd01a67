/* Tests for src/daemon/fence.c: rectangles, convex and concave polygons, border points and
 * vertices, far-away and extreme coordinates, and the polygons it must refuse. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "fence.h"

#define M HL_COORD_MAX_MM

static hl_fence_t make(const hl_mm_t *x, const hl_mm_t *y, uint32_t n)
{
    hl_fence_t f;
    memset(&f, 0, sizeof f);
    assert_null(hl_fence_error(x, y, n));
    assert_int_equal(hl_fence_polygon(&f, x, y, n), HL_OK);
    assert_int_equal(f.n, n);
    return f;
}

static void test_rectangle(void **state)
{
    (void)state;
    hl_fence_t f;
    assert_int_equal(hl_fence_rect(&f, -1000, -500, 3000, 2000), HL_OK);
    assert_int_equal(f.n, 4);
    assert_true(hl_fence_contains(&f, 0, 0));
    assert_true(hl_fence_contains(&f, 2999, 1999));
    assert_true(hl_fence_contains(&f, -1000, 0));    /* left edge */
    assert_true(hl_fence_contains(&f, 3000, 2000));  /* corner */
    assert_true(hl_fence_contains(&f, 1234, -500));  /* bottom edge */
    assert_false(hl_fence_contains(&f, -1001, 0));
    assert_false(hl_fence_contains(&f, 3001, 0));
    assert_false(hl_fence_contains(&f, 0, 2001));
    assert_false(hl_fence_contains(&f, 0, -501));
    assert_false(hl_fence_contains(&f, 3001, 2000)); /* on the top edge's line, beyond it */
    assert_false(hl_fence_contains(&f, -1001, -500));
}

static void test_rectangle_refused(void **state)
{
    (void)state;
    hl_fence_t f;
    assert_int_equal(hl_fence_rect(&f, 0, 0, 0, 10), HL_ERR_RANGE);   /* zero width */
    assert_int_equal(hl_fence_rect(&f, 0, 0, 10, 0), HL_ERR_RANGE);   /* zero height */
    assert_int_equal(hl_fence_rect(&f, 10, 0, 0, 10), HL_ERR_RANGE);  /* min > max */
    assert_int_equal(hl_fence_rect(&f, -M - 1, 0, 10, 10), HL_ERR_RANGE);
    assert_int_equal(hl_fence_rect(&f, 0, 0, 10, M + 1), HL_ERR_RANGE);
    assert_int_equal(hl_fence_rect(NULL, 0, 0, 10, 10), HL_ERR_ARG);
    assert_int_equal(hl_fence_rect(&f, -M, -M, M, M), HL_OK);
}

static void test_convex_triangle_both_windings(void **state)
{
    (void)state;
    const hl_mm_t x[3] = { 0, 6000, 0 }, y[3] = { 0, 0, 3000 };
    const hl_mm_t xr[3] = { 0, 0, 6000 }, yr[3] = { 0, 3000, 0 };
    hl_fence_t ccw = make(x, y, 3), cw = make(xr, yr, 3);
    const struct {
        hl_mm_t x, y;
        bool in;
    } cases[] = {
        { 1000, 1000, true },   { 2000, 2000, true },  /* on the hypotenuse: 2000 + 2*2000 = 6000 */
        { 2001, 2000, false },  { 3000, 1500, true },  { 3001, 1500, false },
        { 0, 3000, true },      { 0, 3001, false },    { 6000, 0, true },
        { -1, 0, false },       { 5999, 1, false },    { 5998, 1, true },
        { 0, 1500, true },      { 3000, 0, true },     { 3000, -1, false },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_int_equal(hl_fence_contains(&ccw, cases[i].x, cases[i].y), cases[i].in);
        assert_int_equal(hl_fence_contains(&cw, cases[i].x, cases[i].y), cases[i].in);
    }
}

/* A U shape open at the top: the notch between the arms is outside. */
static void test_concave(void **state)
{
    (void)state;
    const hl_mm_t x[8] = { 0, 3000, 3000, 2000, 2000, 1000, 1000, 0 };
    const hl_mm_t y[8] = { 0, 0, 3000, 3000, 1000, 1000, 3000, 3000 };
    hl_fence_t f = make(x, y, 8);
    assert_true(hl_fence_contains(&f, 500, 2500));    /* left arm */
    assert_true(hl_fence_contains(&f, 2500, 2500));   /* right arm */
    assert_true(hl_fence_contains(&f, 1500, 500));    /* base */
    assert_false(hl_fence_contains(&f, 1500, 2000));  /* the notch */
    assert_false(hl_fence_contains(&f, 1500, 3000));  /* the notch's open top */
    assert_true(hl_fence_contains(&f, 1500, 1000));   /* notch floor: border */
    assert_true(hl_fence_contains(&f, 1000, 2000));   /* notch wall: border */
    assert_true(hl_fence_contains(&f, 2000, 1000));   /* inner corner vertex */
    assert_false(hl_fence_contains(&f, 1001, 2000));
    assert_false(hl_fence_contains(&f, 1999, 1001));
    /* Rays through vertices: rows at y = 1000 and 3000 pass several vertices. */
    assert_true(hl_fence_contains(&f, 500, 1000));
    assert_true(hl_fence_contains(&f, 2500, 1000));
    assert_false(hl_fence_contains(&f, -1, 1000));
    assert_false(hl_fence_contains(&f, -1, 3000));
    assert_false(hl_fence_contains(&f, 3001, 3000));
    assert_true(hl_fence_contains(&f, 0, 3000));
}

/* Every vertex and every edge midpoint is on the border of a star-shaped polygon, and a
 * row through a spike's tip is counted once. */
static void test_vertices_and_midpoints(void **state)
{
    (void)state;
    const hl_mm_t x[6] = { 0, 4000, 2000, 4000, 0, -2000 };
    const hl_mm_t y[6] = { 0, 0, 2000, 4000, 4000, 2000 };
    hl_fence_t f = make(x, y, 6);
    for (uint32_t i = 0; i < 6; i++) {
        uint32_t j = (i + 1) % 6;
        assert_true(hl_fence_contains(&f, x[i], y[i]));
        assert_true(hl_fence_contains(&f, (x[i] + x[j]) / 2, (y[i] + y[j]) / 2));
    }
    assert_true(hl_fence_contains(&f, 1000, 2000));   /* same row as two vertices */
    assert_false(hl_fence_contains(&f, 3000, 2000));  /* in the notch, same row */
    assert_false(hl_fence_contains(&f, -2001, 2000));
    assert_false(hl_fence_contains(&f, 5000, 2000));
}

static void test_far_outside_and_extremes(void **state)
{
    (void)state;
    hl_fence_t f;
    assert_int_equal(hl_fence_rect(&f, -1000, -1000, 1000, 1000), HL_OK);
    assert_false(hl_fence_contains(&f, INT32_MAX, 0));
    assert_false(hl_fence_contains(&f, INT32_MIN, 0));
    assert_false(hl_fence_contains(&f, 0, INT32_MAX));
    assert_false(hl_fence_contains(&f, INT32_MIN, INT32_MIN));
    assert_false(hl_fence_contains(&f, M, -M));

    /* The largest fence: corners at +-2^22, and a thin diagonal sliver across it. */
    assert_int_equal(hl_fence_rect(&f, -M, -M, M, M), HL_OK);
    assert_true(hl_fence_contains(&f, M, M));
    assert_true(hl_fence_contains(&f, -M, M));
    assert_true(hl_fence_contains(&f, 0, -M));
    assert_false(hl_fence_contains(&f, M + 1, 0));
    assert_false(hl_fence_contains(&f, INT32_MIN, INT32_MAX));
    const hl_mm_t x[3] = { -M, M, M }, y[3] = { -M, M - 1, M };
    hl_fence_t s = make(x, y, 3);
    assert_true(hl_fence_contains(&s, M, M - 1));
    assert_true(hl_fence_contains(&s, 0, 0));        /* on the y = x edge */
    assert_false(hl_fence_contains(&s, M, 0));       /* below the sliver */
    assert_false(hl_fence_contains(&s, 0, 1));       /* just above the diagonal */
    assert_false(hl_fence_contains(&s, 0, -1));      /* the other edge passes y = -0.5 */
    assert_false(hl_fence_contains(&s, -M, -M + 1));
    assert_true(hl_fence_contains(&s, -M, -M));
    assert_false(hl_fence_contains(&s, INT32_MAX, INT32_MAX));
}

static void refused(const hl_mm_t *x, const hl_mm_t *y, uint32_t n, const char *reason)
{
    hl_fence_t f;
    f.n = 99;
    assert_int_equal(hl_fence_polygon(&f, x, y, n), HL_ERR_RANGE);
    assert_int_equal(f.n, 99); /* left untouched */
    const char *why = hl_fence_error(x, y, n);
    assert_non_null(why);
    assert_non_null(strstr(why, reason));
}

static void test_bad_polygons(void **state)
{
    (void)state;
    hl_mm_t x[HL_FENCE_MAX_VERTICES + 1], y[HL_FENCE_MAX_VERTICES + 1];
    /* A 65-gon approximated on a staircase circle would be fine at 64: use a convex
     * fan of points on a parabola, which is simple for any count. */
    for (int i = 0; i <= HL_FENCE_MAX_VERTICES; i++) {
        x[i] = (i - 32) * 1000;
        y[i] = (i - 32) * (i - 32) * 100;
    }
    hl_fence_t f;
    assert_int_equal(hl_fence_polygon(&f, x, y, HL_FENCE_MAX_VERTICES), HL_OK);
    assert_true(hl_fence_contains(&f, 0, 50000));
    assert_false(hl_fence_contains(&f, 0, -1));
    refused(x, y, HL_FENCE_MAX_VERTICES + 1, "more than 64");
    refused(x, y, 2, "at least 3");
    refused(x, y, 0, "at least 3");

    const hl_mm_t cx[4] = { 0, 1000, 2000, 3000 }, cy[4] = { 0, 1000, 2000, 3000 };
    refused(cx, cy, 4, "zero area");
    /* A bow-tie with unequal lobes (so its net area is not zero). */
    const hl_mm_t bx[4] = { 0, 3000, 3000, 0 }, by[4] = { 0, 1000, 0, 2000 };
    refused(bx, by, 4, "cross");
    const hl_mm_t ox[4] = { 0, M + 1, 0, 0 }, oy[4] = { 0, 0, 1000, 500 };
    refused(ox, oy, 4, "outside");
    const hl_mm_t dx[4] = { 0, 1000, 1000, 1000 }, dy[4] = { 0, 0, 1000, 1000 };
    refused(dx, dy, 4, "same point");
    /* A spike that doubles back along its own edge. */
    const hl_mm_t sx[5] = { 0, 2000, 1000, 1000, 0 }, sy[5] = { 0, 0, 0, 1000, 1000 };
    refused(sx, sy, 5, "overlap");
    /* A vertex touching a non-adjacent edge (a pinched polygon). */
    const hl_mm_t px[6] = { 0, 2000, 2000, 1000, 1000, 0 };
    const hl_mm_t py[6] = { 0, 0, 2000, 0, 2000, 2000 };
    refused(px, py, 6, "cross or touch");
    /* A bow-tie whose two lobes have equal and opposite area: zero net area. */
    const hl_mm_t zx[4] = { 0, 1000, 0, 1000 }, zy[4] = { 0, 1000, 1000, 0 };
    assert_int_equal(hl_fence_polygon(&f, zx, zy, 4), HL_ERR_RANGE);
    assert_non_null(hl_fence_error(zx, zy, 4));
    assert_int_equal(hl_fence_polygon(NULL, x, y, 4), HL_ERR_ARG);
    assert_int_equal(hl_fence_polygon(&f, NULL, y, 4), HL_ERR_ARG);
    assert_non_null(hl_fence_error(NULL, y, 4));
}

static void test_contains_rejects_unset_fence(void **state)
{
    (void)state;
    hl_fence_t f;
    memset(&f, 0, sizeof f);
    assert_false(hl_fence_contains(&f, 0, 0));
    assert_false(hl_fence_contains(NULL, 0, 0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rectangle),
        cmocka_unit_test(test_rectangle_refused),
        cmocka_unit_test(test_convex_triangle_both_windings),
        cmocka_unit_test(test_concave),
        cmocka_unit_test(test_vertices_and_midpoints),
        cmocka_unit_test(test_far_outside_and_extremes),
        cmocka_unit_test(test_bad_polygons),
        cmocka_unit_test(test_contains_rejects_unset_fence),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
