/* safety.c - the nearest sonar reading in the way ahead (safety.h). */
#include "houghloc/safety.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdlib.h>

/* Whether an echo at @p range_mm somewhere within @p half_beam of @p bearing may lie in the
 * strip of half-width @p radius_mm ahead: the lobe's point nearest to straight ahead
 * decides (the arc's sideways offset grows with the angle from ahead). */
static bool in_the_way(int32_t radius_mm, hl_bam_t half_beam, hl_bam_t bearing,
                       int32_t range_mm)
{
    int32_t off = abs((int32_t)(int16_t)bearing);   /* 0..32768: from ahead, either side */
    int32_t nearest = off - half_beam;
    if (nearest <= 0)
        return true;                         /* the lobe covers straight ahead */
    if (nearest >= 16384)
        return false;                        /* the whole lobe is abeam or behind */
    double a = nearest * (6.283185307179586 / 65536.0);
    return range_mm * sin(a) <= radius_mm;
}

int32_t hl_safety_ahead_mm(const hl_safety_params_t *p, const hl_bam_t *bearing,
                           const int32_t *range_mm, int32_t n, int32_t *which)
{
    if (which)
        *which = -1;
    if (!p || p->radius_mm < 1 || p->radius_mm > 5000 || n < 0 ||
        (n > 0 && (!bearing || !range_mm)))
        return -1;
    int32_t nearest = -1;
    for (int32_t i = 0; i < n; i++) {
        if (range_mm[i] <= 0 || (nearest >= 0 && range_mm[i] >= nearest))
            continue;
        if (in_the_way(p->radius_mm, p->half_beam, bearing[i], range_mm[i])) {
            nearest = range_mm[i];
            if (which)
                *which = i;
        }
    }
    return nearest;
}
