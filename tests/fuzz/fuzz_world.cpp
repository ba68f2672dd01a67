// fuzz_world.cpp - the simulator's world file parser (tools/sim/world.hpp): the input is
// a world file's text, parsed by World::parse as houghloc-sim and hl-sim-logs load one.
//
// Checked, from world.hpp: a refusal is one line "NAME:LINE: what" and leaves the world
// empty; a world that parses keeps the parser's limits (shape, position and open-area
// counts, finite numbers, positions within +-kWorldCoordMax); parsing the same text again
// into the same object gives the same world (nothing of the first parse leaks into the
// second); and the queries the simulator makes of a world (bounds, a ray cast,
// clearance) keep their contracts on it.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "fuzz.h"
#include "world.hpp"

namespace {

using hlsim::Vec2;
using hlsim::World;

bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

bool empty(const World &w)
{
    World fresh;
    return w.segments.empty() && w.circles.empty() && w.positions.empty() && w.open.empty() &&
           !w.has_orientation && !w.has_tour && w.tile_mm == fresh.tile_mm;
}

void check_world(const World &w)
{
    FUZZ_CHECK(w.segments.size() + w.circles.size() <= hlsim::kWorldMaxShapes);
    FUZZ_CHECK(w.positions.size() <= hlsim::kWorldMaxPositions);
    FUZZ_CHECK(w.open.size() <= hlsim::kWorldMaxOpen);
    for (const hlsim::Segment &s : w.segments)
        FUZZ_CHECK(finite(s.a) && finite(s.b));
    for (const hlsim::Circle &c : w.circles)
        FUZZ_CHECK(finite(c.c) && std::isfinite(c.r) && c.r >= 1.0);
    for (const hlsim::Position &p : w.positions) {
        FUZZ_CHECK(std::fabs(p.pose.x) <= hlsim::kWorldCoordMax);
        FUZZ_CHECK(std::fabs(p.pose.y) <= hlsim::kWorldCoordMax);
        FUZZ_CHECK(p.pose.theta >= -hlsim::kPi && p.pose.theta <= hlsim::kPi);
        FUZZ_CHECK(w.find(p.name) == &p);
    }
    for (const hlsim::Rect &r : w.open)
        FUZZ_CHECK(r.lo.x < r.hi.x && r.lo.y < r.hi.y);
    FUZZ_CHECK(w.tile_mm >= 100.0 && w.tile_mm <= 2000.0);

    Vec2 lo, hi;
    bool any = w.bounds(&lo, &hi);
    FUZZ_CHECK(any == !(w.segments.empty() && w.circles.empty()));
    if (!any)
        return;
    FUZZ_CHECK(finite(lo) && finite(hi) && lo.x <= hi.x && lo.y <= hi.y);
    // A ray from the middle of the world along each axis: a hit is within the range asked.
    Vec2 mid = (lo + hi) * 0.5;
    const double max_dist = 4.0 * hlsim::kWorldCoordMax;
    const Vec2 dirs[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (const Vec2 &d : dirs) {
        hlsim::Hit hit;
        if (w.cast(mid, d, max_dist, &hit)) {
            FUZZ_CHECK(hit.dist > 0.0 && hit.dist < max_dist);
            FUZZ_CHECK(finite(hit.point) && finite(hit.normal));
        }
    }
    double c = w.clearance(mid);
    FUZZ_CHECK(c >= 0.0 && !std::isnan(c));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const std::string text(reinterpret_cast<const char *>(data), size);
    const std::string name = "fuzz.world";
    World w;
    std::string err;
    bool ok = w.parse(text, name, &err);
    if (!ok) {
        FUZZ_CHECK(err.compare(0, name.size() + 1, name + ":") == 0);
        FUZZ_CHECK(err.find('\n') == std::string::npos);
        FUZZ_CHECK(empty(w));
    } else {
        check_world(w);
    }
    // The same text into the same object: the same outcome, the same world.
    const size_t segments = w.segments.size(), circles = w.circles.size();
    const size_t positions = w.positions.size(), open = w.open.size();
    std::string err2;
    FUZZ_CHECK(w.parse(text, name, &err2) == ok);
    FUZZ_CHECK(err2 == (ok ? std::string() : err));
    FUZZ_CHECK(w.segments.size() == segments && w.circles.size() == circles);
    FUZZ_CHECK(w.positions.size() == positions && w.open.size() == open);
    return 0;
}
