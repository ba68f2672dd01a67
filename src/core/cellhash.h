/*
 * cellhash.h (private) - map vectors hashed by the square cell they lie in, for the
 * neighbour searches of refine.c.
 *
 * Cell (cx, cy) = (floor(x / cell_mm), floor(y / cell_mm)); cells share buckets
 * (a power of two, at least twice the capacity), so a search visits the buckets of the
 * cells it wants and checks distances. Stored compactly: the vectors of bucket b are
 * entries start[b] .. start[b + 1] - 1, highest map index first (the order in which
 * refine.c's earlier head-inserted chains listed them, which its results depend on).
 * Memory comes from hl_cellhash_init only.
 */
#ifndef HOUGHLOC_CORE_CELLHASH_H
#define HOUGHLOC_CORE_CELLHASH_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/map.h"

typedef struct hl_cellhash {
    int32_t cell_mm;
    uint32_t capacity;      /* map vectors */
    uint32_t buckets;
    uint32_t *start;        /* [buckets + 1] */
    int32_t *x, *y;         /* [capacity] entries: position, normal, map index */
    hl_bam_t *normal;
    uint32_t *index;
    uint32_t *bucket;       /* [capacity] scratch of hl_cellhash_build */
} hl_cellhash_t;

/** Allocates for @p capacity vectors in cells of @p cell_mm (>= 1). @return false when
 *  memory is short; hl_cellhash_free releases what was allocated either way. */
bool hl_cellhash_init(hl_cellhash_t *h, int32_t cell_mm, uint32_t capacity);
void hl_cellhash_free(hl_cellhash_t *h);
size_t hl_cellhash_mem_bytes(const hl_cellhash_t *h);

/** Hashes map[0 .. n - 1] (n <= capacity), replacing what was there. */
void hl_cellhash_build(hl_cellhash_t *h, const hl_vector_t *map, uint32_t n);

/** The cell coordinate of @p v (finite, |v / cell_mm| < 2^31). */
static inline int32_t hl_cellhash_cell(const hl_cellhash_t *h, double v)
{
    return (int32_t)floor(v / h->cell_mm);
}

static inline uint32_t hl_cellhash_bucket(const hl_cellhash_t *h, int32_t cx, int32_t cy)
{
    uint32_t k = (uint32_t)cx * 73856093u ^ (uint32_t)cy * 19349663u;
    return k & (h->buckets - 1);
}

static inline uint32_t hl_cellhash_bucket_of(const hl_cellhash_t *h, double x, double y)
{
    return hl_cellhash_bucket(h, hl_cellhash_cell(h, x), hl_cellhash_cell(h, y));
}

#endif
