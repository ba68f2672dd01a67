/* peak.c - peak finding and sub-cell interpolation (see peak.h). */
#include "peak.h"

#include <stddef.h>

uint32_t hl_grid_score(const hl_grid_t *g, int32_t ix, int32_t iy, int32_t it)
{
    uint32_t c = g->cells[((int64_t)it * g->ny + iy) * g->nx + ix];
    if (!g->wx)
        return c;
    uint64_t w = (uint64_t)g->wx[ix] * g->wy[iy] * g->wt[it];  /* < 2^24 */
    return (uint32_t)(((uint64_t)c * w) >> 24);
}

/* Highest score over the raster, skipping cells closer than the separation to
 * (cx, cy) when sep2 > 0. */
static void scan_best(const hl_grid_t *g, int64_t cell2, int64_t sep2, int32_t cx,
                      int32_t cy, hl_peak_t *best)
{
    best->score = 0;
    best->ix = best->iy = best->it = 0;
    for (int32_t it = 0; it < g->nt; it++) {
        for (int32_t iy = 0; iy < g->ny; iy++) {
            int64_t dy2 = (int64_t)(iy - cy) * (iy - cy) * cell2;
            for (int32_t ix = 0; ix < g->nx; ix++) {
                if (sep2 > 0 && dy2 + (int64_t)(ix - cx) * (ix - cx) * cell2 < sep2)
                    continue;
                uint32_t s = hl_grid_score(g, ix, iy, it);
                if (s > best->score) {
                    best->score = s;
                    best->ix = ix;
                    best->iy = iy;
                    best->it = it;
                }
            }
        }
    }
}

int hl_peak_find(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, hl_peak_t *out)
{
    int64_t cell2 = (int64_t)cell_mm * cell_mm;
    scan_best(g, cell2, 0, 0, 0, out);
    if (out->score == 0)
        return 0;
    hl_peak_t other;
    int64_t sep2 = sep_mm > 0 ? (int64_t)sep_mm * sep_mm : 1;
    scan_best(g, cell2, sep2, out->ix, out->iy, &other);
    out->second = other.score;
    return 1;
}

int32_t hl_peak_offset(uint32_t l, uint32_t c, uint32_t r, int32_t step)
{
    int64_t den = 2 * ((int64_t)l - 2 * (int64_t)c + (int64_t)r);
    if (den >= 0)
        return 0;   /* not a strict maximum: no curvature to interpolate */
    int64_t num = ((int64_t)l - (int64_t)r) * step;
    /* num / den rounded to nearest, half away from zero; den < 0. */
    int64_t mag = ((num < 0 ? -num : num) + (-den) / 2) / (-den);
    int64_t q = num > 0 ? -mag : mag;
    int64_t half = step / 2;
    if (q > half)
        q = half;
    if (q < -half)
        q = -half;
    return (int32_t)q;
}
