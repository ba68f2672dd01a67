/*
 * votesum.c - several scans' vote rasters added in the first scan's frame (votesum.h).
 */
#include "votesum.h"

#include <math.h>
#include <string.h>

bool hl_votesum_start(hl_votesum_t *v, const hl_loc_surface_t *s, hl_pose_t offset,
                      hl_mm_t corner_x, hl_mm_t corner_y)
{
    uint64_t cells = (uint64_t)s->nx * (uint64_t)s->ny * (uint64_t)s->nt;
    v->started = false;
    if (cells > v->max_cells)
        return false;
    v->geom = *s;
    v->geom.cells = v->cells;
    v->geom.votes = NULL;
    v->geom.x0_mm = corner_x;
    v->geom.y0_mm = corner_y;
    v->geom.theta0 = (hl_bam_t)(s->theta0 - offset.theta);
    memset(v->cells, 0, (size_t)cells * sizeof *v->cells);
    v->started = true;
    return true;
}

/* floor(a / b) for b > 0 */
static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

void hl_votesum_add(hl_votesum_t *v, const hl_loc_surface_t *s, hl_pose_t offset)
{
    const hl_loc_surface_t *g = &v->geom;
    if (!v->started || s->nx != g->nx || s->ny != g->ny || s->nt != g->nt ||
        s->cell_mm != g->cell_mm)
        return;
    const int64_t cell = g->cell_mm;
    const size_t plane = (size_t)g->nx * (size_t)g->ny;
    for (int32_t it = 0; it < g->nt; it++) {
        /* slice it: the first scan's heading there, and where scan k stood from it */
        double th = hl_bam_to_rad((hl_bam_t)(g->theta0 + it * g->theta_step));
        double ox = cos(th) * offset.x_mm - sin(th) * offset.y_mm;
        double oy = sin(th) * offset.x_mm + cos(th) * offset.y_mm;
        /* cell ix of scan k holds a robot at s->x0 + ix * cell (+ half); it stood at that
         * less (ox, oy) at the first scan: cell ix + sx of the sum. Rounded to the nearest
         * cell: the odometry between the scans is good to about that. */
        int64_t sx = floor_div((int64_t)s->x0_mm - g->x0_mm - llround(ox) + cell / 2, cell);
        int64_t sy = floor_div((int64_t)s->y0_mm - g->y0_mm - llround(oy) + cell / 2, cell);
        int64_t x_lo = sx < 0 ? -sx : 0, x_hi = g->nx - (sx > 0 ? sx : 0);
        if (x_lo >= x_hi)
            continue;
        const uint32_t *src = s->cells + (size_t)it * plane;
        uint32_t *dst = v->cells + (size_t)it * plane;
        for (int64_t iy = 0; iy < g->ny; iy++) {
            int64_t jy = iy + sy;
            if (jy < 0 || jy >= g->ny)
                continue;
            const uint32_t *row = src + iy * g->nx;
            uint32_t *out = dst + jy * g->nx + sx;
            for (int64_t ix = x_lo; ix < x_hi; ix++)
                out[ix] += row[ix];
        }
    }
}
