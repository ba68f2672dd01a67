/* peak.c - peak finding and sub-cell interpolation (see peak.h). */
#include "peak.h"
#include "simd.h"

#include <stddef.h>

uint32_t hl_grid_score(const hl_grid_t *g, int32_t ix, int32_t iy, int32_t it)
{
    uint32_t c = g->cells[((int64_t)it * g->ny + iy) * g->nx + ix];
    if (!g->wx)
        return c;
    uint64_t w = (uint64_t)g->wx[ix] * g->wy[iy] * g->wt[it];  /* < 2^24 */
    return (uint32_t)(((uint64_t)c * w) >> 24);
}

/* Highest score over the raster. A plain max over a flat array when there is no prior
 * (the common case), so the compiler can vectorize it. */
HL_VECTOR_KERNEL
static void find_best(const hl_grid_t *g, hl_peak_t *best)
{
    best->score = 0;
    best->ix = best->iy = best->it = 0;
    size_t plane = (size_t)g->nx * g->ny, n = plane * (size_t)g->nt, at = 0;
    if (!g->wx) {
        uint32_t m = 0;
        for (size_t i = 0; i < n; i++)
            m = g->cells[i] > m ? g->cells[i] : m;
        if (m == 0)
            return;
        while (g->cells[at] != m)
            at++;
        best->score = m;
    } else {
        for (int32_t it = 0; it < g->nt; it++)
            for (int32_t iy = 0; iy < g->ny; iy++)
                for (int32_t ix = 0; ix < g->nx; ix++) {
                    uint32_t v = hl_grid_score(g, ix, iy, it);
                    if (v > best->score) {
                        best->score = v;
                        at = (size_t)it * plane + (size_t)iy * g->nx + (size_t)ix;
                    }
                }
    }
    best->it = (int32_t)(at / plane);
    best->iy = (int32_t)(at % plane / (size_t)g->nx);
    best->ix = (int32_t)(at % (size_t)g->nx);
}

/* Highest score among cells at least sqrt(sep2) mm from (cx, cy) in xy; each row skips
 * the run of cells inside the circle. */
static uint32_t find_second(const hl_grid_t *g, int64_t cell2, int64_t sep2, int32_t cx,
                            int32_t cy)
{
    uint32_t best = 0;
    for (int32_t it = 0; it < g->nt; it++)
        for (int32_t iy = 0; iy < g->ny; iy++) {
            int64_t dy2 = (int64_t)(iy - cy) * (iy - cy) * cell2;
            /* cells with (ix - cx)^2 * cell2 < sep2 - dy2 are too close: skip [lo, hi) */
            int32_t lo = g->nx, hi = g->nx;
            if (dy2 < sep2) {
                int32_t r = 0;
                while ((int64_t)(r + 1) * (r + 1) * cell2 < sep2 - dy2)
                    r++;
                lo = cx - r < 0 ? 0 : cx - r;
                hi = cx + r + 1 > g->nx ? g->nx : cx + r + 1;
            }
            for (int32_t ix = 0; ix < lo; ix++) {
                uint32_t v = hl_grid_score(g, ix, iy, it);
                best = v > best ? v : best;
            }
            for (int32_t ix = hi; ix < g->nx; ix++) {
                uint32_t v = hl_grid_score(g, ix, iy, it);
                best = v > best ? v : best;
            }
        }
    return best;
}

int hl_peak_find(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, hl_peak_t *out)
{
    find_best(g, out);
    if (out->score == 0)
        return 0;
    int64_t sep2 = sep_mm > 0 ? (int64_t)sep_mm * sep_mm : 1;
    out->second = find_second(g, (int64_t)cell_mm * cell_mm, sep2, out->ix, out->iy);
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
