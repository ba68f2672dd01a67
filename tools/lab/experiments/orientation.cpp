// orientation.cpp - the orientation experiment (paper, section 6): a baseline map made
// online from six positions in a 1.5 m square, then soundings at a series of headings
// over a 17 degree range at one spot, each localized in (x, y, theta) at a 1.1 degree
// raster. The prediction for each test sounding is the last baseline estimate moved by
// the odometry since, as the online robot would have it.
#include <cmath>
#include <cstdio>

#include "experiment.hpp"
#include "stats.hpp"
#include "houghloc-internal/slam_search.h"

namespace hlexp {

OrientationRow run_orientation(const Soundings &log, const Mode &m, const Context &ctx)
{
    (void)ctx;
    OrientationRow row{ m.name, 0, 0, 0, 0 };
    std::vector<const Sounding *> base = on_channel(log, "SONAR");
    std::vector<const Sounding *> tests = on_channel(log, "SONAR_TEST");
    if (base.empty() || tests.empty() || !base[0]->has_truth) {
        progress("orientation: the log needs SONAR baseline and SONAR_TEST soundings with truth");
        return row;
    }
    hl_slam_t *slam = hl_slam_create_with(&m.slam);
    if (!slam) {
        progress("orientation: %s", hl_slam_params_error(&m.slam));
        return row;
    }
    hl_slam_reset(slam, base[0]->truth);
    hl_slam_step_t step{};
    for (const Sounding *s : base)
        if (hl_slam_update(slam, &s->msg.scan, s->msg.odometry, &step) != HL_OK)
            progress("orientation: baseline sounding %d failed", s->msg.seq);
    hl_pose_t last_pose = step.pose, last_odom = base.back()->msg.odometry;

    std::vector<double> err;
    for (const Sounding *s : tests) {
        hl_pose_t predicted =
            hl_pose_compose(last_pose, hl_pose_between(last_odom, s->msg.odometry));
        hl_loc_result_t r;
        hl_pose_t found;
        hl_status_t st = hl_slam_localize(slam, &s->msg.scan, predicted, &r, &found);
        if (st != HL_OK || !s->has_truth) {
            progress("orientation: test sounding %d: %s", s->msg.seq,
                     st != HL_OK ? hl_status_str(st) : "no ground truth");
            continue;
        }
        double e = hl_bam_diff(found.theta, s->truth.theta) * 360.0 / 65536.0;
        err.push_back(e);
        row.max_abs_deg = std::fmax(row.max_abs_deg, std::fabs(e));
    }
    hl_slam_destroy(slam);
    row.trials = static_cast<int>(err.size());
    row.mean_deg = mean(err);
    row.sigma_deg = sigma(err);
    progress("orientation: %-8s mean %.2f deg  sigma %.2f deg  max |e| %.2f deg  (%d soundings)",
             m.name.c_str(), row.mean_deg, row.sigma_deg, row.max_abs_deg, row.trials);
    return row;
}

}  // namespace hlexp
