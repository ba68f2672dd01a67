/* Tests for src/robot/costmap.c: the grid's layout, the rasterized walls, the inflation
 * against a brute-force distance between cell squares, the fence, and segment checks. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/plan.h"

static hl_costmap_t *costmap(int32_t cell, int32_t radius, int32_t clearance)
{
    hl_plan_params_t p;
    hl_plan_params_default(&p);
    p.cell_mm = cell;
    p.radius_mm = radius;
    p.clearance_mm = clearance;
    p.max_cells = 1 << 18;
    hl_costmap_t *cm = hl_costmap_create(&p);
    assert_non_null(cm);
    return cm;
}

static uint8_t at(const hl_plan_grid_t *g, hl_mm_t x, hl_mm_t y)
{
    int32_t i = (int32_t)floor(((double)x - g->x0_mm) / g->cell_mm + 0.5);
    int32_t j = (int32_t)floor(((double)y - g->y0_mm) / g->cell_mm + 0.5);
    assert_true(i >= 0 && j >= 0 && i < g->cols && j < g->rows);
    return g->cells[j * g->cols + i];
}

static void test_layout_and_walls(void **state)
{
    (void)state;
    hl_costmap_t *cm = costmap(50, 250, 300);
    /* One vector at (1000, 0) facing -x, range 1000: a wall segment from y = -132 to 132. */
    hl_vector_t v = { 1000, 0, 32768, 1000 };
    hl_costmap_input_t in = { .v = &v, .n = 1, .start_x = 0, .start_y = 0, .goal_x = 2000,
                              .goal_y = 500 };
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_OK);
    hl_plan_grid_t g;
    hl_costmap_grid(cm, &g);
    /* The box 0..2000 x -132..500, plus 250 + 300 + 50 each side, on multiples of 50. */
    assert_int_equal(g.cell_mm, 50);
    assert_int_equal(g.x0_mm, -600);
    assert_int_equal(g.y0_mm, -750);
    assert_int_equal(g.cols, (2600 - -600) / 50 + 1);
    assert_int_equal(g.rows, (1100 - -750) / 50 + 1);
    assert_int_equal(g.x0_mm + g.start_col * 50, 0);
    assert_int_equal(g.y0_mm + g.goal_row * 50, 500);
    /* 132 mm reaches into the cells of +-150 (they cover 125..175). */
    for (int y = -150; y <= 150; y += 50)
        assert_int_equal(at(&g, 1000, y), HL_PLAN_CELL_OBSTACLE);
    assert_int_equal(at(&g, 1000, 200), HL_PLAN_CELL_LETHAL);
    assert_int_equal(at(&g, 1050, 0), HL_PLAN_CELL_LETHAL);
    /* Between the squares: 750 is 200 from the wall's, 700 exactly the radius, then the
     * cost falls over the 300 mm of clearance: ceil(252 (550 - d) / 300). */
    assert_int_equal(at(&g, 750, 0), HL_PLAN_CELL_LETHAL);
    assert_int_equal(at(&g, 700, 0), 252);
    assert_int_equal(at(&g, 650, 0), 210);
    assert_int_equal(at(&g, 600, 0), 168);
    assert_int_equal(at(&g, 450, 0), 42);
    assert_int_equal(at(&g, 400, 0), 0);
    assert_false(hl_plan_segment_clear(&g, 0, 0, 2000, 0, HL_PLAN_COST_MAX));
    assert_true(hl_plan_segment_clear(&g, 0, 500, 2000, 500, HL_PLAN_COST_MAX));
    assert_false(hl_plan_segment_clear(&g, 0, 500, 2000, 500, 0));
    assert_false(hl_plan_segment_clear(&g, 0, 0, 99999, 0, 255));   /* off the grid */
    /* From (2000, 500) to the square of (1000, 150): 975 across, 325 up. */
    assert_int_equal(g.goal_clearance_mm, 1028);
    hl_costmap_destroy(cm);
}

/* The squared distance between the squares of two cells (dc, dr) apart, in cells^2. */
static int64_t box2(int32_t dc, int32_t dr)
{
    int64_t a = abs(dc) > 1 ? abs(dc) - 1 : 0, b = abs(dr) > 1 ? abs(dr) - 1 : 0;
    return a * a + b * b;
}

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* Every cell's byte against the nearest obstacle cell found by brute force, for a few
 * cell sizes, radii and clearances (odd ones too). */
static void test_inflation_is_exact(void **state)
{
    (void)state;
    const int32_t cases[][3] = { { 50, 250, 300 }, { 37, 111, 0 }, { 20, 50, 1000 },
                                 { 100, 430, 170 } };
    static hl_vector_t v[80];
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hl_costmap_t *cm = costmap(cases[c][0], cases[c][1], cases[c][2]);
        uint32_t seed = 11 + (uint32_t)c;
        for (int i = 0; i < 80; i++)
            v[i] = (hl_vector_t){ (hl_mm_t)(lcg(&seed) % 6000) - 3000,
                                  (hl_mm_t)(lcg(&seed) % 4000) - 2000,
                                  (hl_bam_t)lcg(&seed), (uint16_t)(lcg(&seed) % 3000) };
        hl_costmap_input_t in = { .v = v, .n = 80, .start_x = -2900, .start_y = 1900,
                                  .goal_x = 2900, .goal_y = -1900 };
        assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_OK);
        hl_plan_grid_t g;
        hl_costmap_grid(cm, &g);
        int32_t n = g.cols * g.rows, n_obst = 0;
        int32_t *oc = malloc((size_t)n * sizeof *oc), *orow = malloc((size_t)n * sizeof *orow);
        assert_non_null(oc);
        assert_non_null(orow);
        for (int32_t k = 0; k < n; k++)
            if (g.cells[k] == HL_PLAN_CELL_OBSTACLE) {
                oc[n_obst] = k % g.cols;
                orow[n_obst++] = k / g.cols;
            }
        assert_true(n_obst > 100);
        double cell = g.cell_mm, r = cases[c][1], clr = cases[c][2];
        int lethal = 0, band = 0;
        for (int32_t k = 0; k < n; k++) {
            if (g.cells[k] == HL_PLAN_CELL_OBSTACLE)
                continue;
            int64_t best = INT64_MAX;
            for (int32_t o = 0; o < n_obst; o++) {
                int64_t d2 = box2(k % g.cols - oc[o], k / g.cols - orow[o]);
                best = d2 < best ? d2 : best;
            }
            double d = sqrt((double)best) * cell;
            int want = (double)best * cell * cell < r * r ? HL_PLAN_CELL_LETHAL
                       : clr > 0 && d < r + clr ? (int)ceil(HL_PLAN_COST_MAX * (r + clr - d) / clr)
                                                : 0;
            assert_int_equal(g.cells[k], want);
            lethal += want == HL_PLAN_CELL_LETHAL;
            band += want > 0 && want <= HL_PLAN_COST_MAX;
        }
        assert_true(lethal > 0);
        assert_true(clr == 0 || band > 0);
        free(oc);
        free(orow);
        hl_costmap_destroy(cm);
    }
}

static void test_start_clearing(void **state)
{
    (void)state;
    hl_costmap_t *cm = costmap(50, 250, 300);
    /* A wall along y = 0; the start 260 mm above it, in the cell of 250. */
    hl_vector_t v[41];
    for (int i = 0; i < 41; i++)
        v[i] = (hl_vector_t){ -2000 + 100 * i, 0, 16384, 1000 };
    hl_costmap_input_t in = { .v = v, .n = 41, .start_x = 0, .start_y = 260, .goal_x = 0,
                              .goal_y = 2000 };
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_OK);
    hl_plan_grid_t g;
    hl_costmap_grid(cm, &g);
    /* Squares within 250 of (0, 260) dropped: the wall's reach up to 25, so 235 below;
     * the cell of 100 is 75 aside (248), that of 150 is 125 aside (266). */
    for (int x = -100; x <= 100; x += 50)
        assert_int_equal(at(&g, x, 0), HL_PLAN_CELL_LETHAL);  /* no longer an obstacle */
    assert_int_equal(at(&g, 150, 0), HL_PLAN_CELL_OBSTACLE);
    assert_int_equal(at(&g, -150, 0), HL_PLAN_CELL_OBSTACLE);
    /* The start's cell (225..275) is 236 from the square of (150, 0): lethal. Its region
     * reaches out to 300 mm and holds only lethal cells. */
    int32_t s = g.start_row * g.cols + g.start_col;
    assert_int_equal(g.cells[s], HL_PLAN_CELL_LETHAL);
    int in_region = 0;
    for (int32_t k = 0; k < g.cols * g.rows; k++) {
        if (!g.start_region[k])
            continue;
        in_region++;
        double dx = g.x0_mm + (k % g.cols) * 50.0, dy = g.y0_mm + (k / g.cols) * 50.0 - 260;
        assert_true(hypot(dx, dy) <= 300);
        assert_int_equal(g.cells[k], HL_PLAN_CELL_LETHAL);
    }
    assert_true(in_region > 5);
    /* Out of the region: the segment up is clear, the one along the wall is not. */
    assert_true(hl_plan_segment_clear(&g, 0, 260, 0, 1000, HL_PLAN_COST_MAX));
    assert_false(hl_plan_segment_clear(&g, 0, 260, 1500, 260, HL_PLAN_COST_MAX));
    hl_costmap_destroy(cm);
}

static bool left_half(void *ctx, hl_mm_t x, hl_mm_t y)
{
    (void)y;
    (*(int *)ctx)++;
    return x <= 0;
}

static void test_fence(void **state)
{
    (void)state;
    hl_costmap_t *cm = costmap(50, 250, 300);
    int calls = 0;
    hl_mm_t ox[1] = { -1000 }, oy[1] = { 0 };
    hl_costmap_input_t in = { .obstacle_x = ox, .obstacle_y = oy, .n_obstacles = 1,
                              .allowed = left_half, .allowed_ctx = &calls, .start_x = -2000,
                              .start_y = 0, .goal_x = 1000, .goal_y = 0 };
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_OK);
    hl_plan_grid_t g;
    hl_costmap_grid(cm, &g);
    assert_int_equal(calls, g.cols * g.rows - 1);   /* every cell but the obstacle */
    assert_int_equal(at(&g, -1000, 0), HL_PLAN_CELL_OBSTACLE);
    assert_int_equal(at(&g, 50, 0), HL_PLAN_CELL_FENCE);
    assert_int_equal(at(&g, 0, 0), 0);              /* the fence is not inflated */
    assert_int_equal(at(&g, -1050, 0), HL_PLAN_CELL_LETHAL);
    assert_int_equal(g.goal_clearance_mm, 2000 - 25);
    assert_false(hl_plan_segment_clear(&g, -500, 0, 500, 0, HL_PLAN_COST_MAX));
    hl_costmap_destroy(cm);
}

/* A leg through the common corner of two obstacle cells touches both. */
static void test_corner_squeeze(void **state)
{
    (void)state;
    hl_costmap_t *cm = costmap(50, 50, 0);
    hl_mm_t ox[2] = { 0, 50 }, oy[2] = { 0, 50 };
    hl_costmap_input_t in = { .obstacle_x = ox, .obstacle_y = oy, .n_obstacles = 2,
                              .start_x = -1000, .start_y = 0, .goal_x = 1000, .goal_y = 0 };
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_OK);
    hl_plan_grid_t g;
    hl_costmap_grid(cm, &g);
    /* Everything but obstacles allowed (254): from the cell of (50, 0) to that of
     * (0, 50) exactly through the corner (25, 25); then the same leg far away. */
    assert_false(hl_plan_segment_clear(&g, 60, -10, -10, 60, HL_PLAN_CELL_FENCE));
    assert_true(hl_plan_segment_clear(&g, 560, -10, 490, 60, HL_PLAN_CELL_FENCE));
    assert_true(hl_plan_segment_clear(&g, 560, -10, 490, 60, 0));
    assert_false(hl_plan_segment_clear(&g, 60, -10, 110, -10, 0));    /* lethal, by (50, 0) */
    assert_true(hl_plan_segment_clear(&g, 60, -10, 110, -10, HL_PLAN_CELL_LETHAL));
    hl_costmap_destroy(cm);
}

static void test_bad_input(void **state)
{
    (void)state;
    hl_plan_params_t p;
    hl_plan_params_default(&p);
    p.cell_mm = 10;
    assert_null(hl_costmap_create(&p));
    assert_null(hl_costmap_create(NULL));
    hl_costmap_destroy(NULL);
    hl_costmap_t *cm = costmap(50, 250, 300);
    assert_int_equal(hl_costmap_build(NULL, NULL), HL_PLAN_BAD_ARG);
    assert_int_equal(hl_costmap_build(cm, NULL), HL_PLAN_BAD_ARG);
    hl_costmap_input_t in = { .n_obstacles = 1 };
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_BAD_ARG);
    hl_mm_t far[1] = { HL_COORD_MAX_MM + 1 };
    in.obstacle_x = far;
    in.obstacle_y = far;
    assert_int_equal(hl_costmap_build(cm, &in), HL_PLAN_BAD_ARG);
    hl_plan_grid_t g;
    hl_costmap_grid(cm, &g);
    assert_int_equal(g.cols, 0);
    assert_false(hl_plan_segment_clear(&g, 0, 0, 0, 0, 255));
    assert_false(hl_plan_segment_clear(NULL, 0, 0, 0, 0, 255));
    assert_true(hl_costmap_mem_bytes(cm) > 3u << 18);
    hl_costmap_destroy(cm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_layout_and_walls),
        cmocka_unit_test(test_inflation_is_exact),
        cmocka_unit_test(test_start_clearing),
        cmocka_unit_test(test_fence),
        cmocka_unit_test(test_corner_squeeze),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
