// houghloc-eval - scores a houghlocd run against ground truth as evo does: ATE after a
// rigid alignment and RPE over segments of travelled distance (metrics.hpp).
//
//   houghloc-eval [options] IN OUT
//
// IN is the daemon's input log (SONAR scans, GROUND_TRUTH), OUT its output log (one
// POSE per scan); both are matched by scan sequence number (runlog.h).
#include <getopt.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "houghloc/bus.h"
#include "houghloc/fixed.h"
#include "houghloc/version.h"
#include "metrics.hpp"
#include "runlog.h"

namespace {

const char kProg[] = "houghloc-eval";
constexpr double kPi = 3.14159265358979323846;

const char kUsage[] =
    "Usage: houghloc-eval [options] IN.lcmlog OUT.lcmlog\n"
    "       houghloc-eval --odometry [options] IN.lcmlog\n"
    "Scores houghlocd's POSE output (OUT) against the GROUND_TRUTH of its input log (IN),\n"
    "scan by scan (matched by scan seq), as evo does:\n"
    "  ATE  position error after the least-squares rigid alignment of the estimate onto\n"
    "       the truth (evo_ape tum GT EST -a): RMSE and maximum;\n"
    "  RPE  translation error of the motion over segments of 1 m travelled, consecutive\n"
    "       segments picked on the estimate (evo_rpe tum GT EST -r trans_part --delta 1\n"
    "       --delta_unit m -a): RMSE and mean, and the RMSE of its components along the\n"
    "       true motion of each segment and across it;\n"
    "and counts the POSE statuses. The last line of the output is\n"
    "  ate_rmse_m=X rpe_trans_rmse_m=X rpe_trans_mean_m=X max_err_m=X scans=N rpe_pairs=N\n"
    "followed, when POSE is scored, by accepted=N rejected_wild=N odometry_only=N\n"
    "(nan when there is no 1 m segment).\n"
    "\n"
    "Options:\n"
    "  --odometry        score the scans' odometry instead of POSE, integrated from the\n"
    "                    first true pose (OUT is not needed and, if given, not read)\n"
    "  --delta M         RPE segment length in metres, up to 100 km (default 1)\n"
    "  --tum-gt FILE     write the ground truth in TUM format (t x y z qx qy qz qw;\n"
    "                    t the scan's time in seconds, z 0, quaternion from the heading)\n"
    "  --tum-est FILE    write the estimate (POSE or odometry, not aligned) likewise\n"
    "  --tsv             print only the last line\n"
    "  -h, --help        this text\n"
    "  -V, --version     the version\n"
    "Exit status: 0 scored; 1 bad input (one line on stderr); 2 bad usage.\n";

struct Options {
    bool odometry = false;
    bool tsv = false;
    double delta = 1.0;
    const char *tum_gt = nullptr;
    const char *tum_est = nullptr;
    const char *in = nullptr;
    const char *out = nullptr;
};

// Usage error: one line, exit status 2.
int usage_error(const std::string &what)
{
    std::fprintf(stderr, "%s: %s (try --help)\n", kProg, what.c_str());
    return 2;
}

hleval::Pose2 to_pose2(int64_t utime, hl_pose_t p)
{
    // Headings in [-pi, pi), so that a TUM quaternion's w is >= 0 as usual.
    return { static_cast<double>(utime) / 1e6, p.x_mm / 1000.0, p.y_mm / 1000.0,
             hl_bam_to_sdeg(p.theta) * (kPi / 180) };
}

// The odometry pose @p odo carried into the map frame by starting it at @p truth0 where
// the odometry read @p odo0: truth0 (+) (odo0^-1 (+) odo), as hl-eval's odometry error
// does, but in double precision.
hleval::Pose2 odometry_in_map(const hleval::Pose2 &truth0, const hleval::Pose2 &odo0,
                              const hleval::Pose2 &odo)
{
    double c0 = std::cos(odo0.theta), s0 = std::sin(odo0.theta);
    double dx = odo.x - odo0.x, dy = odo.y - odo0.y;
    double rx = c0 * dx + s0 * dy, ry = -s0 * dx + c0 * dy;     // in odo0's frame
    double ct = std::cos(truth0.theta), st = std::sin(truth0.theta);
    return { odo.t, truth0.x + ct * rx - st * ry, truth0.y + st * rx + ct * ry,
             std::remainder(truth0.theta + odo.theta - odo0.theta, 2 * kPi) };
}

struct Run {
    hleval::Trajectory gt, est;
    std::size_t missing = 0;        // scans with truth but no POSE
    int status[3] = { 0, 0, 0 };    // HL_BUS_POSE_ACCEPTED, _REJECTED_WILD, _ODOMETRY_ONLY
};

// The scored scans of a loaded run: every SONAR scan with a GROUND_TRUTH pose (and, when
// POSE is scored, a POSE), in the input log's order.
Run collect(const hl_runlog_t &r, bool odometry)
{
    Run run;
    const hl_runlog_stop_t *first = nullptr;
    for (std::size_t i = 0; i < r.n; i++) {
        const hl_runlog_stop_t &s = r.stops[i];
        if (!s.has_scan || !s.has_truth)
            continue;
        if (!odometry && !s.has_pose) {
            run.missing++;
            continue;
        }
        if (!first)
            first = &s;
        run.gt.push_back(to_pose2(s.utime, s.truth));
        if (odometry) {
            run.est.push_back(odometry_in_map(to_pose2(first->utime, first->truth),
                                              to_pose2(first->utime, first->odometry),
                                              to_pose2(s.utime, s.odometry)));
        } else {
            run.est.push_back(to_pose2(s.utime, s.pose));
            if (s.status >= 0 && s.status <= 2)
                run.status[s.status]++;
        }
    }
    return run;
}

// Writes a trajectory in TUM format. @return 0, or 1 after printing why.
int write_tum(const char *path, const hleval::Trajectory &traj)
{
    FILE *f = std::fopen(path, "w");
    if (!f) {
        std::fprintf(stderr, "%s: %s: cannot create: %s\n", kProg, path, std::strerror(errno));
        return 1;
    }
    for (const hleval::Pose2 &p : traj)
        std::fprintf(f, "%s\n", hleval::tum_line(p).c_str());
    bool bad = std::ferror(f) != 0;
    if (std::fclose(f) != 0 || bad) {
        std::fprintf(stderr, "%s: %s: write error: %s\n", kProg, path, std::strerror(errno));
        return 1;
    }
    return 0;
}

void print_scores(const Options &o, const Run &run, const hleval::Scores &s)
{
    if (!o.tsv) {
        if (o.odometry)
            std::printf("odometry of %s (from the first true pose) against its GROUND_TRUTH\n",
                        o.in);
        else
            std::printf("POSE of %s against the GROUND_TRUTH of %s\n", o.out, o.in);
        std::printf("scans      %zu scored", run.gt.size());
        if (!o.odometry)
            std::printf(" (%d accepted, %d rejected wild, %d odometry only; %zu without POSE)",
                        run.status[HL_BUS_POSE_ACCEPTED], run.status[HL_BUS_POSE_REJECTED_WILD],
                        run.status[HL_BUS_POSE_ODOMETRY_ONLY], run.missing);
        std::printf("\nalignment  rotation %.2f deg, translation (%.3f, %.3f) m\n",
                    s.alignment.angle * 180 / kPi, s.alignment.tx,
                    s.alignment.ty);
        std::printf("ATE        rmse %.4f m  mean %.4f m  max %.4f m\n", s.ate.rmse, s.ate.mean,
                    s.ate.max);
        std::printf("RPE %g m    translation rmse %.4f m  mean %.4f m  (%zu segments)\n", o.delta,
                    s.rpe.rmse, s.rpe.mean, s.rpe.n);
        std::printf("           along the path rmse %.4f m, across it %.4f m\n",
                    s.rpe_along.rmse, s.rpe_across.rmse);
    }
    std::printf("ate_rmse_m=%.6f rpe_trans_rmse_m=%.6f rpe_trans_mean_m=%.6f max_err_m=%.6f "
                "scans=%zu rpe_pairs=%zu",
                s.ate.rmse, s.rpe.rmse, s.rpe.mean, s.ate.max, run.gt.size(), s.rpe.n);
    if (!o.odometry)
        std::printf(" accepted=%d rejected_wild=%d odometry_only=%d",
                    run.status[HL_BUS_POSE_ACCEPTED], run.status[HL_BUS_POSE_REJECTED_WILD],
                    run.status[HL_BUS_POSE_ODOMETRY_ONLY]);
    std::printf("\n");
}

int evaluate(const Options &o)
{
    hl_runlog_t r{};
    r.prog = kProg;
    int rc = hl_runlog_load_input(&r, o.in);
    if (rc == 0 && !o.odometry)
        rc = hl_runlog_load_output(&r, o.out);
    Run run;
    if (rc == 0)
        run = collect(r, o.odometry);
    hl_runlog_free(&r);
    if (rc != 0)
        return rc;
    if (run.gt.empty()) {
        std::fprintf(stderr, "%s: %s: no POSE for any scan of %s\n", kProg, o.out, o.in);
        return 1;
    }
    if (run.missing > 0)
        std::fprintf(stderr, "%s: warning: %zu scans of %s have no POSE in %s; scoring the "
                     "other %zu\n", kProg, run.missing, o.in, o.out, run.gt.size());
    if ((o.tum_gt && write_tum(o.tum_gt, run.gt) != 0) ||
        (o.tum_est && write_tum(o.tum_est, run.est) != 0))
        return 1;
    print_scores(o, run, hleval::score(run.gt, run.est, o.delta));
    return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv)
{
    enum { OPT_ODOMETRY = 256, OPT_TSV, OPT_TUM_GT, OPT_TUM_EST, OPT_DELTA };
    static const struct option longopts[] = {
        { "odometry", no_argument, nullptr, OPT_ODOMETRY },
        { "tsv", no_argument, nullptr, OPT_TSV },
        { "tum-gt", required_argument, nullptr, OPT_TUM_GT },
        { "tum-est", required_argument, nullptr, OPT_TUM_EST },
        { "delta", required_argument, nullptr, OPT_DELTA },
        { "help", no_argument, nullptr, 'h' },
        { "version", no_argument, nullptr, 'V' },
        { nullptr, 0, nullptr, 0 },
    };
    Options o;
    opterr = 0;     // one line of our own instead of getopt's
    int c;
    while ((c = getopt_long(argc, argv, ":hV", longopts, nullptr)) != -1) {
        switch (c) {
        case 'h':
            std::fputs(kUsage, stdout);
            return 0;
        case 'V':
            std::printf("houghloc-eval %s\n", HL_VERSION);
            return 0;
        case OPT_ODOMETRY: o.odometry = true; break;
        case OPT_TSV: o.tsv = true; break;
        case OPT_TUM_GT: o.tum_gt = optarg; break;
        case OPT_TUM_EST: o.tum_est = optarg; break;
        case OPT_DELTA: {
            char *end;
            errno = 0;
            o.delta = std::strtod(optarg, &end);
            // plain decimals only: strtod would also skip spaces and read hexadecimal
            if (!(std::isdigit(static_cast<unsigned char>(*optarg)) || *optarg == '.') ||
                std::strpbrk(optarg, "xX") || end == optarg || *end || errno ||
                !(o.delta > 0) || !(o.delta <= 100000.0))
                return usage_error(std::string("--delta '") + optarg +
                                   "' is not a number of metres in (0, 100000]");
            break;
        }
        case ':':
            return usage_error(std::string(argv[optind - 1]) + " needs a value");
        default:
            return usage_error(std::string("unknown option '") + argv[optind - 1] + "'");
        }
    }
    int rest = argc - optind;
    if (o.odometry ? (rest < 1 || rest > 2) : rest != 2)
        return usage_error(o.odometry ? "expected IN (and optionally OUT)" : "expected IN and OUT");
    o.in = argv[optind];
    o.out = rest == 2 ? argv[optind + 1] : nullptr;
    try {
        return evaluate(o);
    } catch (const std::exception &e) {     // not expected: sizes are checked above
        std::fprintf(stderr, "%s: %s\n", kProg, e.what());
        return 1;
    }
}
