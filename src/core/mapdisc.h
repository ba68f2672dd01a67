/*
 * mapdisc.h (private) - the map slots near a point: the index behind the round places of
 * the map's density bound (map.h, hl_map_params_t round_places) and its crowding cull.
 *
 * Slots are chained by square (side twice the density bound's radius, so that a disc of
 * that radius reaches four squares at most), each link carrying the copy of its vector's
 * position and normal that the search tests: one record read a link, where an index
 * holding slot numbers alone reads the map's vectors as well. A search returns the
 * lowest slots found, ascending, so that "the r-th vector near this one" depends only on
 * the vectors array and not on the order of the chains: a map saved and restored
 * chooses exactly as the one that kept running. Memory comes from hl_mapdisc_init only.
 */
#ifndef HOUGHLOC_CORE_MAPDISC_H
#define HOUGHLOC_CORE_MAPDISC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "floordiv.h"
#include "houghloc-internal/map.h"

typedef struct hl_mapdisc_link {
    uint32_t next;          /* the next slot of the chain, or UINT32_MAX */
    hl_mm_t x_mm, y_mm;     /* the slot's vector, as the search tests it */
    hl_bam_t normal;
} hl_mapdisc_link_t;

typedef struct hl_mapdisc {
    hl_floordiv_t square;   /* division by the square's side */
    uint32_t mask;          /* buckets - 1 */
    uint32_t *head;         /* [buckets] first slot of each chain, or UINT32_MAX */
    hl_mapdisc_link_t *link;    /* [capacity] */
    uint32_t *prev;         /* [capacity] the slot before each in its chain, or UINT32_MAX
                               at the head: a slot leaves its chain without a walk */
} hl_mapdisc_t;

/** Squares @p square_mm wide. @return false when memory is short (hl_mapdisc_free
 *  releases what was allocated). */
bool hl_mapdisc_init(hl_mapdisc_t *d, uint32_t capacity, int32_t square_mm);
void hl_mapdisc_free(hl_mapdisc_t *d);
size_t hl_mapdisc_mem_bytes(const hl_mapdisc_t *d, uint32_t capacity);

/** Empties the index, then indexes slots 0 .. n - 1 of @p v. */
void hl_mapdisc_rebuild(hl_mapdisc_t *d, const hl_vector_t *v, uint32_t n);
/** Indexes slot @p slot, holding @p v. */
void hl_mapdisc_link(hl_mapdisc_t *d, const hl_vector_t *v, uint32_t slot);
/** Removes slot @p slot from the index. */
void hl_mapdisc_unlink(hl_mapdisc_t *d, uint32_t slot);
/** The lowest slots (ascending, at most @p max) of the indexed vectors within @p radius of
 *  @p x whose normals lie within @p gate of its; @p radius below two squares (a disc of
 *  it reaches 4 x 4 squares at most: the density bound's radius is half a square, the
 *  crowding cull's one and a half). @return how many. */
uint32_t hl_mapdisc_near(const hl_mapdisc_t *d, const hl_vector_t *x, int32_t radius,
                         int32_t gate, uint32_t *out, uint32_t max);

#endif
