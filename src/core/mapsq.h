/*
 * mapsq.h (private) - which map slots hold a vector of a given place and side: the
 * index behind the map's density bound (map.h, hl_map_params_t).
 *
 * A "place" is a square of square_mm and an eighth of a turn of normals (the side the
 * surface was seen from). Slots are chained per hash bucket in ascending slot order, so
 * that "the r-th vector of this place" depends only on the vectors array: a map saved
 * and restored chooses exactly as the one that kept running. Buckets are a power of
 * two, at least twice the capacity (placehash.h), so chains are short. Memory comes from
 * hl_mapsq_init only.
 */
#ifndef HOUGHLOC_CORE_MAPSQ_H
#define HOUGHLOC_CORE_MAPSQ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "floordiv.h"
#include "houghloc-internal/map.h"

typedef struct hl_mapsq {
    int32_t square_mm;
    hl_floordiv_t square;   /* division by square_mm */
    uint32_t mask;          /* buckets - 1 */
    uint32_t *head;         /* [buckets] first slot of each chain, or UINT32_MAX */
    uint32_t *next;         /* [capacity] next slot in the chain, or UINT32_MAX */
    uint64_t *key;          /* [capacity] each linked slot's place (square and side) */
} hl_mapsq_t;

/** @return false when memory is short (hl_mapsq_free releases what was allocated). */
bool hl_mapsq_init(hl_mapsq_t *q, uint32_t capacity, int32_t square_mm);
void hl_mapsq_free(hl_mapsq_t *q);
size_t hl_mapsq_mem_bytes(const hl_mapsq_t *q, uint32_t capacity);

/** Empties the index, then indexes slots 0 .. n - 1 of @p v. */
void hl_mapsq_rebuild(hl_mapsq_t *q, const hl_vector_t *v, uint32_t n);
/** Indexes slot @p slot, holding @p v[slot]. */
void hl_mapsq_link(hl_mapsq_t *q, const hl_vector_t *v, uint32_t slot);
/** Removes slot @p slot from the index (the place it was linked with). */
void hl_mapsq_unlink(hl_mapsq_t *q, uint32_t slot);
/** How many indexed slots hold a vector of the place of @p x. */
uint32_t hl_mapsq_count(const hl_mapsq_t *q, const hl_vector_t *x);
/** The slot of the @p r-th (from 0, in slot order) vector of the place of @p x;
 *  r < hl_mapsq_count. */
uint32_t hl_mapsq_nth(const hl_mapsq_t *q, const hl_vector_t *x, uint32_t r);

#endif
