// layout.hpp - where the experiments put the robot in a world: Table 1's positions drawn
// per seed on the open floor's tile intersections, and the orientation square and tour
// start the world file declares (docs/manual/houghloc-sim.md, "Data sets").
#ifndef HLSIM_LAYOUT_HPP
#define HLSIM_LAYOUT_HPP

#include <string>
#include <vector>

#include "rng.hpp"
#include "world.hpp"

namespace hlsim {

/** Sounding positions and the orientation square keep this much from every surface. */
constexpr double kPositionClearanceMm = 500.0;

/** The tile intersections inside the world's `open` rectangles at least
 *  kPositionClearanceMm from every surface, west to east, then south to north. */
std::vector<Vec2> open_intersections(const World &w);

/**
 * @p count positions packed as the paper's were (its Figure 2): a random first one of
 * open_intersections(), then each next drawn at random among the free intersections
 * nearest those drawn (their 8 neighbours when any is free); each faces one of the four
 * tile directions at random; named P01, P02, ... in draw order.
 * @return false with one line in @p err when the world declares no `open` floor or it
 * holds fewer than @p count such intersections.
 */
bool draw_positions(const World &w, int count, Rng &rng, std::vector<Position> *out,
                    std::string *err);

/**
 * The checks hl-sim-logs makes before writing anything: the world is closed around
 * every place the robot will be, declares the orientation square and the tour start,
 * and the square's seven positions keep their clearance. @return false with one line.
 */
bool check_layout(const World &w, const std::vector<Position> &positions, std::string *err);

/** The orientation test's square: its south-west corner and side. */
constexpr double kOrientationSideMm = 1500.0;

}  // namespace hlsim
#endif
