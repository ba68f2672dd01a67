/* loc_params.h (private) - limits of the localizer's parameters and the raster sizes
 * they imply, shared by loc_params.c and localize.c. */
#ifndef HOUGHLOC_CORE_LOC_PARAMS_H
#define HOUGHLOC_CORE_LOC_PARAMS_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc-internal/localize.h"

#define HL_LOC_MAX_HALF_STEPS 256
#define HL_LOC_MAX_SIDE_MM (1 << 21)    /* keeps the reciprocal cell division exact */
#define HL_LOC_MAX_CELL_MM 1000

/** Heading slices of a search: 2 * theta_half_steps + 1, or 1 with heading known. */
int32_t hl_loc_slices(const hl_loc_params_t *p, bool search_theta);
/** Cells along one side of a local window of half-width @p window_mm. */
int32_t hl_loc_window_cells(const hl_loc_params_t *p, hl_mm_t window_mm);

#endif
