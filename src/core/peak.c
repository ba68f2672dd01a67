/* peak.c - peak finding and sub-cell interpolation (see peak.h).
 *
 * Speed (docs/results/performance.md): both searches go row by row (one row = the nx cells of
 * one iy and it), so that a row's prior weight wy[iy] * wt[it] is taken once and the
 * inner loop is a plain max over a contiguous run that the compiler vectorizes. The
 * first search keeps each row's best score (in the caller's scratch, when it gives one);
 * the second then skips every row that cannot beat what it has already found, and takes
 * the kept score of a row that the separation circle does not cut. Both are maxima of
 * the same integer scores, so the results are those of a plain cell-by-cell scan.
 */
#include "peak.h"
#include "simd.h"

#include <stdbool.h>
#include <stddef.h>

uint32_t hl_grid_score(const hl_grid_t *g, int32_t ix, int32_t iy, int32_t it)
{
    uint32_t c = g->cells[((int64_t)it * g->ny + iy) * g->nx + ix];
    if (!g->wx)
        return c;
    uint64_t w = (uint64_t)g->wx[ix] * g->wy[iy] * g->wt[it];  /* < 2^24 */
    return (uint32_t)(((uint64_t)c * w) >> 24);
}

/* Largest score of cells x0 .. x1 - 1 of a row without a prior. */
HL_VECTOR_KERNEL
static uint32_t max_plain(const uint32_t *restrict row, int32_t x0, int32_t x1)
{
    uint32_t m = 0;
    for (int32_t ix = x0; ix < x1; ix++)
        m = row[ix] > m ? row[ix] : m;
    return m;
}

/* The same with the prior, when wx[ix] * wyt < 2^32 for every ix of the row (checked by
 * the caller): then (c * wx * wy * wt) >> 24 is a 32 x 32 -> 64 bit product, which
 * vectorizes; the integer is the one hl_grid_score computes. */
HL_VECTOR_KERNEL
static uint32_t max_prior32(const uint32_t *restrict row, const uint32_t *restrict wx,
                            uint32_t wyt, int32_t x0, int32_t x1)
{
    uint32_t m = 0;
    for (int32_t ix = x0; ix < x1; ix++) {
        uint32_t v = (uint32_t)(((uint64_t)row[ix] * (wx[ix] * wyt)) >> 24);
        m = v > m ? v : m;
    }
    return m;
}

/* Row scans: what a row's cells x0 .. x1 - 1 score at best. */
typedef struct rows {
    const hl_grid_t *g;
    bool narrow;            /* prior weights whose products fit in 32 bits */
} rows_t;

static rows_t rows_of(const hl_grid_t *g)
{
    rows_t r = { .g = g, .narrow = false };
    if (g->wx) {
        uint64_t mx = 0, my = 0, mt = 0;
        for (int32_t i = 0; i < g->nx; i++)
            mx = g->wx[i] > mx ? g->wx[i] : mx;
        for (int32_t i = 0; i < g->ny; i++)
            my = g->wy[i] > my ? g->wy[i] : my;
        for (int32_t i = 0; i < g->nt; i++)
            mt = g->wt[i] > mt ? g->wt[i] : mt;
        /* each factor < 2^32, so the product of two fits in 64 bits; test in two steps */
        r.narrow = my * mt <= UINT32_MAX && mx * (my * mt) <= UINT32_MAX;
    }
    return r;
}

static uint32_t row_max(const rows_t *r, int32_t iy, int32_t it, int32_t x0, int32_t x1)
{
    const hl_grid_t *g = r->g;
    const uint32_t *row = g->cells + ((int64_t)it * g->ny + iy) * g->nx;
    if (!g->wx)
        return max_plain(row, x0, x1);
    if (r->narrow)
        return max_prior32(row, g->wx, g->wy[iy] * g->wt[it], x0, x1);
    uint32_t m = 0;
    for (int32_t ix = x0; ix < x1; ix++) {
        uint32_t v = hl_grid_score(g, ix, iy, it);
        m = v > m ? v : m;
    }
    return m;
}

/* Highest score over the raster; ties go to the first cell in [it][iy][ix] order: the
 * first row that reaches the maximum, and its first cell that does. */
static void find_best(const rows_t *r, hl_peak_t *best)
{
    const hl_grid_t *g = r->g;
    best->score = 0;
    best->ix = best->iy = best->it = 0;
    for (int32_t it = 0; it < g->nt; it++)
        for (int32_t iy = 0; iy < g->ny; iy++) {
            uint32_t m = row_max(r, iy, it, 0, g->nx);
            if (g->row_max)
                g->row_max[(int64_t)it * g->ny + iy] = m;
            if (m > best->score) {
                best->score = m;
                best->iy = iy;
                best->it = it;
            }
        }
    if (best->score == 0)
        return;
    while (hl_grid_score(g, best->ix, best->iy, best->it) != best->score)
        best->ix++;
}

int32_t hl_peak_reach(int64_t cell2, int64_t sep2, int32_t dy)
{
    int64_t dy2 = (int64_t)dy * dy * cell2;
    if (dy2 >= sep2)
        return -1;
    /* cells with (ix - cx)^2 * cell2 < sep2 - dy2 are too close */
    int32_t r = 0;
    while ((int64_t)(r + 1) * (r + 1) * cell2 < sep2 - dy2)
        r++;
    return r;
}

/* Highest score among cells at least sqrt(sep2) mm from (cx, cy) in xy; each row skips
 * the run of cells inside the circle. */
static uint32_t find_second(const rows_t *rw, int64_t cell2, int64_t sep2, int32_t cx,
                            int32_t cy)
{
    const hl_grid_t *g = rw->g;
    uint32_t best = 0;
    for (int32_t iy = 0; iy < g->ny; iy++) {
        /* the row's cells too close to the peak: skip [lo, hi) */
        int32_t lo = g->nx, hi = g->nx;
        int32_t r = hl_peak_reach(cell2, sep2, iy - cy);
        if (r >= 0) {
            lo = cx - r < 0 ? 0 : cx - r;
            hi = cx + r + 1 > g->nx ? g->nx : cx + r + 1;
        }
        for (int32_t it = 0; it < g->nt; it++) {
            if (g->row_max) {
                uint32_t m = g->row_max[(int64_t)it * g->ny + iy];
                if (m <= best)
                    continue;   /* nothing in this row can raise the maximum */
                if (lo == hi) {
                    best = m;   /* the circle leaves the whole row */
                    continue;
                }
            }
            uint32_t a = row_max(rw, iy, it, 0, lo), b = row_max(rw, iy, it, hi, g->nx);
            a = a > b ? a : b;
            best = a > best ? a : best;
        }
    }
    return best;
}

static uint32_t second_of(const rows_t *r, int32_t cell_mm, int32_t sep_mm, int32_t cx,
                          int32_t cy)
{
    return find_second(r, (int64_t)cell_mm * cell_mm, hl_peak_sep2(sep_mm), cx, cy);
}

int hl_peak_find(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, hl_peak_t *out)
{
    rows_t r = rows_of(g);
    find_best(&r, out);
    if (out->score == 0)
        return 0;
    out->second = second_of(&r, cell_mm, sep_mm, out->ix, out->iy);
    return 1;
}

uint32_t hl_peak_second(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, int32_t cx,
                        int32_t cy)
{
    rows_t r = rows_of(g);
    return second_of(&r, cell_mm, sep_mm, cx, cy);
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
