/*
 * plan.c - A* over the costmap and the string-pulling of its cell path (plan.h).
 *
 * Costs are integers: a straight step costs 29 and a diagonal one 41 (41/29 = 1.4138,
 * sqrt 2 to 0.03 %), each times (1 + cost / 63) of the cell entered, so the edge of the
 * clearance band costs 5 times open floor; a step inside the start's lethal region costs
 * LETHAL_STEP times. The octile heuristic on the same 29/41 is consistent, so a cell is
 * closed once. Along a path through at most 2^22 cells g stays below 2^30.
 *
 * Open cells sit in a binary heap ordered by f and then by larger g. Nothing else enters
 * the search (no clock, no address, no state of an earlier plan), so the same inputs
 * expand the same cells in the same order and give the same path.
 */
#include "houghloc/plan.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STRAIGHT 29u
#define DIAGONAL 41u
#define COST_SCALE 63u      /* a cell of cost c multiplies a step by 1 + c / COST_SCALE */
#define LETHAL_STEP 10u     /* inside the start's lethal region */

#define NEW (-1)            /* pos[]: never reached */
#define CLOSED (-2)         /* pos[]: expanded */

struct hl_planner {
    hl_plan_params_t p;
    hl_costmap_t *cm;
    hl_plan_allowed_fn allowed;
    void *allowed_ctx;
    hl_mm_t obstacle_x[HL_PLAN_MAX_OBSTACLES], obstacle_y[HL_PLAN_MAX_OBSTACLES];
    uint32_t n_obstacles, next_obstacle;    /* a ring: next_obstacle is the oldest when full */
    /* Per cell, max_cells each. After the search, pos holds the cell path and g the
     * running cost maximum of the string-pulling. */
    uint32_t *g;
    int32_t *pos;           /* index in the heap, or NEW, or CLOSED */
    uint8_t *from;          /* the move (0..7) that reached the cell */
    /* The open cells, a binary heap in two arrays: key = f << 32 | (UINT32_MAX - g), so
     * that one comparison orders by f and then the deeper cell first (fewer equals
     * expanded on open floor); equal keys go by the heap's own order, itself the same for
     * the same inputs. */
    uint64_t *open_key;
    uint32_t *open_idx;
    uint32_t n_open;
};

/* The 8 moves: the four straight ones first. */
static const int8_t MOVE_DC[8] = { 1, 0, -1, 0, 1, -1, -1, 1 };
static const int8_t MOVE_DR[8] = { 0, 1, 0, -1, 1, 1, -1, -1 };

void hl_plan_params_default(hl_plan_params_t *p)
{
    p->cell_mm = 50;
    p->radius_mm = 250;
    p->clearance_mm = 300;
    p->half_beam = hl_bam_from_deg(7.5);
    p->max_half_mm = 150;
    p->wall_range_mm = 2000;
    p->max_cells = 1 << 20;
}

const char *hl_plan_params_error(const hl_plan_params_t *p)
{
    if (!p)
        return "no plan parameters";
    if (p->cell_mm < 20 || p->cell_mm > 500)
        return "plan cell_mm must be 20..500";
    if (p->radius_mm < 50 || p->radius_mm > 2000)
        return "plan radius_mm must be 50..2000";
    if (p->clearance_mm < 0 || p->clearance_mm > 3000)
        return "plan clearance_mm must be 0..3000";
    if (p->half_beam > HL_BAM_PER_TURN / 8)
        return "plan half_beam must be 0..45 degrees";
    if (p->max_half_mm < 0 || p->max_half_mm > 5000)
        return "plan max_half_mm must be 0..5000";
    if (p->wall_range_mm < 100 || p->wall_range_mm > 32767)
        return "plan wall_range_mm must be 100..32767";
    if (p->max_cells < 1024 || p->max_cells > (1 << 22))
        return "plan max_cells must be 1024..4194304";
    return NULL;
}

const char *hl_plan_result_name(hl_plan_result_t r)
{
    switch (r) {
    case HL_PLAN_OK: return "ok";
    case HL_PLAN_GOAL_BLOCKED: return "goal blocked";
    case HL_PLAN_NO_PATH: return "no path";
    case HL_PLAN_TOO_BIG: return "map too big";
    case HL_PLAN_BAD_ARG: return "bad argument";
    }
    return "unknown";
}

hl_planner_t *hl_planner_create(const hl_plan_params_t *p)
{
    if (hl_plan_params_error(p))
        return NULL;
    hl_planner_t *pl = calloc(1, sizeof *pl);
    if (!pl)
        return NULL;
    pl->p = *p;
    size_t n = (size_t)p->max_cells;
    pl->cm = hl_costmap_create(p);
    pl->g = malloc(n * sizeof *pl->g);
    pl->pos = malloc(n * sizeof *pl->pos);
    pl->from = malloc(n);
    pl->open_key = malloc(n * sizeof *pl->open_key);
    pl->open_idx = malloc(n * sizeof *pl->open_idx);
    if (!pl->cm || !pl->g || !pl->pos || !pl->from || !pl->open_key || !pl->open_idx) {
        hl_planner_destroy(pl);
        return NULL;
    }
    return pl;
}

void hl_planner_destroy(hl_planner_t *pl)
{
    if (!pl)
        return;
    hl_costmap_destroy(pl->cm);
    free(pl->g);
    free(pl->pos);
    free(pl->from);
    free(pl->open_key);
    free(pl->open_idx);
    free(pl);
}

size_t hl_planner_mem_bytes(const hl_planner_t *pl)
{
    if (!pl)
        return 0;
    size_t n = (size_t)pl->p.max_cells;
    return sizeof *pl + hl_costmap_mem_bytes(pl->cm) +
           n * (sizeof *pl->g + sizeof *pl->pos + 1 + sizeof *pl->open_key +
                sizeof *pl->open_idx);
}

hl_status_t hl_planner_add_obstacle(hl_planner_t *pl, hl_mm_t x_mm, hl_mm_t y_mm)
{
    if (!pl)
        return HL_ERR_ARG;
    if (x_mm < -HL_COORD_MAX_MM || x_mm > HL_COORD_MAX_MM || y_mm < -HL_COORD_MAX_MM ||
        y_mm > HL_COORD_MAX_MM)
        return HL_ERR_RANGE;
    pl->obstacle_x[pl->next_obstacle] = x_mm;
    pl->obstacle_y[pl->next_obstacle] = y_mm;
    pl->next_obstacle = (pl->next_obstacle + 1) % HL_PLAN_MAX_OBSTACLES;
    if (pl->n_obstacles < HL_PLAN_MAX_OBSTACLES)
        pl->n_obstacles++;
    return HL_OK;
}

void hl_planner_clear_obstacles(hl_planner_t *pl)
{
    if (pl)
        pl->n_obstacles = pl->next_obstacle = 0;
}

uint32_t hl_planner_obstacle_count(const hl_planner_t *pl)
{
    return pl ? pl->n_obstacles : 0;
}

void hl_planner_set_allowed(hl_planner_t *pl, hl_plan_allowed_fn fn, void *ctx)
{
    if (!pl)
        return;
    pl->allowed = fn;
    pl->allowed_ctx = ctx;
}

void hl_planner_grid(const hl_planner_t *pl, hl_plan_grid_t *out)
{
    hl_costmap_grid(pl ? pl->cm : NULL, out);
}

int32_t hl_planner_goal_clearance(const hl_planner_t *pl)
{
    if (!pl)
        return -1;
    hl_plan_grid_t g;
    hl_costmap_grid(pl->cm, &g);
    return g.goal_clearance_mm;
}

/* ---- the open heap ------------------------------------------------------------------- */

static uint64_t open_key(uint32_t f, uint32_t g)
{
    return (uint64_t)f << 32 | (UINT32_MAX - g);
}

static void place(hl_planner_t *pl, uint32_t at, uint64_t key, uint32_t idx)
{
    pl->open_key[at] = key;
    pl->open_idx[at] = idx;
    pl->pos[idx] = (int32_t)at;
}

static void sift_up(hl_planner_t *pl, uint32_t at, uint64_t key, uint32_t idx)
{
    while (at > 0) {
        uint32_t up = (at - 1) / 2;
        if (key >= pl->open_key[up])
            break;
        place(pl, at, pl->open_key[up], pl->open_idx[up]);
        at = up;
    }
    place(pl, at, key, idx);
}

static uint32_t pop(hl_planner_t *pl)
{
    uint32_t top = pl->open_idx[0], n = --pl->n_open;
    uint64_t key = pl->open_key[n];
    uint32_t idx = pl->open_idx[n], at = 0;
    for (;;) {
        uint32_t kid = 2 * at + 1;
        if (kid >= n)
            break;
        kid += kid + 1 < n && pl->open_key[kid + 1] < pl->open_key[kid];
        if (pl->open_key[kid] >= key)
            break;
        place(pl, at, pl->open_key[kid], pl->open_idx[kid]);
        at = kid;
    }
    if (n > 0)
        place(pl, at, key, idx);
    pl->pos[top] = CLOSED;
    return top;
}

/* ---- the search ----------------------------------------------------------------------- */

static uint32_t octile(int32_t dc, int32_t dr)
{
    uint32_t a = (uint32_t)abs(dc), b = (uint32_t)abs(dr);
    return a > b ? STRAIGHT * a + (DIAGONAL - STRAIGHT) * b
                 : STRAIGHT * b + (DIAGONAL - STRAIGHT) * a;
}

/* The cost of stepping into cell n, or 0 when it cannot be entered. */
static uint32_t step_cost(const hl_plan_grid_t *g, uint32_t n, uint32_t base)
{
    uint8_t v = g->cells[n];
    if (v <= HL_PLAN_COST_MAX)
        return base + base * v / COST_SCALE;
    if (v != HL_PLAN_CELL_OBSTACLE && g->start_region[n])
        return base * LETHAL_STEP;
    return 0;
}

static bool search(hl_planner_t *pl, const hl_plan_grid_t *g)
{
    int32_t w = g->cols;
    uint32_t start = (uint32_t)(g->start_row * w + g->start_col);
    uint32_t goal = (uint32_t)(g->goal_row * w + g->goal_col);
    memset(pl->pos, 0xff, (size_t)w * (size_t)g->rows * sizeof *pl->pos);  /* NEW */
    pl->g[start] = 0;
    pl->n_open = 1;
    sift_up(pl, 0, open_key(octile(g->goal_col - g->start_col, g->goal_row - g->start_row), 0),
            start);
    while (pl->n_open > 0) {
        uint32_t at = pop(pl);
        if (at == goal)
            return true;
        int32_t col = (int32_t)(at % (uint32_t)w), row = (int32_t)(at / (uint32_t)w);
        for (int k = 0; k < 8; k++) {
            int32_t nc = col + MOVE_DC[k], nr = row + MOVE_DR[k];
            if (nc < 0 || nr < 0 || nc >= w || nr >= g->rows)
                continue;
            uint32_t n = (uint32_t)(nr * w + nc);
            if (pl->pos[n] == CLOSED)
                continue;
            uint32_t step = step_cost(g, n, k < 4 ? STRAIGHT : DIAGONAL);
            if (!step)
                continue;
            /* A diagonal move touches the corner of both cells beside it. */
            if (k >= 4 && (g->cells[row * w + nc] == HL_PLAN_CELL_OBSTACLE ||
                           g->cells[nr * w + col] == HL_PLAN_CELL_OBSTACLE))
                continue;
            uint32_t ng = pl->g[at] + step;
            if (pl->pos[n] != NEW && ng >= pl->g[n])
                continue;
            pl->g[n] = ng;
            pl->from[n] = (uint8_t)k;
            uint64_t key = open_key(ng + octile(g->goal_col - nc, g->goal_row - nr), ng);
            sift_up(pl, pl->pos[n] == NEW ? pl->n_open++ : (uint32_t)pl->pos[n], key, n);
        }
    }
    return false;
}

/* Writes the cell path, start cell first, into pos[]; @return its length. */
static uint32_t trace_back(hl_planner_t *pl, const hl_plan_grid_t *g)
{
    int32_t w = g->cols;
    int32_t start = g->start_row * w + g->start_col, goal = g->goal_row * w + g->goal_col;
    uint32_t m = 1;
    for (int32_t at = goal; at != start; m++) {
        int k = pl->from[at];
        at -= MOVE_DR[k] * w + MOVE_DC[k];
    }
    uint32_t i = m;
    for (int32_t at = goal;; ) {
        pl->pos[--i] = at;
        if (at == start)
            break;
        int k = pl->from[at];
        at -= MOVE_DR[k] * w + MOVE_DC[k];
    }
    return m;
}

/* ---- string pulling -------------------------------------------------------------------- */

/* The pulled points: 0 the start, 1..m the path cells' centres, m + 1 the goal. The
 * cells' centres are there so that every two neighbours join within their own cells. */
typedef struct pull {
    const hl_plan_grid_t *g;
    const int32_t *cells;
    uint32_t m;
    hl_mm_t sx, sy, gx, gy;
} pull_t;

static void pull_point(const pull_t *pu, uint32_t k, hl_mm_t *x, hl_mm_t *y)
{
    if (k == 0) {
        *x = pu->sx;
        *y = pu->sy;
    } else if (k > pu->m) {
        *x = pu->gx;
        *y = pu->gy;
    } else {
        int32_t at = pu->cells[k - 1], w = pu->g->cols;
        *x = pu->g->x0_mm + (at % w) * pu->g->cell_mm;
        *y = pu->g->y0_mm + (at / w) * pu->g->cell_mm;
    }
}

/* The index in the cell path of point k's cell. */
static uint32_t point_cell(const pull_t *pu, uint32_t k)
{
    return k == 0 ? 0 : k > pu->m ? pu->m - 1 : k - 1;
}

static void add_point(hl_plan_path_t *out, hl_mm_t x, hl_mm_t y)
{
    if (out->n > 0 && out->x_mm[out->n - 1] == x && out->y_mm[out->n - 1] == y)
        return;
    if (out->n == HL_PLAN_MAX_POINTS) {
        out->cut = true;
        return;
    }
    out->x_mm[out->n] = x;
    out->y_mm[out->n] = y;
    out->n++;
}

/* From each point, the farthest later point reachable by a clear straight leg. A leg may
 * meet cells up to HL_PLAN_SMOOTH_COST, or as costly as the A* path between its ends
 * went (in a narrow passage every cell is costly); the start region's cells count 0
 * there, and a leg may cross them. Neighbouring points always join. */
static void string_pull(hl_planner_t *pl, const pull_t *pu, hl_plan_path_t *out)
{
    uint32_t last = pu->m + 1, *worst = pl->g;   /* worst[i]: max cost, path cells to i */
    hl_mm_t ax, ay, bx, by;
    pull_point(pu, 0, &ax, &ay);
    out->n = 0;
    add_point(out, ax, ay);
    for (uint32_t cur = 0; cur < last && !out->cut;) {
        uint32_t first = point_cell(pu, cur), prev = 0;
        for (uint32_t i = first; i < pu->m; i++) {
            uint8_t v = pu->g->cells[pu->cells[i]];
            uint32_t c = v <= HL_PLAN_COST_MAX ? v : 0;
            worst[i] = prev = prev > c ? prev : c;
        }
        uint32_t next = cur + 1;
        for (uint32_t j = last; j > cur + 1; j--) {
            uint32_t w = worst[point_cell(pu, j)];
            uint8_t limit = (uint8_t)(w > HL_PLAN_SMOOTH_COST ? w : HL_PLAN_SMOOTH_COST);
            pull_point(pu, j, &bx, &by);
            if (hl_plan_segment_clear(pu->g, ax, ay, bx, by, limit)) {
                next = j;
                break;
            }
        }
        pull_point(pu, next, &ax, &ay);
        add_point(out, ax, ay);
        cur = next;
    }
    if (out->n == 1) {  /* the goal is the start: still two points */
        out->x_mm[1] = pu->gx;
        out->y_mm[1] = pu->gy;
        out->n = 2;
    }
    double len = 0;
    for (uint32_t k = 1; k < out->n; k++)
        len += hypot((double)out->x_mm[k] - out->x_mm[k - 1],
                     (double)out->y_mm[k] - out->y_mm[k - 1]);
    out->length_mm = (int32_t)lround(len);
}

hl_plan_result_t hl_planner_plan(hl_planner_t *pl, const hl_vector_t *v, uint32_t n,
                                 hl_mm_t start_x, hl_mm_t start_y, hl_mm_t goal_x,
                                 hl_mm_t goal_y, hl_plan_path_t *out)
{
    if (!out)
        return HL_PLAN_BAD_ARG;
    memset(out, 0, sizeof *out);
    if (!pl)
        return HL_PLAN_BAD_ARG;
    hl_costmap_input_t in = {
        .v = v, .n = n,
        .obstacle_x = pl->obstacle_x, .obstacle_y = pl->obstacle_y,
        .n_obstacles = pl->n_obstacles,
        .allowed = pl->allowed, .allowed_ctx = pl->allowed_ctx,
        .start_x = start_x, .start_y = start_y, .goal_x = goal_x, .goal_y = goal_y,
    };
    hl_plan_result_t res = hl_costmap_build(pl->cm, &in);
    if (res != HL_PLAN_OK)
        return res;
    hl_plan_grid_t g;
    hl_costmap_grid(pl->cm, &g);
    if (g.cells[g.goal_row * g.cols + g.goal_col] > HL_PLAN_COST_MAX ||
        (pl->allowed && !pl->allowed(pl->allowed_ctx, goal_x, goal_y)))
        return HL_PLAN_GOAL_BLOCKED;
    if (!search(pl, &g))
        return HL_PLAN_NO_PATH;
    pull_t pu = { &g, pl->pos, trace_back(pl, &g), start_x, start_y, goal_x, goal_y };
    string_pull(pl, &pu, out);
    return HL_PLAN_OK;
}
