// sonar.cpp - first echo within the cone, specular loss, multipath, noise, garbage.
#include "sonar.hpp"

#include <algorithm>
#include <cmath>

namespace hlsim {

namespace {

// Casts one ray of the cone; true if it meets a surface that echoes.
bool echo_along(const World &w, const SonarParams &p, Vec2 o, double angle, Hit *hit)
{
    Vec2 d = Vec2::polar(angle);
    if (!w.cast(o, d, p.max_range_mm, hit))
        return false;
    // Incidence: angle between the ray and the surface normal (which faces the ray).
    double cos_inc = -d.dot(hit->normal);
    return cos_inc >= std::cos(deg2rad(p.critical_deg));
}

// True if @p angle lies within half a cone of @p axis.
bool in_cone(double angle, double axis, double half)
{
    return std::fabs(wrap_pi(angle - axis)) <= half;
}

}  // namespace

double sonar_first_echo(const World &w, const SonarParams &p, Vec2 o, double axis, Hit *out)
{
    double half = deg2rad(p.cone_deg / 2.0);
    double best = -1.0;
    Hit h, best_hit;
    auto consider = [&](double angle) {
        if (echo_along(w, p, o, angle, &h) && (best < 0.0 || h.dist < best)) {
            best = h.dist;
            best_hit = h;
        }
    };
    // Sample the cone evenly, edges included.
    int n = static_cast<int>(std::floor(p.cone_deg / 2.0 / p.ray_step_deg + 1e-9));
    for (int k = -n; k <= n; k++)
        consider(axis + deg2rad(k * p.ray_step_deg));
    consider(axis - half);
    consider(axis + half);
    // The strongest echo of a surface comes from its point of normal incidence. Even
    // sampling can step over it (a thin chair leg at 4 m falls between two rays), so
    // add the exact direction of every such point that lies within the cone.
    for (const Circle &c : w.circles) {
        Vec2 to = c.c - o;
        double a = std::atan2(to.y, to.x);
        if (to.norm() > c.r && in_cone(a, axis, half))
            consider(a);
    }
    for (const Segment &s : w.segments) {
        Vec2 e = s.b - s.a;
        double t = (o - s.a).dot(e) / e.dot(e);
        if (t <= 0.0 || t >= 1.0)
            continue;
        Vec2 to = s.a + e * t - o;
        if (to.norm() < 1e-9)
            continue;
        double a = std::atan2(to.y, to.x);
        if (in_cone(a, axis, half))
            consider(a);
    }
    if (out && best >= 0.0)
        *out = best_hit;
    return best;
}

SonarReading sonar_ping(const World &w, const SonarParams &p, Vec2 o, double axis, Rng &rng)
{
    SonarReading r;
    // The draws happen in a fixed order whatever the outcome, so that one reading's
    // fate does not shift the random stream of every later reading.
    double u_cable = rng.uniform();
    double u_drop = rng.uniform();
    double u_multi = rng.uniform();
    double extra = rng.uniform(p.multipath_min_mm, p.multipath_max_mm);
    double z = rng.normal();
    int64_t cable_raw = rng.uniform_int(p.cable_raw_min, p.cable_raw_max);

    r.true_mm = std::max(0.0, sonar_first_echo(w, p, o, axis));
    if (u_cable < p.p_cable) {
        r.kind = Echo::Cable;
        r.raw = static_cast<uint16_t>(cable_raw);
        return r;
    }
    if (u_drop < p.p_dropout) {
        r.kind = Echo::Dropout;
        r.raw = p.sentinel_raw;
        return r;
    }
    if (r.true_mm <= 0.0) {
        r.kind = Echo::None;
        r.raw = p.sentinel_raw;
        return r;
    }
    double range = r.true_mm;
    r.kind = Echo::Surface;
    if (u_multi < p.p_multipath) {
        r.kind = Echo::Multipath;
        range += extra;
    }
    range += z * (p.noise_sigma_mm + p.noise_frac * range);
    if (range > p.max_range_mm) {  // the echo came back after the board stopped listening
        r.kind = Echo::None;
        r.raw = p.sentinel_raw;
        return r;
    }
    range = std::max(range, 0.0);
    uint16_t raw = hl_calib_raw_for(&p.calib, static_cast<int32_t>(std::lround(range)));
    r.raw = std::min(raw, static_cast<uint16_t>(p.sentinel_raw - 1));
    return r;
}

}  // namespace hlsim
