// sonar.hpp - the physics of one sonar ping (paper, section 4).
//
// A ping returns the first echo within the beam cone, so it blurs objects across the
// cone's width; surfaces struck beyond a critical incidence angle reflect the sound
// away (specular loss); a few readings take a longer bounced path; ranges are noisy;
// and the robot's own cables and lost echoes give garbage raw values. The result is a
// raw reading, through the inverse of a simulated linear calibration, as the robot's
// sonar board would report it.
#ifndef HLSIM_SONAR_HPP
#define HLSIM_SONAR_HPP

#include <cstdint>

#include "houghloc/calib.h"
#include "rng.hpp"
#include "world.hpp"

namespace hlsim {

/** Every sonar effect the simulator models; the defaults are the data sets' values. */
struct SonarParams {
    double cone_deg = 22.0;          // full width of the beam
    double ray_step_deg = 0.5;       // spacing of the rays that sample the cone
    double critical_deg = 40.0;      // no echo when incidence exceeds this
    double max_range_mm = 8000.0;    // no echo beyond this (listening window)
    double noise_sigma_mm = 10.0;    // Gaussian range noise: sigma = this ...
    double noise_frac = 0.01;        // ... plus this fraction of the range
    double p_multipath = 0.05;       // probability of a longer, bounced path
    double multipath_min_mm = 300.0; // the bounce adds uniform [min, max) mm
    double multipath_max_mm = 2000.0;
    double p_cable = 0.03;           // probability of a cable echo (low garbage raw)
    int cable_raw_min = 20;          // cable echoes are uniform raw [min, max]
    int cable_raw_max = 199;
    double p_dropout = 0.03;         // probability of a lost echo (sentinel raw)
    uint16_t sentinel_raw = 16384;   // the sonar board's "no echo received"
    hl_calib_t calib;                // simulated calibration: raw = inverse(range)

    SonarParams()
    {
        hl_calib_default(&calib);
        calib.gain_q16 = 70124;   // 1.07 mm per raw unit
        calib.offset_mm = -35;
    }
};

/** Why a reading has the value it has (for statistics and tests; not in the logs). */
enum class Echo : uint8_t {
    Surface,    // first echo within the cone, with range noise
    Multipath,  // first echo plus a bounced detour
    Cable,      // robot's own cables: low garbage raw
    Dropout,    // echo lost at random: sentinel
    None,       // nothing echoes within the cone and max range: sentinel
};

struct SonarReading {
    uint16_t raw = 0;
    Echo kind = Echo::None;
    double true_mm = 0.0;  // noiseless first-echo distance (0 when none)
};

/**
 * The noiseless first echo: the shortest distance to a surface point seen within the
 * cone about @p axis (radians) at incidence <= the critical angle.
 * @return the distance in mm, or a negative value when nothing echoes.
 */
double sonar_first_echo(const World &w, const SonarParams &p, Vec2 origin, double axis,
                        Hit *hit = nullptr);

/** One ping with every effect of @p p, drawing randomness from @p rng. */
SonarReading sonar_ping(const World &w, const SonarParams &p, Vec2 origin, double axis,
                        Rng &rng);

}  // namespace hlsim
#endif
