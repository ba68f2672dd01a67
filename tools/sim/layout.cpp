// layout.cpp - positions drawn on the open floor, and the layout checks (layout.hpp).
#include "layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hlsim {

namespace {

std::string at(Vec2 p)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "(%.0f, %.0f)", p.x, p.y);
    return buf;
}

bool clear(const World &w, Vec2 p, const char *what, std::string *err)
{
    if (w.clearance(p) >= kPositionClearanceMm)
        return true;
    *err = std::string(what) + " " + at(p) + " is within " +
           std::to_string(static_cast<int>(kPositionClearanceMm)) + " mm of a surface";
    return false;
}

// The candidates at the least distance (ties within a micrometre), in their order.
template <typename Distance>
std::vector<std::size_t> nearest(const std::vector<std::size_t> &candidates, Distance dist)
{
    std::vector<std::size_t> out;
    double best = 1e300;
    for (std::size_t i : candidates) {
        double d = dist(i);
        if (d < best - 1e-6) {
            best = d;
            out.clear();
        }
        if (std::fabs(d - best) < 1e-6)
            out.push_back(i);
    }
    return out;
}

}  // namespace

std::vector<Vec2> open_intersections(const World &w)
{
    std::vector<Vec2> out;
    const double t = w.tile_mm;
    for (const Rect &r : w.open) {
        long i0 = std::lround(std::ceil(r.lo.x / t)), i1 = std::lround(std::floor(r.hi.x / t));
        long j0 = std::lround(std::ceil(r.lo.y / t)), j1 = std::lround(std::floor(r.hi.y / t));
        for (long j = j0; j <= j1; j++)
            for (long i = i0; i <= i1; i++) {
                Vec2 p{static_cast<double>(i) * t, static_cast<double>(j) * t};
                bool seen = false;  // rectangles may overlap
                for (Vec2 q : out)
                    seen = seen || (std::fabs(q.x - p.x) < 1e-6 && std::fabs(q.y - p.y) < 1e-6);
                if (!seen && w.clearance(p) >= kPositionClearanceMm)
                    out.push_back(p);
            }
    }
    return out;
}

bool draw_positions(const World &w, int count, Rng &rng, std::vector<Position> *out,
                    std::string *err)
{
    out->clear();
    if (w.open.empty()) {
        *err = "the world declares no open floor ('open' lines) to draw positions on";
        return false;
    }
    const std::vector<Vec2> free = open_intersections(w);
    const double t = w.tile_mm;
    if (static_cast<int>(free.size()) < count) {
        *err = "the open floor has " + std::to_string(free.size()) + " tile intersections " +
               std::to_string(static_cast<int>(kPositionClearanceMm)) +
               " mm from every surface, fewer than the " + std::to_string(count) +
               " positions to draw";
        return false;
    }
    // A compact cluster, as the paper's positions were (its Figure 2): a random first
    // intersection, then each next one among the free intersections nearest the cluster
    // (its 8 neighbours, when any is free; an obstacle may split the floor, and then the
    // cluster jumps to the nearest free one beyond it), the one nearest the first, ties
    // drawn at random. Growing towards the first keeps the cluster a blob: a snake's
    // ends lie outside the map the others make, and are always wild.
    std::size_t first = static_cast<std::size_t>(
        rng.uniform_int(0, static_cast<int64_t>(free.size()) - 1));
    std::vector<Vec2> cluster{free[first]};
    std::vector<bool> taken(free.size(), false);
    taken[first] = true;
    while (static_cast<int>(cluster.size()) < count) {
        std::vector<std::size_t> open_ones;
        for (std::size_t i = 0; i < free.size(); i++)
            if (!taken[i])
                open_ones.push_back(i);
        std::vector<std::size_t> rim = nearest(open_ones, [&](std::size_t i) {
            double d = 1e300;
            for (Vec2 c : cluster)
                d = std::min(d, std::max(std::fabs(c.x - free[i].x), std::fabs(c.y - free[i].y)));
            return std::max(d, t);   // every 8-neighbour is as near as any
        });
        std::vector<std::size_t> inner =
            nearest(rim, [&](std::size_t i) { return (free[i] - cluster[0]).norm(); });
        std::size_t pick = inner[static_cast<std::size_t>(
            rng.uniform_int(0, static_cast<int64_t>(inner.size()) - 1))];
        taken[pick] = true;
        cluster.push_back(free[pick]);
    }
    for (int k = 0; k < count; k++) {
        double heading = static_cast<double>(rng.uniform_int(0, 3)) * kPi / 2.0;
        char name[16];
        std::snprintf(name, sizeof name, "P%02d", k + 1);
        const Vec2 p = cluster[static_cast<std::size_t>(k)];
        out->push_back({name, Pose{p.x, p.y, wrap_pi(heading)}});
    }
    return true;
}

bool check_layout(const World &w, const std::vector<Position> &positions, std::string *err)
{
    if (!w.has_orientation) {
        *err = "the world declares no orientation square ('orientation X Y')";
        return false;
    }
    if (!w.has_tour) {
        *err = "the world declares no tour start ('tour X Y')";
        return false;
    }
    if (positions.empty()) {
        *err = "no sounding positions";
        return false;
    }
    if (!w.enclosed(w.tour_start, err))
        return false;
    for (const Position &p : positions)
        if (!clear(w, p.pose.pos(), ("position " + p.name).c_str(), err) ||
            !w.enclosed(p.pose.pos(), err))
            return false;
    const double s = kOrientationSideMm;
    const Vec2 c0 = w.orientation_corner;
    for (Vec2 b : {Vec2{0, 0}, Vec2{s / 2, 0}, Vec2{s, 0}, Vec2{s, s}, Vec2{s / 2, s},
                   Vec2{0, s}, Vec2{s / 2, s / 2}})
        if (!clear(w, c0 + b, "orientation position", err) || !w.enclosed(c0 + b, err))
            return false;
    return true;
}

}  // namespace hlsim
