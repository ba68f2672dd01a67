// combined.cpp - combined map-making and localization (paper, section 7): the robot
// localizes each sounding of a space-filling tour against the map made so far and adds
// it, the map culled at random to 1500 vectors. Errors are against ground truth; the
// odometry row integrates the odometry alone from the same start.
#include <cstdio>

#include "experiment.hpp"
#include "figures.hpp"
#include "stats.hpp"

namespace hlexp {

namespace {

const double WILD_MM = 500.0;

CombinedRow summarize(const std::string &mode, const std::vector<double> &err)
{
    CombinedRow row{ mode, static_cast<int>(err.size()), 0, 0, 0, rmse(err), 0, 0 };
    for (double e : err)
        row.max_mm = e > row.max_mm ? e : row.max_mm;
    row.final_mm = err.empty() ? 0 : err.back();
    return row;
}

}  // namespace

std::vector<CombinedRow> run_combined(const Soundings &tour, const Mode &m, const Context &ctx,
                                      bool with_odometry_row)
{
    std::vector<CombinedRow> rows;
    std::vector<const Sounding *> stops = on_channel(tour, "SONAR");
    if (stops.empty() || !stops[0]->has_truth) {
        progress("combined: the log needs SONAR soundings with ground truth");
        return rows;
    }
    hl_slam_t *slam = hl_slam_create_with(&m.slam);
    if (!slam) {
        progress("combined: %s", hl_slam_params_error(&m.slam));
        return rows;
    }
    const hl_pose_t start = stops[0]->truth, odom0 = stops[0]->msg.odometry;
    hl_slam_reset(slam, start);
    Film film(ctx, "fig7_online", m.name == "improved" && ctx.figures);
    std::vector<double> err, odo_err;
    int accepted = 0, rejected = 0, wild = 0;
    std::vector<hl_pose_t> truth_path, est_path, odo_path;
    for (size_t i = 0; i < stops.size(); i++) {
        const Sounding &s = *stops[i];
        // the map as it was when this sounding was localized, for the film
        film.before_step(hl_slam_map(slam));
        hl_slam_step_t out;
        hl_status_t st = hl_slam_update(slam, &s.msg.scan, s.msg.odometry, &out);
        if (st != HL_OK) {
            progress("combined: stop %zu: %s", i, hl_status_str(st));
            continue;
        }
        double e = distance_mm(out.pose, s.truth);
        hl_pose_t odo = hl_pose_compose(start, hl_pose_between(odom0, s.msg.odometry));
        err.push_back(e);
        odo_err.push_back(distance_mm(odo, s.truth));
        accepted += out.status == HL_SLAM_ACCEPTED;
        rejected += out.status == HL_SLAM_REJECTED_WILD;
        wild += out.status == HL_SLAM_ACCEPTED && e > WILD_MM;
        truth_path.push_back(s.truth);
        est_path.push_back(out.pose);
        odo_path.push_back(odo);
        film.after_step(i, stops.size(), s.msg.scan, out.pose, truth_path, est_path, odo_path,
                        hl_map_count(hl_slam_map(slam)));
        if (i % 16 == 15 || i + 1 == stops.size())
            progress("combined: %-8s stop %3zu/%zu  error %6.0f mm  (odometry %6.0f mm)",
                     m.name.c_str(), i + 1, stops.size(), e, odo_err.back());
    }
    hl_slam_destroy(slam);
    film.finish();
    CombinedRow row = summarize(m.name, err);
    row.accepted = accepted;
    row.rejected = rejected;
    row.wild_accepted = wild;
    rows.push_back(row);
    if (with_odometry_row)
        rows.push_back(summarize("odometry", odo_err));
    return rows;
}

}  // namespace hlexp
