/* nearest.c - the polish's matching: nearest facing map vectors and surface normals
 * (see nearest.h). */
#include "nearest.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MARGIN_MM 25            /* a reading's list serves while it moves less than this */
#define LIST_MAX 128            /* a longer list is not kept: the reading searches the cells */
#define POOL_PER_VECTOR 8       /* the lists' room: this many entries a map vector, ... */
#define POOL_MAX (HL_SCAN_MAX_READINGS * LIST_MAX)     /* ... at most */
#define RINGS HL_NEAREST_RINGS

/* How far from its anchor a reading's list reaches: the match distance and the margin. */
static int32_t reach_mm(hl_mm_t match_mm)
{
    return match_mm + MARGIN_MM;
}

/* The hash's cells: a list's reach (its 3 x 3 cells hold a list), or larger so that a
 * normal's radius spans few cells whatever the parameters. */
static int32_t cell_mm(const hl_refine_params_t *p)
{
    int32_t quarter = (p->normal_radius_mm + 3) / 4;
    return reach_mm(p->match_mm) > quarter ? reach_mm(p->match_mm) : quarter;
}

bool hl_nearest_init(hl_nearest_t *n, const hl_refine_params_t *p, uint32_t capacity)
{
    memset(n, 0, sizeof *n);
    n->normal_radius_mm = p->normal_radius_mm;
    n->match_mm = p->match_mm;
    n->capacity = capacity;
    bool ok = hl_cellhash_init(&n->near, cell_mm(p), capacity);
    n->plain.cell_mm = p->normal_radius_mm > p->match_mm ? p->normal_radius_mm : p->match_mm;
    n->plain.buckets = n->near.buckets;
    for (uint32_t k = 0; k < RINGS; k++)
        n->ring_mm[k] = (double)k * reach_mm(p->match_mm) / RINGS;
    n->nx = malloc(capacity * sizeof *n->nx);
    n->ny = malloc(capacity * sizeof *n->ny);
    n->stamp = calloc(capacity, sizeof *n->stamp);
    n->lists = calloc(HL_SCAN_MAX_READINGS, sizeof *n->lists);
    n->pool_size = capacity < POOL_MAX / POOL_PER_VECTOR ? capacity * POOL_PER_VECTOR : POOL_MAX;
    n->pool = malloc(n->pool_size * sizeof *n->pool);
    n->scratch = malloc(capacity * sizeof *n->scratch);
    return ok && n->nx && n->ny && n->stamp && n->lists && n->pool && n->scratch;
}

void hl_nearest_free(hl_nearest_t *n)
{
    hl_cellhash_free(&n->near);
    free(n->nx);
    free(n->ny);
    free(n->stamp);
    free(n->lists);
    free(n->pool);
    free(n->scratch);
    memset(n, 0, sizeof *n);
}

size_t hl_nearest_mem_bytes(const hl_nearest_t *n)
{
    return hl_cellhash_mem_bytes(&n->near) +
           n->capacity * (sizeof *n->nx + sizeof *n->ny + sizeof *n->stamp) +
           HL_SCAN_MAX_READINGS * sizeof *n->lists +
           ((size_t)n->pool_size + n->capacity) * sizeof *n->pool;
}

void hl_nearest_begin(hl_nearest_t *n, const hl_vector_t *map, uint32_t count)
{
    hl_cellhash_build(&n->near, map, count);
    /* every normal and list is stale (both restart before the counter wraps) */
    if (++n->run == 0) {
        memset(n->stamp, 0, n->capacity * sizeof *n->stamp);
        memset(n->lists, 0, HL_SCAN_MAX_READINGS * sizeof *n->lists);
        n->run = 1;
    }
    n->pool_used = 0;
}

/* ---- surface normals ------------------------------------------------------------- */

static void unit_normal(hl_bam_t a, double *x, double *y)
{
    *x = cos(hl_bam_to_rad(a));
    *y = sin(hl_bam_to_rad(a));
}

/* Vector i's surface normal: across the principal axis of the neighbours within
 * normal_radius_mm that face the same way (itself included), oriented towards its
 * sensor; its own normal when fewer than three vectors shape it. The neighbours are
 * sought in the cells that the radius reaches, each entry counted in its own cell only
 * (a bucket holds every cell hashed to it). Their sums are of integers (map positions
 * are whole millimetres) and so exact in any order. */
static void compute_normal(hl_nearest_t *r, const hl_vector_t *map, uint32_t i)
{
    const hl_cellhash_t *g = &r->near;
    const hl_vector_t *a = &map[i];
    const int32_t rad = r->normal_radius_mm, side = g->cell_mm;
    const int64_t r2 = (int64_t)rad * rad;
    int64_t n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    /* map coordinates lie within +-HL_COORD_MAX_MM: none of this overflows */
    int32_t x0 = hl_cellhash_cell(g, a->x_mm - rad), x1 = hl_cellhash_cell(g, a->x_mm + rad);
    int32_t y0 = hl_cellhash_cell(g, a->y_mm - rad), y1 = hl_cellhash_cell(g, a->y_mm + rad);
    for (int32_t cy = y0; cy <= y1; cy++) {
        int32_t lo_y = cy * side, gap_y = lo_y > a->y_mm ? lo_y - a->y_mm
                                         : a->y_mm >= lo_y + side ? a->y_mm - (lo_y + side - 1)
                                                                  : 0;
        for (int32_t cx = x0; cx <= x1; cx++) {
            int32_t lo_x = cx * side, gap_x = lo_x > a->x_mm ? lo_x - a->x_mm
                                             : a->x_mm >= lo_x + side ? a->x_mm - (lo_x + side - 1)
                                                                      : 0;
            if ((int64_t)gap_x * gap_x + (int64_t)gap_y * gap_y > r2)
                continue;   /* the cell lies wholly beyond the radius */
            uint32_t b = hl_cellhash_bucket(g, cx, cy);
            for (uint32_t e = g->start[b]; e < g->start[b + 1]; e++) {
                int32_t ex = g->x[e], ey = g->y[e];
                if (ex < lo_x || ex >= lo_x + side || ey < lo_y || ey >= lo_y + side)
                    continue;   /* another cell's */
                int32_t dx = ex - a->x_mm, dy = ey - a->y_mm;
                int64_t ddx2 = (int64_t)dx * dx, ddy2 = (int64_t)dy * dy;
                if (ddx2 + ddy2 > r2 || abs(hl_bam_diff(a->normal, g->normal[e])) > 10923)
                    continue;   /* 10923: 60 degrees */
                n += 1;
                sx += dx;
                sy += dy;
                sxx += ddx2;
                sxy += (int64_t)dx * dy;
                syy += ddy2;
            }
        }
    }
    double ox, oy;
    unit_normal(a->normal, &ox, &oy);
    r->nx[i] = ox;
    r->ny[i] = oy;
    if (n < 3)
        return;
    double dn = (double)n;
    double mx = (double)sx / dn, my = (double)sy / dn;
    double cxx = (double)sxx / dn - mx * mx, cxy = (double)sxy / dn - mx * my,
           cyy = (double)syy / dn - my * my;
    double axis = 0.5 * atan2(2 * cxy, cxx - cyy);
    double nx = -sin(axis), ny = cos(axis);
    if (nx * ox + ny * oy < 0) {
        nx = -nx;
        ny = -ny;
    }
    r->nx[i] = nx;
    r->ny[i] = ny;
}

/* Makes vector i's normal valid for this run (computed at most once per run: it depends
 * on the map only). */
static void need_normal(hl_nearest_t *r, const hl_vector_t *map, uint32_t i)
{
    if (r->stamp[i] != r->run) {
        compute_normal(r, map, i);
        r->stamp[i] = r->run;
    }
}

/* ---- matching -------------------------------------------------------------------- */

/* Where vector j's bucket comes in the plain method's scan around (x, y): the 3 x 3
 * plain cells row by row, each bucket at its first cell. 9 if not there. */
static int plain_slot(const hl_nearest_t *r, double x, double y, const hl_vector_t *v)
{
    const hl_cellhash_t *g = &r->plain;
    uint32_t bj = hl_cellhash_bucket_of(g, v->x_mm, v->y_mm);
    int32_t cx = hl_cellhash_cell(g, x), cy = hl_cellhash_cell(g, y);
    int slot = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++, slot++)
            if (hl_cellhash_bucket(g, cx + dx, cy + dy) == bj)
                return slot;
    return 9;
}

/* Would the plain method's scan around (x, y) meet vector a before vector b? Bucket by
 * bucket, and within a bucket the higher index first. */
static bool plain_first(const hl_nearest_t *r, const hl_vector_t *map, double x, double y,
                        uint32_t a, uint32_t b)
{
    int sa = plain_slot(r, x, y, &map[a]), sb = plain_slot(r, x, y, &map[b]);
    return sa != sb ? sa < sb : a > b;
}

/* The buckets of the 3 x 3 cells around (wx, wy), each once (cells share buckets), into
 * out; their number. */
static uint32_t buckets_around(const hl_cellhash_t *g, double wx, double wy, uint32_t out[9])
{
    int32_t cx = hl_cellhash_cell(g, wx), cy = hl_cellhash_cell(g, wy);
    uint32_t n = 0;
    for (int ddy = -1; ddy <= 1; ddy++) {
        for (int ddx = -1; ddx <= 1; ddx++) {
            uint32_t b = hl_cellhash_bucket(g, cx + ddx, cy + ddy);
            bool dup = false;
            for (uint32_t k = 0; k < n; k++)
                dup = dup || out[k] == b;
            if (!dup)
                out[n++] = b;
        }
    }
    return n;
}

/* Does map vector j, d2 squared from the world point (wx, wy), beat the best so far
 * (best, best2 squared away; -1 for none)? Nearer, or as near and met first by the plain
 * scan (a tie with the gate itself never matches: strictly closer than match_mm), and
 * its surface facing the robot at (sx, sy). */
static bool beats(hl_nearest_t *r, const hl_vector_t *map, uint32_t j, double d2, int32_t best,
                  double best2, double wx, double wy, double sx, double sy)
{
    if (d2 > best2 ||
        (d2 == best2 && (best < 0 || !plain_first(r, map, wx, wy, j, (uint32_t)best))))
        return false;
    need_normal(r, map, j);
    return r->nx[j] * (sx - wx) + r->ny[j] * (sy - wy) > 0;
}

/* The map vectors within reach_mm of the world point (wx, wy), from the 3 x 3 cells around
 * it (each bucket once), into r->scratch with their rings counted into ring_start[1 ..];
 * their number. */
static uint32_t gather(hl_nearest_t *r, double wx, double wy, uint32_t ring_start[RINGS + 1])
{
    const hl_cellhash_t *g = &r->near;
    double reach = reach_mm(r->match_mm), reach2 = reach * reach;   /* cells at least as large */
    uint32_t buckets[9], nb = buckets_around(g, wx, wy, buckets), n = 0;
    for (uint32_t k = 0; k < nb; k++) {
        for (uint32_t e = g->start[buckets[k]]; e < g->start[buckets[k] + 1]; e++) {
            double dx = wx - g->x[e], dy = wy - g->y[e], d2 = dx * dx + dy * dy;
            if (d2 >= reach2)
                continue;
            uint32_t ring = (uint32_t)(sqrt(d2) * (RINGS / reach));
            ring = ring < RINGS ? ring : RINGS - 1;
            r->scratch[n++] = (struct near_vector){ g->x[e], g->y[e], g->index[e], ring };
            ring_start[ring + 1]++;
        }
    }
    return n;
}

/* Reading i's list anew, anchored at the world point (wx, wy): the map vectors within
 * reach_mm of it, ring by ring outwards (a counting sort: within a ring the order is the
 * hash's, which the walk does not depend on). Its room in the pool is kept for the run,
 * with a quarter to spare for the lists drawn after it. @return false when more vectors
 * lie around than a list holds (LIST_MAX) or the pool has room for: the reading then
 * searches the cells as they lie for the rest of the run. */
static bool draw_list(hl_nearest_t *r, uint32_t i, double wx, double wy)
{
    uint32_t ring_start[RINGS + 1] = { 0 };
    uint32_t n = gather(r, wx, wy, ring_start);
    struct near_list *l = &r->lists[i];
    bool kept = l->run == r->run;       /* room taken earlier in this run */
    l->ax = wx;
    l->ay = wy;
    l->count = n;
    l->run = r->run;
    if (!kept || n > l->room) {         /* room of its own, from what the run has left */
        uint32_t left = r->pool_size - r->pool_used, want = n + n / 4 + 4;
        l->first = r->pool_used;
        l->room = n > LIST_MAX || n > left ? 0 : want < left ? want : left;
        r->pool_used += l->room;
    }
    if (n > l->room) {
        l->count = LIST_MAX + 1;        /* no list: the cells for the rest of the run */
        return false;
    }
    for (uint32_t k = 1; k <= RINGS; k++)
        ring_start[k] += ring_start[k - 1];
    struct near_vector *out = &r->pool[l->first];
    for (uint32_t k = 0; k < n; k++)
        out[ring_start[r->scratch[k].ring]++] = r->scratch[k];
    return true;
}

/* Of a list's n vectors v, the nearest closer than match_mm to the world point (wx, wy)
 * whose surface faces the robot at (sx, sy); -1 if none. Of several at the same
 * distance, the one the plain scan meets first. v is ring by ring from an anchor @p moved
 * from the point, and is walked only until no vector further on can be as near: one at
 * least ring_mm from the anchor lies at least ring_mm - moved from the point (the
 * 1e-6 mm covers rounding). So a normal is needed mostly for the nearest. */
static int32_t nearest_of(hl_nearest_t *r, const hl_vector_t *map, const struct near_vector *v,
                          uint32_t n, double moved, double wx, double wy, double sx, double sy)
{
    double best2 = (double)r->match_mm * r->match_mm, bound = r->match_mm + moved;
    int32_t best = -1;
    for (uint32_t k = 0; k < n && r->ring_mm[v[k].ring] <= bound + 1e-6; k++) {
        double dx = wx - v[k].x, dy = wy - v[k].y, d2 = dx * dx + dy * dy;
        if (beats(r, map, v[k].j, d2, best, best2, wx, wy, sx, sy)) {
            best2 = d2;
            best = (int32_t)v[k].j;
            bound = sqrt(best2) + moved;
        }
    }
    return best;
}

/* As nearest_of, over the map vectors in the 3 x 3 cells around (wx, wy) as they lie, for
 * a reading whose surroundings are too crowded for a list: the plain scan's cost. */
static int32_t nearest_in_cells(hl_nearest_t *r, const hl_vector_t *map, double wx, double wy,
                                double sx, double sy)
{
    const hl_cellhash_t *g = &r->near;
    double best2 = (double)r->match_mm * r->match_mm;
    int32_t best = -1;
    uint32_t buckets[9], nb = buckets_around(g, wx, wy, buckets);
    for (uint32_t k = 0; k < nb; k++) {
        for (uint32_t e = g->start[buckets[k]]; e < g->start[buckets[k] + 1]; e++) {
            double dx = wx - g->x[e], dy = wy - g->y[e], d2 = dx * dx + dy * dy;
            if (beats(r, map, g->index[e], d2, best, best2, wx, wy, sx, sy)) {
                best2 = d2;
                best = (int32_t)g->index[e];
            }
        }
    }
    return best;
}

/* The nearest map vector facing the robot at (sx, sy) within match_mm of reading i's
 * world point (wx, wy) (nearest_of), from the reading's list while it has moved less
 * than MARGIN_MM from the list's anchor, else from a list drawn anew; where more vectors
 * lie around than a list holds, from the cells as they lie for the rest of the run. */
int32_t hl_nearest_facing(hl_nearest_t *r, const hl_vector_t *map, uint32_t i, double wx,
                          double wy, double sx, double sy)
{
    struct near_list *l = &r->lists[i];
    if (l->run == r->run && l->count > LIST_MAX)
        return nearest_in_cells(r, map, wx, wy, sx, sy);
    double mx = wx - l->ax, my = wy - l->ay;
    double moved = l->run == r->run ? sqrt(mx * mx + my * my) : INFINITY;
    if (!(moved < MARGIN_MM)) {
        if (!draw_list(r, i, wx, wy))
            return nearest_in_cells(r, map, wx, wy, sx, sy);
        moved = 0;
    }
    const struct near_vector *v = &r->pool[l->first];
    return nearest_of(r, map, v, l->count, moved, wx, wy, sx, sy);
}

