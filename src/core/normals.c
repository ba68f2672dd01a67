/* normals.c - each reading's surface normal from the line through its neighbours (see
 * normals.h). */
#include "houghloc-internal/normals.h"

#include <math.h>
#include <stddef.h>

#include "houghloc-internal/params.h"
#include "valid_scan.h"

void hl_normals_params_default(hl_normals_params_t *p)
{
    p->half_window = HL_NORMALS_HALF_WINDOW;
    p->reach_mm = HL_NORMALS_REACH_MM;
    /* min_points, max_residual_mm, max_tilt, keep_unfitted: normals.* (params_table.c) */
    hl_params_fill_defaults(p, offsetof(hl_slam_params_t, normals), sizeof *p);
}

const char *hl_normals_params_error(const hl_normals_params_t *p)
{
    if (!p)
        return "no normals parameters";
    if (p->half_window < 1 || p->half_window > HL_NORMALS_MAX_HALF_WINDOW)
        return "normals half_window must be in 1..32";
    if (p->reach_mm < 1 || p->reach_mm > 10000)
        return "normals reach_mm must be in 1..10000";
    if (p->min_points < 3 || p->min_points > 2 * p->half_window + 1)
        return "normals min_points must be in 3..2 x half_window + 1";
    if (p->max_residual_mm < 1 || p->max_residual_mm > 10000)
        return "normals max_residual_mm must be in 1..10000";
    if (p->max_tilt < 1 || p->max_tilt >= HL_BAM_QUARTER_TURN)
        return "normals max_tilt must be above 0 and below 90 degrees";
    return NULL;
}

/* A reading's point in the robot frame, in mm (the residual test is in mm). */
static void point_of(const hl_reading_t *r, double *x, double *y)
{
    double a = hl_bam_to_rad(r->bearing);
    *x = r->range_mm * cos(a);
    *y = r->range_mm * sin(a);
}

/* The tilt of reading i's surface, or false when it has none: the points of the valid
 * readings within half_window places and reach_mm of it make a line (principal axis of
 * their scatter) if there are min_points of them and their RMS distance from it is within
 * max_residual_mm, and the surface is not seen more obliquely than max_tilt. */
static bool fit_one(const hl_normals_params_t *p, const hl_scan_t *in, uint32_t i,
                    const double *px, const double *py, int16_t *tilt)
{
    uint32_t lo = i >= p->half_window ? i - p->half_window : 0;
    uint32_t hi = i + p->half_window < in->count ? i + p->half_window : in->count - 1;
    double reach2 = (double)p->reach_mm * p->reach_mm;
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    uint32_t n = 0;
    for (uint32_t k = lo; k <= hi; k++) {
        if (!in->readings[k].valid)
            continue;
        double dx = px[k] - px[i], dy = py[k] - py[i];  /* about the reading: well scaled */
        if (dx * dx + dy * dy > reach2)
            continue;
        sx += dx;
        sy += dy;
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
        n++;
    }
    if (n < p->min_points)
        return false;
    double mx = sx / n, my = sy / n;
    double cxx = sxx / n - mx * mx, cyy = syy / n - my * my, cxy = sxy / n - mx * my;
    /* The scatter's smaller eigenvalue is the mean squared distance from the best line. */
    double half_sum = (cxx + cyy) / 2, root = sqrt((cxx - cyy) * (cxx - cyy) / 4 + cxy * cxy);
    double across = half_sum - root;
    if (across > (double)p->max_residual_mm * p->max_residual_mm)
        return false;
    double along = 0.5 * atan2(2 * cxy, cxx - cyy);     /* the line's direction */
    double nx = -sin(along), ny = cos(along);
    if (nx * px[i] + ny * py[i] > 0) {                  /* face the sensor */
        nx = -nx;
        ny = -ny;
    }
    const hl_reading_t *r = &in->readings[i];
    hl_bam_t reverse = (hl_bam_t)(r->bearing + HL_BAM_HALF_TURN);
    int32_t d = (int16_t)(uint16_t)(hl_bam_from_rad(atan2(ny, nx)) - reverse);
    if (d < -(int32_t)p->max_tilt || d > (int32_t)p->max_tilt)
        return false;
    *tilt = (int16_t)d;
    return true;
}

static hl_status_t fit(const hl_normals_params_t *p, const hl_scan_t *in, bool check,
                       hl_scan_t *out);

hl_status_t hl_normals_fit(const hl_normals_params_t *p, const hl_scan_t *in, hl_scan_t *out)
{
    return fit(p, in, true, out);
}

hl_status_t hl_normals_fit_valid(const hl_normals_params_t *p, const hl_scan_t *in,
                                 hl_scan_t *out)
{
    return fit(p, in, false, out);
}

/* hl_normals_fit; the scan checked only when @p check. */
static hl_status_t fit(const hl_normals_params_t *p, const hl_scan_t *in, bool check,
                       hl_scan_t *out)
{
    if (!p || !in || !out || hl_normals_params_error(p))
        return HL_ERR_ARG;
    if ((const void *)in < (const void *)(out + 1) && (const void *)out < (const void *)(in + 1))
        return HL_ERR_ARG;
    if (check && hl_scan_check(in) != HL_OK)
        return HL_ERR_RANGE;
    double px[HL_SCAN_MAX_READINGS], py[HL_SCAN_MAX_READINGS];     /* 16 KiB */
    for (uint32_t i = 0; i < in->count; i++)
        if (in->readings[i].valid)
            point_of(&in->readings[i], &px[i], &py[i]);
    out->count = in->count;
    for (uint32_t i = 0; i < in->count; i++) {
        out->readings[i] = in->readings[i];
        if (in->readings[i].valid && !fit_one(p, in, i, px, py, &out->readings[i].tilt))
            out->readings[i].valid = p->keep_unfitted;
    }
    return HL_OK;
}
