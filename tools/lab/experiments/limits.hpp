// limits.hpp - what the simulated sonar allows at best: two "oracle" localizers that no
// robot has, because they use the simulator's own world and physics.
//
//  1. The exact model: each sounding is localized (x, y, heading, from 60 mm and 1.7 deg
//     off its true pose) by comparing every reading with the first echo the simulator's
//     sonar would return from the true world. What remains is the sensor's noise, its
//     body-rotation error and the ring's sampling: a floor no map made of sonar can beat.
//  2. Perfect echo bearings: every reading moved to the bearing its echo really came from
//     (found by casting the simulator's cone into the true world from the true pose),
//     then the improved mode's own experiments, unchanged, with echo estimation off. The
//     gap to the improved mode's figures is what better echo-bearing estimation could
//     still win. (The logs do not record each body step's rotation error, so this also
//     removes it: optimistic by a few tenths of a degree in heading.)
#ifndef HLEXP_LIMITS_HPP
#define HLEXP_LIMITS_HPP

#include <string>
#include <vector>

#include "experiment.hpp"

namespace hlsim {
class World;
}

namespace hlexp {

struct LimitsRow {
    std::string what;           // which oracle and experiment
    int trials;
    int wild;                   // error above 0.5 m
    double pos_mean_mm;         // mean position error of the non-wild trials (NaN: none)
    double heading_mean_deg, heading_sigma_deg;   // NaN when the heading was given
};

struct LimitsInput {
    const Soundings *lab = nullptr;          // lab28
    const Soundings *orientation = nullptr;
    const Soundings *tour = nullptr;
};

std::vector<LimitsRow> run_limits(const LimitsInput &in, const hlsim::World &world,
                                  const Mode &improved, const Context &ctx);

}  // namespace hlexp
#endif
