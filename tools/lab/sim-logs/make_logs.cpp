// make_logs.cpp - hl-sim-logs: writes the simulated data sets of the paper's three
// experiments as LCM event logs (docs/results/experiments.md describes them) and, with
// --continuous, two inputs for the continuous sensor profiles: the sonar ring and a laser
// sampled while the robot drives the tour (the goldens of tests/golden replay them).
//
// Everything is a function of --seed: each data set draws from its own generator,
// seeded with (seed, data-set number), and timestamps are simulated time from a fixed
// base, so the same seed rewrites byte-identical files.
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "houghloc/fixed.h"

#include "laser.hpp"
#include "layout.hpp"
#include "logwriter.hpp"
#include "robot.hpp"
#include "tour.hpp"
#include "world.hpp"

using namespace hlsim;

namespace {

constexpr int64_t kBaseUtime = 1000000000000000LL;  // 1e15 us; any fixed base will do

struct Options {
    uint64_t seed = 1;
    std::string out_dir = "logs";
    std::string world;  // empty: built-in lab
    int tour_min_stops = 100;
    double rotation_sigma_deg = RobotParams{}.rotation_sigma_deg;
    int soundings = 2;          // per Table 1 position
    bool declared = false;      // Table 1 at the world's `position` lines, not drawn
    bool cone = false;          // the first simulator's hard 22-degree cone
    bool continuous = false;    // also the continuous profiles' logs (make logs)
};

constexpr int kPositions = 28;  // the paper's Table 1

// The continuous data sets: a sensor sampled every kContinuousPeriodS while the robot
// drives the first stops of the tour without stopping. The stops are as many as keep
// each log near 250 KB (a laser scan is 181 readings, a ring 16).
constexpr double kContinuousPeriodS = 0.2;
constexpr int kContinuousSonarStops = 36;
constexpr int kLaserStops = 7;

void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: hl-sim-logs [--seed N] [--out-dir DIR] [--world FILE] [--soundings N]\n"
                 "                   [--declared-positions] [--sonar-model M] [--rotation-sigma-deg S]\n"
                 "                   [--continuous]\n"
                 "Writes DIR/lab28.lcmlog, DIR/orientation.lcmlog and DIR/tour.lcmlog:\n"
                 "simulated sonar soundings (SONAR, SONAR_TEST), odometry (ODOMETRY) and\n"
                 "true poses (GROUND_TRUTH) in the default lab world or FILE. They are\n"
                 "written to a temporary folder in DIR and renamed into place together:\n"
                 "a failed run leaves DIR as it was.\n"
                 "  --seed N               everything is a function of it (default 1)\n"
                 "  --soundings N          soundings at each of Table 1's 28 positions, 1..8\n"
                 "                         (default 2: the paper's 7,616 readings)\n"
                 "  --declared-positions   Table 1 at the world's `position` lines instead of\n"
                 "                         28 drawn per seed on its `open` floor\n"
                 "  --sonar-model M        physical (default: echo levels against a threshold)\n"
                 "                         or cone (the first simulator's hard 22-degree cone)\n"
                 "  --rotation-sigma-deg S error of each of the body's rotation steps within\n"
                 "                         a sounding (0..5 degrees; default %.1f)\n"
                 "  --continuous           also DIR/continuous.lcmlog (the 16-transducer ring)\n"
                 "                         and DIR/laser.lcmlog (181 beams over 180 degrees),\n"
                 "                         each sampled every 0.2 s while the robot drives the\n"
                 "                         tour's first stops: the continuous sensor profiles'\n"
                 "                         inputs (make logs; tests/golden)\n"
                 "Same seed, same bytes. Defaults: --seed 1 --out-dir logs.\n",
                 RobotParams{}.rotation_sigma_deg);
}

// One data set's generator: the seed and the data-set number, mixed (splitmix64).
uint64_t mix(uint64_t seed, uint64_t set)
{
    uint64_t z = seed * 0x9E3779B97F4A7C15ULL + set;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

void report(const char *path, const char *shown, const LogStats &s)
{
    struct stat st;
    long size = stat(path, &st) == 0 ? static_cast<long>(st.st_size) : -1;
    double n = s.readings > 0 ? s.readings : 1;
    std::printf("%-28s %7ld bytes  %3d scans  %5d odometry  valid %.1f%%  cable %.1f%%  "
                "sentinel %.1f%%  multipath %.1f%%\n",
                shown, size, s.scans, s.odometry, 100.0 * s.valid / n, 100.0 * s.cable / n,
                100.0 * s.sentinel / n, 100.0 * s.multipath / n);
}

// The name a log will have once renamed into place (write_set): without the temporary
// folder.
std::string final_name(const std::string &path)
{
    std::size_t a = path.find("/.hl-sim-logs.");
    std::size_t b = a == std::string::npos ? a : path.find('/', a + 1);
    return b == std::string::npos ? path : path.substr(0, a) + path.substr(b);
}

bool finish(LogWriter &log, const std::string &path)
{
    if (!log.close()) {
        std::fprintf(stderr, "hl-sim-logs: %s: write failed\n", final_name(path).c_str());
        return false;
    }
    report(path.c_str(), final_name(path).c_str(), log.stats());
    return true;
}

// The simulated robot a data set is recorded with: its own random stream (so the data
// sets do not depend on each other), the default sonar but for the echo model the options
// choose, and the default body but for the rotation-step error the options set.
struct Rig {
    Rng rng;
    SonarParams sonar;
    RobotParams body;
    Robot robot;
    Rig(const World &w, const Options &o, uint64_t set)
        : rng(mix(o.seed, set)), sonar(sonar_of(o)), body(body_of(o)),
          robot(w, sonar, body, rng, kBaseUtime) {}
    static SonarParams sonar_of(const Options &o)
    {
        SonarParams p;
        p.model = o.cone ? SonarParams::Model::Cone : SonarParams::Model::Physical;
        return p;
    }
    static RobotParams body_of(const Options &o)
    {
        RobotParams b;
        b.rotation_sigma_deg = o.rotation_sigma_deg;
        return b;
    }
};

bool open_log(LogWriter *log, const std::string &path)
{
    std::string err;
    if (log->open(path, &err))
        return true;
    std::fprintf(stderr, "hl-sim-logs: %s\n", err.c_str());
    return false;
}

// Experiment 1: the robot set down by hand at each position, sounding o.soundings times
// there. The operator's measurement (the nominal tile intersection and heading) is what
// the ODOMETRY and scan odometry carry; the true pose differs by the placement error.
bool lab28(const World &w, const Options &o, const std::vector<Position> &positions,
           const std::string &path)
{
    Rig rig(w, o, 1);
    Rng &rng = rig.rng;
    Robot &robot = rig.robot;
    const SonarParams &sp = rig.sonar;
    LogWriter log;
    if (!open_log(&log, path))
        return false;
    const double place_sigma_mm = 5.0, place_sigma_deg = 1.0;
    int32_t seq = 0;
    for (const Position &p : positions) {
        Pose truth = p.pose;
        truth.x += rng.normal(0.0, place_sigma_mm);
        truth.y += rng.normal(0.0, place_sigma_mm);
        truth.theta = wrap_pi(truth.theta + deg2rad(rng.normal(0.0, place_sigma_deg)));
        robot.wait(60.0);  // carrying the robot to the next tile
        robot.place(truth, p.pose);
        for (int k = 0; k < o.soundings; k++) {
            log.odometry({OdoSample{robot.utime(), p.pose, 0.0, true, truth}});
            log.sounding(robot.sound(), seq++, sp.calib);
        }
    }
    return finish(log, path);
}

// Experiment 2: a baseline map from six positions in a 1.5 m square, driven with
// odometry; then soundings at 14 headings over 17 degrees at the square's centre.
bool orientation(const World &w, const Options &o, const std::string &path)
{
    Rig rig(w, o, 2);
    Robot &robot = rig.robot;
    const SonarParams &sp = rig.sonar;
    LogWriter log;
    if (!open_log(&log, path))
        return false;
    // The square the world declares (`orientation X Y`: its south-west corner);
    // check_layout has made sure its seven positions keep their clearance.
    const Vec2 c0 = w.orientation_corner;
    const double s = kOrientationSideMm;
    const Vec2 base[6] = {{0, 0}, {s / 2, 0}, {s, 0}, {s, s}, {s / 2, s}, {0, s}};
    const Vec2 centre = c0 + Vec2{s / 2, s / 2};
    Pose start{c0.x, c0.y, 0.0};
    robot.place(start, start);  // odometry frame = world frame at power-on
    int32_t seq = 0;
    for (Vec2 b : base) {
        robot.steer_to(c0 + b);
        robot.turn_to(0.0);
        log.odometry(robot.take_odometry());
        log.sounding(robot.sound(), seq++, sp.calib, "SONAR");
    }
    robot.steer_to(centre);
    const int n = 14;
    const double range_deg = 17.0;
    for (int k = 0; k < n; k++) {
        robot.turn_to(deg2rad(-range_deg / 2 + range_deg * k / (n - 1)));
        log.odometry(robot.take_odometry());
        log.sounding(robot.sound(), seq++, sp.calib, "SONAR_TEST");
    }
    return finish(log, path);
}

// Experiment 3: one sounding at every stop of a space-filling tour of the lab.
bool tour(const World &w, const Options &o, const std::string &path)
{
    Rig rig(w, o, 3);
    Robot &robot = rig.robot;
    const SonarParams &sp = rig.sonar;
    // Start where the world says (the lab: its dense north-west corner) and grow outward.
    std::vector<TourStop> stops = tour_order(w, w.tour_start, w.tile_mm, kTourClearanceMm);
    if (static_cast<int>(stops.size()) < o.tour_min_stops) {
        std::fprintf(stderr, "hl-sim-logs: the tour has %zu stops, want at least %d\n",
                     stops.size(), o.tour_min_stops);
        return false;
    }
    LogWriter log;
    if (!open_log(&log, path))
        return false;
    Pose p0{stops[0].at.x, stops[0].at.y, 0.0};
    robot.place(p0, p0);
    int32_t seq = 0;
    for (const TourStop &s : stops) {
        for (Vec2 v : s.via)
            robot.steer_to(v);
        robot.steer_to(s.at);
        std::vector<OdoSample> odo = robot.take_odometry();
        if (odo.empty())  // the first stop: report where the robot stands
            odo.push_back({robot.utime(), robot.odom(), 0.0, true, robot.truth()});
        log.odometry(odo);
        log.sounding(robot.sound(), seq++, sp.calib);
    }
    return finish(log, path);
}

// The robot drives the first @p stops of the tour without stopping to sound; @p sense
// gets the odometry sample (with the true pose of that instant) every period_s or so:
// the first sample at least that long after the last one it got.
template <class Sense>
bool drive_tour(const World &w, Robot &robot, int stops, double period_s, Sense sense)
{
    std::vector<TourStop> tour = tour_order(w, w.tour_start, w.tile_mm, kTourClearanceMm);
    if (static_cast<int>(tour.size()) < stops) {
        std::fprintf(stderr, "hl-sim-logs: the tour has %zu stops, want at least %d\n",
                     tour.size(), stops);
        return false;
    }
    Pose p0{tour[0].at.x, tour[0].at.y, 0.0};
    robot.place(p0, p0);
    const int64_t period = static_cast<int64_t>(std::llround(period_s * 1e6));
    OdoSample first{robot.utime(), robot.odom(), 0.0, true, robot.truth()};
    sense(first);
    int64_t next = first.utime + period;
    auto take = [&] {
        for (const OdoSample &s : robot.take_odometry())
            if (s.utime >= next) {
                sense(s);
                next = s.utime + period;
            }
    };
    for (int k = 1; k < stops; k++) {
        for (Vec2 v : tour[static_cast<std::size_t>(k)].via) {
            robot.steer_to(v);
            take();
        }
        robot.steer_to(tour[static_cast<std::size_t>(k)].at);
        take();
    }
    return true;
}

// The sonar ring sounded while driving (slam.profile = sonar-continuous): each sample
// fires the 16 transducers once from where the robot truly is, no body rotation.
bool continuous_sonar(const World &w, const Options &o, const std::string &path)
{
    Rig rig(w, o, 4);
    const RobotParams &body = rig.body;
    LogWriter log;
    if (!open_log(&log, path))
        return false;
    int32_t seq = 0;
    bool ok = drive_tour(w, rig.robot, kContinuousSonarStops, kContinuousPeriodS,
                         [&](const OdoSample &at) {
        Sounding s;
        s.utime = at.utime;
        s.odom = at.odom;
        s.truth = at.truth;
        for (int t = 0; t < body.transducers; t++) {
            RingReading r;
            r.transducer = t;
            r.bearing_bam = hl_bam_from_deg(t * body.transducer_spacing_deg);
            r.true_axis = wrap_pi(at.truth.theta + deg2rad(t * body.transducer_spacing_deg));
            r.sonar = sonar_ping(w, rig.sonar, at.truth.pos(), r.true_axis, rig.rng);
            s.readings.push_back(r);
        }
        log.odometry({at});
        log.sounding(s, seq++, rig.sonar.calib);
    });
    return ok && finish(log, path);
}

// A laser scanner sampled while driving (slam.profile = laser).
bool laser(const World &w, const Options &o, const std::string &path)
{
    Rig rig(w, o, 5);
    const LaserParams lp;
    LogWriter log;
    if (!open_log(&log, path))
        return false;
    int32_t seq = 0;
    bool ok = drive_tour(w, rig.robot, kLaserStops, kContinuousPeriodS, [&](const OdoSample &at) {
        LaserScan s;
        s.utime = at.utime;
        s.odom = at.odom;
        s.truth = at.truth;
        s.range_mm = laser_ranges(w, lp, at.truth, rig.rng);
        log.odometry({at});
        log.laser(s, seq++, lp);
    });
    return ok && finish(log, path);
}

// The logs into a temporary folder inside the output folder, then renamed into
// place together: a failed or interrupted run never leaves a mixed set behind.
bool write_set(const World &w, const Options &o, const std::vector<Position> &positions)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);   // like mkdir -p
    if (ec) {
        std::fprintf(stderr, "hl-sim-logs: %s: %s\n", o.out_dir.c_str(), ec.message().c_str());
        return false;
    }
    const std::string tmp = o.out_dir + "/.hl-sim-logs." + std::to_string(getpid());
    fs::remove_all(tmp, ec);
    if (!fs::create_directory(tmp, ec) || ec) {
        std::fprintf(stderr, "hl-sim-logs: %s: %s\n", tmp.c_str(),
                     ec ? ec.message().c_str() : "exists");
        return false;
    }
    const char *names[5] = {"lab28.lcmlog", "orientation.lcmlog", "tour.lcmlog",
                            "continuous.lcmlog", "laser.lcmlog"};
    const int n = o.continuous ? 5 : 3;
    bool ok = lab28(w, o, positions, tmp + "/" + names[0]) &&
              orientation(w, o, tmp + "/" + names[1]) && tour(w, o, tmp + "/" + names[2]) &&
              (!o.continuous || (continuous_sonar(w, o, tmp + "/" + names[3]) &&
                                 laser(w, o, tmp + "/" + names[4])));
    for (int k = 0; ok && k < n; k++) {
        fs::rename(tmp + "/" + names[k], o.out_dir + "/" + names[k], ec);
        if (ec) {
            std::fprintf(stderr, "hl-sim-logs: %s/%s: %s\n", o.out_dir.c_str(), names[k],
                         ec.message().c_str());
            ok = false;
        }
    }
    fs::remove_all(tmp, ec);
    return ok;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        bool has_value = i + 1 < argc;
        if (a == "--help" || a == "-h") {
            usage(stdout);
            return 0;
        } else if (a == "--seed" && has_value) {
            char *end = nullptr;
            const char *v = argv[++i];
            errno = 0;
            unsigned long long s = std::strtoull(v, &end, 10);
            if (*v < '0' || *v > '9' || *end != '\0' || errno == ERANGE) {
                std::fprintf(stderr, "hl-sim-logs: --seed wants a non-negative integer, got '%s'\n", v);
                return 2;
            }
            o.seed = s;
        } else if (a == "--soundings" && has_value) {
            char *end = nullptr;
            const char *v = argv[++i];
            long n = std::strtol(v, &end, 10);
            if (*v == '\0' || *end != '\0' || n < 1 || n > 8) {
                std::fprintf(stderr, "hl-sim-logs: --soundings wants 1..8, got '%s'\n", v);
                return 2;
            }
            o.soundings = static_cast<int>(n);
        } else if (a == "--declared-positions") {
            o.declared = true;
        } else if (a == "--continuous") {
            o.continuous = true;
        } else if (a == "--sonar-model" && has_value) {
            std::string m = argv[++i];
            if (m != "physical" && m != "cone") {
                std::fprintf(stderr, "hl-sim-logs: --sonar-model wants physical or cone, got '%s'\n",
                             m.c_str());
                return 2;
            }
            o.cone = m == "cone";
        } else if (a == "--out-dir" && has_value) {
            o.out_dir = argv[++i];
        } else if (a == "--world" && has_value) {
            o.world = argv[++i];
        } else if (a == "--rotation-sigma-deg" && has_value) {
            char *end = nullptr;
            const char *v = argv[++i];
            double d = std::strtod(v, &end);
            if (*v == '\0' || *end != '\0' || !(d >= 0.0 && d <= 5.0)) {
                std::fprintf(stderr, "hl-sim-logs: --rotation-sigma-deg wants degrees in 0..5, got '%s'\n", v);
                return 2;
            }
            o.rotation_sigma_deg = d;
        } else {
            std::fprintf(stderr, "hl-sim-logs: unknown or incomplete option '%s' (--help)\n",
                         a.c_str());
            return 2;
        }
    }
    World w;
    std::string err;
    if (!World::load_or_lab(o.world, &w, &err)) {
        std::fprintf(stderr, "hl-sim-logs: %s\n", err.c_str());
        return 1;
    }
    std::vector<Position> positions = w.positions;
    Rng layout_rng(mix(o.seed, 0));
    if (!o.declared && !draw_positions(w, kPositions, layout_rng, &positions, &err)) {
        std::fprintf(stderr, "hl-sim-logs: %s\n", err.c_str());
        return 1;
    }
    if (o.declared && positions.empty()) {
        std::fprintf(stderr, "hl-sim-logs: the world has no 'position' lines\n");
        return 1;
    }
    if (!check_layout(w, positions, &err)) {
        std::fprintf(stderr, "hl-sim-logs: %s\n", err.c_str());
        return 1;
    }
    return write_set(w, o, positions) ? 0 : 1;
}
