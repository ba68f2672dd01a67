// laser.hpp - a thin-beam laser range finder (a SICK LMS-type scanner): every beam the
// distance to the first surface on its axis, with Gaussian range noise and an occasional
// lost return. The data sets' laser log (tools/lab/sim-logs) is made of these scans.
#ifndef HLSIM_LASER_HPP
#define HLSIM_LASER_HPP

#include <cstdint>
#include <vector>

#include "rng.hpp"
#include "world.hpp"

namespace hlsim {

struct LaserParams {
    int beams = 181;                 // evenly over the field of view, both edges included
    double fov_deg = 180.0;          // centred on the robot's heading
    double max_range_mm = 30000.0;   // no return beyond this
    double noise_sigma_mm = 10.0;    // Gaussian range noise
    double p_dropout = 0.01;         // a lost return (black or glancing surface)
};

/** One scan: the bearing of beam i is -fov/2 + i * fov / (beams - 1), robot frame. */
struct LaserScan {
    int64_t utime = 0;
    Pose odom;                       // what the odometry says at the scan
    Pose truth;                      // where the scanner really is
    std::vector<int32_t> range_mm;   // one per beam; -1: no return
};

/** The bearing of beam @p i in degrees, robot frame (counter-clockwise from ahead). */
double laser_bearing_deg(const LaserParams &p, int i);

/** Scans from the true pose @p truth, drawing noise and dropouts from @p rng. */
std::vector<int32_t> laser_ranges(const World &w, const LaserParams &p, const Pose &truth,
                                  Rng &rng);

}  // namespace hlsim
#endif
