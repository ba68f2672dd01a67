/*
 * flank.h (internal) - the surface normal of a reading on a wall's flank, from the ring's
 * geometry (an improvement on the paper, for a ring whose cones overlap).
 *
 * A reading is the nearest surface anywhere in its cone. Seen from the side, a wall is
 * nearest at the cone's edge towards the wall's foot, and its surface there is not square
 * to the beam: the paper's tangent (the normal along the beam, reversed) is off by the
 * angle of incidence. On the pseudo-sonar ring of five real buildings (22-degree cones
 * every 2.8 degrees) that puts the median reading's normal 30-42 degrees from the wall's,
 * and half or more of them more than 30 degrees off, beyond the localizer's normal gate, while the
 * echo's place is good to a degree (docs/results/real-buildings.md, "Where the sonar's
 * error goes").
 *
 * The ring says which readings are on a flank: the range grows on one side of the reading
 * and falls on the other (within FLAT_MM a neighbour's range, the reading is on a plateau,
 * a region of constant depth, and stays square to its beam). On a flank the echo lies at
 * the cone's edge on the falling side, and the wall runs through it and the echo of the
 * next reading up the flank, at that reading's edge: the normal is that line's.
 */
#ifndef HOUGHLOC_INTERNAL_FLANK_H
#define HOUGHLOC_INTERNAL_FLANK_H

#include <stdint.h>

#include "houghloc-internal/echo.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Ranges within this of each other are one plateau: the ring's ranges step in 10 mm. */
#define HL_FLANK_FLAT_MM 15

/**
 * Sets the flank readings of @p out (the echo-corrected copy of @p in) to their edge
 * bearings and wall normals. @p order holds the @p n valid readings' indices in bearing
 * order (low 16 bits, as echo.c sorts them); two readings are neighbours when their
 * bearings are at most half the half beam apart. A reading whose line would be seen
 * within 5 degrees of edge-on keeps the tilt it had.
 */
void hl_flank_normals(const hl_echo_params_t *p, const hl_scan_t *in, const uint32_t *order,
                      uint32_t n, hl_scan_t *out);

#ifdef __cplusplus
}
#endif

#endif
