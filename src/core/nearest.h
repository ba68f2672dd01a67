/*
 * nearest.h (private) - the polish's matching (refine.c): for a reading at a world point,
 * the nearest map vector within match_mm whose surface faces the robot, and each map
 * vector's surface normal from its neighbours.
 *
 * Speed (docs/results/performance.md). The results are those of the plain method:
 * estimate every map vector's surface normal from its neighbours, then for each reading
 * scan the 3 x 3 hash cells of normal_radius_mm around it for the nearest facing vector. What makes it
 * cheaper changes not a bit of them:
 *  - normals are computed lazily, only for the vectors a reading comes near, and kept
 *    for the rest of the run; each from exactly the plain method's neighbours, in sums
 *    of integers (exact in any order), found in the cells the radius reaches;
 *  - each reading keeps a list of the map vectors within reach_mm (match_mm and a
 *    margin) of where it lay, ring by ring outwards, and walks it only as far as a
 *    nearer vector could lie while it moves less than the margin: on a laser's dense
 *    map some 3 vectors a reading in an iteration rather than 47 within match_mm and
 *    more in the cells, and a normal needed mostly for the nearest alone; a reading with
 *    more than a list holds around it searches the cells as they lie;
 *  - the order of the candidates matters only between candidates at exactly the same
 *    distance: there the plain scan's order is recomputed (plain_first) and decides.
 *
 * Memory comes from hl_nearest_init only. A run (hl_nearest_begin) is one polish: one
 * map, the normals and the readings' lists kept through its iterations.
 */
#ifndef HOUGHLOC_CORE_NEAREST_H
#define HOUGHLOC_CORE_NEAREST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cellhash.h"
#include "houghloc-internal/refine.h"

#define HL_NEAREST_RINGS 32     /* a list's order: rings of reach_mm / RINGS */

typedef struct hl_nearest {
    hl_mm_t normal_radius_mm, match_mm;
    uint32_t capacity;      /* map vectors */
    hl_cellhash_t near;     /* the map by cells of at least reach_mm */
    hl_cellhash_t plain;    /* the plain method's cells (its order breaks ties): never
                               built, only its cell size and bucket count are used */
    double *nx, *ny;        /* [capacity] unit surface normal, towards the sensors ... */
    uint32_t *stamp;        /* [capacity] ... valid when stamp == run */
    uint32_t run;
    struct near_list {      /* [HL_SCAN_MAX_READINGS] each reading's map vectors ... */
        double ax, ay;      /* ... within reach_mm of this world point (its anchor), */
        uint32_t first, count;  /* pool[first ...]; count > LIST_MAX: no list this run */
        uint32_t room;      /* entries pool[first ...] holds */
        uint32_t run;       /* valid when run == the matcher's run */
    } *lists;
    struct near_vector {    /* a map vector near an anchor */
        int32_t x, y;
        uint32_t j;         /* map index */
        uint32_t ring;      /* the ring round the anchor it lies in */
    } *pool, *scratch;      /* [pool_size] the lists; [capacity] */
    uint32_t pool_size, pool_used;  /* the lists' room, and how much a run has taken */
    double ring_mm[HL_NEAREST_RINGS];   /* each ring's inner edge: a vector in it is at
                                           least so far */
} hl_nearest_t;

/** For maps of up to @p capacity vectors, with @p p's normal radius and match distance
 *  (valid parameters). @return false when memory is short; hl_nearest_free releases
 *  what was allocated either way. */
bool hl_nearest_init(hl_nearest_t *n, const hl_refine_params_t *p, uint32_t capacity);
void hl_nearest_free(hl_nearest_t *n);
size_t hl_nearest_mem_bytes(const hl_nearest_t *n);

/** A new run against map[0 .. count - 1] (1 <= count <= capacity): every normal and
 *  list of the run before is stale. */
void hl_nearest_begin(hl_nearest_t *n, const hl_vector_t *map, uint32_t count);

/** The nearest map vector closer than match_mm to reading @p i's world point (wx, wy)
 *  (i < HL_SCAN_MAX_READINGS) whose surface faces the robot at (sx, sy); -1 if none. Of
 *  several at the same distance, the one the plain scan meets first. Its normal is then
 *  n->nx[j], n->ny[j]. */
int32_t hl_nearest_facing(hl_nearest_t *n, const hl_vector_t *map, uint32_t i, double wx,
                          double wy, double sx, double sy);

#endif
