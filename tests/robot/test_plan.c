/* Tests for src/robot/plan.c (and the grid it builds, costmap.c): walls made of tangent
 * vectors, and every path checked against the vectors' own wall segments in doubles. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "houghloc/plan.h"

#define MAX_V 4000
#define RANGE 1000      /* every test vector's range: half-length 1000 tan 7.5 = 131.7 mm */
#define UP 16384        /* normals, BAM */
#define DOWN 49152
#define LEFT 32768
#define RIGHT 0

typedef struct world {
    hl_vector_t v[MAX_V];
    uint32_t n;
} world_t;

static world_t W;

static double half_len(const hl_vector_t *v)
{
    double h = v->range_mm * tan(hl_bam_to_rad(hl_bam_from_deg(7.5)));
    return h < 150 ? h : 150;
}

/* Vectors whose wall segments cover the straight wall from (x0, y0) to (x1, y1) and no
 * more, seen from the side @p normal points to. */
static void wall(world_t *w, double x0, double y0, double x1, double y1, hl_bam_t normal)
{
    hl_vector_t proto = { 0, 0, normal, RANGE };
    double h = ceil(half_len(&proto)), len = hypot(x1 - x0, y1 - y0);
    int k = (int)ceil((len - 2 * h) / 100);
    for (int i = 0; i <= k; i++) {
        double s = k ? h + (len - 2 * h) * i / k : len / 2;
        assert_true(w->n < MAX_V);
        w->v[w->n++] = (hl_vector_t){ (hl_mm_t)lround(x0 + (x1 - x0) * s / len),
                                      (hl_mm_t)lround(y0 + (y1 - y0) * s / len), normal, RANGE };
    }
}

/* A square room with its walls' normals inward and a door of @p door mm in its right
 * wall, centred on y = 0 (no door when 0). */
static void room(world_t *w, double x0, double y0, double x1, double y1, double door)
{
    wall(w, x0, y0, x1, y0, UP);
    wall(w, x0, y1, x1, y1, DOWN);
    wall(w, x0, y0, x0, y1, RIGHT);
    if (door > 0) {
        wall(w, x1, y0, x1, -door / 2, LEFT);
        wall(w, x1, door / 2, x1, y1, LEFT);
    } else {
        wall(w, x1, y0, x1, y1, LEFT);
    }
}

static double seg_point(double px, double py, double ax, double ay, double bx, double by)
{
    double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(px - ax - t * dx, py - ay - t * dy);
}

static bool crosses(double ax, double ay, double bx, double by, double cx, double cy,
                    double dx, double dy)
{
    double d1 = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    double d2 = (bx - ax) * (dy - ay) - (by - ay) * (dx - ax);
    double d3 = (dx - cx) * (ay - cy) - (dy - cy) * (ax - cx);
    double d4 = (dx - cx) * (by - cy) - (dy - cy) * (bx - cx);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

static double seg_seg(double ax, double ay, double bx, double by, double cx, double cy,
                      double dx, double dy)
{
    if (crosses(ax, ay, bx, by, cx, cy, dx, dy))
        return 0;
    double m = seg_point(ax, ay, cx, cy, dx, dy);
    m = fmin(m, seg_point(bx, by, cx, cy, dx, dy));
    m = fmin(m, seg_point(cx, cy, ax, ay, bx, by));
    return fmin(m, seg_point(dx, dy, ax, ay, bx, by));
}

/* The nearest any leg of @p p from leg @p from on comes to a wall segment of @p w. */
static double path_clearance(const hl_plan_path_t *p, const world_t *w, uint32_t from)
{
    double best = INFINITY;
    for (uint32_t k = from + 1; k < p->n; k++)
        for (uint32_t i = 0; i < w->n; i++) {
            const hl_vector_t *v = &w->v[i];
            double h = half_len(v), a = hl_bam_to_rad(v->normal);
            double tx = -sin(a) * h, ty = cos(a) * h;
            best = fmin(best, seg_seg(p->x_mm[k - 1], p->y_mm[k - 1], p->x_mm[k], p->y_mm[k],
                                      v->x_mm - tx, v->y_mm - ty, v->x_mm + tx, v->y_mm + ty));
        }
    return best;
}

/* The planner rounds a segment's ends to the millimetre: 2 mm of slack for that. */
#define ROUNDING 2.0

static hl_planner_t *planner(void)
{
    hl_plan_params_t p;
    hl_plan_params_default(&p);
    hl_planner_t *pl = hl_planner_create(&p);
    assert_non_null(pl);
    return pl;
}

static void assert_ends(const hl_plan_path_t *p, hl_mm_t sx, hl_mm_t sy, hl_mm_t gx, hl_mm_t gy)
{
    assert_true(p->n >= 2);
    assert_int_equal(p->x_mm[0], sx);
    assert_int_equal(p->y_mm[0], sy);
    assert_int_equal(p->x_mm[p->n - 1], gx);
    assert_int_equal(p->y_mm[p->n - 1], gy);
    assert_false(p->cut);
}

static void test_straight_in_empty_space(void **state)
{
    (void)state;
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 1000, &p), HL_PLAN_OK);
    assert_int_equal(p.n, 2);
    assert_ends(&p, 0, 0, 3000, 1000);
    assert_int_equal(p.length_mm, 3162);
    assert_int_equal(hl_planner_goal_clearance(pl), -1);

    /* The goal where the robot stands: two equal points. */
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 77, -13, 77, -13, &p), HL_PLAN_OK);
    assert_int_equal(p.n, 2);
    assert_ends(&p, 77, -13, 77, -13);
    assert_int_equal(p.length_mm, 0);
    hl_planner_destroy(pl);
}

static void test_wall_detour(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    wall(&W, 1000, -1500, 1000, 1500, LEFT);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 2000, 0, &p), HL_PLAN_OK);
    assert_true(p.n >= 3);
    assert_ends(&p, 0, 0, 2000, 0);
    assert_true(path_clearance(&p, &W, 0) >= 250 - ROUNDING);
    /* Round one end: past it by the radius at least, but not far past. */
    int32_t far = 0;
    for (uint32_t k = 0; k < p.n; k++)
        far = abs(p.y_mm[k]) > far ? abs(p.y_mm[k]) : far;
    assert_true(far >= 1500 + 250);
    assert_true(far <= 1500 + 250 + 300 + 100);
    /* The shortest way at the radius is 2 hypot(1000, 1775) = 4075; the A* path keeps
     * out of the clearance band too, at a price of some length. */
    assert_true(p.length_mm > 4075);
    assert_true(p.length_mm < 4075 * 5 / 4);
    assert_true(p.n <= 4);      /* out, round the end, in: no zigzag */
    hl_planner_destroy(pl);
}

static void test_goal_in_lethal_zone(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    wall(&W, 1000, -1500, 1000, 1500, LEFT);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    /* The wall's cells are centred on x = 1000 and reach down to 975. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 900, 0, &p), HL_PLAN_GOAL_BLOCKED);
    assert_int_equal(p.n, 0);
    assert_int_equal(hl_planner_goal_clearance(pl), 75);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 1000, 40, &p), HL_PLAN_GOAL_BLOCKED);
    assert_int_equal(hl_planner_goal_clearance(pl), 0);
    /* 375 mm off the wall's cells: a cell and a half beyond the radius plans. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 600, 0, &p), HL_PLAN_OK);
    assert_int_equal(hl_planner_goal_clearance(pl), 375);
    assert_ends(&p, 0, 0, 600, 0);
    hl_planner_destroy(pl);
}

static void test_goal_enclosed(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    room(&W, 4000, -1000, 6000, 1000, 0);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 5000, 0, &p), HL_PLAN_NO_PATH);
    assert_int_equal(p.n, 0);
    /* ... and out of it. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 5000, 0, 0, 0, &p), HL_PLAN_NO_PATH);
    /* The same room with a door. */
    memset(&W, 0, sizeof W);
    room(&W, 4000, -1000, 6000, 1000, 900);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 5000, 0, &p), HL_PLAN_OK);
    assert_true(path_clearance(&p, &W, 0) >= 250 - ROUNDING);
    hl_planner_destroy(pl);
}

/* Whether some leg crosses the line x = @p x within |y| < @p half. */
static bool passes(const hl_plan_path_t *p, double x, double half)
{
    for (uint32_t k = 1; k < p->n; k++)
        if (crosses(p->x_mm[k - 1], p->y_mm[k - 1], p->x_mm[k], p->y_mm[k], x, -half, x, half))
            return true;
    return false;
}

static void test_doorway(void **state)
{
    (void)state;
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    memset(&W, 0, sizeof W);
    room(&W, -2000, -2000, 2000, 2000, 450);       /* narrower than the body */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 4000, 0, &p), HL_PLAN_NO_PATH);
    memset(&W, 0, sizeof W);
    room(&W, -2000, -2000, 2000, 2000, 500);       /* the body exactly */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 4000, 0, &p), HL_PLAN_NO_PATH);
    memset(&W, 0, sizeof W);
    room(&W, -2000, -2000, 2000, 2000, 800);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 0, 4000, 0, &p), HL_PLAN_OK);
    assert_ends(&p, 0, 0, 4000, 0);
    assert_true(passes(&p, 2000, 400));
    assert_true(path_clearance(&p, &W, 0) >= 250 - ROUNDING);
    /* Straight through the middle of the door: the only way. */
    assert_int_equal(p.n, 2);
    hl_planner_destroy(pl);
}

static void test_start_next_to_wall(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    wall(&W, -3000, 0, 3000, 0, UP);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 0, 150, 2000, 1500, &p), HL_PLAN_OK);
    assert_ends(&p, 0, 150, 2000, 1500);
    hl_plan_grid_t g;
    hl_planner_grid(pl, &g);
    assert_int_equal(g.cells[g.start_row * g.cols + g.start_col], HL_PLAN_CELL_LETHAL);
    assert_int_equal(g.start_region[g.start_row * g.cols + g.start_col], 1);
    /* Away from the wall: the first leg leaves it, and every later one keeps off it. */
    assert_true(p.y_mm[1] > 150);
    assert_true(path_clearance(&p, &W, 1) >= 250 - ROUNDING);

    /* Stopped next to the wall, heading along it: out, along, and back to the goal. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -2000, 120, 2000, 400, &p), HL_PLAN_OK);
    assert_ends(&p, -2000, 120, 2000, 400);
    assert_true(path_clearance(&p, &W, 1) >= 250 - ROUNDING);
    hl_planner_destroy(pl);
}

/* A corridor at 45 degrees, 560 mm wide, open at (0, 0): its grid cells are all lethal
 * (a diagonal wall's cells stick out), the start's and its neighbours' too. Near the
 * mouth the robot leaves through its lethal region; deeper in, the region (radius + cell
 * = 300 mm) does not reach a free cell. */
static void test_start_deep_in_lethal_zone(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    double o = 280 * sqrt(2);
    wall(&W, -2000, -2000 + o, 0, o, 57344);        /* normals towards the middle */
    wall(&W, -2000, -2000 - o, 0, -o, 24576);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -300, -300, 2000, 2000, &p), HL_PLAN_OK);
    assert_ends(&p, -300, -300, 2000, 2000);
    hl_plan_grid_t g;
    hl_planner_grid(pl, &g);
    for (int dr = -1; dr <= 1; dr++)
        for (int dc = -1; dc <= 1; dc++) {
            int32_t k = (g.start_row + dr) * g.cols + g.start_col + dc;
            assert_int_equal(g.cells[k], HL_PLAN_CELL_LETHAL);
            assert_int_equal(g.start_region[k], 1);
        }
    assert_true(path_clearance(&p, &W, 0) > 200);   /* 280 at the start */
    assert_true(path_clearance(&p, &W, 1) >= 250 - ROUNDING);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -1000, -1000, 2000, 2000, &p),
                     HL_PLAN_NO_PATH);
    hl_planner_destroy(pl);
}

static bool left_of_2000(void *ctx, hl_mm_t x, hl_mm_t y)
{
    (void)ctx;
    (void)y;
    return x <= 2000;
}

/* Localized just outside the fence: back in through the fence's cells within the
 * region's reach, 300 mm. */
static void test_start_outside_fence(void **state)
{
    (void)state;
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    hl_planner_set_allowed(pl, left_of_2000, NULL);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 2150, 0, 0, 0, &p), HL_PLAN_OK);
    assert_ends(&p, 2150, 0, 0, 0);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 2350, 0, 0, 0, &p), HL_PLAN_OK);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 2400, 0, 0, 0, &p), HL_PLAN_NO_PATH);
    /* Outside, the region does not reach along the fence: no way to a goal out there. */
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 2150, 0, 2150, 2000, &p),
                     HL_PLAN_GOAL_BLOCKED);
    hl_planner_destroy(pl);
}

static bool in_rect(void *ctx, hl_mm_t x, hl_mm_t y)
{
    const int32_t *r = ctx;
    return x >= r[0] && y >= r[1] && x <= r[2] && y <= r[3];
}

static void test_allowed_rectangle(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    wall(&W, 0, -2500, 0, 800, LEFT);
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    /* Unfenced, the short way is over the top. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -1000, 0, 1000, 0, &p), HL_PLAN_OK);
    int32_t top = INT32_MIN, bottom = INT32_MAX;
    for (uint32_t k = 0; k < p.n; k++) {
        top = p.y_mm[k] > top ? p.y_mm[k] : top;
        bottom = p.y_mm[k] < bottom ? p.y_mm[k] : bottom;
    }
    assert_true(top >= 800 + 250);
    /* Fenced below y = 1000, the top passage is too narrow: round the bottom. */
    int32_t rect[4] = { -2000, -3500, 2000, 1000 };
    hl_planner_set_allowed(pl, in_rect, rect);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -1000, 0, 1000, 0, &p), HL_PLAN_OK);
    assert_ends(&p, -1000, 0, 1000, 0);
    top = INT32_MIN;
    bottom = INT32_MAX;
    for (uint32_t k = 0; k < p.n; k++) {
        assert_true(in_rect(rect, p.x_mm[k], p.y_mm[k]));   /* convex: legs inside too */
        top = p.y_mm[k] > top ? p.y_mm[k] : top;
        bottom = p.y_mm[k] < bottom ? p.y_mm[k] : bottom;
    }
    assert_true(top <= 1000);
    assert_true(bottom <= -2500 - 250);
    assert_true(path_clearance(&p, &W, 0) >= 250 - ROUNDING);
    hl_plan_grid_t g;
    hl_planner_grid(pl, &g);
    int32_t i = (-1500 - g.x0_mm) / g.cell_mm, j = (1200 - g.y0_mm) / g.cell_mm;
    assert_int_equal(g.cells[j * g.cols + i], HL_PLAN_CELL_FENCE);
    /* A goal outside the fence. */
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -1000, 0, 1000, 1200, &p),
                     HL_PLAN_GOAL_BLOCKED);
    /* Unfenced again. */
    hl_planner_set_allowed(pl, NULL, NULL);
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, -1000, 0, 1000, 1200, &p), HL_PLAN_OK);
    hl_planner_destroy(pl);
}

static double obstacle_clearance(const hl_plan_path_t *p, const hl_mm_t *ox, const hl_mm_t *oy,
                                 int n)
{
    double best = INFINITY;
    for (uint32_t k = 1; k < p->n; k++)
        for (int i = 0; i < n; i++)
            best = fmin(best, seg_point(ox[i], oy[i], p->x_mm[k - 1], p->y_mm[k - 1],
                                        p->x_mm[k], p->y_mm[k]));
    return best;
}

static void test_added_obstacles(void **state)
{
    (void)state;
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    hl_mm_t ox[21], oy[21];
    for (int i = 0; i < 21; i++) {
        ox[i] = 1500;
        oy[i] = -500 + 50 * i;
        assert_int_equal(hl_planner_add_obstacle(pl, ox[i], oy[i]), HL_OK);
    }
    assert_int_equal(hl_planner_obstacle_count(pl), 21);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_ends(&p, 0, 0, 3000, 0);
    assert_true(p.n >= 3);
    assert_true(obstacle_clearance(&p, ox, oy, 21) >= 250);
    /* Kept for every build until cleared. */
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_true(p.n >= 3);
    hl_planner_clear_obstacles(pl);
    assert_int_equal(hl_planner_obstacle_count(pl), 0);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_int_equal(p.n, 2);

    /* One blocks the straight way; 64 more, out of the way, push it out. */
    assert_int_equal(hl_planner_add_obstacle(pl, 1500, 0), HL_OK);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_true(p.n >= 3);
    for (int i = 0; i < HL_PLAN_MAX_OBSTACLES; i++)
        assert_int_equal(hl_planner_add_obstacle(pl, -3000, -3000 + 10 * i), HL_OK);
    assert_int_equal(hl_planner_obstacle_count(pl), HL_PLAN_MAX_OBSTACLES);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_int_equal(p.n, 2);
    /* An extra obstacle is a reading that just stopped the robot: kept however near the
     * start (a wall vector there would be dropped), and the way leaves round it. */
    hl_planner_clear_obstacles(pl);
    assert_int_equal(hl_planner_add_obstacle(pl, 200, 0), HL_OK);
    assert_int_equal(hl_planner_plan(pl, NULL, 0, 0, 0, 3000, 0, &p), HL_PLAN_OK);
    assert_true(p.n >= 3);
    for (uint32_t i = 0; i + 1 < p.n; i++)
        assert_true(seg_point(200, 0, p.x_mm[i], p.y_mm[i], p.x_mm[i + 1], p.y_mm[i + 1]) > 50);
    hl_planner_destroy(pl);
}

/* A deterministic scatter of short walls (the test's own generator). */
static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static void clutter(world_t *w, uint32_t seed, int pieces, int32_t half_side)
{
    memset(w, 0, sizeof *w);
    for (int i = 0; i < pieces; i++) {
        double x = (double)(lcg(&seed) % (uint32_t)(2 * half_side)) - half_side;
        double y = (double)(lcg(&seed) % (uint32_t)(2 * half_side)) - half_side;
        hl_bam_t n = (hl_bam_t)(lcg(&seed) & 0xffff);
        double a = hl_bam_to_rad(n), len = 300 + lcg(&seed) % 600;
        wall(w, x - sin(a) * -len / 2, y - cos(a) * len / 2, x + sin(a) * -len / 2,
             y + cos(a) * len / 2, n);
    }
}

static void test_deterministic(void **state)
{
    (void)state;
    clutter(&W, 7, 60, 4000);
    hl_planner_t *a = planner(), *b = planner();
    hl_plan_path_t p1, p2, p3;
    assert_int_equal(hl_planner_plan(a, W.v, W.n, -4800, -4800, 4800, 4800, &p1), HL_PLAN_OK);
    assert_int_equal(hl_planner_plan(a, W.v, W.n, -4800, -4800, 4800, 4800, &p2), HL_PLAN_OK);
    assert_int_equal(hl_planner_plan(b, W.v, W.n, -4800, -4800, 4800, 4800, &p3), HL_PLAN_OK);
    assert_true(p1.n >= 3);
    assert_memory_equal(&p1, &p2, sizeof p1);
    assert_memory_equal(&p1, &p3, sizeof p1);
    assert_true(path_clearance(&p1, &W, 0) >= 250 - ROUNDING);
    /* Another planner after another plan: the same again (no state carried over). */
    assert_int_equal(hl_planner_plan(b, W.v, W.n, 4800, -4800, -4800, 4800, &p3), HL_PLAN_OK);
    assert_int_equal(hl_planner_plan(b, W.v, W.n, -4800, -4800, 4800, 4800, &p3), HL_PLAN_OK);
    assert_memory_equal(&p1, &p3, sizeof p1);
    hl_planner_destroy(a);
    hl_planner_destroy(b);
}

/* A serpentine of walls in a long box needs more legs than a path holds. */
static void test_cut(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    room(&W, 0, -2000, 800 * 41, 2000, 0);
    for (int k = 1; k <= 40; k++) {
        double x = 800.0 * k;
        if (k % 2)
            wall(&W, x, -1000, x, 2000, LEFT);
        else
            wall(&W, x, -2000, x, 1000, LEFT);
    }
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    assert_int_equal(hl_planner_plan(pl, W.v, W.n, 400, 0, 800 * 41 - 400, 0, &p), HL_PLAN_OK);
    assert_true(p.cut);
    assert_int_equal(p.n, HL_PLAN_MAX_POINTS);
    assert_int_equal(p.x_mm[0], 400);
    assert_true(p.x_mm[p.n - 1] < 800 * 41 - 400);
    assert_true(p.x_mm[p.n - 1] > 800 * 12);     /* four points round each wall end */
    assert_true(path_clearance(&p, &W, 0) >= 250 - ROUNDING);
    double len = 0;
    for (uint32_t k = 1; k < p.n; k++)
        len += hypot(p.x_mm[k] - p.x_mm[k - 1], p.y_mm[k] - p.y_mm[k - 1]);
    assert_int_equal(p.length_mm, lround(len));
    hl_planner_destroy(pl);
}

static void test_bad_params_and_args(void **state)
{
    (void)state;
    hl_plan_params_t d, p;
    hl_plan_params_default(&d);
    assert_null(hl_plan_params_error(&d));
    assert_int_equal(d.half_beam, 1365);
    assert_non_null(hl_plan_params_error(NULL));
    struct { int32_t *field; int32_t bad; const char *name; } cases[] = {
        { &p.cell_mm, 19, "cell_mm" },       { &p.cell_mm, 501, "cell_mm" },
        { &p.radius_mm, 49, "radius_mm" },   { &p.radius_mm, 2001, "radius_mm" },
        { &p.clearance_mm, -1, "clearance_mm" }, { &p.clearance_mm, 3001, "clearance_mm" },
        { &p.max_half_mm, -1, "max_half_mm" },   { &p.max_half_mm, 5001, "max_half_mm" },
        { &p.max_cells, 1023, "max_cells" }, { &p.max_cells, (1 << 22) + 1, "max_cells" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        p = d;
        *cases[i].field = cases[i].bad;
        const char *e = hl_plan_params_error(&p);
        assert_non_null(e);
        assert_non_null(strstr(e, cases[i].name));
        assert_null(hl_planner_create(&p));
    }
    p = d;
    p.half_beam = 8193;
    assert_non_null(strstr(hl_plan_params_error(&p), "half_beam"));
    assert_null(hl_planner_create(NULL));
    hl_planner_destroy(NULL);

    hl_planner_t *pl = planner();
    hl_plan_path_t out;
    hl_vector_t v = { 0, 0, 0, 500 };
    assert_int_equal(hl_planner_plan(NULL, &v, 1, 0, 0, 1000, 0, &out), HL_PLAN_BAD_ARG);
    assert_int_equal(hl_planner_plan(pl, &v, 1, 0, 0, 1000, 0, NULL), HL_PLAN_BAD_ARG);
    assert_int_equal(hl_planner_plan(pl, NULL, 1, 0, 0, 1000, 0, &out), HL_PLAN_BAD_ARG);
    assert_int_equal(hl_planner_plan(pl, &v, HL_MAP_MAX_CAPACITY + 1, 0, 0, 1000, 0, &out),
                     HL_PLAN_BAD_ARG);
    assert_int_equal(hl_planner_plan(pl, &v, 1, HL_COORD_MAX_MM + 1, 0, 1000, 0, &out),
                     HL_PLAN_BAD_ARG);
    assert_int_equal(hl_planner_plan(pl, &v, 1, 0, 0, 0, -HL_COORD_MAX_MM - 1, &out),
                     HL_PLAN_BAD_ARG);
    hl_vector_t wild = { HL_COORD_MAX_MM + 1, 0, 0, 500 };
    assert_int_equal(hl_planner_plan(pl, &wild, 1, 0, 0, 1000, 0, &out), HL_PLAN_BAD_ARG);
    assert_int_equal(out.n, 0);
    hl_plan_grid_t g;
    hl_planner_grid(pl, &g);
    assert_int_equal(g.cols, 0);
    assert_int_equal(hl_planner_goal_clearance(pl), -1);
    /* 100 m at 50 mm cells is 4 million cells, over the default million. */
    assert_int_equal(hl_planner_plan(pl, &v, 1, 0, 0, 100000, 100000, &out), HL_PLAN_TOO_BIG);
    hl_planner_grid(pl, &g);
    assert_int_equal(g.cols, 0);
    assert_int_equal(hl_planner_add_obstacle(NULL, 0, 0), HL_ERR_ARG);
    assert_int_equal(hl_planner_add_obstacle(pl, 0, HL_COORD_MAX_MM + 1), HL_ERR_RANGE);
    assert_int_equal(hl_planner_obstacle_count(pl), 0);
    /* The world's edge is a fence: a goal at the very edge plans within it. */
    assert_int_equal(hl_planner_plan(pl, NULL, 0, HL_COORD_MAX_MM - 2000, 0, HL_COORD_MAX_MM,
                                     0, &out), HL_PLAN_OK);
    assert_string_equal(hl_plan_result_name(HL_PLAN_GOAL_BLOCKED), "goal blocked");
    assert_string_equal(hl_plan_result_name(HL_PLAN_NO_PATH), "no path");
    hl_planner_destroy(pl);
}

/* A lab of 11 x 9 m: outer walls, two inner walls and a few tables, 1,500 vectors with
 * the noise of real echoes. Prints the time of build + plan (sanitized here: see the
 * report for an optimized build's). */
static void test_lab_timing(void **state)
{
    (void)state;
    memset(&W, 0, sizeof W);
    room(&W, 0, -4500, 11000, 4500, 0);
    wall(&W, 4000, -4500, 4000, 2500, RIGHT);
    wall(&W, 4000, -4500, 4000, 2500, LEFT);
    wall(&W, 7500, -2500, 7500, 4500, RIGHT);
    wall(&W, 7500, -2500, 7500, 4500, LEFT);
    for (int t = 0; t < 4; t++)
        room(&W, 1000 + 2500 * t, -3800, 1900 + 2500 * t, -3000, 0);
    uint32_t seed = 3, base = W.n;
    while (W.n < 1500) {
        hl_vector_t v = W.v[lcg(&seed) % base];
        v.x_mm += (hl_mm_t)(lcg(&seed) % 61) - 30;
        v.y_mm += (hl_mm_t)(lcg(&seed) % 61) - 30;
        v.normal = (hl_bam_t)(v.normal + (lcg(&seed) % 1001) - 500);
        v.range_mm = (uint16_t)(400 + lcg(&seed) % 2600);
        W.v[W.n++] = v;
    }
    hl_planner_t *pl = planner();
    hl_plan_path_t p;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    int runs = 20;
    for (int i = 0; i < runs; i++)
        assert_int_equal(hl_planner_plan(pl, W.v, W.n, 1000, 3000, 10000, -3500, &p), HL_PLAN_OK);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double ms = ((t1.tv_sec - t0.tv_sec) * 1e3 + (t1.tv_nsec - t0.tv_nsec) / 1e6) / runs;
    hl_plan_grid_t g;
    hl_planner_grid(pl, &g);
    printf("lab: %u vectors, %d x %d cells, %u points, %d mm, %.2f ms per build + plan\n",
           W.n, g.cols, g.rows, p.n, p.length_mm, ms);
    assert_ends(&p, 1000, 3000, 10000, -3500);
    assert_true(p.n >= 4);      /* below the first inner wall, over the second */
    hl_planner_destroy(pl);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_straight_in_empty_space),
        cmocka_unit_test(test_wall_detour),
        cmocka_unit_test(test_goal_in_lethal_zone),
        cmocka_unit_test(test_goal_enclosed),
        cmocka_unit_test(test_doorway),
        cmocka_unit_test(test_start_next_to_wall),
        cmocka_unit_test(test_start_deep_in_lethal_zone),
        cmocka_unit_test(test_start_outside_fence),
        cmocka_unit_test(test_allowed_rectangle),
        cmocka_unit_test(test_added_obstacles),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_cut),
        cmocka_unit_test(test_bad_params_and_args),
        cmocka_unit_test(test_lab_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
