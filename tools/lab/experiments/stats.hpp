// stats.hpp - the few summary statistics the experiments report.
#ifndef HLEXP_STATS_HPP
#define HLEXP_STATS_HPP

#include <cmath>
#include <vector>

#include "houghloc/scan.h"

namespace hlexp {

inline double mean(const std::vector<double> &v)
{
    double s = 0;
    for (double x : v)
        s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Sample standard deviation (n - 1), as the paper's sigma.
inline double sigma(const std::vector<double> &v)
{
    if (v.size() < 2)
        return 0.0;
    double m = mean(v), s = 0;
    for (double x : v)
        s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

inline double rmse(const std::vector<double> &v)
{
    double s = 0;
    for (double x : v)
        s += x * x;
    return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

inline double distance_mm(hl_pose_t a, hl_pose_t b)
{
    return std::hypot(static_cast<double>(a.x_mm) - b.x_mm, static_cast<double>(a.y_mm) - b.y_mm);
}

}  // namespace hlexp
#endif
