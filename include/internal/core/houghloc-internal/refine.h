/*
 * refine.h (internal) - polishing a Hough pose by point-to-line alignment (an improvement on the
 * paper, which stops at the best raster cell).
 *
 * The Hough peak is only as sharp as its blurred raster. Starting from it, this module
 * matches each valid reading of the scan to the nearest map vector that faces it and
 * moves the pose to minimise the readings' distances to the local surface lines of their
 * matches (iteratively reweighted least squares, Huber weights). A map vector's surface
 * line runs through it, perpendicular to the principal axis of its neighbours that face
 * the same way; a vector with fewer than three such neighbours keeps its own normal.
 * A refinement that leaves the neighbourhood of the start (max_shift_mm, max_turn) or has
 * too few matches is not used: the Hough pose stands.
 *
 * The map is indexed in a spatial hash built per call; all memory comes from
 * hl_refine_create. Floating point: this runs once per scan, after the integer voting.
 */
#ifndef HOUGHLOC_INTERNAL_REFINE_H
#define HOUGHLOC_INTERNAL_REFINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/map.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fixed (were settings): on freiburg-101 every variant tried (radius, iterations, Huber
 * width, match distance) stayed at 0.054-0.061 m ATE, and the sonar tours agreed. */
#define HL_REFINE_NORMAL_RADIUS_MM 400
#define HL_REFINE_MATCH_MM 150
#define HL_REFINE_HUBER_MM 60
#define HL_REFINE_MAX_SHIFT_MM 250
#define HL_REFINE_MAX_TURN_DEG 3
#define HL_REFINE_ITERATIONS 20
#define HL_REFINE_MIN_MATCHES 12

typedef struct hl_refine_params {
    hl_mm_t normal_radius_mm;   /* neighbours that shape a surface line; default 400 */
    hl_mm_t match_mm;           /* a reading pairs with a map vector this close; default 150 */
    hl_mm_t huber_mm;           /* residuals beyond this weigh less; default 60 */
    hl_mm_t max_shift_mm;       /* refuse a result farther from the start; default 250 */
    hl_bam_t max_turn;          /* refuse a result turned more than this; default 3 deg */
    uint16_t iterations;        /* at most; default 20 */
    uint16_t min_matches;       /* fewer matched readings: refuse; default 12 */
} hl_refine_params_t;

void hl_refine_params_default(hl_refine_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_refine_params_error(const hl_refine_params_t *p);

typedef struct hl_refiner hl_refiner_t;

/** @return NULL on invalid parameters, max_map_vectors of 0, or no memory. */
hl_refiner_t *hl_refine_create(const hl_refine_params_t *p, uint32_t max_map_vectors);
void hl_refine_destroy(hl_refiner_t *r);   /* accepts NULL */
size_t hl_refine_mem_bytes(const hl_refiner_t *r);

/**
 * Refines @p start against @p n map vectors.
 * @param heading  false: keep start's heading and refine x, y only.
 * @param[out] out the refined pose, or @p start when the refinement was refused.
 * @return HL_OK when refined; HL_ERR_EMPTY when refused (too few matches, too far, or a
 *         singular system); HL_ERR_CAPACITY when @p n exceeds max_map_vectors;
 *         HL_ERR_RANGE for a bad scan or pose; HL_ERR_ARG for NULL.
 */
hl_status_t hl_refine_run(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                          const hl_scan_t *scan, hl_pose_t start, bool heading,
                          hl_pose_t *out);

#ifdef __cplusplus
}
#endif
#endif
