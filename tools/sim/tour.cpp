// tour.cpp - reachable grid and the outward-growing greedy tour.
#include "tour.hpp"

#include <cmath>
#include <deque>
#include <map>
#include <utility>

namespace hlsim {

namespace {

using Cell = std::pair<long, long>;  // grid indices (i, j): point (i, j) * spacing

const Cell kSteps[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};

Vec2 at(Cell c, double spacing)
{
    return {static_cast<double>(c.first) * spacing, static_cast<double>(c.second) * spacing};
}

Cell snap(Vec2 p, double spacing)
{
    return {std::lround(p.x / spacing), std::lround(p.y / spacing)};
}

Cell add(Cell a, Cell b)
{
    return {a.first + b.first, a.second + b.second};
}

// True if the robot's body fits along the straight step from a to b: no point of the
// path, sampled every 25 mm, comes within kBodyClearance of a surface.
constexpr double kBodyClearance = 250.0;

bool step_clear(const World &w, Vec2 a, Vec2 b)
{
    Vec2 d = b - a;
    int n = static_cast<int>(std::ceil(d.norm() / 25.0));
    for (int k = 0; k <= n; k++)
        if (w.clearance(a + d * (static_cast<double>(k) / n)) < kBodyClearance)
            return false;
    return true;
}

// Flood fill of the free grid from start; the map's value is the discovery order.
std::map<Cell, int> reachable(const World &w, Cell start, double spacing, double clearance)
{
    std::map<Cell, int> seen;
    if (w.clearance(at(start, spacing)) < clearance)
        return seen;
    std::deque<Cell> queue{start};
    seen[start] = 0;
    // A world is bounded by the parser's limits; cap the fill so that an unclosed
    // room cannot run away.
    const std::size_t cap = 100000;
    while (!queue.empty() && seen.size() < cap) {
        Cell c = queue.front();
        queue.pop_front();
        for (Cell s : kSteps) {
            Cell n = add(c, s);
            if (seen.count(n))
                continue;
            if (w.clearance(at(n, spacing)) < clearance ||
                !step_clear(w, at(c, spacing), at(n, spacing)))
                continue;
            seen[n] = static_cast<int>(seen.size());
            queue.push_back(n);
        }
    }
    return seen;
}

}  // namespace

std::vector<Vec2> tour_grid(const World &w, Vec2 start, double spacing, double clearance_mm)
{
    std::vector<Vec2> out;
    for (const auto &kv : reachable(w, snap(start, spacing), spacing, clearance_mm))
        out.push_back(at(kv.first, spacing));
    return out;
}

std::vector<TourStop> tour_order(const World &w, Vec2 start, double spacing,
                                 double clearance_mm)
{
    Cell s0 = snap(start, spacing);
    std::map<Cell, int> free = reachable(w, s0, spacing, clearance_mm);
    std::vector<TourStop> tour;
    if (free.empty())
        return tour;
    Vec2 origin = at(s0, spacing);
    auto dist0 = [&](Cell c) { return (at(c, spacing) - origin).norm(); };
    // Prefer the cell nearest the start; break exact ties by a fixed order.
    auto better = [&](Cell a, Cell b) {
        double da = dist0(a), db = dist0(b);
        if (std::fabs(da - db) > 1e-6)
            return da < db;
        return a < b;
    };
    // Two cells are neighbours if the flood fill could step between them.
    auto linked = [&](Cell a, Cell b) {
        return free.count(b) && step_clear(w, at(a, spacing), at(b, spacing));
    };

    std::map<Cell, bool> visited;
    Cell cur = s0;
    visited[cur] = true;
    tour.push_back({at(cur, spacing), {}});
    while (visited.size() < free.size()) {
        bool found = false;
        Cell next{};
        for (Cell s : kSteps) {
            Cell n = add(cur, s);
            if (!visited.count(n) && linked(cur, n) && (!found || better(n, next))) {
                next = n;
                found = true;
            }
        }
        TourStop stop;
        if (!found) {
            // Dead end: breadth-first search to the nearest unvisited cells (fewest
            // steps), the best of them by distance to the start; drive back through
            // visited cells.
            std::map<Cell, Cell> parent{{cur, cur}};
            std::deque<Cell> queue{cur};
            std::vector<Cell> frontier;
            while (!queue.empty() && frontier.empty()) {
                std::size_t level = queue.size();
                for (std::size_t k = 0; k < level; k++) {
                    Cell c = queue.front();
                    queue.pop_front();
                    for (Cell s : kSteps) {
                        Cell n = add(c, s);
                        if (parent.count(n) || !linked(c, n))
                            continue;
                        parent[n] = c;
                        if (!visited.count(n))
                            frontier.push_back(n);
                        else
                            queue.push_back(n);
                    }
                }
            }
            if (frontier.empty())
                break;  // cannot happen: every free cell is connected
            next = frontier[0];
            for (Cell f : frontier)
                if (better(f, next))
                    next = f;
            std::vector<Vec2> back;
            for (Cell c = parent[next]; c != cur; c = parent[c])
                back.push_back(at(c, spacing));
            stop.via.assign(back.rbegin(), back.rend());
        }
        stop.at = at(next, spacing);
        tour.push_back(stop);
        visited[next] = true;
        cur = next;
    }
    return tour;
}

}  // namespace hlsim
