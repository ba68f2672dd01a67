// hl-tour-study - where a map-making tour's error comes from (docs/kidnap.md, "Ninth
// session"): the tour of a simulated log replayed through hl_slam_update as houghlocd
// replays it, or with the robot's motion known exactly, or each scan localized alone
// against a drift-free map of the scans before it.
//
// The parameters are the daemon's: its configuration loader reads --config and --set.
#include <getopt.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "houghloc/map.h"
#include "houghloc/slam.h"
#include "inputs.hpp"

namespace {

// A stop is "far" beyond this (the paper's wild error; hl-eval score's wild_accepted).
constexpr double kFarMm = 500.0;

void usage(FILE *to)
{
    std::fprintf(to,
        "usage: hl-tour-study --config FILE [--set K=V]... [--mode MODE] [--quiet] TOUR.lcmlog\n"
        "Replays the SONAR scans of a simulated tour log (hl-sim-logs: GROUND_TRUTH for every\n"
        "scan) through the slam of houghlocd's configuration, from the first scan's true\n"
        "pose, and scores each stop's estimate against its truth. MODE:\n"
        "  track   hl_slam_update with the scans' odometry, as houghlocd replays the log\n"
        "          (the default; its RMSE is hl-eval score's on the daemon's output)\n"
        "  exact   the same with each scan's odometry replaced by its true pose: every\n"
        "          prediction is the last estimate moved by the exact motion\n"
        "  oracle  each scan localized from its true pose against a map of the scans before\n"
        "          it at their true poses: one localization's own error, nothing inherited\n"
        "Prints a line per stop (stop, heading error in degrees, position error in mm), then\n"
        "  tour_study mode=MODE stops=N rmse_mm=X heading_rms_deg=X heading_mean_deg=X far=K\n"
        "(far: stops more than 0.5 m off). --quiet prints the last line alone.\n"
        "  --config FILE     houghlocd's configuration (/dev/null: the defaults)\n"
        "  --set K=V         a configuration key, after the file (repeatable)\n"
        "Exit status: 0 done; 1 an error (one line on stderr); 2 bad usage.\n");
}

enum class Mode { Track, Exact, Oracle };

struct Options {
    std::string config, tour;
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
        { "quiet", no_argument, nullptr, 'q' },
        { "help", no_argument, nullptr, 'h' },
        { nullptr, 0, nullptr, 0 },
    };
    for (int c; (c = getopt_long(argc, argv, "c:s:m:qh", longs, nullptr)) != -1;) {
        switch (c) {
        case 'c': o->config = optarg; break;
        case 's': o->sets.push_back(optarg); break;
        case 'm':
            if (!std::strcmp(optarg, "track"))
                o->mode = Mode::Track;
            else if (!std::strcmp(optarg, "exact"))
                o->mode = Mode::Exact;
            else if (!std::strcmp(optarg, "oracle"))
                o->mode = Mode::Oracle;
            else {
                std::fprintf(stderr, "hl-tour-study: --mode wants track, exact or oracle, got '%s'\n",
                             optarg);
                return 2;
            }
            o->mode_name = optarg;
            break;
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
    o->tour = argv[optind];
    return -1;
}

struct SlamDeleter {
    void operator()(hl_slam_t *s) const { hl_slam_destroy(s); }
};

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
    std::unique_ptr<hl_config_t> cfg = hlkid::load_config(o.config, o.sets, &err);
    if (!cfg) {
        std::fprintf(stderr, "hl-tour-study: %s\n", err.c_str());
        return 1;
    }
    const hl_slam_params_t &p = cfg->slam;
    hlexp::Soundings tour;
    if (!hlkid::load_soundings(o.tour, &tour, &err)) {
        std::fprintf(stderr, "hl-tour-study: %s\n", err.c_str());
        return 1;
    }
    if (tour.empty()) {
        std::fprintf(stderr, "hl-tour-study: %s: no SONAR scan\n", o.tour.c_str());
        return 1;
    }
    std::unique_ptr<hl_slam_t, SlamDeleter> slam(hl_slam_create(&p));
    if (!slam) {
        std::fprintf(stderr, "hl-tour-study: cannot create the slam\n");
        return 1;
    }
    hl_slam_reset(slam.get(), tour[0]->truth);
    auto prepared = std::make_unique<hl_scan_t[]>(2);  // the echoed and fitted buffers
    double sum_mm2 = 0.0, sum_deg = 0.0, sum_deg2 = 0.0;
    int stops = 0, far = 0;
    for (size_t i = 0; i < tour.size(); i++) {
        const hlexp::Sounding &s = *tour[i];
        hl_pose_t est;
        if (o.mode == Mode::Oracle) {
            hl_map_t *map = hl_slam_map(slam.get());
            bool scored = false;
            if (hl_map_count(map) > 0) {
                hl_loc_result_t loc;
                scored = hl_slam_localize(slam.get(), &s.msg.scan, s.truth, &loc, &est) == HL_OK;
            }
            const hl_scan_t *put = hl_slam_prepare(&p, &s.msg.scan, &prepared[0], &prepared[1]);
            if (hl_map_add_scan(map, put, s.truth, nullptr) != HL_OK) {
                std::fprintf(stderr, "hl-tour-study: scan %d: cannot add it to the map\n",
                             s.msg.seq);
                return 1;
            }
            if (!scored)
                continue;
        } else {
            hl_slam_step_t step;
            hl_pose_t odometry = o.mode == Mode::Exact ? s.truth : s.msg.odometry;
            hl_status_t st = hl_slam_update(slam.get(), &s.msg.scan, odometry, &step);
            if (st != HL_OK) {
                std::fprintf(stderr, "hl-tour-study: scan %d: hl_slam_update: %s\n", s.msg.seq,
                             hl_status_str(st));
                return 1;
            }
            est = step.pose;
        }
        double deg, mm;
        error_of(est, s.truth, &deg, &mm);
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
