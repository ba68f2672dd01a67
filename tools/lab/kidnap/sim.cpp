// sim.cpp - the kidnap experiment in a simulated world: test soundings at random poses,
// and the map the daemon made on its tour of the world (kidnap.hpp).
#include <algorithm>
#include <memory>
#include <vector>

extern "C" {
#include "houghloc/mapstore.h"
}

#include "logwriter.hpp"
#include "robot.hpp"
#include "tour.hpp"
#include "world.hpp"
#include "kidnap.hpp"

namespace hlkid {

namespace {

using namespace hlsim;

// Where the robot may be set down: this far from every surface (the sim's own clearance,
// World::clearance) ...
constexpr double kClearanceMm = 600.0;
// ... and nearer than that to a stop of the tour that made the map: then the straight
// line to the stop lies inside the free disc around the pose, so the pose is in the
// space the tour went through (not in a closed room, a cupboard or outside the walls).
constexpr double kNearStopMm = kClearanceMm;
constexpr int64_t kBaseUtime = 1000000000000000LL;     // as hl-sim-logs
constexpr long kMaxDraws = 10000000;

bool near_a_stop(const std::vector<Vec2> &stops, Vec2 p)
{
    for (Vec2 s : stops)
        if ((s - p).norm() < kNearStopMm)
            return true;
    return false;
}

// Where the robot drives next: kApartMm to 2 kApartMm from @p from in a random direction,
// a free place (kClearanceMm) with nothing in the straight way. False when 100 draws
// found none (a robot boxed in turns instead).
bool next_place(const World &w, Rng &rng, Vec2 from, Vec2 *to)
{
    for (int draw = 0; draw < 100; draw++) {
        double a = rng.uniform(-kPi, kPi), d = rng.uniform(kApartMm, 2.0 * kApartMm);
        Vec2 dir{std::cos(a), std::sin(a)};
        Vec2 p = from + dir * d;
        Hit hit;
        if (w.clearance(p) >= kClearanceMm && !w.cast(from, dir, d + kClearanceMm, &hit)) {
            *to = p;
            return true;
        }
    }
    return false;
}

}  // namespace

bool write_sim_tests(const std::string &world_path, int trials, int scans, uint64_t seed,
                     const std::string &log_path, std::string *err)
{
    World w;
    if (!World::load_or_lab(world_path, &w, err))
        return false;
    if (!w.has_tour) {
        *err = "the world declares no tour start ('tour X Y')";
        return false;
    }
    // The stops of hl-sim-logs's tour (make_logs.cpp: tour_order over this grid).
    const std::vector<Vec2> stops = tour_grid(w, w.tour_start, w.tile_mm, kTourClearanceMm);
    if (stops.empty()) {
        *err = "the world's tour has no stop";
        return false;
    }
    Vec2 lo = stops[0], hi = stops[0];
    for (Vec2 s : stops) {
        lo = {std::min(lo.x, s.x), std::min(lo.y, s.y)};
        hi = {std::max(hi.x, s.x), std::max(hi.y, s.y)};
    }
    lo = lo - Vec2{kNearStopMm, kNearStopMm};
    hi = hi + Vec2{kNearStopMm, kNearStopMm};

    // The tour's robot: hl-sim-logs's default sonar (the physical echo model) and body
    // (16 transducers x 8 body steps: 128 readings a sounding).
    Rng rng(seed);
    SonarParams sonar;
    RobotParams body;
    Robot robot(w, sonar, body, rng, kBaseUtime);
    LogWriter log;
    if (!log.open(log_path, err))
        return false;
    for (int32_t i = 0; i < trials; i++) {
        Vec2 p;
        long draws = 0;
        do {
            if (++draws > kMaxDraws) {
                *err = "no free pose found in " + std::to_string(kMaxDraws) + " draws";
                return false;
            }
            p = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y)};
        } while (w.clearance(p) < kClearanceMm || !near_a_stop(stops, p));
        Pose truth{p.x, p.y, rng.uniform(-kPi, kPi)};
        robot.wait(60.0);           // carried there
        robot.place(truth, truth);  // its odometry's origin does not matter: only the
                                    // moves between a trial's soundings count
        log.sounding(robot.sound(), i * scans, sonar.calib);
        for (int k = 1; k < scans; k++) {
            Vec2 to;
            if (next_place(w, rng, robot.truth().pos(), &to))
                robot.steer_to(to);
            else
                robot.turn(kPi / 4.0);
            log.sounding(robot.sound(), i * scans + k, sonar.calib);
        }
    }
    if (!log.close()) {
        *err = log_path + ": write failed";
        return false;
    }
    return true;
}

bool load_daemon_map(hl_slam_t *slam, const std::string &path, std::string *err)
{
    uint32_t cap = hl_map_capacity(hl_slam_map(slam));
    std::vector<hl_vector_t> v(cap);
    hl_mapfile_t m{};
    m.vectors = v.data();
    m.max_vectors = cap;
    char why[HL_MAPSTORE_WHY_LEN];
    if (hl_mapstore_load(path.c_str(), &m, why) != HL_OK) {
        *err = why;
        return false;
    }
    return restore_map(slam, m.vectors, m.count, err);
}

}  // namespace hlkid
