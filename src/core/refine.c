/* refine.c - point-to-line polishing of a Hough pose (see refine.h). */
#include "houghloc-internal/refine.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cellhash.h"
#include "valid_scan.h"

#define TWO_PI 6.28318530717958647692
#define MARGIN_MM 25            /* a reading's list serves while it moves less than this */
#define LIST_MAX 128            /* a longer list is not kept: the reading searches the cells */
#define POOL_PER_VECTOR 8       /* the lists' room: this many entries a map vector, ... */
#define POOL_MAX (HL_SCAN_MAX_READINGS * LIST_MAX)     /* ... at most */
#define RINGS 32                /* a list's order: rings of reach_mm / RINGS */

/*
 * Speed (docs/results/performance.md). The results are those of the plain method: estimate every
 * map vector's surface normal from its neighbours, then for each reading scan the 3 x 3
 * hash cells of normal_radius_mm around it for the nearest facing vector. What makes it
 * cheaper changes not a bit of them:
 *  - normals are computed lazily, only for the vectors a reading comes near, and kept
 *    for the rest of the run; each from exactly the plain method's neighbours, in sums
 *    of integers (exact in any order), found in the cells the radius reaches;
 *  - each reading keeps a list of the map vectors within reach_mm (match_mm and a
 *    margin) of where it lay, ring by ring outwards, and walks it only as far as a
 *    nearer vector could lie while it moves less than the margin: on a laser's dense
 *    map some 3 vectors a reading in an iteration rather than 47 within match_mm and
 *    more in the cells, and a normal needed mostly for the nearest alone;
 *  - the order of the candidates matters only between candidates at exactly the same
 *    distance: there the plain scan's order is recomputed (plain_first) and decides.
 */
struct hl_refiner {
    hl_refine_params_t p;
    uint32_t capacity;      /* map vectors */
    hl_cellhash_t near;     /* the map by cells of reach_mm */
    hl_cellhash_t plain;    /* the plain method's cells (its order breaks ties): never
                               built, only its cell size and bucket count are used */
    double *nx, *ny;        /* [capacity] unit surface normal, towards the sensors ... */
    uint32_t *stamp;        /* [capacity] ... valid when stamp == run */
    uint32_t run;
    double *px, *py;        /* [HL_SCAN_MAX_READINGS] valid readings in the robot frame */
    struct near_list {      /* [HL_SCAN_MAX_READINGS] each reading's map vectors ... */
        double ax, ay;      /* ... within reach_mm of this world point (its anchor), */
        uint32_t first, count;  /* pool[first ...]; count > LIST_MAX: no list this run */
        uint32_t room;      /* entries pool[first ...] holds */
        uint32_t run;       /* valid when run == the refiner's run */
    } *lists;
    struct near_vector {    /* a map vector near an anchor */
        int32_t x, y;
        uint32_t j;         /* map index */
        uint32_t ring;      /* the ring round the anchor it lies in */
    } *pool, *scratch;      /* [pool_size] the lists; [capacity] */
    uint32_t pool_size, pool_used;  /* the lists' room, and how much a run has taken */
    double ring_mm[RINGS];  /* each ring's inner edge: a vector in it is at least so far */
};

void hl_refine_params_default(hl_refine_params_t *p)
{
    p->normal_radius_mm = HL_REFINE_NORMAL_RADIUS_MM;
    p->match_mm = HL_REFINE_MATCH_MM;
    p->huber_mm = HL_REFINE_HUBER_MM;
    p->max_shift_mm = HL_REFINE_MAX_SHIFT_MM;
    p->max_turn = hl_bam_from_deg(HL_REFINE_MAX_TURN_DEG);
    p->iterations = HL_REFINE_ITERATIONS;
    p->min_matches = HL_REFINE_MIN_MATCHES;
}

const char *hl_refine_params_error(const hl_refine_params_t *p)
{
    if (!p)
        return "no refinement parameters";
    if (p->normal_radius_mm < 1 || p->normal_radius_mm > 100000)
        return "refine normal_radius_mm must be in 1..100000";
    if (p->match_mm < 1 || p->match_mm > 100000)
        return "refine match_mm must be in 1..100000";
    if (p->huber_mm < 1)
        return "refine huber_mm must be positive";
    if (p->max_shift_mm < 0)
        return "refine max_shift_mm must not be negative";
    if (p->iterations < 1 || p->iterations > 1000)
        return "refine iterations must be in 1..1000";
    return NULL;
}

/* How far from its anchor a reading's list reaches: the match distance and the margin. */
static int32_t reach_mm(const hl_refine_params_t *p)
{
    return p->match_mm + MARGIN_MM;
}

/* The hash's cells: a list's reach (its 3 x 3 cells hold a list), or larger so that a
 * normal's radius spans few cells whatever the parameters. */
static int32_t cell_mm(const hl_refine_params_t *p)
{
    int32_t quarter = (p->normal_radius_mm + 3) / 4;
    return reach_mm(p) > quarter ? reach_mm(p) : quarter;
}

hl_refiner_t *hl_refine_create(const hl_refine_params_t *p, uint32_t max_map_vectors)
{
    if (hl_refine_params_error(p) || max_map_vectors < 1 || max_map_vectors > HL_MAP_MAX_CAPACITY)
        return NULL;
    hl_refiner_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->capacity = max_map_vectors;
    bool ok = hl_cellhash_init(&r->near, cell_mm(p), max_map_vectors);
    r->plain.cell_mm = p->normal_radius_mm > p->match_mm ? p->normal_radius_mm : p->match_mm;
    r->plain.buckets = r->near.buckets;
    for (uint32_t k = 0; k < RINGS; k++)
        r->ring_mm[k] = (double)k * reach_mm(p) / RINGS;
    r->nx = malloc(max_map_vectors * sizeof *r->nx);
    r->ny = malloc(max_map_vectors * sizeof *r->ny);
    r->stamp = calloc(max_map_vectors, sizeof *r->stamp);
    r->px = malloc(HL_SCAN_MAX_READINGS * sizeof *r->px);
    r->py = malloc(HL_SCAN_MAX_READINGS * sizeof *r->py);
    r->lists = calloc(HL_SCAN_MAX_READINGS, sizeof *r->lists);
    r->pool_size = max_map_vectors < POOL_MAX / POOL_PER_VECTOR ? max_map_vectors * POOL_PER_VECTOR
                                                                : POOL_MAX;
    r->pool = malloc(r->pool_size * sizeof *r->pool);
    r->scratch = malloc(max_map_vectors * sizeof *r->scratch);
    if (!ok || !r->nx || !r->ny || !r->stamp || !r->px || !r->py || !r->lists || !r->pool ||
        !r->scratch) {
        hl_refine_destroy(r);
        return NULL;
    }
    return r;
}

void hl_refine_destroy(hl_refiner_t *r)
{
    if (!r)
        return;
    hl_cellhash_free(&r->near);
    free(r->nx);
    free(r->ny);
    free(r->stamp);
    free(r->px);
    free(r->py);
    free(r->lists);
    free(r->pool);
    free(r->scratch);
    free(r);
}

size_t hl_refine_mem_bytes(const hl_refiner_t *r)
{
    return sizeof *r + hl_cellhash_mem_bytes(&r->near) +
           r->capacity * (sizeof *r->nx + sizeof *r->ny + sizeof *r->stamp) +
           HL_SCAN_MAX_READINGS * (sizeof *r->px + sizeof *r->py + sizeof *r->lists) +
           ((size_t)r->pool_size + r->capacity) * sizeof *r->pool;
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
static void compute_normal(hl_refiner_t *r, const hl_vector_t *map, uint32_t i)
{
    const hl_cellhash_t *g = &r->near;
    const hl_vector_t *a = &map[i];
    const int32_t rad = r->p.normal_radius_mm, side = g->cell_mm;
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
static void need_normal(hl_refiner_t *r, const hl_vector_t *map, uint32_t i)
{
    if (r->stamp[i] != r->run) {
        compute_normal(r, map, i);
        r->stamp[i] = r->run;
    }
}

/* ---- matching -------------------------------------------------------------------- */

/* Where vector j's bucket comes in the plain method's scan around (x, y): the 3 x 3
 * plain cells row by row, each bucket at its first cell. 9 if not there. */
static int plain_slot(const hl_refiner_t *r, double x, double y, const hl_vector_t *v)
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
static bool plain_first(const hl_refiner_t *r, const hl_vector_t *map, double x, double y,
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
static bool beats(hl_refiner_t *r, const hl_vector_t *map, uint32_t j, double d2, int32_t best,
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
static uint32_t gather(hl_refiner_t *r, double wx, double wy, uint32_t ring_start[RINGS + 1])
{
    const hl_cellhash_t *g = &r->near;
    double reach = reach_mm(&r->p), reach2 = reach * reach;   /* cells at least as large */
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
static bool draw_list(hl_refiner_t *r, uint32_t i, double wx, double wy)
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
static int32_t nearest_of(hl_refiner_t *r, const hl_vector_t *map, const struct near_vector *v,
                          uint32_t n, double moved, double wx, double wy, double sx, double sy)
{
    double best2 = (double)r->p.match_mm * r->p.match_mm, bound = r->p.match_mm + moved;
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
static int32_t nearest_in_cells(hl_refiner_t *r, const hl_vector_t *map, double wx, double wy,
                                double sx, double sy)
{
    const hl_cellhash_t *g = &r->near;
    double best2 = (double)r->p.match_mm * r->p.match_mm;
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
static int32_t nearest_facing(hl_refiner_t *r, const hl_vector_t *map, uint32_t i,
                              double wx, double wy, double sx, double sy)
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

/* Solves the dim x dim system a * x = b (dim 2 or 3) by Gaussian elimination with
 * partial pivoting. @return false if singular. */
static bool solve(double a[3][3], double b[3], int dim, double x[3])
{
    for (int c = 0; c < dim; c++) {
        int piv = c;
        for (int k = c + 1; k < dim; k++)
            if (fabs(a[k][c]) > fabs(a[piv][c]))
                piv = k;
        if (fabs(a[piv][c]) < 1e-9)
            return false;
        for (int k = 0; k < 3; k++) {
            double t = a[c][k];
            a[c][k] = a[piv][k];
            a[piv][k] = t;
        }
        double t = b[c];
        b[c] = b[piv];
        b[piv] = t;
        for (int k = c + 1; k < dim; k++) {
            double f = a[k][c] / a[c][c];
            for (int l = c; l < dim; l++)
                a[k][l] -= f * a[c][l];
            b[k] -= f * b[c];
        }
    }
    for (int c = dim - 1; c >= 0; c--) {
        double s = b[c];
        for (int l = c + 1; l < dim; l++)
            s -= a[c][l] * x[l];
        x[c] = s / a[c][c];
    }
    return true;
}

/* One Gauss-Newton step of the weighted point-to-line problem at pose (x, y, th) over
 * the nread readings in px, py. @return the number of matched readings; 0 leaves step
 * untouched. */
static uint32_t gauss_newton_step(hl_refiner_t *r, const hl_vector_t *map, uint32_t nread,
                                  const double pose[3], int dim, double step[3])
{
    double a[3][3] = { { 0 } }, b[3] = { 0 };
    double c = cos(pose[2]), s = sin(pose[2]);
    uint32_t matched = 0;
    for (uint32_t i = 0; i < nread; i++) {
        double px = r->px[i], py = r->py[i];
        double wx = pose[0] + c * px - s * py;
        double wy = pose[1] + s * px + c * py;
        int32_t best = nearest_facing(r, map, i, wx, wy, pose[0], pose[1]);
        if (best < 0)
            continue;
        double nx = r->nx[best], ny = r->ny[best];
        double res = nx * (wx - map[best].x_mm) + ny * (wy - map[best].y_mm);
        double j[3] = { nx, ny, nx * (-s * px - c * py) + ny * (c * px - s * py) };
        double w = fabs(res) <= r->p.huber_mm ? 1.0 : r->p.huber_mm / fabs(res);
        for (int k = 0; k < dim; k++) {
            for (int l = 0; l < dim; l++)
                a[k][l] += w * j[k] * j[l];
            b[k] -= w * j[k] * res;
        }
        matched++;
    }
    step[2] = 0;
    if (matched == 0 || !solve(a, b, dim, step))
        return 0;
    return matched;
}

/* The valid readings in the robot frame, in scan order (the same for every iteration). */
static uint32_t gather_readings(hl_refiner_t *r, const hl_scan_t *scan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *rd = &scan->readings[i];
        if (!rd->valid)
            continue;
        double bx, by;
        unit_normal(rd->bearing, &bx, &by);
        r->px[n] = rd->range_mm * bx;
        r->py[n] = rd->range_mm * by;
        n++;
    }
    return n;
}

static hl_status_t run(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, hl_pose_t start, bool heading, bool check,
                       hl_pose_t *out);

hl_status_t hl_refine_run(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                          const hl_scan_t *scan, hl_pose_t start, bool heading,
                          hl_pose_t *out)
{
    return run(r, map, n, scan, start, heading, true, out);
}

hl_status_t hl_refine_run_valid(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                                const hl_scan_t *scan, hl_pose_t start, bool heading,
                                hl_pose_t *out)
{
    return run(r, map, n, scan, start, heading, false, out);
}

/* hl_refine_run; the scan checked only when @p check. */
static hl_status_t run(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, hl_pose_t start, bool heading, bool check,
                       hl_pose_t *out)
{
    if (!r || !scan || !out || (n > 0 && !map))
        return HL_ERR_ARG;
    *out = start;
    if (n > r->capacity)
        return HL_ERR_CAPACITY;
    if ((check && hl_scan_check(scan) != HL_OK) || !hl_pose_in_range(start))
        return HL_ERR_RANGE;
    if (n == 0)
        return HL_ERR_EMPTY;
    hl_cellhash_build(&r->near, map, n);
    /* A new run: every normal and list is stale (both restart before the counter wraps). */
    if (++r->run == 0) {
        memset(r->stamp, 0, r->capacity * sizeof *r->stamp);
        memset(r->lists, 0, HL_SCAN_MAX_READINGS * sizeof *r->lists);
        r->run = 1;
    }
    uint32_t nread = gather_readings(r, scan);
    r->pool_used = 0;

    const double th0 = hl_bam_to_rad(start.theta);
    double pose[3] = { start.x_mm, start.y_mm, th0 };
    int dim = heading ? 3 : 2;
    uint32_t matched = 0;
    for (uint16_t it = 0; it < r->p.iterations; it++) {
        double step[3];
        matched = gauss_newton_step(r, map, nread, pose, dim, step);
        if (matched == 0 || !isfinite(step[0]) || !isfinite(step[1]) || !isfinite(step[2]))
            return HL_ERR_EMPTY;
        pose[0] += step[0];
        pose[1] += step[1];
        pose[2] += step[2];
        if (fabs(step[0]) < 0.5 && fabs(step[1]) < 0.5 && fabs(step[2]) < 1e-5)
            break;
    }
    double dx = pose[0] - start.x_mm, dy = pose[1] - start.y_mm;
    double turn = remainder(pose[2] - th0, TWO_PI);
    if (matched < r->p.min_matches || !isfinite(dx) || !isfinite(dy) || !isfinite(turn) ||
        dx * dx + dy * dy > (double)r->p.max_shift_mm * r->p.max_shift_mm ||
        fabs(turn) > hl_bam_to_rad(r->p.max_turn))
        return HL_ERR_EMPTY;
    hl_pose_t refined = { .x_mm = (hl_mm_t)lround(pose[0]), .y_mm = (hl_mm_t)lround(pose[1]),
                          .theta = hl_bam_from_rad(pose[2]) };
    if (!hl_pose_in_range(refined))
        return HL_ERR_EMPTY;
    *out = refined;
    return HL_OK;
}
