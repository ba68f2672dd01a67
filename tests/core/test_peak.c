/* Tests for src/core/peak.c: the peak, the separate second peak, the prior weights,
 * parabolic interpolation. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "peak.h"

static void test_offset(void **state)
{
    (void)state;
    assert_int_equal(hl_peak_offset(10, 20, 10, 24), 0);
    assert_int_equal(hl_peak_offset(20, 20, 0, 24), -12);  /* vertex half a cell left */
    assert_int_equal(hl_peak_offset(0, 20, 20, 24), 12);
    assert_int_equal(hl_peak_offset(12, 20, 4, 24), -4);   /* 8 / (2 * -24) = -1/6 cell */
    assert_int_equal(hl_peak_offset(20, 20, 20, 24), 0);   /* flat: no curvature */
    assert_int_equal(hl_peak_offset(30, 20, 10, 24), 0);   /* not a maximum */
    assert_int_equal(hl_peak_offset(5, 10, 9, 200), 67);   /* (5-9)/(2(5-20+9)) = 1/3 */
}

static void test_peak_and_separate_second(void **state)
{
    (void)state;
    enum { NX = 50, NY = 40 };
    static uint32_t cells[NX * NY];
    cells[10 * NX + 10] = 900;
    cells[10 * NX + 12] = 800;  /* 2 cells = 48 mm away: same peak */
    cells[30 * NX + 40] = 500;  /* far away: the separate peak */
    hl_grid_t g = { .cells = cells, .nx = NX, .ny = NY, .nt = 1 };
    hl_peak_t p;
    assert_int_equal(hl_peak_find(&g, 24, 500, &p), 1);
    assert_int_equal(p.ix, 10);
    assert_int_equal(p.iy, 10);
    assert_int_equal(p.score, 900);
    assert_int_equal(p.second, 500);
    /* with no separation, the neighbour counts */
    assert_int_equal(hl_peak_find(&g, 24, 0, &p), 1);
    assert_int_equal(p.second, 800);
    /* exactly at the separation distance counts as separate: 21 cells * 24 = 504 */
    cells[10 * NX + 31] = 700;
    assert_int_equal(hl_peak_find(&g, 24, 504, &p), 1);
    assert_int_equal(p.second, 700);
    static uint32_t zero[4];
    hl_grid_t z = { .cells = zero, .nx = 2, .ny = 2, .nt = 1 };
    assert_int_equal(hl_peak_find(&z, 24, 500, &p), 0);
}

static void test_prior_weights(void **state)
{
    (void)state;
    static uint32_t cells[3 * 4 * 2];
    cells[0] = 1000;                    /* (0,0,0), weight 256*128*256 */
    cells[12 + 2 * 4 + 3] = 600;        /* (3,2,1), weight 256*256*256 */
    uint32_t wx[4] = { 256, 256, 256, 256 }, wy[3] = { 128, 256, 256 }, wt[2] = { 256, 256 };
    hl_grid_t g = { .cells = cells, .nx = 4, .ny = 3, .nt = 2, .wx = wx, .wy = wy, .wt = wt };
    assert_int_equal(hl_grid_score(&g, 0, 0, 0), 500);
    hl_peak_t p;
    assert_int_equal(hl_peak_find(&g, 100, 150, &p), 1);
    assert_int_equal(p.ix, 3);
    assert_int_equal(p.iy, 2);
    assert_int_equal(p.it, 1);
    assert_int_equal(p.score, 600);
    assert_int_equal(p.second, 500);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offset),
        cmocka_unit_test(test_peak_and_separate_second),
        cmocka_unit_test(test_prior_weights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
