// hl-tour-study - where a map-making tour's error comes from
// (docs/results/relocalization.md): the tour of a simulated log replayed through
// hl_slam_update as houghlocd replays it, or with the robot's motion known exactly, or
// each scan localized alone against a drift-free map of the scans before it, or tracked
// and then its stops fitted to every match between two of them (loop closure, outside
// the paper's method).
//
// The parameters are the core's table (houghloc/params.h), read from --config and --set
// in houghlocd's form (inputs.hpp).
#include <getopt.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "houghloc-internal/closure.h"
#include "houghloc-internal/posegraph.h"
#include "houghloc/mapstore.h"
}

#include "houghloc-internal/map.h"
#include "houghloc-internal/slam_search.h"
#include "houghloc-internal/slam_params.h"
#include "inputs.hpp"

namespace {

using Pose2 = hl_pg_pose_t;
using Edge = hl_pg_edge_t;

// A stop is "far" beyond this (the paper's wild error; hl-eval score's wild_accepted).
constexpr double kFarMm = 500.0;

// Loop closure after the tour (--mode graph): the rules of houghlocd's own loop closure
// (slam.close_loops; houghloc-internal/closure.h), applied once to the tracked tour instead of at
// every stop: each stop matched against each earlier stop at least HL_CLOSURE_GAP before
// it and within HL_CLOSURE_RADIUS_MM, in a map of that stop and its neighbours, by the
// tracker's local search from the stop's estimate; a match counts as the daemon's does
// (hl_closure_counts: the confidence, the guard's votes and wild error) but with no gate on how
// far it moves the stop: nothing has been fitted yet.

void usage(FILE *to)
{
    std::fprintf(to,
        "usage: hl-tour-study --config FILE [--set K=V]... [--mode MODE] [--write-map MAP]\n"
        "                     [--quiet] TOUR.lcmlog\n"
        "Replays the SONAR scans of a simulated tour log (hl-sim-logs: GROUND_TRUTH for every\n"
        "scan) through the slam of houghlocd's configuration, from the first scan's true\n"
        "pose, and scores each stop's estimate against its truth. MODE:\n"
        "  track   hl_slam_update with the scans' odometry, as houghlocd replays the log\n"
        "          (the default; its RMSE is hl-eval score's on the daemon's output)\n"
        "  exact   the same with each scan's odometry replaced by its true pose: every\n"
        "          prediction is the last estimate moved by the exact motion\n"
        "  oracle  each scan localized from its true pose against a map of the scans before\n"
        "          it at their true poses: one localization's own error, nothing inherited\n"
        "  graph   track, then each stop matched against the earlier stops near it and\n"
        "          every stop moved to the least-squares fit of all the matches (loop\n"
        "          closure after the tour, by houghlocd's rules; one line on stderr says\n"
        "          how many matches were kept)\n"
        "(Loop closure as the tour goes is houghlocd's own: --set slam.close_loops=true.)\n"
        "Prints a line per stop (stop, heading error in degrees, position error in mm), then\n"
        "  tour_study mode=MODE stops=N rmse_mm=X heading_rms_deg=X heading_mean_deg=X far=K\n"
        "(far: stops more than 0.5 m off). --quiet prints the last line alone.\n"
        "  --config FILE     the tracker's keys in houghlocd's form, the studies' too\n"
        "                    (/dev/null: the defaults)\n"
        "  --set K=V         a key, after the file (repeatable)\n"
        "  --write-map MAP   (track, exact, graph) the tour's map as a houghlocd map file\n"
        "                    (hl-kidnap --map reads it): the slam's own; with graph, the\n"
        "                    scans the tour mapped drawn again at the fitted poses\n"
        "Exit status: 0 done; 1 an error (one line on stderr); 2 bad usage.\n");
}

enum class Mode { Track, Exact, Oracle, Graph };

struct Options {
    std::string config, tour, write_map;
    std::vector<std::string> sets;
    Mode mode = Mode::Track;
    const char *mode_name = "track";
    bool quiet = false;
};

// Parses argv into @p o; returns -1 to go on, else the exit status.
int parse(int argc, char **argv, Options *o)
{
    static const struct option longs[] = {
        { "config", required_argument, nullptr, 'c' },
        { "set", required_argument, nullptr, 's' },
        { "mode", required_argument, nullptr, 'm' },
        { "write-map", required_argument, nullptr, 'w' },
        { "quiet", no_argument, nullptr, 'q' },
        { "help", no_argument, nullptr, 'h' },
        { nullptr, 0, nullptr, 0 },
    };
    static const struct { const char *name; Mode mode; } modes[] = {
        { "track", Mode::Track }, { "exact", Mode::Exact },
        { "oracle", Mode::Oracle }, { "graph", Mode::Graph },
    };
    for (int c; (c = getopt_long(argc, argv, "c:s:m:w:qh", longs, nullptr)) != -1;) {
        switch (c) {
        case 'c': o->config = optarg; break;
        case 's': o->sets.push_back(optarg); break;
        case 'm': {
            const auto *m = std::find_if(std::begin(modes), std::end(modes), [](const auto &e) {
                return !std::strcmp(e.name, optarg);
            });
            if (m == std::end(modes)) {
                std::fprintf(stderr,
                             "hl-tour-study: --mode wants track, exact, oracle or graph, got '%s'\n",
                             optarg);
                return 2;
            }
            o->mode = m->mode;
            o->mode_name = m->name;
            break;
        }
        case 'w': o->write_map = optarg; break;
        case 'q': o->quiet = true; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    const char *missing = o->config.empty() ? "--config" :
                          optind + 1 != argc ? "one TOUR.lcmlog operand" : nullptr;
    if (missing) {
        std::fprintf(stderr, "hl-tour-study: wants %s (--help)\n", missing);
        return 2;
    }
    if (o->mode == Mode::Oracle && !o->write_map.empty()) {
        std::fprintf(stderr, "hl-tour-study: --write-map is for a tracked tour, not --mode oracle\n");
        return 2;
    }
    o->tour = argv[optind];
    return -1;
}

using hlkid::MapDeleter;
using hlkid::SlamDeleter;
struct GraphDeleter {
    void operator()(hl_posegraph_t *g) const { hl_posegraph_destroy(g); }
};

// A tour as its tracker left it: each stop's estimate, whether its scan went into the map,
// and the scan as the map saw it (at its echo bearings, with its normals).
struct Tracked {
    std::vector<hl_pose_t> est;
    std::vector<bool> mapped;
    std::vector<hl_scan_t> placed;
    std::vector<hl_vector_t> own;   // the slam's own map at the end (track, exact), as
    hl_rng_t own_rng{};             // houghlocd saves it; empty when the poses moved after
    uint64_t own_version = 0;
};

// The tour through hl_slam_update, with its odometry or (@p exact) its true poses.
bool track(const hl_slam_params_t &p, const hlexp::Soundings &tour, bool exact, Tracked *t,
           std::string *err)
{
    std::unique_ptr<hl_slam_t, SlamDeleter> slam(hl_slam_create_with(&p));
    if (!slam) {
        *err = "cannot create the slam";
        return false;
    }
    hl_slam_reset(slam.get(), tour[0]->truth);
    auto scratch = std::make_unique<hl_scan_t[]>(2);    // the echoed and fitted buffers
    t->placed.resize(tour.size());
    for (size_t i = 0; i < tour.size(); i++) {
        const hlexp::Sounding &s = *tour[i];
        hl_slam_step_t step;
        hl_status_t st = hl_slam_update(slam.get(), &s.msg.scan,
                                        exact ? s.truth : s.msg.odometry, &step);
        if (st != HL_OK) {
            *err = "scan " + std::to_string(s.msg.seq) + ": hl_slam_update: " +
                   hl_status_str(st);
            return false;
        }
        t->est.push_back(step.pose);
        t->mapped.push_back(step.status != HL_SLAM_REJECTED_WILD);
        t->placed[i] = *hl_slam_prepare(&p, &s.msg.scan, &scratch[0], &scratch[1]);
    }
    const hl_map_t *map = hl_slam_map(slam.get());
    t->own.assign(hl_map_vectors(map), hl_map_vectors(map) + hl_map_count(map));
    t->own_rng = hl_map_rng(map);
    t->own_version = hl_map_version(map);
    return true;
}

// Each scan from its true pose against the scans before it at theirs; the first scan has
// nothing to be matched against and gets no estimate (@p scored false).
bool oracle(const hl_slam_params_t &p, const hlexp::Soundings &tour, Tracked *t,
            std::vector<bool> *scored, std::string *err)
{
    std::unique_ptr<hl_slam_t, SlamDeleter> slam(hl_slam_create_with(&p));
    if (!slam) {
        *err = "cannot create the slam";
        return false;
    }
    hl_map_t *map = hl_slam_map(slam.get());
    auto scratch = std::make_unique<hl_scan_t[]>(2);
    for (const auto &s : tour) {
        hl_loc_result_t loc;
        hl_pose_t est = s->truth;
        scored->push_back(hl_map_count(map) > 0 &&
                          hl_slam_localize(slam.get(), &s->msg.scan, s->truth, &loc, &est) ==
                              HL_OK);
        t->est.push_back(est);
        const hl_scan_t *put = hl_slam_prepare(&p, &s->msg.scan, &scratch[0], &scratch[1]);
        if (hl_map_add_scan(map, put, s->truth, nullptr) != HL_OK) {
            *err = "scan " + std::to_string(s->msg.seq) + ": cannot add it to the map";
            return false;
        }
    }
    return true;
}

// Stop @p k matched against stop @p j and its neighbours (those HL_CLOSURE_GAP before k);
// false when the match does not count (above).
bool match(const hlexp::Soundings &tour, const Tracked &t, size_t j, size_t k, hl_map_t *sub,
           hl_slam_t *probe, Pose2 *found)
{
    hl_slam_state_t state;
    hl_slam_get_state(probe, &state);
    hl_map_restore(sub, nullptr, 0, 0, state.cull_rng);
    for (long q = static_cast<long>(j) - HL_CLOSURE_SIDE;
         q <= static_cast<long>(j) + HL_CLOSURE_SIDE && q + HL_CLOSURE_GAP <= static_cast<long>(k);
         q++)
        if (q >= 0)
            hl_map_add_scan(sub, &t.placed[q], t.est[q], nullptr);
    if (hl_slam_restore(probe, &state, hl_map_vectors(sub), hl_map_count(sub)) != HL_OK)
        return false;
    hl_loc_result_t loc;
    hl_pose_t pose;
    if (hl_slam_localize(probe, &tour[k]->msg.scan, t.est[k], &loc, &pose) != HL_OK)
        return false;
    *found = hl_pg_from_pose(pose);
    return hl_closure_counts(&loc, pose, t.est[k], HL_SLAM_MIN_VOTES, HL_SLAM_WILD_MM);
}

// Loop closure: the tracked stops moved to the least-squares fit of their steps and of
// every match between two of them (above).
bool close_loops(const hl_slam_params_t &p, const hlexp::Soundings &tour, Tracked *t,
                 std::string *err)
{
    const size_t n = t->est.size();
    std::unique_ptr<hl_slam_t, SlamDeleter> probe(hl_slam_create_with(&p));
    std::unique_ptr<hl_map_t, MapDeleter> sub(hl_map_create(p.map_capacity, p.seed));
    if (!probe || !sub) {
        *err = "cannot create the slam";
        return false;
    }
    std::vector<Pose2> poses;
    std::vector<Edge> edges;
    for (size_t i = 0; i < n; i++) {
        poses.push_back(hl_pg_from_pose(t->est[i]));
        if (i > 0)
            edges.push_back(Edge{ static_cast<uint32_t>(i - 1), static_cast<uint32_t>(i),
                                  hl_pg_between(poses[i - 1], poses[i]), false });
    }
    int tried = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t j = 0; j + HL_CLOSURE_GAP <= k; j++) {
            if (std::hypot(poses[j].x - poses[k].x, poses[j].y - poses[k].y) >
                HL_CLOSURE_RADIUS_MM)
                continue;
            Pose2 found;
            tried++;
            if (match(tour, *t, j, k, sub.get(), probe.get(), &found))
                edges.push_back(Edge{ static_cast<uint32_t>(j), static_cast<uint32_t>(k),
                                      hl_pg_between(poses[j], found), true });
        }
    std::unique_ptr<hl_posegraph_t, GraphDeleter> graph(
        hl_posegraph_create(static_cast<uint32_t>(n), static_cast<uint32_t>(edges.size())));
    if (!graph) {
        *err = "cannot create the pose graph";
        return false;
    }
    size_t proposed = edges.size() - (n - 1);
    uint32_t n_edges = static_cast<uint32_t>(edges.size());
    uint32_t dropped = hl_posegraph_fit(graph.get(), poses.data(), static_cast<uint32_t>(n),
                                        edges.data(), &n_edges, nullptr, 0, HL_CLOSURE_SIGMA_MM,
                                        hl_bam_to_rad(hl_bam_from_deg(HL_CLOSURE_SIGMA_DEG)),
                                        HL_CLOSURE_KERNEL,
                                        HL_CLOSURE_OUTLIER);
    std::fprintf(stderr, "hl-tour-study: graph: %d matches tried, %zu counted, %zu kept\n", tried,
                 proposed, proposed - dropped);
    for (size_t i = 0; i < n; i++)
        t->est[i] = hl_pg_to_pose(poses[i]);
    t->own.clear();     // the map is drawn again at the fitted poses (write_map)
    return true;
}

// The tour's map, saved as houghlocd saves its map: the slam's own (track, exact), or the
// scans the tour mapped drawn again at the fitted poses into a map made as the slam makes
// its own (graph).
bool write_map(const hl_slam_params_t &p, const hlexp::Soundings &tour, const Tracked &t,
               const std::string &path, std::string *err)
{
    hl_map_params_t mp;
    hl_slam_map_params(&p, &mp);
    std::unique_ptr<hl_map_t, MapDeleter> map(hl_map_create_with(&mp));
    if (!map) {
        *err = "cannot create the map";
        return false;
    }
    if (!t.own.empty()) {
        hl_map_restore(map.get(), t.own.data(), static_cast<uint32_t>(t.own.size()),
                       t.own_version, t.own_rng);
    } else {
        for (size_t i = 0; i < t.est.size(); i++)
            if (t.mapped[i] &&
                hl_map_add_scan(map.get(), &t.placed[i], t.est[i], nullptr) != HL_OK) {
                *err = "scan " + std::to_string(tour[i]->msg.seq) + ": cannot map it there";
                return false;
            }
    }
    hl_mapfile_t m{};
    m.state.started = true;
    m.state.pose = t.est.back();
    m.state.odom = tour.back()->msg.odometry;
    m.state.map_version = hl_map_version(map.get());
    m.state.cull_rng = hl_map_rng(map.get());
    m.capacity = p.map_capacity;
    m.count = hl_map_count(map.get());
    std::vector<hl_vector_t> v(hl_map_vectors(map.get()), hl_map_vectors(map.get()) + m.count);
    m.vectors = v.data();
    m.last_request_seq = 0;    // no request yet (request numbers start at 1)
    m.last_scan_utime = tour.back()->msg.utime;
    m.scans = tour.size();
    char why[HL_MAPSTORE_WHY_LEN];
    if (hl_mapstore_save(path.c_str(), &m, why) != HL_OK) {
        *err = why;
        return false;
    }
    return true;
}

// The error of @p est against @p truth: heading (degrees, signed), position (mm).
void error_of(hl_pose_t est, hl_pose_t truth, double *deg, double *mm)
{
    *deg = hl_bam_diff(est.theta, truth.theta) * (360.0 / 65536.0);
    *mm = std::hypot(static_cast<double>(est.x_mm) - truth.x_mm,
                     static_cast<double>(est.y_mm) - truth.y_mm);
}

int run(const Options &o)
{
    std::string err;
    std::unique_ptr<hl_params_t> cfg = hlkid::load_config(o.config, o.sets, &err);
    if (!cfg) {
        std::fprintf(stderr, "hl-tour-study: %s\n", err.c_str());
        return 1;
    }
    const hl_slam_params_t &p = *hl_params_slam(cfg.get());
    hlexp::Soundings tour;
    if (!hlkid::load_soundings(o.tour, &tour, &err)) {
        std::fprintf(stderr, "hl-tour-study: %s\n", err.c_str());
        return 1;
    }
    if (tour.empty()) {
        std::fprintf(stderr, "hl-tour-study: %s: no SONAR scan\n", o.tour.c_str());
        return 1;
    }
    Tracked t;
    std::vector<bool> scored(tour.size(), true);
    bool ok = o.mode == Mode::Oracle ? (scored.clear(), oracle(p, tour, &t, &scored, &err))
                                     : track(p, tour, o.mode == Mode::Exact, &t, &err);
    if (ok && o.mode == Mode::Graph)
        ok = close_loops(p, tour, &t, &err);
    if (ok && !o.write_map.empty())
        ok = write_map(p, tour, t, o.write_map, &err);
    if (!ok) {
        std::fprintf(stderr, "hl-tour-study: %s\n", err.c_str());
        return 1;
    }
    double sum_mm2 = 0.0, sum_deg = 0.0, sum_deg2 = 0.0;
    int stops = 0, far = 0;
    for (size_t i = 0; i < tour.size(); i++) {
        if (!scored[i])
            continue;
        double deg, mm;
        error_of(t.est[i], tour[i]->truth, &deg, &mm);
        stops++;
        sum_mm2 += mm * mm;
        sum_deg += deg;
        sum_deg2 += deg * deg;
        far += mm > kFarMm;
        if (!o.quiet)
            std::printf("%zu\t%.2f\t%.0f\n", i + 1, deg, mm);
    }
    double n = stops > 0 ? stops : 1;
    std::printf("tour_study mode=%s stops=%d rmse_mm=%.1f heading_rms_deg=%.2f "
                "heading_mean_deg=%.3f far=%d\n",
                o.mode_name, stops, std::sqrt(sum_mm2 / n), std::sqrt(sum_deg2 / n),
                sum_deg / n, far);
    return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    int st = parse(argc, argv, &o);
    return st >= 0 ? st : run(o);
}
