// calib_fit.hpp - fitting the linear raw -> mm sonar calibration (paper, section 4).
//
// The paper placed a box at known distances from 1 m to 4 m, read the sonar, and fitted
// a linear function. This module reads such (distance, raw) pairs, simulates them, and
// fits mm = gain * raw + offset by least squares, with one round of outlier rejection
// (a stray multipath echo would otherwise tilt the line).
#ifndef HLSIM_CALIB_FIT_HPP
#define HLSIM_CALIB_FIT_HPP

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "rng.hpp"
#include "sonar.hpp"

namespace hlsim {

struct CalibPair {
    double mm = 0.0;   // known distance
    double raw = 0.0;  // raw sonar reading
    int line = 0;      // input line (0 when simulated)
};

struct CalibFit {
    double gain = 0.0;     // mm per raw unit
    double offset = 0.0;   // mm
    double rms_mm = 0.0;   // residual RMS over the pairs kept
    int used = 0;          // pairs in the final fit
    int garbage = 0;       // pairs dropped as cable echo / no-echo sentinel
    int outliers = 0;      // pairs dropped by the residual test
    int32_t gain_q16() const;  // as hl_calib_t.gain_q16
    int32_t offset_mm() const; // as hl_calib_t.offset_mm
};

constexpr std::size_t kCalibMaxPairs = 100000;

/**
 * Reads "distance_mm raw" lines ('#' comments and blank lines allowed).
 * On error returns false with @p err = "NAME:LINE: what was wrong".
 */
bool calib_read_pairs(std::istream &in, const std::string &name, std::vector<CalibPair> *out,
                      std::string *err);

/**
 * Simulates the paper's procedure: a cardboard box face-on to transducer 0 at
 * @p from_mm, from_mm + step_mm, ... to_mm, @p per_distance pings at each, with every
 * effect of @p sonar.
 */
std::vector<CalibPair> calib_simulate(const SonarParams &sonar, Rng &rng, double from_mm,
                                      double to_mm, double step_mm, int per_distance);

/**
 * Least-squares fit of mm = gain * raw + offset. Pairs with raw below @p min_raw or at
 * or above @p sentinel_raw are garbage and ignored. After a first fit, pairs whose
 * residual exceeds max(@p outlier_floor_mm, 5 robust sigmas) are dropped and the line
 * refitted. @return false with @p err when fewer than two distinct raw values remain.
 */
bool calib_fit(const std::vector<CalibPair> &pairs, uint16_t min_raw, uint16_t sentinel_raw,
               double outlier_floor_mm, CalibFit *fit, std::string *err);

}  // namespace hlsim
#endif
