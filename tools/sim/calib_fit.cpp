// calib_fit.cpp - reading, simulating and fitting calibration pairs.
#include "calib_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace hlsim {

int32_t CalibFit::gain_q16() const
{
    return static_cast<int32_t>(std::lround(gain * 65536.0));
}

int32_t CalibFit::offset_mm() const
{
    return static_cast<int32_t>(std::lround(offset));
}

bool calib_read_pairs(std::istream &in, const std::string &name, std::vector<CalibPair> *out,
                      std::string *err)
{
    out->clear();
    std::string line;
    int lineno = 0;
    auto fail = [&](const std::string &what) {
        *err = name + ":" + std::to_string(lineno) + ": " + what;
        out->clear();
        return false;
    };
    while (std::getline(in, line)) {
        lineno++;
        if (line.size() > 1000)
            return fail("line longer than 1000 characters");
        std::size_t hash = line.find('#');
        if (hash != std::string::npos)
            line.resize(hash);
        std::istringstream words(line);
        std::vector<std::string> w;
        std::string t;
        while (words >> t)
            w.push_back(t);
        if (w.empty())
            continue;
        if (w.size() != 2)
            return fail("expected 'distance_mm raw', got " + std::to_string(w.size()) + " fields");
        double v[2];
        for (int i = 0; i < 2; i++) {
            errno = 0;
            char *end = nullptr;
            v[i] = std::strtod(w[static_cast<std::size_t>(i)].c_str(), &end);
            if (*end != '\0' || end == w[static_cast<std::size_t>(i)].c_str() || errno == ERANGE ||
                !std::isfinite(v[i]))
                return fail("'" + w[static_cast<std::size_t>(i)] + "' is not a finite number");
        }
        if (v[0] <= 0.0 || v[0] > 32767.0)
            return fail("distance " + w[0] + " outside (0, 32767] mm");
        if (v[1] < 0.0 || v[1] > 65535.0 || v[1] != std::floor(v[1]))
            return fail("raw reading " + w[1] + " is not an integer 0..65535");
        if (out->size() >= kCalibMaxPairs)
            return fail("too many pairs (limit " + std::to_string(kCalibMaxPairs) + ")");
        out->push_back({v[0], v[1], lineno});
    }
    if (in.bad())
        return fail("read error");
    return true;
}

std::vector<CalibPair> calib_simulate(const SonarParams &sonar, Rng &rng, double from_mm,
                                      double to_mm, double step_mm, int per_distance)
{
    std::vector<CalibPair> pairs;
    for (double d = from_mm; d <= to_mm + 1e-9; d += step_mm) {
        // A 600 mm cardboard box, its face square to the beam at distance d.
        World w;
        w.add_box({d + 200.0, 0.0}, 400.0, 600.0, 0.0);
        for (int i = 0; i < per_distance; i++) {
            SonarReading r = sonar_ping(w, sonar, {0.0, 0.0}, 0.0, rng);
            pairs.push_back({d, static_cast<double>(r.raw), 0});
        }
    }
    return pairs;
}

namespace {

// Least squares over the kept pairs; false if the system is degenerate.
bool fit_line(const std::vector<const CalibPair *> &kept, double *gain, double *offset)
{
    Eigen::Index n = static_cast<Eigen::Index>(kept.size());
    if (n < 2)
        return false;
    Eigen::MatrixXd a(n, 2);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; i++) {
        a(i, 0) = kept[static_cast<std::size_t>(i)]->raw;
        a(i, 1) = 1.0;
        b(i) = kept[static_cast<std::size_t>(i)]->mm;
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    if (qr.rank() < 2)
        return false;
    Eigen::Vector2d x = qr.solve(b);
    *gain = x(0);
    *offset = x(1);
    return std::isfinite(*gain) && std::isfinite(*offset);
}

double residual(const CalibPair &p, double gain, double offset)
{
    return p.mm - (gain * p.raw + offset);
}

}  // namespace

bool calib_fit(const std::vector<CalibPair> &pairs, uint16_t min_raw, uint16_t sentinel_raw,
               double outlier_floor_mm, CalibFit *fit, std::string *err)
{
    *fit = CalibFit();
    std::vector<const CalibPair *> kept;
    for (const CalibPair &p : pairs) {
        if (p.raw < min_raw || p.raw >= sentinel_raw)
            fit->garbage++;
        else
            kept.push_back(&p);
    }
    double g, o;
    if (!fit_line(kept, &g, &o)) {
        *err = "need at least two distinct raw values (" + std::to_string(kept.size()) +
               " usable pairs)";
        return false;
    }
    // Robust scale: 1.4826 x median absolute residual estimates sigma for Gaussian noise.
    std::vector<double> absr;
    for (const CalibPair *p : kept)
        absr.push_back(std::fabs(residual(*p, g, o)));
    std::nth_element(absr.begin(), absr.begin() + static_cast<long>(absr.size() / 2), absr.end());
    double limit = std::max(outlier_floor_mm, 5.0 * 1.4826 * absr[absr.size() / 2]);
    std::vector<const CalibPair *> inliers;
    for (const CalibPair *p : kept)
        if (std::fabs(residual(*p, g, o)) <= limit)
            inliers.push_back(p);
    double g2, o2;
    if (inliers.size() < kept.size() && fit_line(inliers, &g2, &o2)) {
        fit->outliers = static_cast<int>(kept.size() - inliers.size());
        kept = inliers;
        g = g2;
        o = o2;
    }
    double ss = 0.0;
    for (const CalibPair *p : kept) {
        double r = residual(*p, g, o);
        ss += r * r;
    }
    fit->gain = g;
    fit->offset = o;
    fit->used = static_cast<int>(kept.size());
    fit->rms_mm = std::sqrt(ss / static_cast<double>(kept.size()));
    if (g <= 0.0 || g > 16.0) {
        *err = "fitted gain " + std::to_string(g) + " mm per raw unit is outside (0, 16]";
        return false;
    }
    return true;
}

}  // namespace hlsim
