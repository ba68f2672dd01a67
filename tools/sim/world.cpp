// world.cpp - world file parser and ray casting.
#include "world.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace hlsim {

namespace {

// Rays start at the sensor; ignore hits closer than this so a ray cast from a surface
// point (as a bounce would) does not hit its own surface again.
constexpr double kEps = 1e-6;

std::vector<std::string> split_words(const std::string &s)
{
    std::vector<std::string> words;
    std::istringstream in(s);
    std::string w;
    while (in >> w)
        words.push_back(w);
    return words;
}

// A token quoted in an error message: itself when it is printable ASCII of a sane
// length, else its length only (a binary file must not put bytes on the terminal).
std::string shown(const std::string &tok)
{
    bool text = tok.size() <= 40 && std::all_of(tok.begin(), tok.end(), [](char c) {
        return c >= 0x21 && c <= 0x7e;
    });
    return text ? "'" + tok + "'" : "a " + std::to_string(tok.size()) + "-byte non-text word";
}

bool parse_number(const std::string &tok, double *out, std::string *what)
{
    errno = 0;
    char *end = nullptr;
    double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
        *what = shown(tok) + " is not a finite number";
        return false;
    }
    *out = v;
    return true;
}

bool valid_name(const std::string &n)
{
    if (n.empty() || n.size() > 32)
        return false;
    return std::all_of(n.begin(), n.end(), [](char ch) {
        return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') ||
               (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
    });
}

// The optional last word of a shape line.
bool parse_surface(const std::string &word, Surface *out)
{
    if (word == "smooth")
        *out = Surface::Smooth;
    else if (word == "rough")
        *out = Surface::Rough;
    else if (word == "thin")
        *out = Surface::Thin;
    else
        return false;
    return true;
}

// Whether strtod reads all of @p tok (nan and inf included).
bool numeric(const std::string &tok)
{
    char *end = nullptr;
    (void)std::strtod(tok.c_str(), &end);
    return end != tok.c_str() && *end == '\0';
}

// Parses @p count numbers after the keyword of a directive line, each a coordinate.
bool parse_coords(const std::vector<std::string> &w, std::size_t count, const char *usage,
                  double *v, std::string *what)
{
    if (w.size() != count + 1) {
        *what = std::string(usage);
        return false;
    }
    for (std::size_t i = 0; i < count; i++) {
        if (!parse_number(w[1 + i], &v[i], what))
            return false;
        if (std::fabs(v[i]) > kWorldCoordMax) {
            *what = "coordinate " + w[1 + i] + " beyond +-4000000 mm";
            return false;
        }
    }
    return true;
}

Vec2 facing(Vec2 n, Vec2 dir)
{
    return n.dot(dir) > 0.0 ? n * -1.0 : n;
}

double point_segment_dist(Vec2 p, const Segment &s)
{
    Vec2 e = s.b - s.a;
    double len2 = e.dot(e);
    double t = len2 > 0.0 ? std::clamp((p - s.a).dot(e) / len2, 0.0, 1.0) : 0.0;
    return (p - (s.a + e * t)).norm();
}

}  // namespace

void World::add_box(Vec2 c, double w, double h, double angle)
{
    Vec2 u = Vec2::polar(angle) * (w / 2.0);
    Vec2 v = Vec2::polar(angle + kPi / 2.0) * (h / 2.0);
    Vec2 p[4] = {c - u - v, c + u - v, c + u + v, c - u + v};
    for (int i = 0; i < 4; i++)
        segments.push_back({p[i], p[(i + 1) % 4]});
}

// Parses one comment-stripped line; on error sets *what (without file:line).
bool World::parse_line(const std::string &line, std::string *what)
{
    std::vector<std::string> w = split_words(line);
    if (w.empty())
        return true;
    const std::string &kw = w[0];

    // position NAME x y heading_deg: the name is not a number, handle it first.
    if (kw == "position") {
        if (w.size() != 5) {
            *what = "position needs NAME x y heading_deg";
            return false;
        }
        if (!valid_name(w[1])) {
            *what = "position name '" + w[1] + "' must be 1-32 of A-Z a-z 0-9 _ -";
            return false;
        }
        if (find(w[1])) {
            *what = "duplicate position name '" + w[1] + "'";
            return false;
        }
        if (positions.size() >= kWorldMaxPositions) {
            *what = "too many positions (limit " + std::to_string(kWorldMaxPositions) + ")";
            return false;
        }
        double v[3];
        for (int i = 0; i < 3; i++)
            if (!parse_number(w[2 + i], &v[i], what))
                return false;
        if (std::fabs(v[0]) > kWorldCoordMax || std::fabs(v[1]) > kWorldCoordMax) {
            *what = "position coordinate beyond +-4000000 mm";
            return false;
        }
        if (std::fabs(v[2]) > 360.0) {
            *what = "heading must be within +-360 degrees";
            return false;
        }
        positions.push_back({w[1], Pose{v[0], v[1], wrap_pi(deg2rad(v[2]))}});
        return true;
    }

    if (kw == "tiles" || kw == "open" || kw == "orientation" || kw == "tour")
        return parse_layout(w, what);
    if (kw == "start")
        return parse_start(w, what);

    // A shape line may end with a surface word.
    Surface surface = Surface::Smooth;
    if (w.size() > 1 && parse_surface(w.back(), &surface))
        w.pop_back();

    std::size_t want;
    if (kw == "segment" || kw == "box")
        want = 4;
    else if (kw == "circle")
        want = 3;
    else if (kw == "rbox")
        want = 5;
    else if (kw == "polygon")
        want = 0;  // checked below
    else {
        *what = "unknown keyword " + shown(kw) + " (expected segment, polygon, box, rbox, circle, "
                "position, tiles, open, orientation, tour, start)";
        return false;
    }
    std::size_t n = w.size() - 1;
    // One word too many that is not a number: a misspelt surface.
    bool extra = kw == "polygon" ? n >= 7 && n % 2 != 0 : n == want + 1;
    Surface second;
    if (extra && parse_surface(w.back(), &second)) {
        *what = "more than one surface word";
        return false;
    }
    if (extra && !numeric(w.back())) {
        *what = "unknown surface " + shown(w.back()) + " (expected smooth, rough or thin)";
        return false;
    }
    if (kw == "polygon") {
        if (n < 6 || n % 2 != 0) {
            *what = "polygon needs at least 3 x y pairs, got " + std::to_string(n) + " numbers";
            return false;
        }
    } else if (n != want) {
        *what = kw + " needs " + std::to_string(want) + " numbers, got " + std::to_string(n);
        return false;
    }
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; i++)
        if (!parse_number(w[1 + i], &v[i], what))
            return false;
    // Every number except an rbox angle is a length or coordinate in mm.
    for (std::size_t i = 0; i < n; i++) {
        if (kw == "rbox" && i == 4)
            continue;
        if (std::fabs(v[i]) > kWorldCoordMax) {
            *what = "coordinate " + w[1 + i] + " beyond +-4000000 mm";
            return false;
        }
    }
    std::size_t adds = kw == "circle" ? 1 : kw == "segment" ? 1 : kw == "polygon" ? n / 2 : 4;
    if (segments.size() + circles.size() + adds > kWorldMaxShapes) {
        *what = "too many shapes (limit " + std::to_string(kWorldMaxShapes) + ")";
        return false;
    }

    std::size_t first_segment = segments.size();
    if (kw == "segment") {
        Segment s{{v[0], v[1]}, {v[2], v[3]}};
        if ((s.b - s.a).norm() < 1.0) {
            *what = "segment shorter than 1 mm";
            return false;
        }
        segments.push_back(s);
    } else if (kw == "polygon") {
        std::size_t k = n / 2;
        for (std::size_t i = 0; i < k; i++) {
            Vec2 a{v[2 * i], v[2 * i + 1]};
            Vec2 b{v[2 * ((i + 1) % k)], v[2 * ((i + 1) % k) + 1]};
            if ((b - a).norm() < 1.0) {
                *what = "polygon side " + std::to_string(i + 1) + " shorter than 1 mm";
                return false;
            }
            segments.push_back({a, b});
        }
    } else if (kw == "box") {
        double w_ = std::fabs(v[2] - v[0]), h_ = std::fabs(v[3] - v[1]);
        if (w_ < 1.0 || h_ < 1.0) {
            *what = "box sides must be at least 1 mm";
            return false;
        }
        add_box({(v[0] + v[2]) / 2, (v[1] + v[3]) / 2}, w_, h_, 0.0);
    } else if (kw == "rbox") {
        if (v[2] < 1.0 || v[3] < 1.0) {
            *what = "rbox width and depth must be at least 1 mm";
            return false;
        }
        if (std::fabs(v[4]) > 360.0) {
            *what = "rbox angle must be within +-360 degrees";
            return false;
        }
        add_box({v[0], v[1]}, v[2], v[3], deg2rad(v[4]));
    } else {  // circle
        if (v[2] < 1.0) {
            *what = "circle radius must be at least 1 mm";
            return false;
        }
        circles.push_back({{v[0], v[1]}, v[2], surface});
    }
    for (std::size_t i = first_segment; i < segments.size(); i++)
        segments[i].surface = surface;
    return true;
}

// The experiments' layout: tiles, open, orientation, tour.
bool World::parse_layout(const std::vector<std::string> &w, std::string *what)
{
    const std::string &kw = w[0];
    double v[4];
    if (kw == "tiles") {
        if (seen_tiles_) {
            *what = "tiles given twice";
            return false;
        }
        if (w.size() != 2) {
            *what = "tiles needs 1 number (the tile size in mm)";
            return false;
        }
        if (!parse_number(w[1], &v[0], what))
            return false;
        if (v[0] < 100.0 || v[0] > 2000.0) {
            *what = "tile size " + w[1] + " outside 100..2000 mm";
            return false;
        }
        tile_mm = v[0];
        seen_tiles_ = true;
    } else if (kw == "open") {
        if (!parse_coords(w, 4, "open needs X0 Y0 X1 Y1", v, what))
            return false;
        if (!(v[0] < v[2] && v[1] < v[3])) {
            *what = "open rectangle needs X0 < X1 and Y0 < Y1";
            return false;
        }
        if (open.size() >= kWorldMaxOpen) {
            *what = "too many open rectangles (limit " + std::to_string(kWorldMaxOpen) + ")";
            return false;
        }
        open.push_back({{v[0], v[1]}, {v[2], v[3]}});
    } else {
        bool is_tour = kw == "tour";
        bool &seen = is_tour ? has_tour : has_orientation;
        if (seen) {
            *what = kw + " given twice";
            return false;
        }
        if (!parse_coords(w, 2, is_tour ? "tour needs X Y" : "orientation needs X Y", v, what))
            return false;
        (is_tour ? tour_start : orientation_corner) = Vec2{v[0], v[1]};
        seen = true;
    }
    return true;
}

// start X Y HEADING_DEG: where houghloc-sim sets the robot down unless told otherwise.
// Only the numbers are checked here; whether the point is free space depends on shapes
// that may come after the line, so houghloc-sim checks that (as it checks --start).
bool World::parse_start(const std::vector<std::string> &w, std::string *what)
{
    if (has_start) {
        *what = "start given twice";
        return false;
    }
    double v[3];
    if (w.size() != 4) {
        *what = "start needs X Y HEADING_DEG";
        return false;
    }
    for (int i = 0; i < 3; i++)
        if (!parse_number(w[1 + i], &v[i], what))
            return false;
    if (std::fabs(v[0]) > kWorldCoordMax || std::fabs(v[1]) > kWorldCoordMax) {
        *what = "start coordinate beyond +-4000000 mm";
        return false;
    }
    if (std::fabs(v[2]) > 360.0) {
        *what = "heading must be within +-360 degrees";
        return false;
    }
    start = Pose{v[0], v[1], wrap_pi(deg2rad(v[2]))};
    has_start = true;
    return true;
}

bool World::parse(const std::string &text, const std::string &name, std::string *err)
{
    *this = World();
    std::istringstream in(text);
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        lineno++;
        std::string what;
        if (line.size() > kWorldMaxLine)
            what = "line longer than " + std::to_string(kWorldMaxLine) + " characters";
        else {
            std::size_t hash = line.find('#');
            if (hash != std::string::npos)
                line.resize(hash);
            parse_line(line, &what);
        }
        if (!what.empty()) {
            *err = name + ":" + std::to_string(lineno) + ": " + what;
            *this = World();
            return false;
        }
    }
    return true;
}

bool World::load(const std::string &path, std::string *err)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        *err = path + ": cannot open";
        return false;
    }
    std::ostringstream ss;
    ss << f.rdbuf();
    return parse(ss.str(), path, err);
}

bool World::load_or_lab(const std::string &path, World *out, std::string *err)
{
    if (path.empty()) {
        *out = lab();
        return true;
    }
    return out->load(path, err);
}

World World::lab()
{
    World w;
    std::string err;
    // The compiled-in text is tested (tests/sim/test_world.cpp); it cannot fail.
    w.parse(lab_text(), "lab.world", &err);
    return w;
}

bool World::cast(Vec2 o, Vec2 d, double max_dist, Hit *hit) const
{
    double best = max_dist;
    bool found = false;
    for (const Segment &s : segments) {
        Vec2 e = s.b - s.a;
        double denom = d.cross(e);
        if (std::fabs(denom) < 1e-12)
            continue;  // parallel: a grazing ray returns nothing anyway
        Vec2 ao = s.a - o;
        double t = ao.cross(e) / denom;
        double u = ao.cross(d) / denom;
        if (t > kEps && t < best && u >= 0.0 && u <= 1.0) {
            best = t;
            found = true;
            hit->dist = t;
            hit->point = o + d * t;
            Vec2 n{-e.y, e.x};
            hit->normal = facing(n * (1.0 / e.norm()), d);
            hit->surface = s.surface;
            hit->radius = 0.0;
        }
    }
    for (const Circle &c : circles) {
        Vec2 oc = o - c.c;
        double b = oc.dot(d);
        double disc = b * b - (oc.dot(oc) - c.r * c.r);
        if (disc < 0.0)
            continue;
        double sq = std::sqrt(disc);
        double t = -b - sq;
        if (t <= kEps)
            t = -b + sq;  // origin inside the circle: the far side
        if (t > kEps && t < best) {
            best = t;
            found = true;
            hit->dist = t;
            hit->point = o + d * t;
            hit->normal = facing((hit->point - c.c) * (1.0 / c.r), d);
            hit->surface = c.surface;
            hit->radius = c.r;
        }
    }
    return found;
}

double World::clearance(Vec2 p) const
{
    double best = std::numeric_limits<double>::infinity();
    for (const Segment &s : segments)
        best = std::min(best, point_segment_dist(p, s));
    for (const Circle &c : circles)
        best = std::min(best, std::max(0.0, (p - c.c).norm() - c.r));
    return best;
}

bool World::enclosed(Vec2 p, std::string *err) const
{
    Hit h;
    for (int deg = 0; deg < 360; deg++) {
        if (!cast(p, Vec2::polar(deg2rad(deg)), 2.0 * kWorldCoordMax, &h)) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "the world is not closed around (%.1f, %.1f): a ray at %d degrees "
                          "meets nothing",
                          p.x, p.y, deg);
            *err = buf;
            return false;
        }
    }
    return true;
}

const Position *World::find(const std::string &name) const
{
    for (const Position &p : positions)
        if (p.name == name)
            return &p;
    return nullptr;
}

bool World::bounds(Vec2 *lo, Vec2 *hi) const
{
    if (segments.empty() && circles.empty())
        return false;
    double inf = std::numeric_limits<double>::infinity();
    *lo = {inf, inf};
    *hi = {-inf, -inf};
    auto grow = [&](Vec2 p, double r) {
        lo->x = std::min(lo->x, p.x - r);
        lo->y = std::min(lo->y, p.y - r);
        hi->x = std::max(hi->x, p.x + r);
        hi->y = std::max(hi->y, p.y + r);
    };
    for (const Segment &s : segments) {
        grow(s.a, 0.0);
        grow(s.b, 0.0);
    }
    for (const Circle &c : circles)
        grow(c.c, c.r);
    return true;
}

}  // namespace hlsim
