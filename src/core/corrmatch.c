/* corrmatch.c - correlative scan matching by branch and bound (corrmatch.h). */
#include "houghloc-internal/corrmatch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/fixed.h"

#define MAX_LEVELS 8            /* the coarsest level's square: 128 cells (6.4 m) */
#define KERNEL_R 3              /* a point's field reaches this many cells (3 sigma) */
#define KERNEL_W (2 * KERNEL_R + 1)
#define SUBCELL 8               /* a point's place within its cell, to an eighth */
#define MAX_ANGLES 1025
#define POLISH_MIN_MM 2.0       /* the polish stops at steps this fine */

typedef struct cand {
    int32_t score;          /* the sum of field values (an upper bound above level 0) */
    int32_t tx, ty;         /* the square's lowest offset from the centre, cells */
    int16_t a;              /* the turn, steps from the centre's heading */
    int16_t h;              /* level: the square is 2^h cells a side */
} cand_t;

struct hl_corr {
    uint8_t kernel[SUBCELL][SUBCELL][KERNEL_W][KERNEL_W];
    uint8_t *levels;        /* [MAX_LEVELS][level_cap] */
    size_t level_cap;
    int32_t *cells;         /* [angles][points][2]: the query's points turned, in cells */
    size_t cells_cap;
    cand_t *top;
    size_t top_cap;
    /* The search under way: */
    int32_t w, hgt, n_levels;
    double x0, y0;          /* the lower corner of cell (0, 0), mm */
    uint32_t n_query;
    int32_t wc;             /* the window, cells each side */
    int32_t na;             /* ... turns each side */
    double step;            /* ... radians a turn */
    /* The best leaf so far, and the pose the runner-up must be distinct from (the runner-up
     * search stops at its first leaf): */
    cand_t best;
    bool excluding;
    bool found_one;
    cand_t excl;
    double distinct_cells, distinct_steps;
};

hl_corr_t *hl_corr_create(void)
{
    hl_corr_t *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    /* A point at (sx + 0.5) / SUBCELL of its cell: each cell's value by the distance from
     * the point to the cell's centre. */
    for (int sx = 0; sx < SUBCELL; sx++)
        for (int sy = 0; sy < SUBCELL; sy++)
            for (int i = 0; i < KERNEL_W; i++)
                for (int j = 0; j < KERNEL_W; j++) {
                    double dx = (i - KERNEL_R) - (sx + 0.5) / SUBCELL + 0.5;
                    double dy = (j - KERNEL_R) - (sy + 0.5) / SUBCELL + 0.5;
                    double d2 = (dx * dx + dy * dy) * HL_CORR_CELL_MM * HL_CORR_CELL_MM;
                    c->kernel[sx][sy][j][i] =
                        (uint8_t)lround(255 * exp(-d2 / (2 * HL_CORR_SIGMA_MM * HL_CORR_SIGMA_MM)));
                }
    return c;
}

void hl_corr_destroy(hl_corr_t *c)
{
    if (!c)
        return;
    free(c->levels);
    free(c->cells);
    free(c->top);
    free(c);
}

size_t hl_corr_mem_bytes(const hl_corr_t *c)
{
    return sizeof *c + MAX_LEVELS * c->level_cap + c->cells_cap * sizeof *c->cells +
           c->top_cap * sizeof *c->top;
}

uint32_t hl_corr_points(const hl_scan_t *scan, hl_pg_pose_t at, hl_corr_point_t *out,
                        uint32_t n, uint32_t max)
{
    for (uint32_t k = 0; k < scan->count && n < max; k++) {
        const hl_reading_t *r = &scan->readings[k];
        if (!r->valid || r->range_mm > HL_CORR_RANGE_MM)
            continue;
        double a = at.theta + hl_bam_to_rad(r->bearing);
        out[n++] = (hl_corr_point_t){ (float)(at.x + r->range_mm * cos(a)),
                                      (float)(at.y + r->range_mm * sin(a)) };
    }
    return n;
}

/* Grows *p to hold @p n items of @p size. */
static bool reserve(void **p, size_t *cap, size_t n, size_t size)
{
    if (n <= *cap)
        return true;
    void *q = realloc(*p, n * size);
    if (!q)
        return false;
    *p = q;
    *cap = n;
    return true;
}

static uint8_t *level(const hl_corr_t *c, int h)
{
    return c->levels + (size_t)h * c->level_cap;
}

/* The field's box: where the query's points can fall (the centre, the farthest query
 * point and the window) and the map's points reach, @return false when the two miss. */
static bool frame_field(hl_corr_t *c, const hl_corr_point_t *map, uint32_t n_map,
                        double reach, hl_pg_pose_t center)
{
    double margin = KERNEL_R * HL_CORR_CELL_MM;
    double lo_x = map[0].x, hi_x = map[0].x, lo_y = map[0].y, hi_y = map[0].y;
    for (uint32_t k = 1; k < n_map; k++) {
        lo_x = fmin(lo_x, map[k].x);
        hi_x = fmax(hi_x, map[k].x);
        lo_y = fmin(lo_y, map[k].y);
        hi_y = fmax(hi_y, map[k].y);
    }
    lo_x = fmax(lo_x - margin, center.x - reach);
    hi_x = fmin(hi_x + margin, center.x + reach);
    lo_y = fmax(lo_y - margin, center.y - reach);
    hi_y = fmin(hi_y + margin, center.y + reach);
    if (!(lo_x < hi_x && lo_y < hi_y))
        return false;
    c->x0 = floor(lo_x / HL_CORR_CELL_MM) * HL_CORR_CELL_MM;
    c->y0 = floor(lo_y / HL_CORR_CELL_MM) * HL_CORR_CELL_MM;
    c->w = (int32_t)ceil((hi_x - c->x0) / HL_CORR_CELL_MM) + 1;
    c->hgt = (int32_t)ceil((hi_y - c->y0) / HL_CORR_CELL_MM) + 1;
    return (size_t)c->w * (size_t)c->hgt <= HL_CORR_MAX_CELLS;
}

/* Level 0: each cell the nearness of the nearest map point; level h: the largest of
 * level 0 over the 2^h x 2^h cells from it up. */
static void draw_field(hl_corr_t *c, const hl_corr_point_t *map, uint32_t n_map)
{
    size_t cells = (size_t)c->w * (size_t)c->hgt;
    uint8_t *f = level(c, 0);
    memset(f, 0, cells);
    for (uint32_t k = 0; k < n_map; k++) {
        double fx = (map[k].x - c->x0) / HL_CORR_CELL_MM;
        double fy = (map[k].y - c->y0) / HL_CORR_CELL_MM;
        int32_t cx = (int32_t)floor(fx), cy = (int32_t)floor(fy);
        int sx = (int)((fx - cx) * SUBCELL), sy = (int)((fy - cy) * SUBCELL);
        sx = sx < SUBCELL ? sx : SUBCELL - 1;
        sy = sy < SUBCELL ? sy : SUBCELL - 1;
        for (int j = 0; j < KERNEL_W; j++) {
            int32_t y = cy + j - KERNEL_R;
            if (y < 0 || y >= c->hgt)
                continue;
            for (int i = 0; i < KERNEL_W; i++) {
                int32_t x = cx + i - KERNEL_R;
                uint8_t v = c->kernel[sx][sy][j][i];
                if (x >= 0 && x < c->w && v > f[(size_t)y * c->w + x])
                    f[(size_t)y * c->w + x] = v;
            }
        }
    }
    for (int h = 1; h < c->n_levels; h++) {
        const uint8_t *lo = level(c, h - 1);
        uint8_t *hi = level(c, h);
        int32_t s = 1 << (h - 1);
        for (int32_t y = 0; y < c->hgt; y++)
            for (int32_t x = 0; x < c->w; x++) {
                uint8_t m = lo[(size_t)y * c->w + x];
                if (x + s < c->w && lo[(size_t)y * c->w + x + s] > m)
                    m = lo[(size_t)y * c->w + x + s];
                if (y + s < c->hgt) {
                    const uint8_t *row = lo + (size_t)(y + s) * c->w;
                    if (row[x] > m)
                        m = row[x];
                    if (x + s < c->w && row[x + s] > m)
                        m = row[x + s];
                }
                hi[(size_t)y * c->w + x] = m;
            }
    }
}

/* The query's points turned by each of the search's turns and put at the centre, as
 * cells of the field. */
static void turn_query(hl_corr_t *c, const hl_corr_point_t *q, hl_pg_pose_t center)
{
    for (int32_t a = -c->na; a <= c->na; a++) {
        double theta = center.theta + a * c->step, cs = cos(theta), sn = sin(theta);
        int32_t *out = c->cells + (size_t)(a + c->na) * c->n_query * 2;
        for (uint32_t k = 0; k < c->n_query; k++) {
            double x = center.x + cs * q[k].x - sn * q[k].y;
            double y = center.y + sn * q[k].x + cs * q[k].y;
            out[2 * k] = (int32_t)floor((x - c->x0) / HL_CORR_CELL_MM);
            out[2 * k + 1] = (int32_t)floor((y - c->y0) / HL_CORR_CELL_MM);
        }
    }
}

/* A square's score: over the query's points, the largest field value within the square
 * of 2^k.h cells from each point's cell (level k.h), so that no pose within scores more.
 * A square that begins below the field's first row or column and reaches into it is read
 * from the field's edge, whose cell of that level covers the part inside. */
static int32_t score(const hl_corr_t *c, cand_t k)
{
    const uint8_t *f = level(c, k.h);
    const int32_t *p = c->cells + (size_t)(k.a + c->na) * c->n_query * 2;
    int32_t side = 1 << k.h, sum = 0;
    for (uint32_t i = 0; i < c->n_query; i++) {
        int32_t x = p[2 * i] + k.tx, y = p[2 * i + 1] + k.ty;
        if (x < 0 && x + side > 0)
            x = 0;
        if (y < 0 && y + side > 0)
            y = 0;
        if ((uint32_t)x < (uint32_t)c->w && (uint32_t)y < (uint32_t)c->hgt)
            sum += f[(size_t)y * c->w + x];
    }
    return sum;
}

static int by_score(const void *a, const void *b)
{
    int32_t sa = ((const cand_t *)a)->score, sb = ((const cand_t *)b)->score;
    return (sa < sb) - (sa > sb);
}

/* Whether every pose of square @p k is too near the best to be a runner-up. */
static bool all_excluded(const hl_corr_t *c, cand_t k)
{
    if (fabs((double)(k.a - c->excl.a)) > c->distinct_steps)
        return false;
    int32_t side = (1 << k.h) - 1;
    double fx = fmax(fabs((double)(k.tx - c->excl.tx)), fabs((double)(k.tx + side - c->excl.tx)));
    double fy = fmax(fabs((double)(k.ty - c->excl.ty)), fabs((double)(k.ty + side - c->excl.ty)));
    return hypot(fx, fy) <= c->distinct_cells;
}

/* Depth first through @p list (sorted best first): a square whose bound is no better
 * than the best leaf so far holds nothing better, nor do those after it. */
static void branch(hl_corr_t *c, cand_t *list, int n)
{
    for (int i = 0; i < n; i++) {
        cand_t k = list[i];
        if (k.score <= c->best.score)
            return;
        if (c->excluding && all_excluded(c, k))
            continue;
        if (k.h == 0) {
            c->best = k;
            if (c->excluding) {
                c->found_one = true;
                return;
            }
            continue;
        }
        cand_t kids[4];
        int m = 0;
        int32_t s = 1 << (k.h - 1);
        for (int dy = 0; dy <= s; dy += s)
            for (int dx = 0; dx <= s; dx += s) {
                cand_t kid = { 0, k.tx + dx, k.ty + dy, k.a, (int16_t)(k.h - 1) };
                if (kid.tx > c->wc || kid.ty > c->wc)
                    continue;
                kid.score = score(c, kid);
                kids[m++] = kid;
            }
        qsort(kids, (size_t)m, sizeof *kids, by_score);
        branch(c, kids, m);
        if (c->found_one)
            return;
    }
}

/* The best leaf of the window whose score beats @p floor (c->best.score stays @p floor
 * and c->best.h -1 when none does). */
static void search(hl_corr_t *c, int n_top, int32_t floor_score)
{
    c->best = (cand_t){ floor_score, 0, 0, 0, -1 };
    c->found_one = false;
    branch(c, c->top, n_top);
}

/* The field at a point, between cell centres. */
static double field_at(const hl_corr_t *c, double x, double y)
{
    double fx = (x - c->x0) / HL_CORR_CELL_MM - 0.5, fy = (y - c->y0) / HL_CORR_CELL_MM - 0.5;
    int32_t ix = (int32_t)floor(fx), iy = (int32_t)floor(fy);
    double ax = fx - ix, ay = fy - iy, v = 0;
    const uint8_t *f = level(c, 0);
    for (int j = 0; j <= 1; j++)
        for (int i = 0; i <= 1; i++) {
            int32_t x1 = ix + i, y1 = iy + j;
            if ((uint32_t)x1 < (uint32_t)c->w && (uint32_t)y1 < (uint32_t)c->hgt)
                v += (i ? ax : 1 - ax) * (j ? ay : 1 - ay) * f[(size_t)y1 * c->w + x1];
        }
    return v;
}

static double smooth_score(const hl_corr_t *c, const hl_corr_point_t *q, hl_pg_pose_t p)
{
    double cs = cos(p.theta), sn = sin(p.theta), sum = 0;
    for (uint32_t k = 0; k < c->n_query; k++)
        sum += field_at(c, p.x + cs * q[k].x - sn * q[k].y, p.y + sn * q[k].x + cs * q[k].y);
    return sum / (255.0 * c->n_query);
}

/* The best leaf polished below the cell and the turn's step: a hill climb on the field
 * read between cell centres, its steps halved while no move gains. */
static hl_pg_pose_t polish(const hl_corr_t *c, const hl_corr_point_t *q, hl_pg_pose_t p,
                           double *best)
{
    double mm = HL_CORR_CELL_MM / 2, rad = c->step / 2;
    *best = smooth_score(c, q, p);
    while (mm >= POLISH_MIN_MM) {
        bool moved = false;
        for (int d = 0; d < 6; d++) {
            hl_pg_pose_t t = p;
            double sign = d & 1 ? -1 : 1;
            if (d < 2)
                t.x += sign * mm;
            else if (d < 4)
                t.y += sign * mm;
            else
                t.theta += sign * rad;
            double s = smooth_score(c, q, t);
            if (s > *best) {
                *best = s;
                p = t;
                moved = true;
            }
        }
        if (!moved) {
            mm /= 2;
            rad /= 2;
        }
    }
    return p;
}

/* The search's sizes for @p p and the query's reach, the field framed and its memory
 * made: @return false when the region is out of range or the field too large. */
static bool prepare(hl_corr_t *c, const hl_corr_point_t *map, uint32_t n_map,
                    const hl_corr_point_t *query, uint32_t n_query, hl_pg_pose_t center,
                    const hl_corr_params_t *p, int *n_top)
{
    double far = 0;
    for (uint32_t k = 0; k < n_query; k++)
        far = fmax(far, hypot(query[k].x, query[k].y));
    far = fmax(far, HL_CORR_CELL_MM);
    c->wc = (int32_t)ceil(p->window_mm / HL_CORR_CELL_MM);
    c->step = fmax(HL_CORR_MIN_STEP_RAD,
                   acos(1 - HL_CORR_CELL_MM * HL_CORR_CELL_MM / (2 * far * far)));
    if (p->window_rad / c->step > MAX_ANGLES / 2)
        return false;
    c->na = (int32_t)ceil(p->window_rad / c->step);
    c->n_levels = 1;
    while (c->n_levels < MAX_LEVELS && (1 << (c->n_levels - 1)) < 2 * c->wc + 1)
        c->n_levels++;
    if (!frame_field(c, map, n_map, far + (c->wc + 1) * HL_CORR_CELL_MM, center))
        return false;
    size_t cells = (size_t)c->w * (size_t)c->hgt;
    size_t n_angles = (size_t)(2 * c->na + 1);
    int32_t per_side = (2 * c->wc) / (1 << (c->n_levels - 1)) + 1;
    *n_top = (int)(n_angles * (size_t)per_side * (size_t)per_side);
    c->n_query = n_query;
    return reserve((void **)&c->levels, &c->level_cap, cells, MAX_LEVELS) &&
           reserve((void **)&c->cells, &c->cells_cap, n_angles * n_query * 2,
                   sizeof *c->cells) &&
           reserve((void **)&c->top, &c->top_cap, (size_t)*n_top, sizeof *c->top);
}

/* The coarsest squares covering the region at every turn, best first. */
static void seed_top(hl_corr_t *c)
{
    int32_t side = 1 << (c->n_levels - 1);
    int n = 0;
    for (int32_t a = -c->na; a <= c->na; a++)
        for (int32_t ty = -c->wc; ty <= c->wc; ty += side)
            for (int32_t tx = -c->wc; tx <= c->wc; tx += side) {
                cand_t k = { 0, tx, ty, (int16_t)a, (int16_t)(c->n_levels - 1) };
                k.score = score(c, k);
                c->top[n++] = k;
            }
    qsort(c->top, (size_t)n, sizeof *c->top, by_score);
}

bool hl_corr_search(hl_corr_t *c, const hl_corr_point_t *map, uint32_t n_map,
                    const hl_corr_point_t *query, uint32_t n_query, hl_pg_pose_t center,
                    const hl_corr_params_t *p, hl_corr_result_t *out)
{
    *out = (hl_corr_result_t){ false, center, 0, 0 };
    int n = 0;
    if (n_map == 0 || n_query == 0 || n_map > HL_CORR_MAX_POINTS ||
        n_query > HL_CORR_MAX_POINTS || !(p->window_mm >= 0) ||
        !(p->window_mm <= HL_CORR_MAX_WINDOW_MM) || !(p->window_rad >= 0) ||
        !(p->min_score >= 0 && p->min_score <= 1) ||
        !(p->runner_share >= 0 && p->runner_share <= 1) ||
        !prepare(c, map, n_map, query, n_query, center, p, &n))
        return false;
    draw_field(c, map, n_map);
    turn_query(c, query, center);
    seed_top(c);
    /* Only a leaf above the floor is an answer: every square whose bound is below it is
     * pruned unseen, which is most of a region where the stop is not. */
    double full = 255.0 * n_query;
    c->excluding = false;
    search(c, n, (int32_t)ceil(p->min_score * full) - 1);
    if (c->best.h < 0)
        return true;
    cand_t best = c->best;
    out->score = best.score / full;
    out->pose = (hl_pg_pose_t){ center.x + best.tx * HL_CORR_CELL_MM,
                                center.y + best.ty * HL_CORR_CELL_MM,
                                center.theta + best.a * c->step };
    if (p->runner_share < 1) {
        c->excluding = true;
        c->excl = best;
        c->distinct_cells = p->distinct_mm / HL_CORR_CELL_MM;
        c->distinct_steps = p->distinct_rad / c->step;
        search(c, n, (int32_t)ceil(p->runner_share * best.score) - 1);
        if (c->found_one) {
            out->runner_up = c->best.score / full;
            return true;
        }
    }
    out->matched = true;
    out->pose = polish(c, query, out->pose, &out->score);
    return true;
}
