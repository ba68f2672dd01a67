/*
 * map.h - the map of tangent vectors (paper, sections 2 and 4), as a program reads a
 * tracker's map (hl_slam_map, slam.h).
 *
 * A tangent vector is a surface point seen by sonar with the surface normal pointing
 * back toward the sensor that saw it; the sensor stood range_mm away along the normal.
 * A tracker's map holds at most its capacity (slam.map_capacity, params.h) and culls
 * itself as it grows; the tracker owns it, and the pointers below stay valid until the
 * tracker changes the map (its next hl_slam_update, reset, restore or destroy).
 */
#ifndef HOUGHLOC_MAP_H
#define HOUGHLOC_MAP_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/count.h"
#include "houghloc/export.h"
#include "houghloc/rng.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_MAP_MAX_CAPACITY (1u << 20)

typedef struct hl_vector {
    hl_mm_t x_mm;       /* surface point, |x| <= HL_COORD_MAX_MM */
    hl_mm_t y_mm;
    hl_bam_t normal;    /* points from the surface back to the sensor */
    uint16_t range_mm;  /* sensing distance, 0..HL_RANGE_MAX_MM */
} hl_vector_t;

/* A map: owned by its tracker (or made by the core's internal modules). */
typedef struct hl_map hl_map_t;

/** Vectors held now, 0..hl_map_capacity. */
HL_API uint32_t hl_map_count(const hl_map_t *map);
/** The most vectors the map holds (the tracker's slam.map_capacity). */
HL_API uint32_t hl_map_capacity(const hl_map_t *map);
/** Increments on every change; stops at HL_COUNT_MAX (count.h), never wraps. */
HL_API uint64_t hl_map_version(const hl_map_t *map);
/** The hl_map_count vectors, valid until the next change to the map (the array is the
 *  map's: do not free it). */
HL_API const hl_vector_t *hl_map_vectors(const hl_map_t *map);

/** Checks one vector's fields against their ranges (coordinates within
 *  HL_COORD_MAX_MM, range within HL_RANGE_MAX_MM): what hl_slam_restore accepts. */
HL_API bool hl_vector_in_range(const hl_vector_t *v);
/** The sensor position a vector was seen from (surface point + range along normal), mm. */
HL_API void hl_vector_origin(const hl_vector_t *v, hl_mm_t *x_mm, hl_mm_t *y_mm);

#ifdef __cplusplus
}
#endif
#endif
