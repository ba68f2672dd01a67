/*
 * costmap.c - the planner's grid (plan.h): wall segments and extra obstacles rasterized,
 * inflated through an exact Euclidean distance transform (edt.c), fenced, and the start's lethal
 * region marked.
 *
 * The inflation measures between whole cells: a cell is lethal when some point of it is
 * within radius_mm of some point of an obstacle cell. The distance between two cell
 * squares whose centres are (dx, dy) cells apart is the distance between centres after
 * each |d| is shortened by one cell, which is the centre distance to the obstacle cell
 * grown by its 8 neighbours. So the transform runs on the obstacles grown by one cell:
 * its column pass looks at three columns and takes one row off the distance, its row
 * pass is Meijster, Roerdink and Hesselink's (2000) lower envelope of parabolas. All in
 * integers; squared distances in cells^2. The cells a wall or a beam crosses come from
 * gridwalk.c.
 *
 * Coordinates inside the grid are in half millimetres from the grid's corner
 * (X = 2 (x - x0) + cell_mm), so that an odd cell's borders are whole numbers too.
 */
#include "houghloc/plan.h"

#include "edt.h"
#include "gridwalk.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct hl_costmap {
    hl_plan_params_t p;
    int32_t tan_q16;        /* tan(half_beam), Q16 */
    int32_t band;           /* cells: column distances are capped here, beyond any cost */
    uint32_t lut_n;         /* squared cell distances below this are lethal or cost */
    uint8_t *lut;           /* lut_n: the cell byte for each squared distance */
    uint8_t *cells, *region, *dist;  /* max_cells each; dist: the column pass */
    int32_t max_cols;       /* every grid has at least max_cells / max_cols rows */
    int32_t *env_s, *env_t; /* max_cols each: the row pass's parabolas and their starts */
    int32_t *queue;         /* queue_n: the start region's flood */
    int32_t queue_n;
    hl_plan_grid_t grid;
};

/* Rounds v / 2^14 to nearest (ties away from zero), for Q14 products. */
static int32_t round_q14(int64_t v)
{
    return (int32_t)(v >= 0 ? (v + 8192) / 16384 : -((-v + 8192) / 16384));
}

static void free_all(hl_costmap_t *cm)
{
    free(cm->lut);
    free(cm->cells);
    free(cm->region);
    free(cm->dist);
    free(cm->env_s);
    free(cm->env_t);
    free(cm->queue);
    free(cm);
}

/* The cell byte for each squared distance (cells^2) inside the band, and its length. */
static void fill_lut(hl_costmap_t *cm)
{
    int64_t c = cm->p.cell_mm, r = cm->p.radius_mm, clr = cm->p.clearance_mm;
    for (uint32_t d2 = 0; d2 < cm->lut_n; d2++) {
        if ((int64_t)d2 * c * c < r * r) {
            cm->lut[d2] = HL_PLAN_CELL_LETHAL;
            continue;
        }
        double d = sqrt((double)d2) * (double)c;
        long cost = clr > 0 ? (long)ceil(HL_PLAN_COST_MAX * ((double)(r + clr) - d) / (double)clr)
                            : 0;
        cm->lut[d2] = (uint8_t)(cost < 0 ? 0 : cost > HL_PLAN_COST_MAX ? HL_PLAN_COST_MAX : cost);
    }
}

hl_costmap_t *hl_costmap_create(const hl_plan_params_t *p)
{
    if (hl_plan_params_error(p))
        return NULL;
    hl_costmap_t *cm = calloc(1, sizeof *cm);
    if (!cm)
        return NULL;
    cm->p = *p;
    cm->tan_q16 = (int32_t)(((int64_t)hl_sin(p->half_beam) << 16) / hl_cos(p->half_beam));
    int64_t c = p->cell_mm, reach = (int64_t)p->radius_mm + p->clearance_mm;
    cm->lut_n = (uint32_t)((reach * reach + c * c - 1) / (c * c));
    /* Column distances matter below sqrt(lut_n) cells; +3 for the one-cell growth and
     * the rounding (at most 5000 / 20 + 3 = 253: fits the dist bytes). */
    cm->band = (int32_t)((reach + c - 1) / c) + 3;
    int64_t margin = reach + c;
    int64_t min_rows = (2 * margin + c - 1) / c + 1;
    cm->max_cols = (int32_t)(p->max_cells / min_rows);
    int64_t win = 2 * (((int64_t)p->radius_mm + c + c - 1) / c) + 1;
    cm->queue_n = (int32_t)(win * win);
    size_t n = (size_t)p->max_cells;
    cm->lut = malloc(cm->lut_n);
    cm->cells = malloc(n);
    cm->region = malloc(n);
    cm->dist = malloc(n);
    cm->env_s = malloc((size_t)cm->max_cols * sizeof *cm->env_s);
    cm->env_t = malloc((size_t)cm->max_cols * sizeof *cm->env_t);
    cm->queue = malloc((size_t)cm->queue_n * sizeof *cm->queue);
    if (!cm->lut || !cm->cells || !cm->region || !cm->dist || !cm->env_s || !cm->env_t ||
        !cm->queue) {
        free_all(cm);
        return NULL;
    }
    fill_lut(cm);
    cm->grid.goal_clearance_mm = -1;
    return cm;
}

void hl_costmap_destroy(hl_costmap_t *cm)
{
    if (cm)
        free_all(cm);
}

size_t hl_costmap_mem_bytes(const hl_costmap_t *cm)
{
    if (!cm)
        return 0;
    return sizeof *cm + cm->lut_n + 3 * (size_t)cm->p.max_cells +
           2 * (size_t)cm->max_cols * sizeof(int32_t) + (size_t)cm->queue_n * sizeof(int32_t);
}

void hl_costmap_grid(const hl_costmap_t *cm, hl_plan_grid_t *out)
{
    if (!out)
        return;
    if (cm)
        *out = cm->grid;
    else
        *out = (hl_plan_grid_t){ .goal_clearance_mm = -1 };
}

/* ---- building ----------------------------------------------------------------------- */

/* The two ends of a vector's wall segment: along the tangent, half-length
 * range * tan(half_beam) capped at max_half_mm. */
static void wall_ends(const hl_costmap_t *cm, const hl_vector_t *v, int64_t e[4])
{
    int64_t half = ((int64_t)v->range_mm * cm->tan_q16 + 32768) >> 16;
    if (half > cm->p.max_half_mm)
        half = cm->p.max_half_mm;
    int32_t tx = round_q14(-half * hl_sin(v->normal)), ty = round_q14(half * hl_cos(v->normal));
    e[0] = (int64_t)v->x_mm - tx;
    e[1] = (int64_t)v->y_mm - ty;
    e[2] = (int64_t)v->x_mm + tx;
    e[3] = (int64_t)v->y_mm + ty;
}

static bool in_world(int64_t x, int64_t y)
{
    return x >= -HL_COORD_MAX_MM && x <= HL_COORD_MAX_MM && y >= -HL_COORD_MAX_MM &&
           y <= HL_COORD_MAX_MM;
}

static void grow_box(int64_t box[4], int64_t x, int64_t y)
{
    if (x < box[0]) box[0] = x;
    if (y < box[1]) box[1] = y;
    if (x > box[2]) box[2] = x;
    if (y > box[3]) box[3] = y;
}

/* Checks the input, and lays out the grid over everything plus the margin. */
static hl_plan_result_t lay_out(hl_costmap_t *cm, const hl_costmap_input_t *in)
{
    if ((in->n && !in->v) || in->n > HL_MAP_MAX_CAPACITY ||
        (in->n_obstacles && (!in->obstacle_x || !in->obstacle_y)) ||
        !in_world(in->start_x, in->start_y) || !in_world(in->goal_x, in->goal_y))
        return HL_PLAN_BAD_ARG;
    int64_t box[4] = { in->start_x, in->start_y, in->start_x, in->start_y };
    grow_box(box, in->goal_x, in->goal_y);
    for (uint32_t k = 0; k < in->n_obstacles; k++) {
        if (!in_world(in->obstacle_x[k], in->obstacle_y[k]))
            return HL_PLAN_BAD_ARG;
        grow_box(box, in->obstacle_x[k], in->obstacle_y[k]);
    }
    for (uint32_t k = 0; k < in->n; k++) {
        if (!hl_vector_in_range(&in->v[k]))
            return HL_PLAN_BAD_ARG;
        int64_t e[4];
        wall_ends(cm, &in->v[k], e);
        grow_box(box, e[0], e[1]);
        grow_box(box, e[2], e[3]);
    }
    int64_t c = cm->p.cell_mm, m = (int64_t)cm->p.radius_mm + cm->p.clearance_mm + c;
    int64_t i0 = hl_walk_floor_div(box[0] - m, c), j0 = hl_walk_floor_div(box[1] - m, c);
    int64_t cols = -hl_walk_floor_div(-(box[2] + m), c) - i0 + 1;
    int64_t rows = -hl_walk_floor_div(-(box[3] + m), c) - j0 + 1;
    if (cols * rows > cm->p.max_cells || cols > cm->max_cols)
        return HL_PLAN_TOO_BIG;
    hl_plan_grid_t *g = &cm->grid;
    g->cols = (int32_t)cols;
    g->rows = (int32_t)rows;
    g->cell_mm = cm->p.cell_mm;
    g->x0_mm = (hl_mm_t)(i0 * c);
    g->y0_mm = (hl_mm_t)(j0 * c);
    g->cells = cm->cells;
    g->start_region = cm->region;
    g->start_col = (int32_t)hl_walk_floor_div(2 * ((int64_t)in->start_x - g->x0_mm) + c, 2 * c);
    g->start_row = (int32_t)hl_walk_floor_div(2 * ((int64_t)in->start_y - g->y0_mm) + c, 2 * c);
    g->goal_col = (int32_t)hl_walk_floor_div(2 * ((int64_t)in->goal_x - g->x0_mm) + c, 2 * c);
    g->goal_row = (int32_t)hl_walk_floor_div(2 * ((int64_t)in->goal_y - g->y0_mm) + c, 2 * c);
    return HL_PLAN_OK;
}

/* Marks every cell a segment touches as an obstacle; @return how many became one. */
static uint32_t draw_segment(hl_costmap_t *cm, int64_t ax, int64_t ay, int64_t bx, int64_t by)
{
    const hl_plan_grid_t *g = &cm->grid;
    walk_t w;
    hl_walk_init(&w, g, ax, ay, bx, by);
    uint32_t added = 0;
    do {
        uint8_t *v = &cm->cells[(size_t)w.row * (size_t)g->cols + (size_t)w.col];
        added += *v != HL_PLAN_CELL_OBSTACLE;
        *v = HL_PLAN_CELL_OBSTACLE;
    } while (hl_walk_next(&w));
    return added;
}

/* ---- evidence: wall segments for, beams against ----------------------------------------- */

/* A beam's carving stops this short of its echo, so that a surface does not clear its own
 * cells (its segment is a cell or two thick where it crosses the grid at an angle). */
#define CARVE_SHORT_MM 150

static void add_saturating(uint8_t *v)
{
    if (*v < 255)
        (*v)++;
}

/* Counts one more for every cell the segment touches, in @p count (a max_cells array). */
static void count_segment(const hl_plan_grid_t *g, uint8_t *count, int64_t ax, int64_t ay,
                          int64_t bx, int64_t by)
{
    walk_t w;
    hl_walk_init(&w, g, ax, ay, bx, by);
    do {
        if (hl_walk_in_grid(g, w.col, w.row))
            add_saturating(&count[(size_t)w.row * (size_t)g->cols + (size_t)w.col]);
    } while (hl_walk_next(&w));
}

/* A vector's beam, from where its sensor stood to CARVE_SHORT_MM before its surface
 * point; false when it is shorter than that. */
static bool beam_ends(const hl_vector_t *v, int64_t e[4])
{
    int64_t len = (int64_t)v->range_mm - CARVE_SHORT_MM;
    if (len <= 0)
        return false;
    int64_t c = hl_cos(v->normal), s = hl_sin(v->normal);
    e[0] = (int64_t)v->x_mm + round_q14((int64_t)v->range_mm * c);
    e[1] = (int64_t)v->y_mm + round_q14((int64_t)v->range_mm * s);
    e[2] = (int64_t)v->x_mm + round_q14(CARVE_SHORT_MM * c);
    e[3] = (int64_t)v->y_mm + round_q14(CARVE_SHORT_MM * s);
    return true;
}

/* The obstacle cells of the map's vectors: wall segments counted in hits, beams in free
 * (both max_cells scratch arrays), a cell an obstacle when its hits outnumber its free.
 * @return how many cells became obstacles. */
static uint32_t draw_walls(hl_costmap_t *cm, const hl_costmap_input_t *in, uint8_t *hits,
                           uint8_t *free_)
{
    const hl_plan_grid_t *g = &cm->grid;
    size_t n = (size_t)g->cols * (size_t)g->rows;
    memset(hits, 0, n);
    memset(free_, 0, n);
    for (uint32_t k = 0; k < in->n; k++) {
        const hl_vector_t *v = &in->v[k];
        int64_t e[4];
        if (beam_ends(v, e))
            count_segment(g, free_, e[0], e[1], e[2], e[3]);
        if (v->range_mm > cm->p.wall_range_mm)
            continue;
        wall_ends(cm, v, e);
        count_segment(g, hits, e[0], e[1], e[2], e[3]);
    }
    uint32_t added = 0;
    for (size_t i = 0; i < n; i++)
        if (hits[i] > free_[i]) {
            cm->cells[i] = HL_PLAN_CELL_OBSTACLE;
            added++;
        }
    return added;
}

/* Squared distance, in half millimetres, from point (X, Y) to the square of cell
 * (col, row); both in grid half-mm. */
static int64_t point_to_cell2(const hl_plan_grid_t *g, int64_t X, int64_t Y, int32_t col,
                              int32_t row)
{
    int64_t c = g->cell_mm;
    int64_t dx = llabs(X - (2 * (int64_t)col * c + c)) - c;
    int64_t dy = llabs(Y - (2 * (int64_t)row * c + c)) - c;
    dx = dx > 0 ? dx : 0;
    dy = dy > 0 ? dy : 0;
    return dx * dx + dy * dy;
}

/* Drops the obstacle cells within radius_mm of the start: the robot stands there. */
static uint32_t clear_start(hl_costmap_t *cm, hl_mm_t sx, hl_mm_t sy)
{
    const hl_plan_grid_t *g = &cm->grid;
    int64_t X = 2 * ((int64_t)sx - g->x0_mm) + g->cell_mm;
    int64_t Y = 2 * ((int64_t)sy - g->y0_mm) + g->cell_mm;
    int64_t r2 = 4 * (int64_t)cm->p.radius_mm * cm->p.radius_mm;
    int32_t k = cm->p.radius_mm / cm->p.cell_mm + 1;
    uint32_t dropped = 0;
    for (int32_t row = g->start_row - k; row <= g->start_row + k; row++)
        for (int32_t col = g->start_col - k; col <= g->start_col + k; col++) {
            if (!hl_walk_in_grid(g, col, row))
                continue;
            uint8_t *v = &cm->cells[(size_t)row * (size_t)g->cols + (size_t)col];
            if (*v == HL_PLAN_CELL_OBSTACLE && point_to_cell2(g, X, Y, col, row) < r2) {
                *v = 0;
                dropped++;
            }
        }
    return dropped;
}

/* Cells outside the allowed area or the world: obstacles for the search, not inflated. */
static void fence(hl_costmap_t *cm, const hl_costmap_input_t *in)
{
    const hl_plan_grid_t *g = &cm->grid;
    for (int32_t j = 0; j < g->rows; j++) {
        int64_t y = g->y0_mm + (int64_t)j * g->cell_mm;
        uint8_t *row = cm->cells + (size_t)j * (size_t)g->cols;
        for (int32_t i = 0; i < g->cols; i++) {
            int64_t x = g->x0_mm + (int64_t)i * g->cell_mm;
            if (row[i] == HL_PLAN_CELL_OBSTACLE)
                continue;
            if (!in_world(x, y) ||
                (in->allowed && !in->allowed(in->allowed_ctx, (hl_mm_t)x, (hl_mm_t)y)))
                row[i] = HL_PLAN_CELL_FENCE;
        }
    }
}

/* From the goal to the nearest obstacle cell's square, mm, looking in growing rings;
 * -1 when there is none. A cell of ring k is at least (k - 1) cells from any point of
 * the goal's cell. */
static int32_t goal_clearance(const hl_costmap_t *cm, hl_mm_t gx, hl_mm_t gy,
                              uint32_t obstacles)
{
    const hl_plan_grid_t *g = &cm->grid;
    if (!obstacles)
        return -1;
    int64_t X = 2 * ((int64_t)gx - g->x0_mm) + g->cell_mm;
    int64_t Y = 2 * ((int64_t)gy - g->y0_mm) + g->cell_mm;
    int64_t best = INT64_MAX, c2 = 2 * (int64_t)g->cell_mm;
    int32_t kmax = g->cols > g->rows ? g->cols : g->rows;
    for (int32_t k = 0; k <= kmax; k++) {
        int64_t near = (k - 1) * c2;
        if (near > 0 && near * near >= best)
            break;
        for (int32_t row = g->goal_row - k; row <= g->goal_row + k; row++) {
            bool edge = row == g->goal_row - k || row == g->goal_row + k;
            for (int32_t col = g->goal_col - k; col <= g->goal_col + k;
                 col += edge || k == 0 ? 1 : 2 * k) {
                size_t i = (size_t)row * (size_t)g->cols + (size_t)col;
                if (!hl_walk_in_grid(g, col, row) || cm->cells[i] != HL_PLAN_CELL_OBSTACLE)
                    continue;
                int64_t d2 = point_to_cell2(g, X, Y, col, row);
                if (d2 < best)
                    best = d2;
            }
        }
    }
    return best == INT64_MAX ? -1 : (int32_t)lround(sqrt((double)best) / 2);
}

/* The start's lethal region: lethal and fence cells 8-connected to the start cell, with
 * their centres within radius_mm + cell_mm of the start (a body can only be that far
 * into the zone). Breadth first from the start cell. */
static void mark_start_region(hl_costmap_t *cm, hl_mm_t sx, hl_mm_t sy)
{
    const hl_plan_grid_t *g = &cm->grid;
    int64_t reach = (int64_t)cm->p.radius_mm + cm->p.cell_mm;
    int32_t head = 0, tail = 0, w = g->cols;
    int32_t start = g->start_row * w + g->start_col;
    memset(cm->region, 0, (size_t)w * (size_t)g->rows);
    cm->region[start] = 1;
    cm->queue[tail++] = start;
    while (head < tail) {
        int32_t at = cm->queue[head++], col = at % w, row = at / w;
        for (int32_t dr = -1; dr <= 1; dr++)
            for (int32_t dc = -1; dc <= 1; dc++) {
                int32_t nc = col + dc, nr = row + dr, n = nr * w + nc;
                if (!hl_walk_in_grid(g, nc, nr) || cm->region[n] ||
                    (cm->cells[n] != HL_PLAN_CELL_LETHAL && cm->cells[n] != HL_PLAN_CELL_FENCE))
                    continue;
                int64_t dx = g->x0_mm + (int64_t)nc * g->cell_mm - sx;
                int64_t dy = g->y0_mm + (int64_t)nr * g->cell_mm - sy;
                if (dx * dx + dy * dy > reach * reach || tail >= cm->queue_n)
                    continue;
                cm->region[n] = 1;
                cm->queue[tail++] = n;
            }
    }
}

hl_plan_result_t hl_costmap_build(hl_costmap_t *cm, const hl_costmap_input_t *in)
{
    if (!cm)
        return HL_PLAN_BAD_ARG;
    cm->grid.cols = cm->grid.rows = 0;
    cm->grid.goal_clearance_mm = -1;
    if (!in)
        return HL_PLAN_BAD_ARG;
    hl_plan_result_t res = lay_out(cm, in);
    if (res != HL_PLAN_OK) {
        cm->grid.cols = cm->grid.rows = 0;
        return res;
    }
    hl_plan_grid_t *g = &cm->grid;
    memset(cm->cells, 0, (size_t)g->cols * (size_t)g->rows);
    /* region and dist are free until the inflation and the start region use them */
    uint32_t obstacles = draw_walls(cm, in, cm->region, cm->dist);
    obstacles -= clear_start(cm, in->start_x, in->start_y);
    /* after clear_start: a safety stop's reading is no misplaced echo (plan.h) */
    for (uint32_t k = 0; k < in->n_obstacles; k++)
        obstacles += draw_segment(cm, in->obstacle_x[k], in->obstacle_y[k], in->obstacle_x[k],
                                  in->obstacle_y[k]);
    hl_edt_columns(cm->cells, cm->dist, cm->grid.cols, cm->grid.rows, (uint8_t)cm->band);
    for (int32_t j = 0; j < g->rows; j++) {
        size_t row = (size_t)j * (size_t)g->cols;
        hl_edt_row(cm->dist + row, cm->cells + row, g->cols, cm->band, cm->lut, cm->lut_n,
                   cm->env_s, cm->env_t);
    }
    fence(cm, in);
    g->goal_clearance_mm = goal_clearance(cm, in->goal_x, in->goal_y, obstacles);
    mark_start_region(cm, in->start_x, in->start_y);
    return HL_PLAN_OK;
}
