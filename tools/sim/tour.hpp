// tour.hpp - a space-filling tour over the floor-tile grid (paper, section 7).
//
// The paper sorted its sounding positions "into a space-filling order, simulating the
// path of a robot controlled by a planner that grows its map slowly by pushing the
// envelope of the well-mapped area". Here the stops are the reachable grid points with
// enough clearance; from the start the robot always steps to the unvisited neighbour
// nearest the start, so the visited region grows outward as a compact blob. At a dead
// end it drives back through visited points (without sounding) to the nearest unvisited
// one.
#ifndef HLSIM_TOUR_HPP
#define HLSIM_TOUR_HPP

#include <vector>

#include "world.hpp"

namespace hlsim {

/** The lab tour (logs/tour.lcmlog): floor-tile grid, clearance, and the start in the
 *  dense north-west corner. */
constexpr double kTileMm = 609.6;
constexpr double kTourClearanceMm = 350.0;
inline Vec2 lab_tour_start() { return {kTileMm, 11 * kTileMm}; }

struct TourStop {
    Vec2 at;                // where the robot sounds
    std::vector<Vec2> via;  // visited grid points it drives through first (dead ends)
};

/**
 * Grid points k * @p spacing reachable from @p start by 4-neighbour steps whose
 * endpoints have at least @p clearance_mm to every surface and whose straight path
 * keeps 250 mm (the robot's radius plus a margin) from every surface. @p start is snapped to the nearest grid point.
 */
std::vector<Vec2> tour_grid(const World &w, Vec2 start, double spacing, double clearance_mm);

/** The space-filling tour over tour_grid(), beginning at the (snapped) start. */
std::vector<TourStop> tour_order(const World &w, Vec2 start, double spacing,
                                 double clearance_mm);

}  // namespace hlsim
#endif
