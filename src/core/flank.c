/* flank.c - the normals of readings on a wall's flank (flank.h). */
#include "houghloc-internal/flank.h"

#include <math.h>
#include <stdlib.h>

/* The falling side of reading a: -1 when the range falls towards lower bearings (the
 * wall's foot is there), +1 towards higher ones, 0 on a plateau, at a peak or a dip, or
 * without a neighbour on both sides. */
static int falling_side(const hl_scan_t *in, const uint32_t *order, int32_t lo, uint32_t a,
                        int32_t hi)
{
    if (lo < 0 || hi < 0)
        return 0;
    int32_t r = in->readings[order[a] & 0xFFFF].range_mm;
    int32_t rl = in->readings[order[lo] & 0xFFFF].range_mm;
    int32_t rh = in->readings[order[hi] & 0xFFFF].range_mm;
    if (abs(rl - r) <= HL_FLANK_FLAT_MM || abs(rh - r) <= HL_FLANK_FLAT_MM)
        return 0;
    if (rl < r && r < rh)
        return -1;
    if (rh < r && r < rl)
        return 1;
    return 0;
}

/* The neighbour of position a in @p order on @p dir's side (-1 or +1), or -1 if the next
 * reading round the ring is farther than @p gap. */
static int32_t neighbour(const hl_scan_t *in, const uint32_t *order, uint32_t n, uint32_t a,
                         int dir, int32_t gap)
{
    if (n < 2)
        return -1;
    uint32_t k = dir < 0 ? (a + n - 1) % n : (a + 1) % n;
    int32_t d = hl_bam_diff(in->readings[order[k] & 0xFFFF].bearing,
                            in->readings[order[a] & 0xFFFF].bearing);
    return d * dir > 0 && d * dir <= gap ? (int32_t)k : -1;
}

/* The echo of @p r at its cone's edge on @p side, as a point in mm. */
static void edge_point(const hl_echo_params_t *p, const hl_reading_t *r, int side, double *x,
                       double *y)
{
    double a = hl_bam_to_rad((hl_bam_t)(r->bearing + side * (int32_t)p->half_beam));
    *x = r->range_mm * cos(a);
    *y = r->range_mm * sin(a);
}

void hl_flank_normals(const hl_echo_params_t *p, const hl_scan_t *in, const uint32_t *order,
                      uint32_t n, hl_scan_t *out)
{
    const int32_t gap = p->half_beam / 2;
    const int32_t edge_on = HL_BAM_QUARTER_TURN - hl_bam_from_deg(5.0);
    for (uint32_t a = 0; a < n; a++) {
        int32_t lo = neighbour(in, order, n, a, -1, gap), hi = neighbour(in, order, n, a, 1, gap);
        int side = falling_side(in, order, lo, a, hi);
        if (side == 0)
            continue;
        const hl_reading_t *ri = &in->readings[order[a] & 0xFFFF];
        const hl_reading_t *up = &in->readings[order[side < 0 ? hi : lo] & 0xFFFF];
        double xi, yi, xk, yk;
        edge_point(p, ri, side, &xi, &yi);
        edge_point(p, up, side, &xk, &yk);
        double nx = yi - yk, ny = xk - xi;      /* square to the wall ... */
        if (nx * xi + ny * yi > 0) {            /* ... facing the sensor */
            nx = -nx;
            ny = -ny;
        }
        hl_reading_t *o = &out->readings[order[a] & 0xFFFF];
        o->bearing = (hl_bam_t)(ri->bearing + side * (int32_t)p->half_beam);
        int32_t tilt = hl_bam_diff(hl_bam_from_rad(atan2(ny, nx)),
                                   (hl_bam_t)(o->bearing + HL_BAM_HALF_TURN));
        if (tilt > -edge_on && tilt < edge_on)
            o->tilt = (int16_t)tilt;
    }
}
