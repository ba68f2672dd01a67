// rng.hpp - the simulator's one seeded random generator.
//
// Every random draw in the simulator (sonar noise, garbage readings, rotation and
// odometry errors, placement errors) comes from one Rng, so a data set is a function of
// its seed. std::mt19937_64's sequence is fixed by the C++ standard; the conversions to
// uniform and normal variates are written out here because std::uniform_real_distribution
// and std::normal_distribution are implementation-defined.
#ifndef HLSIM_RNG_HPP
#define HLSIM_RNG_HPP

#include <cmath>
#include <cstdint>
#include <random>

#include "geom.hpp"

namespace hlsim {

class Rng {
public:
    explicit Rng(uint64_t seed) : gen_(seed) {}

    /** Uniform in [0, 1), 53 random bits. */
    double uniform() { return static_cast<double>(gen_() >> 11) * 0x1.0p-53; }

    /** Uniform in [lo, hi). */
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    /** Uniform integer in [lo, hi] (small ranges; modulo bias < 2^-40). */
    int64_t uniform_int(int64_t lo, int64_t hi)
    {
        uint64_t span = static_cast<uint64_t>(hi - lo) + 1u;
        return lo + static_cast<int64_t>(gen_() % span);
    }

    /** Standard normal by the Box-Muller transform; the second variate is kept. */
    double normal()
    {
        if (have_spare_) {
            have_spare_ = false;
            return spare_;
        }
        double u1 = 1.0 - uniform();   // (0, 1]: log() stays finite
        double u2 = uniform();
        double r = std::sqrt(-2.0 * std::log(u1));
        double a = 2.0 * kPi * u2;
        spare_ = r * std::sin(a);
        have_spare_ = true;
        return r * std::cos(a);
    }

    /** Normal with the given mean and standard deviation (sigma 0 draws nothing). */
    double normal(double mean, double sigma)
    {
        return sigma > 0.0 ? mean + sigma * normal() : mean;
    }

private:
    std::mt19937_64 gen_;
    bool have_spare_ = false;
    double spare_ = 0.0;
};

}  // namespace hlsim
#endif
