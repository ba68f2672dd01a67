/**
 * @file walls.h
 * @brief Square walls: which way a building's walls run, from surface normals.
 *
 * Most buildings are drawn with their walls square to one another. Folded four times
 * round (a wall and the walls square to it alike), the normals of what a scan or a map
 * sees point along one axis; the folded normals' mean resultant length R says how
 * clearly (1: every normal on the axis; about 0: a uniform spread, corners and clutter).
 * The map's axis is a heading reference that does not drift: a scan whose wall normals,
 * at the heading tracking gave it, lie a little off the map's axis was turned by that
 * much (slam.wall_gain; loop closure's square walls use a scan's own axis instead).
 */
#ifndef HOUGHLOC_INTERNAL_WALLS_H
#define HOUGHLOC_INTERNAL_WALLS_H

#include <stdint.h>

#include "houghloc/map.h"
#include "houghloc/scan.h"

/* Tracking's square walls (slam.wall_gain): the map and the scan must each hold at least
 * HL_WALLS_MIN_READINGS normals with an R of HL_WALLS_MIN_R or more, and the scan that
 * many within HL_WALLS_WINDOW_DEG of the map's axis. Normals farther off are other
 * surfaces (a wall not square to the building, a corner, clutter, a sonar reading's
 * normal gone wrong) and are left out. */
#define HL_WALLS_MIN_READINGS 8
#define HL_WALLS_MIN_R 0.2
#define HL_WALLS_WINDOW_DEG 10

/** The walls' axis of a set of normals: radians in (-pi/4, pi/4], R and how many. */
typedef struct hl_walls {
    double axis;
    double r;
    uint32_t n;
} hl_walls_t;

/** The axis of the valid readings of @p scan in its robot's frame. */
hl_walls_t hl_walls_of_scan(const hl_scan_t *scan);

/** The axis of @p count map vectors in the map frame. */
hl_walls_t hl_walls_of_vectors(const hl_vector_t *v, uint32_t count);

/** How far the normals of @p scan at @p heading lie from @p axis, folded: the mean over
 *  those within @p window of it (radians), their number in @p inliers (0: the mean is 0). */
double hl_walls_offset(const hl_scan_t *scan, double heading, double axis, double window,
                       uint32_t *inliers);

#endif
