/* prior.c - the odometry prior's weights over a vote raster (prior.h). */
#include "prior.h"

#include <math.h>

#include "houghloc-internal/fixed.h"

static uint32_t gaussian_q8(double d, double sigma)
{
    return (uint32_t)lround(256.0 * exp(-0.5 * d * d / (sigma * sigma)));
}

void hl_prior_weights(const hl_loc_surface_t *s, hl_pose_t predicted, double sigma_mm,
                      double sigma_theta, uint32_t *wx, uint32_t *wy, uint32_t *wt)
{
    for (int32_t i = 0; i < s->nx; i++)
        wx[i] = gaussian_q8(s->x0_mm + (i + 0.5) * s->cell_mm - predicted.x_mm, sigma_mm);
    for (int32_t i = 0; i < s->ny; i++)
        wy[i] = gaussian_q8(s->y0_mm + (i + 0.5) * s->cell_mm - predicted.y_mm, sigma_mm);
    for (int32_t i = 0; i < s->nt; i++)
        wt[i] = gaussian_q8(hl_bam_diff((hl_bam_t)(s->theta0 + i * s->theta_step),
                                        predicted.theta), sigma_theta);
}
