/*
 * fence.h - the geofence: where destinations may lie (a rectangle or a polygon in the
 * map frame, millimetres). Pure geometry, integers only.
 */
#ifndef HOUGHLOC_FENCE_H
#define HOUGHLOC_FENCE_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/fixed.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_FENCE_MAX_VERTICES 64

typedef struct hl_fence {
    uint32_t n;                             /* 3..HL_FENCE_MAX_VERTICES; a rectangle is 4 */
    hl_mm_t x_mm[HL_FENCE_MAX_VERTICES];    /* within +-HL_COORD_MAX_MM */
    hl_mm_t y_mm[HL_FENCE_MAX_VERTICES];
} hl_fence_t;

/** An axis-aligned rectangle. @return HL_ERR_RANGE unless min < max on both axes and
 *  all within +-HL_COORD_MAX_MM. */
hl_status_t hl_fence_rect(hl_fence_t *f, hl_mm_t min_x, hl_mm_t min_y, hl_mm_t max_x,
                          hl_mm_t max_y);

/**
 * A simple polygon from @p n vertices in order (either winding).
 * @return HL_ERR_RANGE for fewer than 3 or more than HL_FENCE_MAX_VERTICES vertices, a
 *         coordinate out of range, zero area, or edges that cross each other.
 */
hl_status_t hl_fence_polygon(hl_fence_t *f, const hl_mm_t *x_mm, const hl_mm_t *y_mm,
                             uint32_t n);

/** A one-line reason for the last HL_ERR_RANGE of hl_fence_polygon/rect, for messages. */
const char *hl_fence_error(const hl_mm_t *x_mm, const hl_mm_t *y_mm, uint32_t n);

/** @return true when (x, y) is inside the fence or on its border. */
bool hl_fence_contains(const hl_fence_t *f, hl_mm_t x_mm, hl_mm_t y_mm);

#ifdef __cplusplus
}
#endif
#endif
