/*
 * tiles.h (private) - the sparse path of a large vote raster (localize.c): the blur and
 * the peak search over the tiles near votes alone, and of those only the ones that can
 * hold the peaks.
 *
 * Why. A search over a whole building's map votes into a raster of millions of cells,
 * and its votes land in few of them (freiburg-101's paper mode: 5-7 % of 10-14 million
 * cells, in 35-65 % of the 32 x 16-cell tiles), while clearing, blurring and searching
 * the whole raster cost a pass over every cell each, several times the raster's size in
 * memory traffic. What the search needs of the blurred raster is its highest cell, the
 * highest one far enough from it, and a few cells beside the first.
 *
 * How. The vote loop keeps, for each tile (TILE_W x TILE_H cells of xy, through every
 * slice), the most votes a cell of it holds (hl_tiles_note). The blurred raster is zero
 * wherever no vote lies within the kernels' reach (each pass sums taps times inputs, and
 * (0 + 128) >> 8 is 0), and nowhere above 256 times the most votes of a cell within reach
 * (the taps are weights summing to 256 and each rounded pass keeps the bound, blur.h): so
 * a tile within reach of votes has a bound, the other tiles are zero. The search blurs
 * tiles from the highest bound down (hl_blur3_box: hl_blur3's integers, in small buffers
 * that stay in cache), each into a block of its own in a store, and stops where the
 * bounds fall below what it has found: the peak and second peak of hl_peak_find (no
 * prior), ties included. A cell read later (hl_tiles_cell) or the whole surface
 * (hl_tiles_lay_out) blurs what it needs first.
 *
 * The vote raster stays zero outside what a run wrote: the next run clears the tiles
 * this one voted into (hl_tiles_clear_votes) instead of the whole raster.
 *
 * Memory comes from hl_tiles_init only.
 */
#ifndef HOUGHLOC_CORE_TILES_H
#define HOUGHLOC_CORE_TILES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "blur.h"
#include "peak.h"

#define HL_TILE_W_SHIFT 5
#define HL_TILE_H_SHIFT 4
#define HL_TILE_W (1 << HL_TILE_W_SHIFT)
#define HL_TILE_H (1 << HL_TILE_H_SHIFT)

typedef struct hl_tiles {
    uint32_t capacity;      /* tiles of the largest raster */
    int32_t max_nt;
    /* the raster of the last hl_tiles_begin, and what hl_tiles_search blurs */
    int32_t nx, ny, nt, ntx, nty;
    const uint16_t *votes;
    const hl_kernel_t *kx, *ky, *kt;
    uint32_t *store;

    uint16_t *most;         /* [capacity] per tile: the most votes of a cell (the vote loop's
                               notes); zero between runs */
    uint32_t *voted;        /* [capacity] the tiles that had votes, nvoted of them */
    uint16_t *voted_most;   /* [capacity] ... and their most votes */
    uint32_t nvoted;
    /* the tiles within the kernels' reach of votes, in index order, nout of them */
    uint32_t *out;          /* [capacity] tile index */
    uint32_t *bound;        /* [capacity] no blurred cell of it is above this */
    size_t *at;             /* [capacity] where its block is in the store: its cells
                               [it][iy - y0][ix - x0], w x h x nt of them */
    uint32_t *max;          /* [capacity] its largest blurred value, once blurred */
    uint8_t *done;          /* [capacity] blurred */
    uint32_t *order;        /* [capacity] positions in out[], by bound, highest first */
    uint32_t nout;
    uint32_t *scratch;      /* hl_blur3_box's */
} hl_tiles_t;

/** Allocates for rasters of at most @p max_cells cells, @p max_side cells a side and
 *  @p max_nt slices. @return false when memory is short (hl_tiles_free releases what
 *  was allocated). */
bool hl_tiles_init(hl_tiles_t *t, uint64_t max_cells, int64_t max_side, int32_t max_nt);
void hl_tiles_free(hl_tiles_t *t);
size_t hl_tiles_mem_bytes(const hl_tiles_t *t);

/** Whether a raster of @p nx x @p ny x @p nt fits what hl_tiles_init allocated. */
bool hl_tiles_fit(const hl_tiles_t *t, int32_t nx, int32_t ny, int32_t nt);

/** Starts a raster (hl_tiles_fit must hold, and the voted tiles must have been cleared):
 *  the vote loop then notes every cell it votes into (hl_tiles_note). */
void hl_tiles_begin(hl_tiles_t *t, int32_t nx, int32_t ny, int32_t nt);

/** Notes that cell (ix, iy) of some slice now holds @p votes, in @p most (the tiles'
 *  `most`, whose tiles are @p ntx a row). */
static inline void hl_tiles_note(uint16_t *most, uint32_t ntx, uint32_t ix, uint32_t iy,
                                 uint16_t votes)
{
    uint16_t *m = most + (iy >> HL_TILE_H_SHIFT) * ntx + (ix >> HL_TILE_W_SHIFT);
    *m = votes > *m ? votes : *m;
}

/** Lists the tiles noted as voted and clears the notes (after the vote loop, always). */
void hl_tiles_take_votes(hl_tiles_t *t);

/**
 * hl_peak_find (no prior weights) over hl_blur3's blur of @p votes with the kernels
 * given, blurring into @p store (nx * ny * nt cells) only the tiles it needs. The
 * arguments must stay in place until the next hl_tiles_begin (hl_tiles_cell and
 * hl_tiles_lay_out blur more of them). @return 0 if every blurred cell is 0.
 */
int hl_tiles_search(hl_tiles_t *t, const uint16_t *votes, const hl_kernel_t *kx,
                    const hl_kernel_t *ky, const hl_kernel_t *kt, uint32_t *store,
                    int32_t cell_mm, int32_t sep_mm, hl_peak_t *pk);

/** The blurred cell (ix, iy, it) of the last search. */
uint32_t hl_tiles_cell(hl_tiles_t *t, int32_t ix, int32_t iy, int32_t it);

/** Lays the last search's blurred raster out in @p raster ([nt][ny][nx], hl_blur3's
 *  layout), which must be zero. */
void hl_tiles_lay_out(hl_tiles_t *t, uint32_t *raster);

/** Zeroes the votes of the tiles listed as voted (in the raster begun last), and forgets
 *  them. */
void hl_tiles_clear_votes(hl_tiles_t *t, uint16_t *votes);

#endif
