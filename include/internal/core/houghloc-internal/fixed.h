/*
 * fixed.h (internal) - polar to cartesian in the core's fixed-point formats
 * (houghloc/fixed.h states the formats, ranges and error bounds): the vote loop's and the
 * map's conversions.
 */
#ifndef HOUGHLOC_INTERNAL_FIXED_H
#define HOUGHLOC_INTERNAL_FIXED_H

#include <stdint.h>

#include "houghloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Cartesian offset of a point at @p range_mm along @p angle, rounded to the millimetre.
 * @param[in] range_mm  0..HL_RANGE_MAX_MM (larger values are clamped).
 */
void hl_polar_to_xy(int32_t range_mm, hl_bam_t angle, int32_t *x_mm, int32_t *y_mm);

/** As hl_polar_to_xy, in Q8 millimetres (1/256 mm), from the Q30 table. */
void hl_polar_to_xy_q8(int32_t range_mm, hl_bam_t angle, int32_t *x_q8, int32_t *y_q8);

#ifdef __cplusplus
}
#endif
#endif
