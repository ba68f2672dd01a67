// laser.cpp - the thin-beam laser range finder (laser.hpp).
#include "laser.hpp"

#include <cmath>

namespace hlsim {

double laser_bearing_deg(const LaserParams &p, int i)
{
    return p.beams > 1 ? -p.fov_deg / 2.0 + i * p.fov_deg / (p.beams - 1) : 0.0;
}

std::vector<int32_t> laser_ranges(const World &w, const LaserParams &p, const Pose &truth,
                                  Rng &rng)
{
    std::vector<int32_t> out(static_cast<std::size_t>(p.beams > 0 ? p.beams : 0), -1);
    for (int i = 0; i < p.beams; i++) {
        double axis = truth.theta + deg2rad(laser_bearing_deg(p, i));
        Hit h;
        // Both draws are made for every beam, so one beam's outcome never shifts the
        // random stream of the next.
        double noise = rng.normal(0.0, p.noise_sigma_mm);
        bool lost = rng.uniform() < p.p_dropout;
        if (lost || !w.cast(truth.pos(), Vec2::polar(axis), p.max_range_mm, &h))
            continue;
        double mm = h.dist + noise;
        out[static_cast<std::size_t>(i)] = static_cast<int32_t>(std::lround(mm < 0.0 ? 0.0 : mm));
    }
    return out;
}

}  // namespace hlsim
