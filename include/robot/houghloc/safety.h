/*
 * safety.h - the way ahead as the sonar hears it, for the safety stop (drive.h).
 *
 * A sonar reading says that something lies at its range somewhere within its transducer's
 * lobe, not where in it. A reading is in the way when some point of its lobe's arc lies
 * ahead of the robot and within the strip its body sweeps driving straight on (no farther
 * to either side than its radius): an echo that may be in the way is taken to be, since
 * braking early costs a few seconds and a collision costs the robot. Transducers are taken
 * to sit at the robot's centre, as the scan takes them (sounder.h).
 *
 * Pure: readings in, a distance out.
 */
#ifndef HOUGHLOC_SAFETY_H
#define HOUGHLOC_SAFETY_H

#include <stdint.h>

#include "houghloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_safety_params {
    int32_t radius_mm;      /* the robot's body: half the width of the swept strip, 1..5000 */
    hl_bam_t half_beam;     /* half the lobe's width (a Polaroid-type transducer: 11 degrees) */
} hl_safety_params_t;

/**
 * The nearest of @p n readings in the way ahead: reading i lies at @p bearing[i] (robot
 * frame, counter-clockwise from ahead) and @p range_mm[i] from the centre (0 or negative:
 * no echo, skipped). @p which (may be NULL) gets that reading's index, -1 for none.
 * @return that reading's range in mm, or -1 when none is in the way (or @p p is NULL or
 *         invalid).
 */
int32_t hl_safety_ahead_mm(const hl_safety_params_t *p, const hl_bam_t *bearing,
                           const int32_t *range_mm, int32_t n, int32_t *which);

#ifdef __cplusplus
}
#endif
#endif
