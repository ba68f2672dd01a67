/*
 * edt.h (private to src/robot) - the costmap's Euclidean distance transform (edt.c).
 */
#ifndef HOUGHLOC_ROBOT_EDT_H
#define HOUGHLOC_ROBOT_EDT_H

#include <stdint.h>

/* The column pass over a grid of w x h cell bytes (HL_PLAN_CELL_*): @p dist = rows to the
 * nearest cell, in the same column, with an obstacle in its own or a neighbouring column,
 * capped at @p cap. */
void hl_edt_columns(const uint8_t *cells, uint8_t *dist, int32_t w, int32_t h, uint8_t cap);

/* The row pass for one row of w cells: @p d its column distances, @p out its cell bytes,
 * each non-obstacle cell set to lut[squared distance] (0 at lut_n or beyond); columns at
 * @p band are left out. @p s and @p t: w int32_t each of scratch (the envelope). */
void hl_edt_row(const uint8_t *d, uint8_t *out, int32_t w, int32_t band, const uint8_t *lut,
                uint32_t lut_n, int32_t *s, int32_t *t);

#endif
