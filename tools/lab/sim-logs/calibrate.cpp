// calibrate.cpp - hl-calibrate: fits the linear raw -> mm sonar calibration from
// (known distance, raw reading) pairs, as the paper did with a box at 1 m to 4 m, and
// prints it in configuration syntax, or refuses a fit the core would not accept.
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "calib_fit.hpp"
#include "houghloc/calib.h"

using namespace hlsim;

namespace {

void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: hl-calibrate FILE                  fit pairs from FILE ('-': stdin)\n"
                 "       hl-calibrate --simulate [--seed N]  fit simulated pairs\n"
                 "       hl-calibrate --simulate --print-pairs [--seed N]\n"
                 "\n"
                 "Input: one pair per line, 'distance_mm raw' (known distance in mm, raw\n"
                 "sonar reading 0..65535); '#' starts a comment. Raw values below 200\n"
                 "(cable echoes) or at/above 16384 (no echo) are ignored; residuals beyond\n"
                 "5 robust sigmas (at least 100 mm) are dropped and the line refitted.\n"
                 "--simulate: a box face-on at 1000, 1250, ... 4000 mm, 8 pings each, with\n"
                 "the simulator's sonar physics and calibration (1.07 mm/raw, -35 mm).\n"
                 "Output: residual RMS and the fit as configuration lines:\n"
                 "  calibration.gain_q16 = N     (mm per raw unit x 65536, 1..1048576)\n"
                 "  calibration.offset_mm = N    (-10000..10000)\n"
                 "A fit outside those ranges (hl_calib_error) is refused: exit status 1.\n"
                 "Exit status: 0 fitted; 1 bad input or an unusable fit; 2 bad usage.\n");
}

// Rounds @p v to int32, saturating, so an absurd fit reaches hl_calib_error as an
// out-of-range value rather than as an undefined conversion.
int32_t saturate_i32(double v)
{
    if (!(v > INT32_MIN))       // also NaN
        return INT32_MIN;
    if (v >= INT32_MAX)
        return INT32_MAX;
    return static_cast<int32_t>(std::lround(v));
}

}  // namespace

int main(int argc, char **argv)
{
    bool simulate = false, print_pairs = false;
    uint64_t seed = 1;
    std::string path;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            usage(stdout);
            return 0;
        } else if (a == "--simulate") {
            simulate = true;
        } else if (a == "--print-pairs") {
            print_pairs = true;
        } else if (a == "--seed" && i + 1 < argc) {
            char *end = nullptr;
            const char *v = argv[++i];
            errno = 0;
            seed = std::strtoull(v, &end, 10);
            if (*v < '0' || *v > '9' || *end != '\0' || errno == ERANGE) {
                std::fprintf(stderr, "hl-calibrate: --seed wants an integer 0..%llu, got '%s'\n",
                             static_cast<unsigned long long>(UINT64_MAX), v);
                return 2;
            }
        } else if (path.empty() && (a == "-" || a[0] != '-')) {
            path = a;
        } else {
            std::fprintf(stderr, "hl-calibrate: unknown, incomplete or extra argument '%s' "
                                 "(try --help)\n", a.c_str());
            return 2;
        }
    }
    if (simulate == !path.empty()) {
        std::fprintf(stderr, "hl-calibrate: give an input file ('-' for stdin) or --simulate "
                             "(try --help)\n");
        return 2;
    }

    std::vector<CalibPair> pairs;
    SonarParams sp;
    if (simulate) {
        Rng rng(seed);
        pairs = calib_simulate(sp, rng, 1000.0, 4000.0, 250.0, 8);
    } else {
        std::string err;
        bool ok;
        if (path == "-") {
            ok = calib_read_pairs(std::cin, "stdin", &pairs, &err);
        } else {
            std::ifstream f(path);
            if (!f) {
                std::fprintf(stderr, "hl-calibrate: %s: cannot open\n", path.c_str());
                return 1;
            }
            ok = calib_read_pairs(f, path, &pairs, &err);
        }
        if (!ok) {
            std::fprintf(stderr, "hl-calibrate: %s\n", err.c_str());
            return 1;
        }
    }
    if (print_pairs) {
        for (const CalibPair &p : pairs)
            std::printf("%.0f %.0f\n", p.mm, p.raw);
        return 0;
    }

    CalibFit fit;
    std::string err;
    if (!calib_fit(pairs, sp.calib.min_raw, sp.calib.sentinel_raw, 100.0, &fit, &err)) {
        std::fprintf(stderr, "hl-calibrate: %s\n", err.c_str());
        return 1;
    }
    hl_calib_t calib = sp.calib;
    calib.gain_q16 = saturate_i32(fit.gain * 65536.0);
    calib.offset_mm = saturate_i32(fit.offset);
    if (const char *bad = hl_calib_error(&calib)) {
        std::fprintf(stderr, "hl-calibrate: the fit mm = %.5g * raw %+.5g is unusable: %s\n",
                     fit.gain, fit.offset, bad);
        return 1;
    }
    std::printf("# %zu pairs: %d used, %d garbage (cable echo / no echo), %d outliers\n",
                pairs.size(), fit.used, fit.garbage, fit.outliers);
    std::printf("# mm = %.5f * raw %+.2f; residual RMS %.1f mm\n", fit.gain, fit.offset,
                fit.rms_mm);
    if (simulate)
        std::printf("# simulated truth: mm = %.5f * raw %+d\n", sp.calib.gain_q16 / 65536.0,
                    sp.calib.offset_mm);
    std::printf("calibration.gain_q16 = %d\n", calib.gain_q16);
    std::printf("calibration.offset_mm = %d\n", calib.offset_mm);
    return 0;
}
