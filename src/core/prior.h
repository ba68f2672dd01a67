/*
 * prior.h (private to the core) - the odometry prior's weights over a vote raster
 * (prior.c): the localizer attenuates each cell's votes by them (paper, section 6).
 */
#ifndef HOUGHLOC_CORE_PRIOR_H
#define HOUGHLOC_CORE_PRIOR_H

#include <stdint.h>

#include "houghloc-internal/localize.h"

/* Gaussian weights in Q8 (256 = 1) of each cell centre's distance from @p predicted, per
 * axis: @p wx (s->nx), @p wy (s->ny) with @p sigma_mm, @p wt (s->nt) with @p sigma_theta
 * (binary angle units). */
void hl_prior_weights(const hl_loc_surface_t *s, hl_pose_t predicted, double sigma_mm,
                      double sigma_theta, uint32_t *wx, uint32_t *wy, uint32_t *wt);

#endif
