// overrides.cpp - see overrides.hpp.
#include "overrides.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>

namespace hlexp {

namespace {

using Setter = std::function<void(Mode *, double)>;

// Each name, its range and how it lands in the mode. The localizer parameters go to
// both the Table 1 localizer and the online cycle's.
const std::map<std::string, std::pair<std::pair<double, double>, Setter>> &setters()
{
    static const std::map<std::string, std::pair<std::pair<double, double>, Setter>> s = {
        { "cell_mm", { { 1, 1000 }, [](Mode *m, double v) { m->loc.cell_mm = m->slam.loc.cell_mm = (hl_mm_t)v; } } },
        { "group_mm", { { 0, 1000 }, [](Mode *m, double v) { m->loc.group_mm = m->slam.loc.group_mm = (hl_mm_t)v; } } },
        { "map_per_place", { { 0, 1000 }, [](Mode *m, double v) { m->slam.map_per_place = (uint32_t)v; } } },
        { "heading_gain", { { 0, 1 }, [](Mode *m, double v) { m->slam.heading_gain = v; } } },
        { "blur_sigma_mm", { { 0, 1000 }, [](Mode *m, double v) { m->loc.blur_sigma_mm = m->slam.loc.blur_sigma_mm = (hl_mm_t)v; } } },
        { "blur_sigma_theta_deg", { { 0, 10 }, [](Mode *m, double v) { m->loc.blur_sigma_theta = m->slam.loc.blur_sigma_theta = hl_bam_from_deg(v); } } },
        { "normal_gate_deg", { { 0, 180 }, [](Mode *m, double v) { m->loc.normal_gate = m->slam.loc.normal_gate = v >= 180 ? 32768 : hl_bam_from_deg(v); } } },
        { "theta_step_deg", { { 0.1, 10 }, [](Mode *m, double v) { m->loc.theta_step = m->slam.loc.theta_step = hl_bam_from_deg(v); } } },
        { "theta_half_steps", { { 0, 256 }, [](Mode *m, double v) { m->loc.theta_half_steps = m->slam.loc.theta_half_steps = (uint16_t)v; } } },
        { "prior_sigma_mm", { { 1, 100000 }, [](Mode *m, double v) { m->loc.prior_sigma_mm = m->slam.loc.prior_sigma_mm = (hl_mm_t)v; } } },
        { "prior_sigma_theta_deg", { { 0.1, 180 }, [](Mode *m, double v) { m->loc.prior_sigma_theta = m->slam.loc.prior_sigma_theta = hl_bam_from_deg(v); } } },
        { "interpolate", { { 0, 1 }, [](Mode *m, double v) { m->interpolate = m->slam.interpolate = v != 0; } } },
        { "use_prior", { { 0, 1 }, [](Mode *m, double v) { m->slam.use_prior = v != 0; } } },
        { "guarded", { { 0, 1 }, [](Mode *m, double v) { m->slam.guarded = v != 0; } } },
        { "window_mm", { { 0, 100000 }, [](Mode *m, double v) { m->slam.window_mm = (hl_mm_t)v; } } },
        { "wild_mm", { { 1, 100000 }, [](Mode *m, double v) { m->slam.wild_mm = (hl_mm_t)v; } } },
        { "min_confidence", { { 0, 1 }, [](Mode *m, double v) { m->slam.min_confidence = v; } } },
        { "min_peak_ratio", { { 0, 1 }, [](Mode *m, double v) { m->slam.min_peak_ratio = v; } } },
        { "map_capacity", { { 1, 1 << 20 }, [](Mode *m, double v) { m->slam.map_capacity = (uint32_t)v; } } },
        { "echo_bearings", { { 0, 1 }, [](Mode *m, double v) { m->slam.echo_bearings = v != 0; } } },
        { "echo_cap", { { 0, 255 }, [](Mode *m, double v) { m->slam.echo.cap_q8 = (uint16_t)std::lround(v * 256); } } },
        { "echo_tie", { { 0, 255 }, [](Mode *m, double v) { m->slam.echo.tie_q8 = (uint16_t)std::lround(v * 256); } } },
        { "echo_half_beam_deg", { { 1, 45 }, [](Mode *m, double v) { m->slam.echo.half_beam = hl_bam_from_deg(v); } } },
        { "refine", { { 0, 1 }, [](Mode *m, double v) { m->slam.refine = v != 0; } } },
        { "refine_heading", { { 0, 1 }, [](Mode *m, double v) { m->slam.refine_heading = v != 0; } } },
        { "refine_radius_mm", { { 1, 100000 }, [](Mode *m, double v) { m->slam.refine_params.normal_radius_mm = (hl_mm_t)v; } } },
        { "refine_match_mm", { { 1, 100000 }, [](Mode *m, double v) { m->slam.refine_params.match_mm = (hl_mm_t)v; } } },
        { "refine_max_shift_mm", { { 0, 100000 }, [](Mode *m, double v) { m->slam.refine_params.max_shift_mm = (hl_mm_t)v; } } },
        { "table1_prior_sigma_mm", { { 0, 100000 }, [](Mode *m, double v) { m->prior_sigma_mm = v; } } },
    };
    return s;
}

}  // namespace

const char *override_names()
{
    return "cell_mm blur_sigma_mm blur_sigma_theta_deg normal_gate_deg theta_step_deg\n"
           "theta_half_steps prior_sigma_mm prior_sigma_theta_deg interpolate use_prior\n"
           "guarded window_mm wild_mm min_confidence min_peak_ratio map_capacity\n"
           "echo_bearings echo_cap echo_tie echo_half_beam_deg refine refine_heading\n"
           "refine_radius_mm refine_match_mm refine_max_shift_mm table1_prior_sigma_mm\n"
           "group_mm map_per_place heading_gain";
}

bool apply_override(const std::string &setting, Mode *paper, Mode *improved, std::string *err)
{
    size_t dot = setting.find('.'), eq = setting.find('=');
    if (dot == std::string::npos || eq == std::string::npos || eq < dot) {
        *err = "--set wants MODE.NAME=VALUE, not '" + setting + "'";
        return false;
    }
    std::string mode = setting.substr(0, dot), name = setting.substr(dot + 1, eq - dot - 1);
    std::string value = setting.substr(eq + 1);
    Mode *m = mode == "paper" ? paper : mode == "improved" ? improved : nullptr;
    if (!m) {
        *err = "--set: unknown mode '" + mode + "' (paper or improved)";
        return false;
    }
    auto it = setters().find(name);
    if (it == setters().end()) {
        *err = "--set: unknown parameter '" + name + "'";
        return false;
    }
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(value.c_str(), &end);
    const auto &range = it->second.first;
    if (value.empty() || *end || errno || !std::isfinite(v) || v < range.first || v > range.second) {
        char lim[64];
        std::snprintf(lim, sizeof lim, "%g..%g", range.first, range.second);
        *err = "--set: " + name + " must be a number in " + lim + ", not '" + value + "'";
        return false;
    }
    it->second.second(m, v);
    return true;
}

}  // namespace hlexp
