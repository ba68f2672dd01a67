/*
 * votelone.h (private) - the vote loop of localize.c for a map of lone vectors (no
 * merging, localize.group_mm = 0) without vote_once: every pair votes 1.
 *
 * Why. The paper mode's global search casts two million votes a scan or so, one
 * read-modify-write of a raster cell each, and the general loop (a candidate, then its
 * headings) spends more instructions per vote than memory: a group's weights, a
 * reading's stamps, the context reloaded past the stores.
 *
 * How. One reading's candidates that pass the normal gate under some heading are listed
 * with their slice range (hl_votelone_list). Then heading by heading, a plain loop over
 * the list computes each candidate's cell and its tile (written to be vectorized, no
 * branch: a candidate that does not vote under this heading, or lands outside the
 * raster, gets weight 0 and one of cells 0-3, of tile 0), and a second loop adds the
 * weights and notes the cells in the tiles. The cells are not divided by the cell size
 * vote by vote: a point and an offset are split into quotient and remainder once, and
 * the cell is the quotients' difference less a borrow. Adding 0 to a cell writes back
 * what it held, and noting it leaves its tile's most votes as they were (a bound already
 * noted, or zero), so the raster, its notes and the counts are those of the general
 * loop: a saturating sum of ones and a running maximum do not depend on the order of the
 * votes (tests/core/test_votelone.c).
 *
 * Memory comes from hl_votelone_init only.
 */
#ifndef HOUGHLOC_CORE_VOTELONE_H
#define HOUGHLOC_CORE_VOTELONE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "gate.h"
#include "vgroup.h"

typedef struct hl_votelone {
    uint32_t capacity, n;
    int32_t lo_min, hi_max;  /* the listed candidates' slices */
    /* per group of the map (hl_votelone_prepare): its point, 1/256 mm from the raster
     * origin, as quotient and remainder by the cell in 1/256 mm */
    int32_t *gqx, *grx, *gqy, *gry;
    /* a listed candidate's, and the slices it votes in */
    int32_t *qx, *rx, *qy, *ry;
    int32_t *lo, *hi;
    uint32_t *cell, *tile;  /* one heading's cells and tiles */
    uint32_t *w;            /* ... and weights */
    /* The tiles' notes of every fourth vote but the first, in three lanes of their own
     * (tiles: how many): the notes of a run of votes into one tile, each the greater of
     * the last note and a cell, would otherwise wait on one another. hl_votelone_fold
     * merges them into the tiles' own. */
    uint32_t tiles;
    uint16_t *lane[3];
} hl_votelone_t;

/** The raster and one reading's offsets under each heading (localize.c's vote_ctx). */
typedef struct hl_votelone_raster {
    int32_t nx, ny, nt;
    uint32_t width_q8, height_q8;
    int32_t cell_q8;        /* the cell in 1/256 mm */
    const int32_t *tx, *ty; /* [nt] */
    uint16_t *votes;
    uint16_t *most;         /* the tiles' notes (tiles.h), or NULL */
    uint32_t ntx;
} hl_votelone_raster_t;

/** Allocates for @p capacity groups and, for the sparse path's notes, @p tiles tiles
 *  (0: none). */
bool hl_votelone_init(hl_votelone_t *v, uint32_t capacity, uint32_t tiles);
void hl_votelone_free(hl_votelone_t *v);
size_t hl_votelone_mem_bytes(const hl_votelone_t *v);

/** Starts a reading's list. */
static inline void hl_votelone_clear(hl_votelone_t *v)
{
    v->n = 0;
    v->lo_min = INT32_MAX;
    v->hi_max = -1;
}

/** Splits the @p n groups' points (@p gx, @p gy) by the cell, @p cell_q8 (a run's). */
void hl_votelone_prepare(hl_votelone_t *v, const int32_t *gx, const int32_t *gy, uint32_t n,
                         int32_t cell_q8);

/** Lists group @p k as voting in slices @p lo .. @p hi (lo <= hi). */
static inline void hl_votelone_push(hl_votelone_t *v, uint32_t k, int32_t lo, int32_t hi)
{
    uint32_t i = v->n++;
    v->qx[i] = v->gqx[k];
    v->rx[i] = v->grx[k];
    v->qy[i] = v->gqy[k];
    v->ry[i] = v->gry[k];
    v->lo[i] = lo;
    v->hi[i] = hi;
    v->lo_min = lo < v->lo_min ? lo : v->lo_min;
    v->hi_max = hi > v->hi_max ? hi : v->hi_max;
}

/** Lists the candidate groups @p cand (@p n of them, lone vectors of @p g) that pass
 *  @p gate about the reading's normal @p tn0, adds their pairs to @p pairs and casts
 *  their votes into @p r; @return how many. */
uint32_t hl_votelone_vote(hl_votelone_t *v, const hl_vgroups_t *g, const uint32_t *cand,
                          uint32_t n, const gate_t *gate, uint16_t tn0,
                          const hl_votelone_raster_t *r, uint32_t *pairs);

/** Casts the listed candidates' votes into @p r; @return how many. */
uint32_t hl_votelone_cast(hl_votelone_t *v, const hl_votelone_raster_t *r);

/** Merges the lanes' notes of the first @p n tiles into @p most, and zeroes them (after
 *  the casts into a raster with notes). */
void hl_votelone_fold(hl_votelone_t *v, uint16_t *most, uint32_t n);

#endif
