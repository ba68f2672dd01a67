/* refine.c - point-to-line polishing of a Hough pose (see refine.h). */
#include "houghloc/refine.h"

#include <math.h>
#include <stdlib.h>

#define TWO_PI 6.28318530717958647692

struct hl_refiner {
    hl_refine_params_t p;
    uint32_t capacity;      /* map vectors */
    uint32_t buckets;       /* power of two, >= 2 * capacity */
    int32_t cell_mm;        /* hash cell: the larger of normal_radius_mm and match_mm */
    int32_t *head;          /* [buckets] first vector in the bucket, -1 if none */
    int32_t *next;          /* [capacity] next vector in the same bucket */
    double *nx, *ny;        /* [capacity] unit surface normal, towards the sensors */
};

void hl_refine_params_default(hl_refine_params_t *p)
{
    p->normal_radius_mm = 400;
    p->match_mm = 150;
    p->huber_mm = 60;
    p->max_shift_mm = 250;
    p->max_turn = hl_bam_from_deg(3.0);
    p->iterations = 20;
    p->min_matches = 12;
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

hl_refiner_t *hl_refine_create(const hl_refine_params_t *p, uint32_t max_map_vectors)
{
    if (hl_refine_params_error(p) || max_map_vectors < 1 || max_map_vectors > HL_MAP_MAX_CAPACITY)
        return NULL;
    hl_refiner_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->capacity = max_map_vectors;
    r->buckets = 1;
    while (r->buckets < 2 * max_map_vectors)
        r->buckets <<= 1;
    r->cell_mm = p->normal_radius_mm > p->match_mm ? p->normal_radius_mm : p->match_mm;
    r->head = malloc(r->buckets * sizeof *r->head);
    r->next = malloc(max_map_vectors * sizeof *r->next);
    r->nx = malloc(max_map_vectors * sizeof *r->nx);
    r->ny = malloc(max_map_vectors * sizeof *r->ny);
    if (!r->head || !r->next || !r->nx || !r->ny) {
        hl_refine_destroy(r);
        return NULL;
    }
    return r;
}

void hl_refine_destroy(hl_refiner_t *r)
{
    if (!r)
        return;
    free(r->head);
    free(r->next);
    free(r->nx);
    free(r->ny);
    free(r);
}

size_t hl_refine_mem_bytes(const hl_refiner_t *r)
{
    return sizeof *r + r->buckets * sizeof *r->head +
           r->capacity * (sizeof *r->next + sizeof *r->nx + sizeof *r->ny);
}

/* ---- the spatial hash ------------------------------------------------------------ */

static int32_t cell_of(const hl_refiner_t *r, double v)
{
    return (int32_t)floor(v / r->cell_mm);
}

static uint32_t bucket_of(const hl_refiner_t *r, int32_t cx, int32_t cy)
{
    uint32_t h = (uint32_t)cx * 73856093u ^ (uint32_t)cy * 19349663u;
    return h & (r->buckets - 1);
}

static void index_map(hl_refiner_t *r, const hl_vector_t *map, uint32_t n)
{
    for (uint32_t b = 0; b < r->buckets; b++)
        r->head[b] = -1;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t b = bucket_of(r, cell_of(r, map[i].x_mm), cell_of(r, map[i].y_mm));
        r->next[i] = r->head[b];
        r->head[b] = (int32_t)i;
    }
}

/* Calls visit(ctx, j) for every map vector in the 3 x 3 cells around (x, y). Vectors of
 * other cells that share a bucket are visited too; callers check the distance. */
typedef void (*visit_fn)(void *ctx, uint32_t j);

static void for_neighbours(const hl_refiner_t *r, double x, double y, visit_fn visit, void *ctx)
{
    int32_t cx = cell_of(r, x), cy = cell_of(r, y);
    uint32_t seen[9];
    int nseen = 0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            uint32_t b = bucket_of(r, cx + dx, cy + dy);
            bool dup = false;
            for (int k = 0; k < nseen; k++)
                dup = dup || seen[k] == b;
            if (dup)
                continue;
            seen[nseen++] = b;
            for (int32_t j = r->head[b]; j >= 0; j = r->next[j])
                visit(ctx, (uint32_t)j);
        }
    }
}

/* ---- surface normals ------------------------------------------------------------- */

static void unit_normal(hl_bam_t a, double *x, double *y)
{
    *x = cos(hl_bam_to_rad(a));
    *y = sin(hl_bam_to_rad(a));
}

struct shape {
    const hl_refiner_t *r;
    const hl_vector_t *map;
    uint32_t self;
    double r2;
    double n, sx, sy, sxx, sxy, syy;
};

static void add_to_shape(void *ctx, uint32_t j)
{
    struct shape *s = ctx;
    const hl_vector_t *a = &s->map[s->self], *b = &s->map[j];
    double dx = (double)b->x_mm - a->x_mm, dy = (double)b->y_mm - a->y_mm;
    if (dx * dx + dy * dy > s->r2 || abs(hl_bam_diff(a->normal, b->normal)) > 10923) /* 60 deg */
        return;
    s->n += 1;
    s->sx += dx;
    s->sy += dy;
    s->sxx += dx * dx;
    s->sxy += dx * dy;
    s->syy += dy * dy;
}

/* Each vector's surface normal: across the principal axis of the neighbours that face
 * the same way (itself included), oriented towards its sensor; its own normal when fewer
 * than three vectors shape it. */
static void estimate_normals(hl_refiner_t *r, const hl_vector_t *map, uint32_t n)
{
    double r2 = (double)r->p.normal_radius_mm * r->p.normal_radius_mm;
    for (uint32_t i = 0; i < n; i++) {
        double ox, oy;
        unit_normal(map[i].normal, &ox, &oy);
        r->nx[i] = ox;
        r->ny[i] = oy;
        struct shape s = { .r = r, .map = map, .self = i, .r2 = r2 };
        for_neighbours(r, map[i].x_mm, map[i].y_mm, add_to_shape, &s);
        if (s.n < 3)
            continue;
        double mx = s.sx / s.n, my = s.sy / s.n;
        double cxx = s.sxx / s.n - mx * mx, cxy = s.sxy / s.n - mx * my, cyy = s.syy / s.n - my * my;
        double axis = 0.5 * atan2(2 * cxy, cxx - cyy);
        double nx = -sin(axis), ny = cos(axis);
        if (nx * ox + ny * oy < 0) {
            nx = -nx;
            ny = -ny;
        }
        r->nx[i] = nx;
        r->ny[i] = ny;
    }
}

/* ---- alignment ------------------------------------------------------------------- */

struct match {
    const hl_refiner_t *r;
    const hl_vector_t *map;
    double wx, wy;          /* the reading's point in the world */
    double sx, sy;          /* the robot */
    double best2;
    int32_t best;
};

static void nearest_facing(void *ctx, uint32_t j)
{
    struct match *m = ctx;
    const hl_vector_t *v = &m->map[j];
    double dx = m->wx - v->x_mm, dy = m->wy - v->y_mm, d2 = dx * dx + dy * dy;
    if (d2 >= m->best2)
        return;
    /* the surface must face the robot */
    if (m->r->nx[j] * (m->sx - m->wx) + m->r->ny[j] * (m->sy - m->wy) <= 0)
        return;
    m->best2 = d2;
    m->best = (int32_t)j;
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

/* One Gauss-Newton step of the weighted point-to-line problem at pose (x, y, th).
 * @return the number of matched readings; 0 leaves step untouched. */
static uint32_t gauss_newton_step(const hl_refiner_t *r, const hl_vector_t *map,
                                  const hl_scan_t *scan, const double pose[3], int dim,
                                  double step[3])
{
    double a[3][3] = { { 0 } }, b[3] = { 0 };
    double c = cos(pose[2]), s = sin(pose[2]);
    double gate2 = (double)r->p.match_mm * r->p.match_mm;
    uint32_t matched = 0;
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *rd = &scan->readings[i];
        if (!rd->valid)
            continue;
        double bx, by;
        unit_normal(rd->bearing, &bx, &by);
        double px = rd->range_mm * bx, py = rd->range_mm * by;
        struct match m = { .r = r, .map = map, .sx = pose[0], .sy = pose[1], .best2 = gate2,
                           .best = -1 };
        m.wx = pose[0] + c * px - s * py;
        m.wy = pose[1] + s * px + c * py;
        for_neighbours(r, m.wx, m.wy, nearest_facing, &m);
        if (m.best < 0)
            continue;
        double nx = r->nx[m.best], ny = r->ny[m.best];
        double res = nx * (m.wx - map[m.best].x_mm) + ny * (m.wy - map[m.best].y_mm);
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

hl_status_t hl_refine_run(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                          const hl_scan_t *scan, hl_pose_t start, bool heading,
                          hl_pose_t *out)
{
    if (!r || !scan || !out || (n > 0 && !map))
        return HL_ERR_ARG;
    *out = start;
    if (n > r->capacity)
        return HL_ERR_CAPACITY;
    if (hl_scan_check(scan) != HL_OK || !hl_pose_in_range(start))
        return HL_ERR_RANGE;
    if (n == 0)
        return HL_ERR_EMPTY;
    index_map(r, map, n);
    estimate_normals(r, map, n);

    const double th0 = hl_bam_to_rad(start.theta);
    double pose[3] = { start.x_mm, start.y_mm, th0 };
    int dim = heading ? 3 : 2;
    uint32_t matched = 0;
    for (uint16_t it = 0; it < r->p.iterations; it++) {
        double step[3];
        matched = gauss_newton_step(r, map, scan, pose, dim, step);
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
