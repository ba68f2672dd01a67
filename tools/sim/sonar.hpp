// sonar.hpp - the physics of one sonar ping (paper, section 4).
//
// A ping returns the first echo strong enough to cross the board's threshold, so it
// blurs objects across the beam's width. Echo strength follows the transducer's beam
// pattern, spreading and absorption, and what was struck: a smooth wall reflects the
// sound away unless it faces the sensor, a rough one scatters some back at any angle,
// a concave corner returns it from wide angles, a chair leg or an edge only weakly
// (docs/manual/houghloc-sim.md, "Echo model"; the older hard-cone model stays selectable). A few
// readings take a longer bounced path; ranges are noisy; and the robot's own cables and
// lost echoes give garbage raw values. The result is a raw reading, through the inverse
// of a simulated linear calibration, as the robot's sonar board would report it.
#ifndef HLSIM_SONAR_HPP
#define HLSIM_SONAR_HPP

#include <cstdint>
#include <vector>

#include "houghloc/calib.h"
#include "rng.hpp"
#include "world.hpp"

namespace hlsim {

/** Every sonar effect the simulator models; the defaults are the data sets' values. */
struct SonarParams {
    enum class Model : uint8_t {
        Cone,      // every surface in a hard 22-degree cone echoes (the first simulator)
        Physical,  // echo levels against a threshold (docs/manual/houghloc-sim.md, "Echo model")
    };
    Model model = Model::Physical;
    double cone_deg = 22.0;          // Cone: full width of the beam
    double ray_step_deg = 0.5;       // spacing of the rays that sample the beam
    double critical_deg = 40.0;      // no specular echo when incidence exceeds this
    double max_range_mm = 8000.0;    // no echo beyond this (listening window)
    // Physical: the transducer and the air (Polaroid 600-series on a 6500 board)
    double frequency_hz = 49400.0;
    double sound_speed_m_s = 343.2;  // dry air at 20 C
    double aperture_radius_mm = 19.0;
    double absorption_db_per_m = 1.6;  // one way
    double threshold_db = -61.0;     // detection level, relative to the source at 1 m
    // Physical: what the targets return
    double specular_width_deg = 10.0;  // smooth surfaces: specular lobe, Gaussian width
    double rough_specular_db = -3.0;   // rough surfaces: specular part, relative
    double rough_diffuse_db = -20.0;   // rough surfaces: Lambert part at normal incidence
    double thin_radius_mm = 12.5;      // a thin segment echoes as a cylinder this thick
    double thin_below_mm = 30.0;       // circles thinner than this are thin targets
    double edge_ts_db = -30.0;         // convex edges and free ends: target strength
    double corner_join_mm = 10.0;      // segments this close meet at a corner
    double corner_tolerance_deg = 10.0;  // a corner within 90 +- this is a retro-reflector
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

/** One possible echo of a ping (Physical model). */
struct EchoCandidate {
    double range_mm = 0.0;
    double level_db = 0.0;  // relative to the source level at 1 m; compare to threshold_db
    Hit hit;                // what returned it (for a corner or edge: the vertex)
};

/** Two-way beam pattern of the circular piston, in dB (0 on the axis), at @p off_axis
 *  radians; -infinity beyond the first null (side lobes are not modelled). */
double sonar_beam_db(const SonarParams &p, double off_axis);

/** Half-width of the main lobe, to the first null of the beam pattern (radians). */
double sonar_main_lobe(const SonarParams &p);

/**
 * Every echo the Physical model finds for a ping along @p axis, within the main lobe
 * and max_range_mm, whatever its level (one per ray that meets an echoing surface, and
 * one per visible corner or edge). The reading is the nearest at or above threshold_db.
 */
std::vector<EchoCandidate> sonar_echoes(const World &w, const SonarParams &p, Vec2 origin,
                                        double axis);

/**
 * The noiseless first echo along @p axis (radians). Cone model: the shortest distance to
 * a surface point seen within the cone at incidence <= the critical angle. Physical: the
 * nearest echo whose level reaches threshold_db.
 * @return the distance in mm, or a negative value when nothing echoes.
 */
double sonar_first_echo(const World &w, const SonarParams &p, Vec2 origin, double axis,
                        Hit *hit = nullptr);

/** One ping with every effect of @p p, drawing randomness from @p rng. */
SonarReading sonar_ping(const World &w, const SonarParams &p, Vec2 origin, double axis,
                        Rng &rng);

}  // namespace hlsim
#endif
