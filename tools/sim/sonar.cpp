// sonar.cpp - the first echo (hard cone, or echo levels against a threshold), multipath,
// noise, garbage.
#include "sonar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hlsim {

namespace {

// Casts one ray of the cone; true if it meets a surface that echoes (Cone model).
bool echo_along(const World &w, const SonarParams &p, Vec2 o, double angle, Hit *hit)
{
    Vec2 d = Vec2::polar(angle);
    if (!w.cast(o, d, p.max_range_mm, hit))
        return false;
    // Incidence: angle between the ray and the surface normal (which faces the ray).
    double cos_inc = -d.dot(hit->normal);
    return cos_inc >= std::cos(deg2rad(p.critical_deg));
}

// True if @p angle lies within @p half of @p axis.
bool in_cone(double angle, double axis, double half)
{
    return std::fabs(wrap_pi(angle - axis)) <= half;
}

// Calls f(angle) for every direction that samples the beam of half-width @p half: even
// steps, the edges, and the exact direction of every surface's point of normal
// incidence within it (the strongest echo of a surface comes from there; even sampling
// can step over it, as over a thin chair leg at 4 m).
template <class F>
void for_each_ray(const World &w, const SonarParams &p, Vec2 o, double axis, double half, F f)
{
    int n = static_cast<int>(std::floor(rad2deg(half) / p.ray_step_deg + 1e-9));
    for (int k = -n; k <= n; k++)
        f(axis + deg2rad(k * p.ray_step_deg));
    f(axis - half);
    f(axis + half);
    for (const Circle &c : w.circles) {
        Vec2 to = c.c - o;
        double a = std::atan2(to.y, to.x);
        if (to.norm() > c.r && in_cone(a, axis, half))
            f(a);
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
            f(a);
    }
}

double cone_first_echo(const World &w, const SonarParams &p, Vec2 o, double axis, Hit *out)
{
    double best = -1.0;
    Hit h, best_hit;
    for_each_ray(w, p, o, axis, deg2rad(p.cone_deg / 2.0), [&](double angle) {
        if (echo_along(w, p, o, angle, &h) && (best < 0.0 || h.dist < best)) {
            best = h.dist;
            best_hit = h;
        }
    });
    if (out && best >= 0.0)
        *out = best_hit;
    return best;
}

// ---- Physical model: levels in dB relative to the source level at 1 m ------------------

constexpr double kNegInf = -std::numeric_limits<double>::infinity();
constexpr double kFirstNullX = 3.8317059702075123;  // first zero of J1
constexpr double kMinRangeM = 0.01;                  // keeps the logarithms finite
constexpr double kVertexSeeMm = 5.0;                  // a vertex is seen if nothing is nearer

double ka(const SonarParams &p)
{
    return 2.0 * kPi * p.frequency_hz / p.sound_speed_m_s * (p.aperture_radius_mm / 1000.0);
}

double metres(double mm) { return std::max(mm / 1000.0, kMinRangeM); }

// A mirror-like surface (plane at normal incidence, corner reflector): the echo comes
// from the sensor's image at twice the range. In the sonar equation, two-way spreading
// 40 log r with the plane's target strength 20 log(r / 2).
double mirror_db(const SonarParams &p, double mm)
{
    double r = metres(mm);
    return -20.0 * std::log10(2.0 * r) - 2.0 * p.absorption_db_per_m * r;
}

// A small target of strength @p ts_db: two-way spherical spreading and absorption.
double point_db(const SonarParams &p, double mm, double ts_db)
{
    double r = metres(mm);
    return -40.0 * std::log10(r) - 2.0 * p.absorption_db_per_m * r + ts_db;
}

// A vertical cylinder of radius @p radius_mm at normal incidence: 10 log(a r / 2).
double cylinder_db(const SonarParams &p, double mm, double radius_mm)
{
    return point_db(p, mm, 10.0 * std::log10(metres(radius_mm) * metres(mm) / 2.0));
}

// Powers add: the level of two echoes arriving together.
double add_db(double a, double b)
{
    if (a == kNegInf)
        return b;
    if (b == kNegInf)
        return a;
    double m = std::max(a, b);
    return m + 10.0 * std::log10(std::pow(10.0, (a - m) / 10.0) + std::pow(10.0, (b - m) / 10.0));
}

// Level of the echo of one ray that met @p h at incidence @p inc (radians), before the
// beam pattern.
double surface_db(const SonarParams &p, const Hit &h, double inc)
{
    bool circle = h.radius > 0.0;
    if (h.surface == Surface::Thin || (circle && h.radius < p.thin_below_mm))
        return cylinder_db(p, h.dist, circle ? h.radius : p.thin_radius_mm);
    double base = circle ? cylinder_db(p, h.dist, h.radius) : mirror_db(p, h.dist);
    double specular = kNegInf;
    if (inc <= deg2rad(p.critical_deg)) {
        double x = inc / deg2rad(p.specular_width_deg);
        specular = base - 10.0 * std::log10(std::exp(1.0)) * x * x;
    }
    if (h.surface == Surface::Smooth)
        return specular;
    double c = std::cos(inc);
    double diffuse = c > 0.0 ? base + p.rough_diffuse_db + 10.0 * std::log10(c * c) : kNegInf;
    return add_db(specular + p.rough_specular_db, diffuse);
}

// A direction leaving a vertex along a segment, and whether that segment is rough.
struct HalfLine {
    double angle;
    bool rough;
};

// The half-lines of non-thin segments that end at @p c or pass through it, sorted by
// angle, near-duplicates (a desk's side along the wall) merged.
std::vector<HalfLine> half_lines(const World &w, const SonarParams &p, Vec2 c)
{
    std::vector<HalfLine> out;
    auto add = [&](Vec2 d, Surface s) {
        out.push_back({std::atan2(d.y, d.x), s == Surface::Rough});
    };
    for (const Segment &s : w.segments) {
        if (s.surface == Surface::Thin)
            continue;
        bool at_a = (s.a - c).norm() <= p.corner_join_mm;
        bool at_b = (s.b - c).norm() <= p.corner_join_mm;
        if (at_a && !at_b) {
            add(s.b - c, s.surface);
        } else if (at_b && !at_a) {
            add(s.a - c, s.surface);
        } else if (!at_a && !at_b) {
            Vec2 e = s.b - s.a;
            double t = std::clamp((c - s.a).dot(e) / e.dot(e), 0.0, 1.0);
            if ((s.a + e * t - c).norm() <= p.corner_join_mm) {
                add(e, s.surface);
                add(e * -1.0, s.surface);
            }
        }
    }
    std::sort(out.begin(), out.end(),
              [](const HalfLine &a, const HalfLine &b) { return a.angle < b.angle; });
    std::vector<HalfLine> merged;
    for (const HalfLine &h : out)
        if (merged.empty() || h.angle - merged.back().angle > deg2rad(1.0))
            merged.push_back(h);
    if (merged.size() > 1 && merged.front().angle + 2.0 * kPi - merged.back().angle <= deg2rad(1.0))
        merged.pop_back();
    return merged;
}

// The echo of vertex @p c seen from @p o, before the beam pattern: a concave right
// corner returns like a mirror from any direction inside it (a retro-reflector); a
// convex edge or a free end diffracts weakly; a straight joint returns nothing.
double vertex_db(const World &w, const SonarParams &p, Vec2 o, Vec2 c)
{
    std::vector<HalfLine> lines = half_lines(w, p, c);
    double range = (o - c).norm();
    if (lines.empty())
        return kNegInf;
    // The wedge between the half-lines on either side of the sensor's direction.
    Vec2 to_o = o - c;
    double v = std::atan2(to_o.y, to_o.x);
    std::size_t hi = 0;
    while (hi < lines.size() && lines[hi].angle <= v)
        hi++;
    const HalfLine &a = lines[(hi + lines.size() - 1) % lines.size()];
    const HalfLine &b = lines[hi % lines.size()];
    double wedge = lines.size() == 1 ? 2.0 * kPi : b.angle - a.angle;
    if (wedge <= 0.0)
        wedge += 2.0 * kPi;
    double tol = deg2rad(p.corner_tolerance_deg);
    if (std::fabs(wedge - kPi / 2.0) <= tol)
        return mirror_db(p, range) + (a.rough ? p.rough_specular_db : 0.0) +
               (b.rough ? p.rough_specular_db : 0.0);
    if (std::fabs(wedge - kPi) <= tol)
        return kNegInf;
    return point_db(p, range, p.edge_ts_db);
}

}  // namespace

double sonar_main_lobe(const SonarParams &p)
{
    double x = ka(p);
    return x > kFirstNullX ? std::asin(kFirstNullX / x) : kPi / 2.0;
}

double sonar_beam_db(const SonarParams &p, double off_axis)
{
    off_axis = std::fabs(off_axis);
    if (off_axis >= sonar_main_lobe(p))
        return kNegInf;
    double x = ka(p) * std::sin(off_axis);
    if (x < 1e-9)
        return 0.0;
    double d = 2.0 * std::cyl_bessel_j(1.0, x) / x;  // pressure, one way
    return 40.0 * std::log10(std::fabs(d));          // intensity, out and back
}

std::vector<EchoCandidate> sonar_echoes(const World &w, const SonarParams &p, Vec2 o,
                                        double axis)
{
    std::vector<EchoCandidate> out;
    double half = sonar_main_lobe(p);
    Hit h;
    for_each_ray(w, p, o, axis, half, [&](double angle) {
        Vec2 d = Vec2::polar(angle);
        if (!w.cast(o, d, p.max_range_mm, &h))
            return;
        double inc = std::acos(std::clamp(-d.dot(h.normal), -1.0, 1.0));
        double level = surface_db(p, h, inc) + sonar_beam_db(p, wrap_pi(angle - axis));
        if (level > kNegInf)
            out.push_back({h.dist, level, h});
    });
    // Corners and edges: the ends of segments, each point once.
    std::vector<Vec2> seen;
    auto vertex = [&](Vec2 c) {
        Vec2 to = c - o;
        double range = to.norm();
        double angle = std::atan2(to.y, to.x);
        if (range < 1.0 || range > p.max_range_mm || !in_cone(angle, axis, half))
            return;
        for (Vec2 s : seen)
            if ((s - c).norm() <= p.corner_join_mm)
                return;
        seen.push_back(c);
        Hit blocker;
        if (w.cast(o, to * (1.0 / range), range, &blocker) && blocker.dist < range - kVertexSeeMm)
            return;  // hidden behind something nearer
        double level = vertex_db(w, p, o, c) + sonar_beam_db(p, wrap_pi(angle - axis));
        if (level == kNegInf)
            return;
        EchoCandidate e;
        e.range_mm = range;
        e.level_db = level;
        e.hit.dist = range;
        e.hit.point = c;
        e.hit.normal = (o - c) * (1.0 / range);
        out.push_back(e);
    };
    for (const Segment &s : w.segments) {
        if (s.surface == Surface::Thin)
            continue;
        vertex(s.a);
        vertex(s.b);
    }
    return out;
}

double sonar_first_echo(const World &w, const SonarParams &p, Vec2 o, double axis, Hit *out)
{
    if (p.model == SonarParams::Model::Cone)
        return cone_first_echo(w, p, o, axis, out);
    double best = -1.0;
    for (const EchoCandidate &e : sonar_echoes(w, p, o, axis)) {
        if (e.level_db >= p.threshold_db && (best < 0.0 || e.range_mm < best)) {
            best = e.range_mm;
            if (out)
                *out = e.hit;
        }
    }
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
