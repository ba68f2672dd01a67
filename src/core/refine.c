/* refine.c - point-to-line polishing of a Hough pose (see refine.h). */
#include "houghloc-internal/refine.h"

#include <math.h>
#include <stdlib.h>

#include "nearest.h"
#include "valid_scan.h"

#define TWO_PI 6.28318530717958647692

/* The matching, the polish's cost, is nearest.c's; this is the Gauss-Newton fit. */
struct hl_refiner {
    hl_refine_params_t p;
    uint32_t capacity;      /* map vectors */
    hl_nearest_t match;     /* the nearest facing vectors and their normals */
    double *px, *py;        /* [HL_SCAN_MAX_READINGS] valid readings in the robot frame */
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

hl_refiner_t *hl_refine_create(const hl_refine_params_t *p, uint32_t max_map_vectors)
{
    if (hl_refine_params_error(p) || max_map_vectors < 1 || max_map_vectors > HL_MAP_MAX_CAPACITY)
        return NULL;
    hl_refiner_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->capacity = max_map_vectors;
    bool ok = hl_nearest_init(&r->match, p, max_map_vectors);
    r->px = malloc(HL_SCAN_MAX_READINGS * sizeof *r->px);
    r->py = malloc(HL_SCAN_MAX_READINGS * sizeof *r->py);
    if (!ok || !r->px || !r->py) {
        hl_refine_destroy(r);
        return NULL;
    }
    return r;
}

void hl_refine_destroy(hl_refiner_t *r)
{
    if (!r)
        return;
    hl_nearest_free(&r->match);
    free(r->px);
    free(r->py);
    free(r);
}

size_t hl_refine_mem_bytes(const hl_refiner_t *r)
{
    return sizeof *r + hl_nearest_mem_bytes(&r->match) +
           HL_SCAN_MAX_READINGS * (sizeof *r->px + sizeof *r->py);
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
        int32_t best = hl_nearest_facing(&r->match, map, i, wx, wy, pose[0], pose[1]);
        if (best < 0)
            continue;
        double nx = r->match.nx[best], ny = r->match.ny[best];
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
        double a = hl_bam_to_rad(rd->bearing);
        r->px[n] = rd->range_mm * cos(a);
        r->py[n] = rd->range_mm * sin(a);
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
    hl_nearest_begin(&r->match, map, n);
    uint32_t nread = gather_readings(r, scan);

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
