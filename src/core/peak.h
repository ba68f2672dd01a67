/*
 * peak.h (private) - the highest cell of a blurred vote raster, the best separate
 * peak, and parabolic sub-cell interpolation.
 *
 * With a prior, a cell's score is blurred * wx[ix] * wy[iy] * wt[it] >> 24, the weights
 * in Q8 (256 = 1.0), so scores stay below 2^24 like the blurred values themselves.
 * Ties go to the first cell in [it][iy][ix] order.
 */
#ifndef HOUGHLOC_CORE_PEAK_H
#define HOUGHLOC_CORE_PEAK_H

#include <stdint.h>

typedef struct hl_grid {
    const uint32_t *cells;  /* [nt][ny][nx] */
    int32_t nx, ny, nt;
    const uint32_t *wx, *wy, *wt;   /* Q8 prior weights, or all NULL for none */
    uint32_t *row_max;      /* NULL, or nt * ny cells of scratch apart from `cells`:
                               hl_peak_find keeps each row's best score there and then
                               skips most of the second-peak search */
} hl_grid_t;

typedef struct hl_peak {
    int32_t ix, iy, it;
    uint32_t score;         /* at the peak */
    uint32_t second;        /* best score at least sep_cells away in xy; 0 if none */
} hl_peak_t;

/** The score of one cell. */
uint32_t hl_grid_score(const hl_grid_t *g, int32_t ix, int32_t iy, int32_t it);

/**
 * Finds the peak and the best cell whose xy distance from it is at least
 * @p sep_mm (in cells of @p cell_mm). @return 0 if every score is 0.
 */
int hl_peak_find(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, hl_peak_t *out);

/**
 * The best score at least @p sep_mm in xy from the cell (@p cx, @p cy), as
 * hl_peak_find's second peak (for another grid over the same cells, e.g. without the
 * prior's weights).
 */
uint32_t hl_peak_second(const hl_grid_t *g, int32_t cell_mm, int32_t sep_mm, int32_t cx,
                        int32_t cy);

/** The separation @p sep_mm squared as the second peak's search takes it (1 when 0:
 *  only the peak's own cell is too close). */
static inline int64_t hl_peak_sep2(int32_t sep_mm)
{
    return sep_mm > 0 ? (int64_t)sep_mm * sep_mm : 1;
}

/**
 * The cells of a row @p dy rows from the peak's that are too close to it for the second
 * peak: those with |ix - cx| <= the returned value, where (ix - cx)^2 cell2 + dy^2 cell2
 * < sep2 (@p cell2 the cell's side squared, @p sep2 hl_peak_sep2's); -1 when none is.
 */
int32_t hl_peak_reach(int64_t cell2, int64_t sep2, int32_t dy);

/**
 * Offset of the vertex of the parabola through (-1, l), (0, c), (1, r), in units of
 * @p step (so within +-step/2 when c is the largest), rounded to nearest.
 */
int32_t hl_peak_offset(uint32_t l, uint32_t c, uint32_t r, int32_t step);

#endif
